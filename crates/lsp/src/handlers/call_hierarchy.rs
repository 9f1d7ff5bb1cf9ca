//! Call hierarchy over subpath embedding: a path calls the subpaths it embeds.

use crate::conv::*;
use crate::state::*;
use millpath_ide::{CallItem, Location as IdeLocation, Pos};
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

fn lsp_range((s, e): (Pos, Pos)) -> Range {
    Range {
        start: pos(s),
        end: pos(e),
    }
}

fn item(c: &CallItem) -> Option<CallHierarchyItem> {
    let range = lsp_range((c.at.start, c.at.end));
    Some(CallHierarchyItem {
        name: c.name.clone(),
        kind: SymbolKind::FUNCTION,
        tags: None,
        detail: c
            .at
            .path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned()),
        uri: to_uri(&c.at.path)?,
        range,
        selection_range: range,
        data: None,
    })
}

/// The ide item of a client's item (its name and the file defining it).
fn from_lsp(i: &CallHierarchyItem) -> Option<CallItem> {
    let path = to_path(&i.uri)?;
    let at = |p: Position| Pos {
        line: p.line,
        col: p.character,
    };
    Some(CallItem {
        name: i.name.clone(),
        at: IdeLocation {
            path,
            start: at(i.selection_range.start),
            end: at(i.selection_range.end),
        },
    })
}

pub(crate) async fn prepare_call_hierarchy(
    b: &Backend,
    params: CallHierarchyPrepareParams,
) -> Result<Option<Vec<CallHierarchyItem>>> {
    let doc = params.text_document_position_params;
    let (a, ws) = b.analysis(&doc.text_document.uri).await?;
    let at = offset(&a, doc.position);
    blocking(move || {
        millpath_ide::prepare_call_hierarchy(&a, &ws, at)
            .and_then(|c| item(&c))
            .map(|i| vec![i])
    })
    .await
}

pub(crate) async fn incoming_calls(
    b: &Backend,
    params: CallHierarchyIncomingCallsParams,
) -> Result<Option<Vec<CallHierarchyIncomingCall>>> {
    let ws = b.snapshot();
    let name = params.item.name;
    blocking(move || {
        Some(
            millpath_ide::incoming_calls(&ws, &name)
                .into_iter()
                .filter_map(|c| {
                    Some(CallHierarchyIncomingCall {
                        from: item(&c.item)?,
                        from_ranges: c.ranges.into_iter().map(lsp_range).collect(),
                    })
                })
                .collect(),
        )
    })
    .await
}

pub(crate) async fn outgoing_calls(
    b: &Backend,
    params: CallHierarchyOutgoingCallsParams,
) -> Result<Option<Vec<CallHierarchyOutgoingCall>>> {
    let ws = b.snapshot();
    let Some(it) = from_lsp(&params.item) else {
        return Ok(None);
    };
    blocking(move || {
        Some(
            millpath_ide::outgoing_calls(&ws, &it)
                .into_iter()
                .filter_map(|c| {
                    Some(CallHierarchyOutgoingCall {
                        to: item(&c.item)?,
                        from_ranges: c.ranges.into_iter().map(lsp_range).collect(),
                    })
                })
                .collect(),
        )
    })
    .await
}
