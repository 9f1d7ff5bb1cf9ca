//! Completion.

use crate::conv::*;
use crate::state::*;
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

pub(crate) async fn completion(
    b: &Backend,
    params: CompletionParams,
) -> Result<Option<CompletionResponse>> {
    let (a, ws) = b
        .analysis(&params.text_document_position.text_document.uri)
        .await?;
    let at = offset(&a, params.text_document_position.position);
    guarded(|| {
        let found = if millpath_ide::is_toml(&a.path) {
            millpath_ide::settings_completion(&a, &ws, at)
        } else {
            millpath_ide::completion(&a, &ws, at)
        };
        let items = found
            .into_iter()
            .map(|c| CompletionItem {
                label: c.label,
                detail: Some(c.detail),
                insert_text: Some(c.insert),
                ..Default::default()
            })
            .collect();
        Some(CompletionResponse::Array(items))
    })
}
