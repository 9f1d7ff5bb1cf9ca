//! The velocity profile: the moves, shortened by their blend arcs, and the arcs between
//! them become pieces, each with a speed cap and an acceleration; a backward pass limits the
//! speed at every join by what the rest can still brake from, a forward pass by what the
//! pieces before can reach, and each piece takes its trapezoid. Linear in the moves.

use super::corners::{join, Join};
use super::segments::{Seg, NORMAL_SHARE};
use super::{trapezoid, Bucket, CYCLE};
use crate::machine::Machine;

/// What is left of a move before a blend arc is taken into the arc when it would take less
/// than this (s): ARC_BLEND_GAP_CYCLES (4) servo cycles.
const GAP_TIME: f64 = 4.0 * CYCLE;

/// Pieces that take less than this (s) ramp their speed evenly instead of a trapezoid
/// (LinuxCNC's ARC_BLEND_RAMP_FREQ, 100 Hz).
const RAMP_TIME: f64 = 0.01;

struct Piece {
    item: usize,
    bucket: Bucket,
    len: f64,
    cap: f64,
    acc: f64,
    /// May ramp (a cut that ends tangent into the next piece).
    ramp: bool,
}

/// Each move's tangential acceleration and speed cap, given how it is joined at both ends.
fn limits(s: &Seg, before: Option<&Join>, after: Option<&Join>) -> (f64, f64) {
    let reduce = |j: Option<&Join>| match j {
        Some(Join::Tangent { reduce, .. }) => *reduce,
        _ => 0.0,
    };
    let mut acc = s.acc * (1.0 - reduce(before).max(reduce(after)));
    // a parabolic blend on either side, and the last move of all (the planner keeps its
    // blend condition with nothing to blend into), halve it
    if matches!(after, None | Some(Join::Parabolic { .. }))
        || matches!(before, Some(Join::Parabolic { .. }))
    {
        acc *= 0.5;
    }
    if !s.circular {
        return (acc, s.cap());
    }
    // the last move is never finalised: an arc keeps the tangential half it starts with
    if after.is_none() {
        return (acc * 0.5, s.cap());
    }
    // arcs: the speed within the sideways share, and the tangential acceleration what is
    // left of `acc` at the arc's top speed (tc.c `pmCircleActualMaxVel`)
    let cutoff = (NORMAL_SHARE * acc * s.r_eff).sqrt();
    let sideways = s.vmax * s.vmax / s.r_eff;
    if sideways > NORMAL_SHARE * acc {
        (acc * 0.5, s.req.min(cutoff))
    } else {
        let share = (1.0 - (sideways / acc).powi(2)).max(0.0).sqrt();
        (acc * share, s.cap())
    }
}

/// The time of each piece with its item and statistics line, in program order.
pub(super) fn times(segs: &[Seg], m: &Machine) -> Vec<(usize, Bucket, f64)> {
    let n = segs.len();
    // joins[k]: between segs[k] and segs[k + 1]
    let mut joins = Vec::with_capacity(n.saturating_sub(1));
    let mut trim_start = 0.0;
    for k in 1..n {
        let j = join(&segs[k - 1], segs[k - 1].len - trim_start, &segs[k], m);
        trim_start = match j {
            Join::Arc { trim, .. } => trim,
            _ => 0.0,
        };
        joins.push(j);
    }
    // pieces and the highest speed at the start of each (limit[i]: into piece i)
    let mut pieces: Vec<Piece> = Vec::with_capacity(2 * n);
    let mut limit: Vec<f64> = Vec::with_capacity(2 * n + 1);
    let mut into: f64 = 0.0;
    for (k, s) in segs.iter().enumerate() {
        let before = k.checked_sub(1).map(|i| &joins[i]);
        let after = joins.get(k);
        let trim = |j: Option<&Join>| match j {
            Some(Join::Arc { trim, .. }) => *trim,
            _ => 0.0,
        };
        let (acc, cap) = limits(s, before, after);
        let mut len = s.len - trim(before) - trim(after);
        // a short rest of a line goes into the blend arc after it (blendCheckConsume)
        let mut consumed = 0.0;
        if let Some(Join::Arc { plan, .. }) = after {
            if !s.circular && len < plan * GAP_TIME {
                consumed = len.max(0.0);
                len = 0.0;
            }
        }
        if len > 1e-9 {
            let cap = cap.min(len / (CYCLE * 1.02));
            pieces.push(Piece {
                item: s.item,
                bucket: s.bucket,
                len,
                cap,
                acc,
                ramp: !s.rapid && matches!(after, Some(Join::Tangent { .. } | Join::Arc { .. })),
            });
            limit.push(into.min(cap));
            into = cap;
        }
        into = match after {
            None | Some(Join::Stop) => 0.0,
            Some(Join::Tangent { kink_vel, .. }) => into.min(*kink_vel),
            Some(Join::Parabolic { v }) => into.min(*v),
            Some(Join::Arc { len, cap, acc, .. }) => {
                let len = len + consumed;
                let cap = cap.min(len / (CYCLE * 1.02));
                pieces.push(Piece {
                    item: s.item,
                    bucket: s.bucket,
                    len,
                    cap,
                    acc: *acc,
                    ramp: !s.rapid,
                });
                limit.push(into.min(cap));
                cap
            }
        };
    }
    limit.push(0.0);
    // backward: the highest entry speed that can still brake to every later limit
    let p = pieces.len();
    let mut w = limit;
    for i in (0..p).rev() {
        let brake = (w[i + 1] * w[i + 1] + 2.0 * pieces[i].acc * pieces[i].len).sqrt();
        w[i] = w[i].min(brake);
    }
    // forward: what the pieces reach, and each one's time
    let mut entry = 0.0;
    let mut out = Vec::with_capacity(p);
    for (i, pc) in pieces.iter().enumerate() {
        let exit = w[i + 1].min((entry * entry + 2.0 * pc.acc * pc.len).sqrt());
        let ramp = 2.0 * pc.len / (entry + exit.min(pc.cap));
        let t = if pc.ramp && exit > 0.0 && ramp < RAMP_TIME {
            ramp
        } else {
            trapezoid(pc.len, pc.cap, pc.acc, entry, exit)
        };
        out.push((pc.item, pc.bucket, t));
        entry = exit;
    }
    out
}
