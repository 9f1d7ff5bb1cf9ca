//! Semantic tokens in the protocol's relative form, for a range of lines, and the edit that
//! turns one result into the next (`semanticTokens/full/delta`).

use crate::{semantic_tokens, Analysis};

/// One token as the protocol sends it: line delta, start delta, length, type, modifiers.
pub type RelToken = [u32; 5];

/// The tokens of the document in relative form; with `lines`, only those starting on a line
/// in `start..=end` (the first one relative to the document start, as the protocol wants).
pub fn relative_tokens(a: &Analysis, lines: Option<(u32, u32)>) -> Vec<RelToken> {
    let mut data = Vec::new();
    let (mut line, mut col) = (0u32, 0u32);
    for t in semantic_tokens(a) {
        let s = a.index.pos(t.start);
        let e = a.index.pos(t.end);
        // the protocol has no multi-line tokens without a client capability
        if e.line != s.line {
            continue;
        }
        if let Some((first, last)) = lines {
            if s.line < first {
                continue;
            }
            if s.line > last {
                break;
            }
        }
        let delta_line = s.line - line;
        let delta_start = if delta_line == 0 { s.col - col } else { s.col };
        data.push([delta_line, delta_start, e.col - s.col, t.kind, 0]);
        line = s.line;
        col = s.col;
    }
    data
}

/// Replace `delete` tokens at token index `start` by `insert`.
#[derive(Debug, Clone, PartialEq)]
pub struct TokenEdit {
    pub start: usize,
    pub delete: usize,
    pub insert: Vec<RelToken>,
}

/// The single edit from `old` to `new` (common head and tail kept); `None` when they are
/// equal. Relative tokens make an edit in one line shift nothing after it, so the middle
/// part is small for a keystroke.
pub fn token_edit(old: &[RelToken], new: &[RelToken]) -> Option<TokenEdit> {
    let head = old.iter().zip(new).take_while(|(a, b)| a == b).count();
    if head == old.len() && head == new.len() {
        return None;
    }
    let max_tail = old.len().min(new.len()) - head;
    let tail = old
        .iter()
        .rev()
        .zip(new.iter().rev())
        .take(max_tail)
        .take_while(|(a, b)| a == b)
        .count();
    Some(TokenEdit {
        start: head,
        delete: old.len() - head - tail,
        insert: new[head..new.len() - tail].to_vec(),
    })
}

/// `old` with the edit applied (what a client does with a delta).
pub fn apply_token_edit(old: &[RelToken], e: &TokenEdit) -> Vec<RelToken> {
    let start = e.start.min(old.len());
    let end = (start + e.delete).min(old.len());
    let mut out = old[..start].to_vec();
    out.extend_from_slice(&e.insert);
    out.extend_from_slice(&old[end..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(n: u32) -> RelToken {
        [n, n, 1, 0, 0]
    }

    #[test]
    fn an_edit_applied_gives_the_new_tokens() {
        let cases: Vec<(Vec<RelToken>, Vec<RelToken>)> = vec![
            (vec![], vec![t(1)]),
            (vec![t(1)], vec![]),
            (vec![t(1), t(2), t(3)], vec![t(1), t(9), t(3)]),
            (vec![t(1), t(2), t(3)], vec![t(1), t(2), t(2), t(3)]),
            (vec![t(1), t(1), t(1)], vec![t(1), t(1)]),
            (vec![t(4), t(5)], vec![t(6), t(7), t(8)]),
        ];
        for (old, new) in cases {
            let e = token_edit(&old, &new).expect("different");
            assert_eq!(apply_token_edit(&old, &e), new, "{old:?} → {new:?}: {e:?}");
        }
        assert_eq!(token_edit(&[t(1)], &[t(1)]), None);
    }

    #[test]
    fn a_change_in_the_middle_is_a_small_edit() {
        let old: Vec<RelToken> = (0..100).map(t).collect();
        let mut new = old.clone();
        new[50] = t(500);
        let e = token_edit(&old, &new).unwrap();
        assert_eq!((e.start, e.delete, e.insert.len()), (50, 1, 1));
    }
}
