//! Document and workspace symbols.

use crate::conv::*;
use crate::state::*;
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

pub(crate) async fn document_symbol(
    b: &Backend,
    params: DocumentSymbolParams,
) -> Result<Option<DocumentSymbolResponse>> {
    let (a, _) = b.analysis(&params.text_document.uri).await?;
    #[allow(deprecated)]
    fn conv(a: &millpath_ide::Analysis, s: &millpath_ide::Symbol) -> DocumentSymbol {
        DocumentSymbol {
            name: s.name.clone(),
            detail: Some(s.detail.clone()),
            kind: if s.is_path {
                SymbolKind::MODULE
            } else {
                SymbolKind::FIELD
            },
            tags: None,
            deprecated: None,
            range: range(&a.index, s.start, s.end),
            selection_range: range(&a.index, s.name_start, s.name_end),
            children: Some(s.children.iter().map(|c| conv(a, c)).collect()),
        }
    }
    guarded(|| {
        Some(DocumentSymbolResponse::Nested(
            millpath_ide::document_symbols(&a)
                .iter()
                .map(|s| conv(&a, s))
                .collect(),
        ))
    })
}

pub(crate) async fn symbol(
    b: &Backend,
    params: WorkspaceSymbolParams,
) -> Result<Option<WorkspaceSymbolResponse>> {
    let ws = b.snapshot();
    guarded(|| {
        let out: Vec<WorkspaceSymbol> = millpath_ide::workspace_symbols(&ws, &params.query)
            .into_iter()
            .filter_map(|(name, l)| {
                Some(WorkspaceSymbol {
                    name,
                    kind: SymbolKind::MODULE,
                    tags: None,
                    container_name: None,
                    location: OneOf::Left(loc(&l)?),
                    data: None,
                })
            })
            .collect();
        Some(WorkspaceSymbolResponse::Nested(out))
    })
}
