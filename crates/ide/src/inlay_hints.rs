//! Inlay hints: inherited depths after the elements that do not set them.

use crate::common::*;
use crate::provenance::provenance;
use crate::Analysis;
use millpath_syntax::Kind;
use millpath_syntax::Style;

/// An inlay hint after the byte offset.
#[derive(Debug, Clone, PartialEq)]
pub struct Hint {
    pub offset: usize,
    pub label: String,
}

/// Inherited depths (B, D, I) shown after elements that do not set them.
pub fn inlay_hints(a: &Analysis) -> Vec<Hint> {
    inlay_hints_in(a, 0, usize::MAX)
}

/// Inlay hints of the elements overlapping the byte range `start..end`: the cost is that of
/// those elements (plus one traversal per path, made once per analysis).
pub fn inlay_hints_in(a: &Analysis, start: usize, end: usize) -> Vec<Hint> {
    let mut out = Vec::new();
    for p in a.ast.paths() {
        if p.span.end < start || p.span.start > end {
            continue;
        }
        for el in p.elements() {
            if el.span.end < start || el.span.start > end {
                continue;
            }
            let keys: &[char] = match el.kind.value {
                Kind::Mill | Kind::Bars | Kind::Drill(Style::Mill) | Kind::Helix(Style::Mill) => {
                    &['B']
                }
                Kind::Mark | Kind::Drill(Style::Mark) | Kind::Helix(Style::Mark) => &['D'],
                Kind::Helix(Style::Bars) => &['B', 'D'],
                _ => continue,
            };
            let Some((path, seg)) = segment_of(a, el) else {
                continue;
            };
            let rows = provenance(a, path, el, seg);
            let mut parts = Vec::new();
            for k in keys {
                let own = el.params.iter().any(|p| p.value.starts_with(*k));
                if let (false, Some(r)) = (own, rows.iter().find(|r| r.key == *k)) {
                    parts.push(format!("{k}{}", r.value));
                }
            }
            if !parts.is_empty() {
                out.push(Hint {
                    offset: el.geometry.span.end,
                    label: format!("⇐ {}", parts.join(" ")),
                });
            }
        }
    }
    out
}
