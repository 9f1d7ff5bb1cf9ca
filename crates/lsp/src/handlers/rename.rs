//! Rename of path names across the workspace, with prepareRename.

use crate::conv::*;
use crate::state::*;
use std::collections::HashMap;
use tower_lsp_server::jsonrpc::{Error, Result};
use tower_lsp_server::ls_types::*;

pub(crate) async fn prepare_rename(
    b: &Backend,
    params: TextDocumentPositionParams,
) -> Result<Option<PrepareRenameResponse>> {
    let (a, _) = b.analysis(&params.text_document.uri).await?;
    let at = offset(&a, params.position);
    guarded(|| {
        millpath_ide::prepare_rename(&a, at).map(|(start, end, name)| {
            PrepareRenameResponse::RangeWithPlaceholder {
                range: range(&a.index, start, end),
                placeholder: name,
            }
        })
    })
}

pub(crate) async fn rename(b: &Backend, params: RenameParams) -> Result<Option<WorkspaceEdit>> {
    let doc = params.text_document_position;
    let (a, ws) = b.analysis(&doc.text_document.uri).await?;
    let at = offset(&a, doc.position);
    let new_name = params.new_name;
    let edits = blocking(move || millpath_ide::rename(&a, &ws, at, &new_name))
        .await?
        .map_err(|message| Error {
            // RequestFailed: the request was valid, the rename cannot be done (the reason)
            code: tower_lsp_server::jsonrpc::ErrorCode::ServerError(-32803),
            message: message.into(),
            data: None,
        })?;
    let mut changes: HashMap<Uri, Vec<TextEdit>> = HashMap::new();
    for e in edits {
        if let Some(l) = loc(&e.location) {
            changes.entry(l.uri).or_default().push(TextEdit {
                range: l.range,
                new_text: e.text,
            });
        }
    }
    Ok(Some(WorkspaceEdit {
        changes: Some(changes),
        ..Default::default()
    }))
}
