//! Traversal order of a path's segments (reference-input.md §5.2) with turn markers.

use crate::args;
use crate::build::with_pos;
use crate::diag::{Diags, Msg};
use crate::front::drawing::{RawPath, RawSegment, SegKind, Shape, SweepKind};
use crate::geom::P2;
use std::collections::HashMap;

/// Traversal order of a path's segments (§5.2), with turn markers (seed manual §4.2.15).
pub fn traverse(raw: &RawPath, start: P2, end: P2, diags: &mut Diags) -> Vec<Step> {
    let segs = &raw.segments;
    let mut taken = vec![false; segs.len()];
    let mut out: Vec<Step> = Vec::new();
    let mut trail: Vec<usize> = Vec::new();
    let mut p = start;
    let at = |s: &RawSegment, p: P2| -> bool {
        match &s.shape {
            Shape::Circle { c, .. } => c.near(p),
            sh => sh.start().near(p) || sh.end().near(p),
        }
    };
    let is_turn = |p: P2| raw.turns.iter().any(|m| m.pos.near(p));
    // end points on a grid much coarser than the point tolerance: a point's candidates are
    // in its cell or a neighbour cell (keeps the walk linear on large paths)
    const CELL: f64 = 1e-3;
    let cell = |p: P2| ((p.x / CELL).floor() as i64, (p.y / CELL).floor() as i64);
    let mut grid: HashMap<(i64, i64), Vec<usize>, foldhash::fast::RandomState> = HashMap::default();
    for (i, s) in segs.iter().enumerate() {
        let (a, b) = (s.shape.start(), s.shape.end());
        grid.entry(cell(a)).or_default().push(i);
        if cell(b) != cell(a) {
            grid.entry(cell(b)).or_default().push(i);
        }
    }
    let candidates = |taken: &[bool], p: P2| -> Vec<usize> {
        let (cx, cy) = cell(p);
        let mut v: Vec<usize> = Vec::new();
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(list) = grid.get(&(cx.saturating_add(dx), cy.saturating_add(dy))) {
                    v.extend(
                        list.iter()
                            .copied()
                            .filter(|&i| !taken[i] && at(&segs[i], p)),
                    );
                }
            }
        }
        v.sort_unstable();
        v.dedup();
        v
    };
    let mut untaken = segs.len();
    loop {
        let remaining = untaken > 0;
        let cands = candidates(&taken, p);
        if cands.is_empty() {
            let must_return = if remaining { true } else { !p.near(end) };
            if must_return && is_turn(p) && !trail.is_empty() {
                // walk back to the last point where untraversed segments start (or the end)
                while let Some(k) = trail.pop() {
                    let step = out[k];
                    if matches!(segs[step.index].shape, Shape::Circle { .. }) {
                        continue;
                    }
                    out.push(Step {
                        index: step.index,
                        reversed: !step.reversed,
                        turn_back: true,
                    });
                    let sh = &segs[step.index].shape;
                    p = if step.reversed { sh.end() } else { sh.start() };
                    let open = !candidates(&taken, p).is_empty();
                    if open || (!remaining && p.near(end)) {
                        break;
                    }
                }
                continue;
            }
            if !remaining {
                break;
            }
            if p.near(end) {
                let first = (0..segs.len()).find(|&i| !taken[i]).unwrap_or(0);
                let count = taken.iter().filter(|t| !**t).count();
                let o = with_pos(&segs[first].origin, segs[first].shape.start());
                diags.error(Msg::NotReached, o, args![count]);
            } else {
                let o = out.last().map_or_else(
                    || raw.origin(),
                    |s| {
                        let sh = &segs[s.index].shape;
                        with_pos(
                            &segs[s.index].origin,
                            if s.reversed { sh.end() } else { sh.start() },
                        )
                    },
                );
                diags.error(Msg::NoMoreSegments, o, args![p]);
            }
            break;
        }
        let best = *cands
            .iter()
            .min_by(|&&a, &&b| {
                let (sa, sb) = (&segs[a], &segs[b]);
                let ka = (
                    sa.order(),
                    sa.kind.preference(),
                    sa.shape.start().dist(sa.shape.end()),
                );
                let kb = (
                    sb.order(),
                    sb.kind.preference(),
                    sb.shape.start().dist(sb.shape.end()),
                );
                ka.partial_cmp(&kb).unwrap_or(std::cmp::Ordering::Equal)
            })
            .unwrap_or(&cands[0]);
        taken[best] = true;
        untaken -= 1;
        let s = &segs[best];
        let reversed = matches!(s.shape, Shape::Path(_)) && s.shape.end().near(p);
        out.push(Step {
            index: best,
            reversed,
            turn_back: false,
        });
        trail.push(out.len() - 1);
        if let Shape::Path(_) = s.shape {
            p = if reversed {
                s.shape.start()
            } else {
                s.shape.end()
            };
        }
    }
    if let Some(last) = out.last() {
        let sh = &segs[last.index].shape;
        let last_end = if last.reversed { sh.start() } else { sh.end() };
        let last_end = if matches!(sh, Shape::Circle { .. }) {
            sh.start()
        } else {
            last_end
        };
        if !last_end.near(end) {
            let o = raw
                .end
                .as_ref()
                .map_or_else(|| raw.origin(), |m| m.origin.clone());
            diags.error(Msg::EndNotAtLast, o, args![end]);
        }
    }
    out
}

/// A turn-back copy of a segment: sweeps and embeddings return as sweeps, mill and mark
/// segments are milled again.
pub(crate) fn turn_back_kind(kind: SegKind) -> SegKind {
    match kind {
        SegKind::Mill(s) => SegKind::Mill(s),
        _ => SegKind::Sweep(SweepKind::Hidden),
    }
}

/// One step of the traversal: a segment (index into the path's segments), maybe reversed;
/// `turn_back` marks the automatic way back from a turn marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Step {
    pub index: usize,
    pub reversed: bool,
    pub turn_back: bool,
}
