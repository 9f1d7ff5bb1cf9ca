//! Inlay hints.

use crate::conv::*;
use crate::state::*;
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

pub(crate) async fn inlay_hint(
    b: &Backend,
    params: InlayHintParams,
) -> Result<Option<Vec<InlayHint>>> {
    let (a, _) = b.analysis(&params.text_document.uri).await?;
    let (start, end) = (offset(&a, params.range.start), offset(&a, params.range.end));
    guarded(|| {
        Some(
            millpath_ide::inlay_hints_in(&a, start, end)
                .into_iter()
                .map(|h| InlayHint {
                    position: pos(a.index.pos(h.offset)),
                    label: InlayHintLabel::String(h.label),
                    kind: Some(InlayHintKind::PARAMETER),
                    text_edits: None,
                    tooltip: None,
                    padding_left: Some(true),
                    padding_right: None,
                    data: None,
                })
                .collect(),
        )
    })
}
