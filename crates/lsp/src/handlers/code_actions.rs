//! Quick fixes.

use crate::conv::*;
use crate::state::*;
use std::collections::HashMap;
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

pub(crate) async fn code_action(
    b: &Backend,
    params: CodeActionParams,
) -> Result<Option<CodeActionResponse>> {
    let uri = params.text_document.uri.clone();
    let (a, _) = b.analysis(&uri).await?;
    let (s, e) = (offset(&a, params.range.start), offset(&a, params.range.end));
    guarded(|| {
        let actions = millpath_ide::code_actions(&a, s, e)
            .into_iter()
            .map(|act| {
                let mut changes = HashMap::new();
                changes.insert(uri.clone(), act.edits.iter().map(|x| edit(&a, x)).collect());
                CodeActionOrCommand::CodeAction(CodeAction {
                    title: act.title,
                    kind: Some(CodeActionKind::QUICKFIX),
                    edit: Some(WorkspaceEdit {
                        changes: Some(changes),
                        ..Default::default()
                    }),
                    ..Default::default()
                })
            })
            .collect();
        Some(actions)
    })
}
