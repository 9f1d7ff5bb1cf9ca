//! Selection ranges: parameter → element → path → file.

use crate::common::*;
use crate::Analysis;

/// The ranges around `offset`, innermost first, each containing the one before.
pub fn selection_ranges(a: &Analysis, offset: usize) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    if let Some((p, el)) = element_at(a, offset) {
        if let Some(prm) = el
            .params
            .iter()
            .find(|p| p.span.start <= offset && offset <= p.span.end)
        {
            out.push((prm.span.start, prm.span.end));
        } else if el.geometry.span.start <= offset && offset <= el.geometry.span.end {
            out.push((el.geometry.span.start, el.geometry.span.end));
        }
        out.push(trimmed(a, &el.span));
        out.push(trimmed(a, &p.span));
    } else if let Some(p) = path_at(a, offset) {
        if p.name.span.start <= offset && offset <= p.name.span.end {
            out.push((p.name.span.start, p.name.span.end));
        }
        out.push(trimmed(a, &p.span));
    }
    out.push((0, a.src.len()));
    // nested and growing only (a range equal to its inner one is dropped)
    out.dedup();
    out
}
