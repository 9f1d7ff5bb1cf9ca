//! Document and range formatting.

use crate::conv::*;
use crate::state::*;
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

pub(crate) async fn formatting(
    b: &Backend,
    params: DocumentFormattingParams,
) -> Result<Option<Vec<TextEdit>>> {
    let (a, _) = b.analysis(&params.text_document.uri).await?;
    guarded(|| {
        millpath_ide::format(&a).filter(|f| *f != a.src).map(|f| {
            vec![TextEdit {
                range: range(&a.index, 0, a.src.len()),
                new_text: f,
            }]
        })
    })
}

pub(crate) async fn range_formatting(
    b: &Backend,
    params: DocumentRangeFormattingParams,
) -> Result<Option<Vec<TextEdit>>> {
    let (a, _) = b.analysis(&params.text_document.uri).await?;
    let (s, e) = (offset(&a, params.range.start), offset(&a, params.range.end));
    guarded(|| {
        millpath_ide::format_range(&a, s, e)
            .map(|edits| edits.iter().map(|x| edit(&a, x)).collect())
    })
}
