//! Semantic tokens.

use crate::state::*;
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

pub(crate) async fn semantic_tokens_full(
    b: &Backend,
    params: SemanticTokensParams,
) -> Result<Option<SemanticTokensResult>> {
    let (a, _) = b.analysis(&params.text_document.uri).await?;
    guarded(|| {
        let mut data = Vec::new();
        let (mut line, mut col) = (0u32, 0u32);
        for t in millpath_ide::semantic_tokens(&a) {
            let s = a.index.pos(t.start);
            let e = a.index.pos(t.end);
            if e.line != s.line {
                continue;
            }
            let delta_line = s.line - line;
            let delta_start = if delta_line == 0 { s.col - col } else { s.col };
            data.push(SemanticToken {
                delta_line,
                delta_start,
                length: e.col - s.col,
                token_type: t.kind,
                token_modifiers_bitset: 0,
            });
            line = s.line;
            col = s.col;
        }
        Some(SemanticTokensResult::Tokens(SemanticTokens {
            result_id: None,
            data,
        }))
    })
}
