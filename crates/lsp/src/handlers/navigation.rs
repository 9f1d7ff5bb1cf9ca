//! Go to definition, references, document highlight and document links.

use crate::conv::*;
use crate::state::*;
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

pub(crate) async fn goto_definition(
    b: &Backend,
    params: GotoDefinitionParams,
) -> Result<Option<GotoDefinitionResponse>> {
    let (a, ws) = b
        .analysis(&params.text_document_position_params.text_document.uri)
        .await?;
    let at = offset(&a, params.text_document_position_params.position);
    guarded(|| {
        let locs: Vec<Location> = millpath_ide::definition(&a, &ws, at)
            .iter()
            .filter_map(loc)
            .collect();
        (!locs.is_empty()).then_some(GotoDefinitionResponse::Array(locs))
    })
}

pub(crate) async fn references(
    b: &Backend,
    params: ReferenceParams,
) -> Result<Option<Vec<Location>>> {
    let (a, ws) = b
        .analysis(&params.text_document_position.text_document.uri)
        .await?;
    let at = offset(&a, params.text_document_position.position);
    let with_declaration = params.context.include_declaration;
    guarded(|| {
        let mut out = Vec::new();
        if with_declaration {
            out.extend(millpath_ide::definition(&a, &ws, at).iter().filter_map(loc));
        }
        out.extend(millpath_ide::references(&a, &ws, at).iter().filter_map(loc));
        Some(out)
    })
}

pub(crate) async fn document_highlight(
    b: &Backend,
    params: DocumentHighlightParams,
) -> Result<Option<Vec<DocumentHighlight>>> {
    let doc = params.text_document_position_params;
    let (a, _) = b.analysis(&doc.text_document.uri).await?;
    let at = offset(&a, doc.position);
    guarded(|| {
        Some(
            millpath_ide::document_highlights(&a, at)
                .into_iter()
                .map(|h| DocumentHighlight {
                    range: range(&a.index, h.start, h.end),
                    kind: Some(if h.write {
                        DocumentHighlightKind::WRITE
                    } else {
                        DocumentHighlightKind::READ
                    }),
                })
                .collect(),
        )
    })
}

pub(crate) async fn document_link(
    b: &Backend,
    params: DocumentLinkParams,
) -> Result<Option<Vec<DocumentLink>>> {
    let (a, ws) = b.analysis(&params.text_document.uri).await?;
    blocking(move || {
        Some(
            millpath_ide::document_links(&a, &ws)
                .into_iter()
                .map(|l| DocumentLink {
                    range: range(&a.index, l.start, l.end),
                    target: to_uri(&l.target),
                    tooltip: Some(format!("{}:{}", l.target.display(), l.line + 1)),
                    data: None,
                })
                .collect(),
        )
    })
    .await
}
