//! Semantic tokens: the whole document (with a result id), a range of lines, and the delta
//! against the previous result of the document (an unknown id gives the whole tokens).

use crate::state::*;
use millpath_ide::{relative_tokens, token_edit, RelToken};
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

fn lsp_tokens(data: &[RelToken]) -> Vec<SemanticToken> {
    data.iter()
        .map(|t| SemanticToken {
            delta_line: t[0],
            delta_start: t[1],
            length: t[2],
            token_type: t[3],
            token_modifiers_bitset: t[4],
        })
        .collect()
}

/// The document's tokens, remembered under a new result id.
async fn full_tokens(b: &Backend, uri: &Uri) -> Result<(String, Vec<RelToken>)> {
    let (a, _) = b.analysis(uri).await?;
    let data = guarded(|| relative_tokens(&a, None))?;
    let id = b
        .state
        .lock()
        .map(|mut s| s.results.keep_tokens(uri.as_str(), data.clone()))
        .unwrap_or_default();
    Ok((id, data))
}

pub(crate) async fn semantic_tokens_full(
    b: &Backend,
    params: SemanticTokensParams,
) -> Result<Option<SemanticTokensResult>> {
    let (id, data) = full_tokens(b, &params.text_document.uri).await?;
    Ok(Some(SemanticTokensResult::Tokens(SemanticTokens {
        result_id: Some(id),
        data: lsp_tokens(&data),
    })))
}

pub(crate) async fn semantic_tokens_full_delta(
    b: &Backend,
    params: SemanticTokensDeltaParams,
) -> Result<Option<SemanticTokensFullDeltaResult>> {
    let uri = params.text_document.uri;
    let old: Option<Vec<RelToken>> = b.state.lock().ok().and_then(|s| {
        s.results
            .tokens(uri.as_str(), &params.previous_result_id)
            .map(<[RelToken]>::to_vec)
    });
    let (id, data) = full_tokens(b, &uri).await?;
    let Some(old) = old else {
        return Ok(Some(SemanticTokensFullDeltaResult::Tokens(
            SemanticTokens {
                result_id: Some(id),
                data: lsp_tokens(&data),
            },
        )));
    };
    // edits index the flat integer array: five per token
    let edits = guarded(|| token_edit(&old, &data))?
        .map(|e| SemanticTokensEdit {
            start: (e.start * 5) as u32,
            delete_count: (e.delete * 5) as u32,
            data: Some(lsp_tokens(&e.insert)),
        })
        .into_iter()
        .collect();
    Ok(Some(SemanticTokensFullDeltaResult::TokensDelta(
        SemanticTokensDelta {
            result_id: Some(id),
            edits,
        },
    )))
}

pub(crate) async fn semantic_tokens_range(
    b: &Backend,
    params: SemanticTokensRangeParams,
) -> Result<Option<SemanticTokensRangeResult>> {
    let (a, _) = b.analysis(&params.text_document.uri).await?;
    let r = params.range;
    // tokens are single-line: those starting on the range's lines (its last line only up to
    // its end column is not worth the cut; clients ask for whole visible lines)
    let data = guarded(|| relative_tokens(&a, Some((r.start.line, r.end.line))))?;
    Ok(Some(SemanticTokensRangeResult::Tokens(SemanticTokens {
        result_id: None,
        data: lsp_tokens(&data),
    })))
}
