//! Folding ranges and selection ranges.

use crate::conv::*;
use crate::state::*;
use millpath_ide::FoldKind;
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

pub(crate) async fn folding_range(
    b: &Backend,
    params: FoldingRangeParams,
) -> Result<Option<Vec<FoldingRange>>> {
    let (a, _) = b.analysis(&params.text_document.uri).await?;
    guarded(|| {
        Some(
            millpath_ide::folding_ranges(&a)
                .into_iter()
                .map(|f| FoldingRange {
                    start_line: a.index.pos(f.start).line,
                    end_line: a.index.pos(f.end).line,
                    kind: Some(match f.kind {
                        FoldKind::Comment => FoldingRangeKind::Comment,
                        FoldKind::Path => FoldingRangeKind::Region,
                    }),
                    ..Default::default()
                })
                .collect(),
        )
    })
}

pub(crate) async fn selection_range(
    b: &Backend,
    params: SelectionRangeParams,
) -> Result<Option<Vec<SelectionRange>>> {
    let (a, _) = b.analysis(&params.text_document.uri).await?;
    guarded(|| {
        Some(
            params
                .positions
                .iter()
                .map(|p| {
                    // outermost first, each the parent of the next
                    let mut sel: Option<SelectionRange> = None;
                    for (s, e) in millpath_ide::selection_ranges(&a, offset(&a, *p))
                        .into_iter()
                        .rev()
                    {
                        sel = Some(SelectionRange {
                            range: range(&a.index, s, e),
                            parent: sel.map(Box::new),
                        });
                    }
                    sel.unwrap_or(SelectionRange {
                        range: Range { start: *p, end: *p },
                        parent: None,
                    })
                })
                .collect(),
        )
    })
}
