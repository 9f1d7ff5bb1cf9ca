//! Folding ranges: every path block and every run of two or more comment lines.
//!
//! Folding ranges: paths (header to the line before `}`), runs of two or more comment lines.

use crate::Analysis;
use millpath_syntax::{Item, PathItem};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FoldKind {
    Path,
    Comment,
}

/// A foldable range in byte offsets (the lines of `start` and `end` fold).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Fold {
    pub start: usize,
    pub end: usize,
    pub kind: FoldKind,
}

/// Paths from their header to their last line before `}`; comment blocks of two or more
/// consecutive comment lines (at the top level or inside a path).
pub fn folding_ranges(a: &Analysis) -> Vec<Fold> {
    let mut out = Vec::new();
    let mut run: Option<(usize, usize, usize)> = None; // start, end, lines
    let flush = |run: &mut Option<(usize, usize, usize)>, out: &mut Vec<Fold>| {
        if let Some((start, end, n)) = run.take() {
            if n >= 2 {
                out.push(Fold {
                    start,
                    end,
                    kind: FoldKind::Comment,
                });
            }
        }
    };
    let comment = |span: &std::ops::Range<usize>, run: &mut Option<(usize, usize, usize)>| {
        *run = Some(match *run {
            Some((s, _, n)) => (s, span.end, n + 1),
            None => (span.start, span.end, 1),
        });
    };
    for item in &a.ast.items {
        match item {
            Item::Comment(c) => comment(&c.span, &mut run),
            Item::Path(p) => {
                flush(&mut run, &mut out);
                // the closing `}` stays visible
                let body_end = a.src[..p.span.end.min(a.src.len())]
                    .trim_end_matches(|c: char| c == '}' || c.is_whitespace())
                    .len();
                if a.src[p.span.start..body_end.max(p.span.start)].contains('\n') {
                    out.push(Fold {
                        start: p.span.start,
                        end: body_end,
                        kind: FoldKind::Path,
                    });
                }
                for pi in &p.items {
                    match pi {
                        PathItem::Comment(c) => comment(&c.span, &mut run),
                        _ => flush(&mut run, &mut out),
                    }
                }
                flush(&mut run, &mut out);
            }
            _ => flush(&mut run, &mut out),
        }
    }
    flush(&mut run, &mut out);
    out.sort_by_key(|f| f.start);
    out
}
