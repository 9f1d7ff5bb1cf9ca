//! The walk of reference-input.md §5.2: the traversal order of a path's segments with turn
//! markers, and the ties storage order broke (`order_choice.rs` warns about them).

use crate::args;
use crate::build::candidates::{canonical_duplicate, rivals};
use crate::build::eval::with_pos;
use crate::diag::{Diags, Msg};
use crate::front::drawing::{RawPath, RawSegment, SegKind, Shape, SweepKind};
use crate::geom::P2;
use std::collections::HashMap;

/// The walk's preference of a candidate (§5.2 step 3): order, kind, chord; the lowest wins.
pub type Key = (f64, u8, f64);

/// A choice the storage (= drawing) order made: at `at`, step `step` took segment `chosen`
/// although `rivals` were just as good and would give another result. `lost_to`: the
/// weakest winner `chosen` lost to at earlier steps, if it was a candidate there.
#[derive(Debug, Clone, PartialEq)]
pub struct Tie {
    pub step: usize,
    pub chosen: usize,
    pub rivals: Vec<usize>,
    pub at: P2,
    pub lost_to: Option<Key>,
}

/// The walk of §5.2: the steps, and the ties that storage order broke.
pub fn walk(raw: &RawPath, start: P2, end: P2, diags: &mut Diags) -> (Vec<Step>, Vec<Tie>) {
    walk_with(raw, start, end, diags, None)
}

/// [`walk`]; `contested` notes every segment that was one of several candidates at a step
/// (the only ones whose texts the walk compares).
pub(crate) fn walk_with(
    raw: &RawPath,
    start: P2,
    end: P2,
    diags: &mut Diags,
    mut contested: Option<&mut Vec<usize>>,
) -> (Vec<Step>, Vec<Tie>) {
    let segs = &raw.segments;
    let mut ties: Vec<Tie> = Vec::new();
    let mut lost_to: Vec<Option<Key>> = vec![None; segs.len()];
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
                    // nothing walked: the walk ends where it starts
                    || raw.start_origin(),
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
        let key = |i: usize| -> Key {
            let s = &segs[i];
            (
                s.order(),
                s.kind.preference(),
                s.shape.start().dist(s.shape.end()),
            )
        };
        let mut best = *cands
            .iter()
            .min_by(|&&a, &&b| {
                key(a)
                    .partial_cmp(&key(b))
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .unwrap_or(&cands[0]);
        if cands.len() > 1 {
            if let Some(c) = contested.as_deref_mut() {
                c.extend_from_slice(&cands);
            }
            best = canonical_duplicate(segs, &cands, best, p, key);
            let rivals = rivals(segs, &cands, best, p, key);
            if !rivals.is_empty() {
                ties.push(Tie {
                    step: out.len(),
                    chosen: best,
                    rivals,
                    at: p,
                    lost_to: lost_to[best],
                });
            }
            let won = key(best);
            for &c in cands.iter().filter(|&&c| c != best) {
                let weaker = match lost_to[c] {
                    Some(w) => won > w,
                    None => true,
                };
                if weaker {
                    lost_to[c] = Some(won);
                }
            }
        }
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
    (out, ties)
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
