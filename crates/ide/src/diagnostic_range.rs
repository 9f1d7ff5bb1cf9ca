//! Where a compiler diagnostic lands in the document, as a byte range.
//!
//! Where a diagnostic lands: an element's line without its trailing comment, a path's name, a
//! drawing's entity line.

use crate::common::element_at;
use crate::{Analysis, Pos};
use millpath_core::diag::Origin;

/// The byte range a diagnostic points at: an element's line without its trailing comment,
/// a path's name, a drawing entity's whole line; `None` for diagnostics about the file as a
/// whole (shown at its start).
pub fn diagnostic_range(a: &Analysis, origin: &Origin) -> Option<(usize, usize)> {
    match origin {
        Origin::Span { start, end, .. } => {
            let (start, end) = (
                (*start as usize).min(a.src.len()),
                (*end as usize).min(a.src.len()),
            );
            // one line is enough to point at an element
            let mut stop = a.src[start..end].find('\n').map_or(end, |p| start + p);
            if let Some(c) = element_at(a, start)
                .and_then(|(_, el)| el.comment.as_ref())
                .filter(|c| c.span.start > start && c.span.start < stop)
            {
                stop = a.src[..c.span.start].trim_end().len().max(start);
            }
            Some((start, stop))
        }
        Origin::Path { name, .. } => a
            .ast
            .paths()
            .find(|p| *p.name.value == **name)
            .map(|p| (p.name.span.start, p.name.span.end)),
        // a drawing: the entity's DXF line (1-based, as `millpath check` reports it)
        Origin::Entity(e) => Some(line_range(a, e.line)),
        Origin::FileLine { line, .. } => Some(line_range(a, *line)),
        _ => None,
    }
}

/// The whole 1-based line `line` of the document.
fn line_range(a: &Analysis, line: usize) -> (usize, usize) {
    let l = line.saturating_sub(1) as u32;
    let start = a.index.offset(Pos { line: l, col: 0 });
    let end = a.src[start..]
        .find(['\r', '\n'])
        .map_or(a.src.len(), |e| start + e);
    (start, end)
}
