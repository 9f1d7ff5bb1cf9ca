//! The candidates of one step of the walk (`walk.rs`) that are as good as the best: rivals
//! (another result in a re-saved drawing) and duplicates (the same G-code).

use crate::front::drawing::{RawSegment, Shape};
use crate::geom::{Geom, P2};

fn class(s: &RawSegment) -> u8 {
    match s.shape {
        Shape::Circle { .. } => 0,
        Shape::Path(Geom::Line { .. }) => 1,
        Shape::Path(Geom::Arc { .. }) => 2,
    }
}

/// The segment as the walk takes it at `p` (reversed when it ends there).
fn oriented(s: &RawSegment, p: P2) -> Shape {
    match &s.shape {
        Shape::Path(g) if g.end().near(p) => Shape::Path(g.reversed()),
        sh => sh.clone(),
    }
}

fn tokens(s: &RawSegment) -> &[String] {
    s.text.as_ref().map_or(&[], |t| &t.tokens[..])
}

/// Taking one or the other makes no difference (a duplicate, maybe drawn the other way).
fn alike(a: &RawSegment, b: &RawSegment, p: P2) -> bool {
    a.kind == b.kind && tokens(a) == tokens(b) && oriented(a, p) == oriented(b, p)
}

/// The candidates as good as `best` (same key, same storage class) that are not duplicates
/// of it: any of them could be first in a re-saved drawing.
pub(crate) fn rivals<K: PartialEq>(
    segs: &[RawSegment],
    cands: &[usize],
    best: usize,
    p: P2,
    key: impl Fn(usize) -> K,
) -> Vec<usize> {
    let (b, kb) = (&segs[best], key(best));
    cands
        .iter()
        .copied()
        .filter(|&c| {
            c != best && class(&segs[c]) == class(b) && key(c) == kb && !alike(&segs[c], b, p)
        })
        .collect()
}

/// Among `best` and its duplicates (equally good, alike), the one with the smallest numbers
/// as drawn: which of them is taken changes no G-code, but the text shows it, and this
/// choice does not depend on the drawing's order.
pub(crate) fn canonical_duplicate<K: PartialEq>(
    segs: &[RawSegment],
    cands: &[usize],
    best: usize,
    p: P2,
    key: impl Fn(usize) -> K,
) -> usize {
    let numbers = |s: &RawSegment| match s.shape {
        Shape::Circle { c, r } => [c.x, c.y, r, 0.0, 0.0],
        Shape::Path(Geom::Line { a, b }) => [a.x, a.y, b.x, b.y, 0.0],
        Shape::Path(Geom::Arc { c, r, a0, a1, .. }) => [c.x, c.y, r, a0, a1],
    };
    let (b, kb) = (&segs[best], key(best));
    let mut pick = best;
    for &c in cands {
        let s = &segs[c];
        if c != best && class(s) == class(b) && key(c) == kb && alike(s, b, p) {
            let smaller = numbers(s)
                .iter()
                .zip(numbers(&segs[pick]).iter())
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .is_some_and(|o| o.is_lt());
            if smaller {
                pick = c;
            }
        }
    }
    pick
}
