//! Document highlight: every use of a path name in the document; on an element, every
//! element of its chain.
//!
//! Document highlight: every use of a name (the header as the definition), or every element of the
//! chain under the cursor.

use crate::common::*;
use crate::navigation::name_token_at;
use crate::provenance::chain_firsts;
use crate::Analysis;

/// A highlighted range; `write` marks the definition (`path NAME`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Highlight {
    pub start: usize,
    pub end: usize,
    pub write: bool,
}

pub fn document_highlights(a: &Analysis, offset: usize) -> Vec<Highlight> {
    if let Some(n) = name_token_at(a, offset) {
        let mut out = Vec::new();
        for p in a.ast.paths() {
            if p.name.value == n.name {
                out.push(Highlight {
                    start: p.name.span.start,
                    end: p.name.span.end,
                    write: true,
                });
            }
            for el in p.elements() {
                for prm in &el.params {
                    if prm.value.strip_prefix('>') == Some(n.name.as_str()) {
                        out.push(Highlight {
                            start: prm.span.start,
                            end: prm.span.end,
                            write: false,
                        });
                    }
                }
            }
        }
        return out;
    }
    chain_elements(a, offset)
}

/// The elements of the chain of the segment at `offset` (just the element when it is not
/// part of a chain).
fn chain_elements(a: &Analysis, offset: usize) -> Vec<Highlight> {
    let Some((_, el)) = element_at(a, offset) else {
        return Vec::new();
    };
    let whole = |start: usize, end: usize| Highlight {
        start,
        end,
        write: false,
    };
    let own = vec![whole(el.kind.span.start, el.geometry.span.end)];
    let Some((path, Some(seg))) = segment_of(a, el) else {
        return own;
    };
    let firsts = chain_firsts(path, &a.traversals);
    let Some(first) = firsts.get(&seg.object) else {
        return own;
    };
    let mut out: Vec<Highlight> = path
        .segments
        .iter()
        .filter(|s| firsts.get(&s.object) == Some(first))
        .filter_map(|s| {
            let start = a.objects.get(s.object).and_then(|o| match &o.origin {
                millpath_core::diag::Origin::Span { start, .. } => Some(*start as usize),
                _ => None,
            })?;
            let (_, e) = element_at(a, start)?;
            Some(whole(e.kind.span.start, e.geometry.span.end))
        })
        .collect();
    out.sort_by_key(|h| h.start);
    out.dedup();
    if out.is_empty() {
        own
    } else {
        out
    }
}
