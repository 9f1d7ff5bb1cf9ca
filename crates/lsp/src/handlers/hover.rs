//! Hover.

use crate::conv::*;
use crate::state::*;
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

pub(crate) async fn hover(b: &Backend, params: HoverParams) -> Result<Option<Hover>> {
    let (a, ws) = b
        .analysis(&params.text_document_position_params.text_document.uri)
        .await?;
    let at = offset(&a, params.text_document_position_params.position);
    guarded(|| {
        let found = if millpath_ide::is_toml(&a.path) {
            millpath_ide::settings_hover(&a, &ws, at)
        } else {
            millpath_ide::hover(&a, &ws, at)
        };
        found.map(|h| Hover {
            contents: HoverContents::Markup(MarkupContent {
                kind: MarkupKind::Markdown,
                value: h.markdown,
            }),
            range: Some(range(&a.index, h.start, h.end)),
        })
    })
}
