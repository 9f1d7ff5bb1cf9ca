//! How LinuxCNC's planner joins two moves (tp.c `tpHandleBlendArc`, blendmath.c): a stop,
//! a nearly tangent join taken at a limited speed, a circular blend arc within the path
//! tolerance, or the older parabolic blend, whichever it judges fastest.

use super::segments::{dot, Seg, NORMAL_SHARE};
use super::CYCLE;
use crate::machine::Machine;
use std::f64::consts::PI;

/// A join of two moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Join {
    /// The tool stops (a change between sweep and cut, a reversal).
    Stop,
    /// Nearly tangent: no blend; the speed at the join is at most `kink_vel`, and both moves
    /// accelerate with `1 − reduce` of their limit.
    Tangent { kink_vel: f64, reduce: f64 },
    /// A blend arc of length `len` replacing `trim` of both moves, run at most at `cap` and
    /// accelerating along the arc with `acc`; planned for the speed `plan`.
    Arc {
        trim: f64,
        len: f64,
        cap: f64,
        acc: f64,
        plan: f64,
    },
    /// A parabolic blend: both moves accelerate with half their limit; the corner at `v`.
    Parabolic { v: f64 },
}

/// Reversals closer than 2° stop (tp.c SHARP_CORNER_DEG).
const SHARP: f64 = (2.0 * PI / 180.0) * (2.0 * PI / 180.0);
/// The share of the axis acceleration a kink may take before a blend is preferred
/// (ARC_BLEND_KINK_RATIO).
const KINK_RATIO: f64 = 0.1;
/// A blend may use at most this share of a move (BLEND_DIST_FRACTION).
const BLEND_SHARE: f64 = 0.5;

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The largest value of the per-axis `bounds` any direction in the plane with the unit
/// normal `n` may use (blendmath.c `calculateInscribedDiameter`).
fn in_plane(n: [f64; 3], bounds: [f64; 3]) -> f64 {
    (0..3)
        .map(|i| {
            // the axis' unit vector projected on the plane
            let mut p = [-n[0] * n[i], -n[1] * n[i], -n[2] * n[i]];
            p[i] += 1.0;
            p[i] = p[i].abs().max(1e-12);
            bounds[i] / dot(p, p).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

/// How the planner joins `prev` (of which `prev_left` is left after its own start's blend)
/// and `next`.
pub(super) fn join(prev: &Seg, prev_left: f64, next: &Seg, m: &Machine) -> Join {
    if prev.rapid != next.rapid {
        return Join::Stop;
    }
    let (u1, u2) = (prev.u1, next.u0);
    let sum = [u1[0] + u2[0], u1[1] + u2[1], u1[2] + u2[2]];
    if dot(sum, sum) < SHARP {
        return Join::Stop;
    }
    let acc = [
        m.max_acceleration.x,
        m.max_acceleration.y,
        m.max_acceleration.z,
    ];
    // the kink: the acceleration a sudden turn at full speed asks of the axes in one cycle
    let v_max = prev.cap().min(next.cap());
    let a_inst = v_max / CYCLE + next.acc;
    let diff = sub(u2, u1);
    let mut scale = (0..3)
        .map(|i| (a_inst * diff[i]).abs() / acc[i])
        .fold(0.0, f64::max);
    if prev.circular || next.circular {
        scale /= 0.5;
    }
    if scale < KINK_RATIO {
        return Join::Tangent {
            kink_vel: v_max,
            reduce: scale,
        };
    }
    let kink_vel = v_max * KINK_RATIO / scale;
    let arc = blend_arc(prev, prev_left, next, m, acc);
    let (parabolic, v_blend) = parabolic_speed(prev, next, m.path_tolerance);
    // the planner takes the fastest: the parabolic blend counts half (it halves the
    // acceleration of both moves), ties go to the earlier kind
    let arc_speed = arc.map_or(0.0, |a| match a {
        Join::Arc { cap, .. } => cap,
        _ => 0.0,
    });
    let perf = [parabolic / 2.0, kink_vel, arc_speed];
    let best = (0..3).fold(0, |b, i| if perf[i] > perf[b] { i } else { b });
    match best {
        0 => Join::Parabolic { v: v_blend },
        1 => Join::Tangent {
            kink_vel,
            reduce: KINK_RATIO,
        },
        _ => arc.unwrap_or(Join::Stop),
    }
}

/// The blend arc (blendmath.c `blendInit3FromLineLine`, `blendComputeParameters`). With
/// an arc the planner blends only in the arc's own plane (a helix or a line leaving the plane
/// gets none), and at most over a third of the arc; the arc's curvature is left out.
fn blend_arc(prev: &Seg, prev_left: f64, next: &Seg, m: &Machine, acc: [f64; 3]) -> Option<Join> {
    let (u1, u2) = (prev.u1, next.u0);
    let b = cross(u1, u2);
    let bl = dot(b, b).sqrt();
    if bl < 1e-9 {
        return None;
    }
    let normal = [b[0] / bl, b[1] / bl, b[2] / bl];
    // the arcs are in XY: the blend's plane must be theirs (pmUnitCartsColinear)
    if (prev.circular || next.circular) && normal[0].hypot(normal[1]) > 1e-6 {
        return None;
    }
    let share = |s: &Seg| if s.circular { 1.0 / 3.0 } else { BLEND_SHARE };
    // θ: half the angle between the moves (π/2 straight on), φ: the turn
    let theta = (-dot(u1, u2)).clamp(-1.0, 1.0).acos() / 2.0;
    let phi = PI - 2.0 * theta;
    let tolerance = m.path_tolerance.min(prev.len * 0.25).min(next.len * 0.25);
    let a_max = in_plane(normal, acc);
    let a_n = a_max * NORMAL_SHARE;
    let vel = [
        m.max_velocity.x / 60.0,
        m.max_velocity.y / 60.0,
        m.max_velocity.z / 60.0,
    ];
    let v_req = prev.cap().max(next.cap());
    // the fastest the blend may go: within the plane's speed, or (two lines) the
    // triangle's altitude of both moves' limits
    let phi_eff = phi.min(PI * 0.49);
    let v1 = prev.vmax.min(next.vmax / phi_eff.cos());
    let v2 = next.vmax.min(prev.vmax / phi_eff.cos());
    let base = sub(
        [u2[0] * v2, u2[1] * v2, u2[2] * v2],
        [u1[0] * v1, u1[1] * v1, u1[2] * v1],
    );
    let base = dot(base, base).sqrt();
    let alt = if prev.circular || next.circular || base <= 0.0 {
        0.0
    } else {
        v1 * v2 * phi.sin() / base
    };
    let v_goal = v_req.min(alt.max(in_plane(normal, vel)));
    let l1 = prev_left.min(prev.len * share(prev));
    let l2 = next.len * share(next);
    let h_tol = tolerance / (1.0 - theta.sin());
    let d_tol = theta.cos() * h_tol;
    let d_geom = l1.min(l2).min(d_tol);
    let r_geom = theta.tan() * d_geom;
    let v_plan = (a_n * r_geom).sqrt().min(v_goal);
    // a short blend: as large as a parabolic blend of the same speed would be
    let a_par = a_max * 0.5;
    let v_triangle = (2.0 * a_par * d_geom).sqrt();
    let s_blend = v_triangle.min(v_plan) / a_par * v_plan;
    let r_blend = (s_blend / phi).min(r_geom);
    let r_plan = (v_plan * v_plan / a_n).max(r_blend);
    let len = r_plan * phi;
    if !(r_plan >= 1e-12 && len >= 1e-6 && len.is_finite()) {
        return None;
    }
    Some(Join::Arc {
        trim: r_plan / theta.tan(),
        len,
        cap: v_plan.min(v_req).min(len / CYCLE),
        acc: a_max * 0.5,
        plan: v_plan,
    })
}

/// A parabolic blend (tp.c `tpComputeBlendVelocity`): its net speed along the corner (how
/// the planner rates it) and the speed the moves hand over at; neither move has its final
/// length yet, so only half of each counts.
fn parabolic_speed(prev: &Seg, next: &Seg, tolerance: f64) -> (f64, f64) {
    let a1 = prev.acc * 0.5 * if prev.circular { 0.5 } else { 1.0 };
    let a2 = next.acc * if next.circular { 0.5 } else { 1.0 };
    let reach1 = (a1 * prev.len / 2.0).sqrt().min(prev.cap());
    let reach2 = (a2 * next.len / 2.0).sqrt().min(next.cap());
    let t_reach = (prev.len / reach1).min(next.len / reach2);
    let t_blend = t_reach.min((reach1 / a1).max(reach2 / a2));
    let mut vb1 = reach1.min(t_blend * a1);
    let mut vb2 = reach2.min(t_blend * a2);
    let theta = (-dot(prev.u1, next.u0)).clamp(-1.0, 1.0).acos() / 2.0;
    let c = theta.cos();
    if tolerance > 0.0 && c > (PI / 2.0 - 1e-3).cos() {
        let v = 2.0 * (a1 * tolerance / c).sqrt();
        vb1 = vb1.min(v);
        vb2 = vb2.min(v);
    }
    let sane = |v: f64| if v.is_finite() { v.max(0.0) } else { 0.0 };
    (sane(theta.sin() * (vb1 + vb2) / 2.0), sane(vb1.min(vb2)))
}
