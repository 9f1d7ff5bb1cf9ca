//! A program's moves as GRBL's planner receives them: arcs cut into chords by the arc
//! tolerance `$12` (as GRBL's arc generator counts them), every end point rounded to whole
//! steps (`$100–$102`), a move without a step dropped, and per block its length, unit
//! direction, top speed and acceleration as the axis limits allow along it.

use super::Grbl;
use crate::emit::timing::Bucket;
use crate::emit::Item;
use crate::geom::P3;
use std::f64::consts::TAU;

/// One planner block (mm, mm/s, mm/s²).
#[derive(Debug, Clone, Copy)]
pub(super) struct Block {
    pub item: usize,
    pub bucket: Bucket,
    pub len: f64,
    pub unit: [f64; 3],
    /// The speed asked for (the feed, or the rapid rate) within the axes' rate.
    pub nominal: f64,
    pub acc: f64,
}

/// GRBL's cap on the chords of one arc (its segment counter is 16 bits wide).
const MAX_CHORDS: f64 = 65_535.0;

/// GRBL's tolerance for an arc that ends where it starts (a full circle, not nothing).
const ANGLE_EPSILON: f64 = 5e-7;

/// The largest value of per-axis `limits` a move along `unit` may use: each axis that moves
/// allows its own limit divided by its share of the move.
pub(super) fn along(limits: [f64; 3], unit: [f64; 3]) -> f64 {
    (0..3)
        .filter(|&i| unit[i] != 0.0)
        .map(|i| (limits[i] / unit[i]).abs())
        .fold(f64::INFINITY, f64::min)
}

/// The chord end points of an arc from `from` to `to` around `centre` (XY), as GRBL's arc
/// generator places them: as many chords as keep the arc tolerance, the climb shared evenly
/// (an arc too short for two chords is one straight move).
fn chords(from: P3, to: P3, centre: (f64, f64), ccw: bool, tol: f64) -> Vec<P3> {
    let r0 = (from.x - centre.0, from.y - centre.1);
    let r1 = (to.x - centre.0, to.y - centre.1);
    let radius = r0.0.hypot(r0.1);
    let mut travel = (r0.0 * r1.1 - r0.1 * r1.0).atan2(r0.0 * r1.0 + r0.1 * r1.1);
    if ccw {
        if travel <= ANGLE_EPSILON {
            travel += TAU;
        }
    } else if travel >= -ANGLE_EPSILON {
        travel -= TAU;
    }
    let per = (tol * (2.0 * radius - tol)).sqrt();
    let n = (0.5 * travel * radius).abs() / per;
    let n = if n.is_finite() {
        n.floor().min(MAX_CHORDS)
    } else {
        0.0
    };
    if n < 1.0 {
        return vec![to];
    }
    let count = n as usize;
    let a0 = r0.1.atan2(r0.0);
    let mut out: Vec<P3> = (1..count)
        .map(|i| {
            let f = i as f64 / n;
            let a = a0 + travel * f;
            P3 {
                x: centre.0 + radius * a.cos(),
                y: centre.1 + radius * a.sin(),
                z: from.z + (to.z - from.z) * f,
            }
        })
        .collect();
    out.push(to);
    out
}

/// Hands the planner blocks of `items` to `each` in order (one at a time: a program's arcs
/// may be millions of chords), the tool starting at `start`; `feed_override` scales the feeds
/// (not the rapids), as GRBL's override does.
pub(super) fn blocks(
    items: &[Item],
    start: P3,
    g: &Grbl,
    feed_override: f64,
    mut each: impl FnMut(Block),
) {
    let spm = [g.steps_per_mm.x, g.steps_per_mm.y, g.steps_per_mm.z];
    let rate = [
        g.max_rate.x / 60.0,
        g.max_rate.y / 60.0,
        g.max_rate.z / 60.0,
    ];
    let acc = [g.acceleration.x, g.acceleration.y, g.acceleration.z];
    let steps = |p: P3| [p.x * spm[0], p.y * spm[1], p.z * spm[2]].map(f64::round);
    let mut at = steps(start);
    let mut pos = start;
    for (item, it) in items.iter().enumerate() {
        let Some((bucket, rapid)) = Bucket::of(it.kind) else {
            continue;
        };
        let t = it.target;
        let to = t.end(pos);
        let points = match t.arc {
            Some((c, ccw)) => chords(pos, to, (c.x, c.y), ccw, g.arc_tolerance),
            None => vec![to],
        };
        pos = to;
        for p in points {
            let next = steps(p);
            let d: [f64; 3] = std::array::from_fn(|i| (next[i] - at[i]) / spm[i]);
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if !(len > 0.0 && len.is_finite()) {
                continue;
            }
            at = next;
            let unit = [d[0] / len, d[1] / len, d[2] / len];
            let top = along(rate, unit);
            let asked = if rapid {
                top
            } else {
                // GRBL's floor for a feed: 1 mm/min
                (it.feed * feed_override).max(1.0) / 60.0
            };
            each(Block {
                item,
                bucket,
                len,
                unit,
                nominal: asked.min(top),
                acc: along(acc, unit),
            });
        }
    }
}
