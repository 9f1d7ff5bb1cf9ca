//! A program's moves as LinuxCNC's planner receives them: length, requested speed, the
//! speed and acceleration limits the controller derives from the axis limits (for lines the
//! axis limits projected on the move; for arcs and helixes the in-plane limits, the
//! centripetal cap and the helix's effective radius), and the tangents at both ends.

use super::Bucket;
use crate::emit::Item;
use crate::geom::P3;
use crate::machine::{Axes, Machine};

/// The share of the acceleration an arc may use sideways (LinuxCNC's
/// BLEND_ACC_RATIO_NORMAL: √(1 − 0.5²), the tangential share being 0.5).
pub(super) const NORMAL_SHARE: f64 = 0.866_025_403_784_438_6;

/// One move (mm, mm/s, mm/s²).
#[derive(Debug, Clone, Copy)]
pub(super) struct Seg {
    pub item: usize,
    pub bucket: Bucket,
    pub rapid: bool,
    /// An arc or helix (its tangential acceleration is a share of `acc`).
    pub circular: bool,
    pub len: f64,
    /// The requested speed: the feed (sweeps: the axis limit) within `vmax`.
    pub req: f64,
    /// The speed limit of the axes along the move (arcs: also the centripetal cap).
    pub vmax: f64,
    /// The acceleration limit along the move.
    pub acc: f64,
    /// Arcs: the radius of curvature the planner caps the speed with (the helix's
    /// `r + h²/r`, `h` its climb).
    pub r_eff: f64,
    /// Unit tangents at the start and the end.
    pub u0: [f64; 3],
    pub u1: [f64; 3],
}

impl Seg {
    /// The speed the move runs at when nothing else limits it.
    pub fn cap(&self) -> f64 {
        self.req.min(self.vmax)
    }
}

pub(super) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn per_second(a: &Axes) -> Axes {
    Axes {
        x: a.x / 60.0,
        y: a.y / 60.0,
        z: a.z / 60.0,
    }
}

/// The time the slowest axis needs for the displacement `d` at its own `limit` (LinuxCNC
/// computes the move's speed and acceleration limits as length / this time).
fn axis_time(d: [f64; 3], limit: &Axes) -> f64 {
    [limit.x, limit.y, limit.z]
        .iter()
        .zip(d)
        .filter(|(_, c)| c.abs() > 1e-12)
        .map(|(l, c)| c.abs() / l)
        .fold(0.0, f64::max)
}

/// Moves shorter than this (mm) are not moves: the programs are written to 0.001 mm, so such
/// a move is none in the program (e.g. from a start a hair above the first sweep height).
const MIN_MOVE: f64 = 5e-4;

/// The moves of `items` (starting at `start`); moves without length or with a degenerate
/// speed are left out (they take no time and do not break a blend). `feed_override` scales the
/// feeds of the cuts (not the sweeps) within the axes' limits, as LinuxCNC's override does.
pub(super) fn segments(items: &[Item], start: P3, m: &Machine, feed_override: f64) -> Vec<Seg> {
    let vel = per_second(&m.max_velocity);
    let acc = m.max_acceleration;
    let mut pos = start;
    let mut out = Vec::new();
    for (item, it) in items.iter().enumerate() {
        let Some((bucket, rapid)) = Bucket::of(it.kind) else {
            continue;
        };
        let t = it.target;
        let to = t.end(pos);
        let d = [to.x - pos.x, to.y - pos.y, to.z - pos.z];
        let seg = match t.arc {
            None => line(d, &vel, &acc),
            Some((c, ccw)) => {
                let ends = [[pos.x - c.x, pos.y - c.y], [to.x - c.x, to.y - c.y]];
                arc(it.len, d, ends, ccw, &vel, &acc)
            }
        };
        pos = to;
        let Some(seg) = seg else { continue };
        let req = if rapid {
            seg.vmax
        } else {
            seg.vmax.min(it.feed * feed_override / 60.0)
        };
        let ok = |v: f64| v > 0.0 && v.is_finite();
        if seg.len > MIN_MOVE && ok(req) && ok(seg.vmax) && ok(seg.acc) {
            out.push(Seg {
                item,
                bucket,
                rapid,
                req,
                ..seg
            });
        }
    }
    out
}

fn blank(len: f64, vmax: f64, acc: f64, u0: [f64; 3], u1: [f64; 3]) -> Seg {
    Seg {
        item: 0,
        bucket: Bucket::Mill,
        rapid: false,
        circular: false,
        len,
        req: vmax,
        vmax,
        acc,
        r_eff: f64::INFINITY,
        u0,
        u1,
    }
}

/// A straight move by `d`: speed and acceleration as the slowest axis allows.
fn line(d: [f64; 3], vel: &Axes, acc: &Axes) -> Option<Seg> {
    let len = dot(d, d).sqrt();
    if len <= 1e-9 {
        return None;
    }
    let u = [d[0] / len, d[1] / len, d[2] / len];
    Some(blank(
        len,
        len / axis_time(d, vel),
        len / axis_time(d, acc),
        u,
        u,
    ))
}

/// An arc in XY of recorded length `flat` (r·sweep) climbing `d[2]`, from `r0` (start
/// relative to the centre), as LinuxCNC limits it: in the plane the slower axis and the
/// centripetal cap `√(0.866·a·r)`; the climb by the Z axis; then the speed capped on the
/// effective radius of the helix `r + h²/r` (h: the climb). `ends`: the start and the end
/// relative to the centre.
fn arc(
    flat: f64,
    d: [f64; 3],
    ends: [[f64; 2]; 2],
    ccw: bool,
    vel: &Axes,
    acc: &Axes,
) -> Option<Seg> {
    let [r0, r1] = ends;
    let r = (r0[0] * r0[0] + r0[1] * r0[1]).sqrt();
    let len = (flat * flat + d[2] * d[2]).sqrt();
    if len <= 1e-9 || r <= 1e-9 || flat <= 1e-12 {
        return None;
    }
    let (v_axes, a_axes) = (vel.x.min(vel.y), acc.x.min(acc.y));
    let v_planar = (NORMAL_SHARE * a_axes * r).sqrt().min(v_axes);
    let vmax = len / axis_time(d, vel).max(flat / v_planar);
    let amax = len / axis_time(d, acc).max(flat / a_axes);
    let r_eff = r + d[2] * d[2] / r;
    // the planner's own cap (pmCircleActualMaxVel)
    let vmax = vmax.min((NORMAL_SHARE * amax * r_eff).sqrt());
    let (h, uz) = (flat / len, d[2] / len);
    let s = if ccw { 1.0 } else { -1.0 };
    let tangent = |rx: f64, ry: f64| {
        let rr = (rx * rx + ry * ry).sqrt();
        [-s * ry / rr * h, s * rx / rr * h, uz]
    };
    Some(Seg {
        circular: true,
        r_eff,
        ..blank(
            len,
            vmax,
            amax,
            tangent(r0[0], r0[1]),
            tangent(r1[0], r1[1]),
        )
    })
}
