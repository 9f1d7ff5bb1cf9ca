//! Code lenses and the server command `millpath.server.preview`.

use crate::conv::*;
use crate::state::*;
use crate::PreviewParams;
use serde_json::Value;
use tower_lsp_server::jsonrpc::{Error, Result};
use tower_lsp_server::ls_types::*;

pub(crate) async fn code_lens(
    b: &Backend,
    params: CodeLensParams,
) -> Result<Option<Vec<CodeLens>>> {
    let uri = params.text_document.uri;
    let (a, ws) = b.analysis(&uri).await?;
    // a cancelled request stops the compile of the statistics as well
    let (_guard, cancelled) = crate::cancel::on_drop();
    blocking(move || {
        Some(
            millpath_ide::code_lenses_until(&a, &ws, &|| cancelled.get())?
                .into_iter()
                .map(|l| {
                    let p = pos(a.index.pos(l.offset));
                    CodeLens {
                        range: Range { start: p, end: p },
                        command: Some(Command {
                            title: l.title,
                            command: "millpath.preview".into(),
                            arguments: Some(vec![
                                serde_json::json!(uri.as_str()),
                                serde_json::json!(l.path),
                            ]),
                        }),
                        data: None,
                    }
                })
                .collect(),
        )
    })
    .await
}

pub(crate) async fn execute_command(
    b: &Backend,
    params: ExecuteCommandParams,
) -> Result<Option<Value>> {
    if params.command != "millpath.server.preview" {
        return Err(Error::method_not_found());
    }
    let uri = params
        .arguments
        .first()
        .and_then(Value::as_str)
        .and_then(|s| s.parse::<Uri>().ok())
        .ok_or_else(|| Error::invalid_params("expected the document URI"))?;
    let path = params
        .arguments
        .get(1)
        .and_then(Value::as_str)
        .map(str::to_string);
    let r = b
        .gcode_preview(PreviewParams {
            text_document: TextDocumentIdentifier { uri },
            path,
        })
        .await?;
    Ok(serde_json::to_value(r).ok())
}
