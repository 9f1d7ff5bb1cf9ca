//! Time estimates that know the machine: a trapezoidal velocity profile per move with
//! look-ahead blending at corners, after LinuxCNC's trajectory planner. Used by the
//! statistics when machine limits are set (`[machine]` in `millpath.toml`); without them
//! the statistics keep the reference's model (length / F · 1.4, reference-output.md §14).
//!
//! The model, in mm and seconds:
//!
//! * **Speed of a move** `v`: cuts (G01/G02/G03) at min(F, axis limits), sweeps (G00) at the
//!   axis limits alone. The axis limit along a unit direction `u` is `min_i(V_i / |u_i|)` over
//!   the axes the move uses (a move along X at `V_x`, a 45° move in XY with equal limits at
//!   `√2·V`). Arcs turn through every direction of their plane: `min(V_x, V_y)` for their XY
//!   part (and `V_z / |u_z|` for a helix's climb), and the centripetal limit `v ≤ √(a·R)`.
//! * **Acceleration of a move** `a`: as LinuxCNC, each phase (accelerating, decelerating)
//!   uses half of MAX_ACCELERATION, projected on the move like the speed: `min_i(A_i/2 / |u_i|)`
//!   (arcs: `min(A_x, A_y)/2`).
//! * **One move** of length `L` from entry speed `v0` to exit speed `v1` (both ≤ `v`): the
//!   trapezoid `t = (v−v0)/a + (v−v1)/a + (L − d0 − d1)/v` with `d0 = (v²−v0²)/2a`,
//!   `d1 = (v²−v1²)/2a` when `d0 + d1 ≤ L`; else a triangle with the peak
//!   `vp = √((2aL + v0² + v1²)/2)`, `t = (vp−v0)/a + (vp−v1)/a`. From and to rest this is
//!   `L/v + v/a` when `L ≥ v²/a` (the seed's critical distance `d = F²/A`), else `2·√(L/a)`.
//! * **Corners** (G64 P): between two moves of the same mode (sweep/sweep or cut/cut) turning
//!   by the angle `θ`, the planner blends with a circular arc tangent to both moves whose
//!   middle stays within the path tolerance `P` of the programmed corner: with
//!   `c = cos(θ/2)`, `r = P·c/(1−c)`, and the arc's tangent points no farther than half the
//!   shorter move from the corner (`r·tan(θ/2) ≤ L_min/2`). The corner speed is
//!   `min(v_prev, v_next, √(a_n·r))` with `a_n` the smaller acceleration of the two moves.
//!   Straight on (`θ ≈ 0`) it is `min(v_prev, v_next)`: collinear pieces do not slow down; a
//!   reversal, a change between sweep and cut, and the program's start and end are stops.
//! * **Look-ahead** (linear in the number of moves): a backward pass limits the speed at the
//!   start of every move by the corner speed and by what the move can still decelerate to the
//!   next limit (`√(w_next² + 2aL)`); a forward pass limits the exit speed by what the move can
//!   accelerate to (`√(v_entry² + 2aL)`). Each move's time is then its trapezoid.
//!
//! Moves without length take no time and do not break a blend (nor do comments).

use crate::emit::{Item, Kind};
use crate::geom::P3;
use serde::Deserialize;

/// The path tolerance (G64 P, mm) when none is set.
pub const DEFAULT_PATH_TOLERANCE: f64 = 0.05;

/// One value per axis.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axes {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

impl Axes {
    /// The same value on every axis.
    pub fn all(v: f64) -> Axes {
        Axes { x: v, y: v, z: v }
    }
    pub fn values(&self) -> [(&'static str, f64); 3] {
        [("x", self.x), ("y", self.y), ("z", self.z)]
    }
    /// The largest value along the unit direction `u` that keeps every axis within its own:
    /// `min_i(self_i / |u_i|)`.
    fn along(&self, u: [f64; 3]) -> f64 {
        [self.x, self.y, self.z]
            .iter()
            .zip(u)
            .filter(|(_, c)| c.abs() > 1e-12)
            .map(|(l, c)| l / c.abs())
            .fold(f64::INFINITY, f64::min)
    }
}

/// The machine's limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Machine {
    /// Maximum velocity per axis (mm/min); sweeps run at it.
    pub max_velocity: Axes,
    /// MAX_ACCELERATION per axis (mm/s²); each phase of a move uses half of it.
    pub max_acceleration: Axes,
    /// G64 P: how far (mm) a blended corner may leave the programmed path.
    pub path_tolerance: f64,
}

/// Estimated times in seconds, by statistics line.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Times {
    pub mill: f64,
    pub drill: f64,
    pub sweep: f64,
}

#[derive(Clone, Copy)]
enum Bucket {
    Mill,
    Drill,
    Sweep,
}

/// One move as the planner sees it (mm, mm/s, mm/s²).
struct Mv {
    /// Index of the item.
    item: usize,
    bucket: Bucket,
    rapid: bool,
    len: f64,
    /// Target speed.
    v: f64,
    /// Acceleration of one phase.
    a: f64,
    /// Unit tangents at the start and the end.
    u0: [f64; 3],
    u1: [f64; 3],
}

fn unit(d: [f64; 3], len: f64) -> [f64; 3] {
    [d[0] / len, d[1] / len, d[2] / len]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The moves of `items` (starting at `start`) with their speeds and tangents.
fn moves(items: &[Item], start: P3, m: &Machine) -> Vec<Mv> {
    let vmax = Axes {
        x: m.max_velocity.x / 60.0,
        y: m.max_velocity.y / 60.0,
        z: m.max_velocity.z / 60.0,
    };
    let amax = Axes {
        x: m.max_acceleration.x / 2.0,
        y: m.max_acceleration.y / 2.0,
        z: m.max_acceleration.z / 2.0,
    };
    let mut pos = start;
    let mut out = Vec::new();
    for (item, it) in items.iter().enumerate() {
        let (bucket, rapid) = match it.kind {
            Kind::Mill => (Bucket::Mill, false),
            Kind::Drill => (Bucket::Drill, false),
            Kind::HSweep | Kind::VSweep => (Bucket::Sweep, true),
            Kind::Comment => continue,
        };
        let t = it.target;
        let to = P3 {
            x: t.x.unwrap_or(pos.x),
            y: t.y.unwrap_or(pos.y),
            z: t.z.unwrap_or(pos.z),
        };
        let d = [to.x - pos.x, to.y - pos.y, to.z - pos.z];
        let mv = match t.arc {
            None => {
                let len = dot(d, d).sqrt();
                let u = unit(d, len);
                Mv {
                    item,
                    bucket,
                    rapid,
                    len,
                    v: vmax.along(u),
                    a: amax.along(u),
                    u0: u,
                    u1: u,
                }
            }
            Some((c, ccw)) => {
                // the recorded length of an arc is r·sweep in XY; a helix climbs d[2] on it
                let (rx0, ry0) = (pos.x - c.x, pos.y - c.y);
                let (rx1, ry1) = (to.x - c.x, to.y - c.y);
                let r = (rx0 * rx0 + ry0 * ry0).sqrt();
                let len = (it.len * it.len + d[2] * d[2]).sqrt();
                let (h, uz) = (it.len / len, d[2] / len);
                let s = if ccw { 1.0 } else { -1.0 };
                let tangent = |rx: f64, ry: f64| {
                    let rr = (rx * rx + ry * ry).sqrt();
                    [-s * ry / rr * h, s * rx / rr * h, uz]
                };
                let plane = |l: &Axes| l.x.min(l.y) / h;
                let climb = |l: &Axes| {
                    if uz.abs() > 1e-12 {
                        l.z / uz.abs()
                    } else {
                        f64::INFINITY
                    }
                };
                let a = plane(&amax).min(climb(&amax));
                let centripetal = (amax.x.min(amax.y) * r).sqrt();
                Mv {
                    item,
                    bucket,
                    rapid,
                    len,
                    v: plane(&vmax).min(climb(&vmax)).min(centripetal),
                    a,
                    u0: tangent(rx0, ry0),
                    u1: tangent(rx1, ry1),
                }
            }
        };
        pos = to;
        let v = if rapid {
            mv.v
        } else {
            mv.v.min(it.feed / 60.0)
        };
        // no length (or a degenerate speed): no time, no corner
        if mv.len > 1e-9 && v > 0.0 && v.is_finite() && mv.a > 0.0 && mv.a.is_finite() {
            out.push(Mv { v, ..mv });
        }
    }
    out
}

/// The highest speed at the corner from `p` into `n` (see the module comment).
fn corner(p: &Mv, n: &Mv, tolerance: f64) -> f64 {
    if p.rapid != n.rapid {
        return 0.0;
    }
    let cos = dot(p.u1, n.u0).clamp(-1.0, 1.0);
    // half the turning angle θ: c = cos(θ/2), s = sin(θ/2)
    let c = ((1.0 + cos) / 2.0).sqrt();
    let s = ((1.0 - cos) / 2.0).sqrt();
    let vmax = p.v.min(n.v);
    if s < 1e-9 {
        return vmax;
    }
    if c < 1e-9 {
        return 0.0;
    }
    // r = P·c/(1−c), with 1−c = s²/(1+c) for precision at small angles
    let r_tolerance = tolerance * c * (1.0 + c) / (s * s);
    let r_length = 0.5 * p.len.min(n.len) * c / s;
    let r = r_tolerance.min(r_length);
    vmax.min((p.a.min(n.a) * r).sqrt())
}

/// Time of a move of length `l` at target speed `v` and acceleration `a`, entered at `v0`
/// and left at `v1`.
pub fn trapezoid(l: f64, v: f64, a: f64, v0: f64, v1: f64) -> f64 {
    let d0 = (v * v - v0 * v0) / (2.0 * a);
    let d1 = (v * v - v1 * v1) / (2.0 * a);
    if d0 + d1 <= l {
        (v - v0) / a + (v - v1) / a + (l - d0 - d1) / v
    } else {
        let vp = ((2.0 * a * l + v0 * v0 + v1 * v1) / 2.0)
            .sqrt()
            .max(v0.max(v1));
        (vp - v0) / a + (vp - v1) / a
    }
}

/// The estimated times of a program's items, the tool starting at rest at `start`.
pub fn plan(items: &[Item], start: P3, m: &Machine) -> Times {
    let mut times = Times::default();
    for (_, bucket, t) in planned(items, start, m) {
        match bucket {
            Bucket::Mill => times.mill += t,
            Bucket::Drill => times.drill += t,
            Bucket::Sweep => times.sweep += t,
        }
    }
    times
}

/// The estimated time (seconds) of every item, the tool starting at rest at `start`
/// (comments and moves without length: 0).
pub fn item_times(items: &[Item], start: P3, m: &Machine) -> Vec<f64> {
    let mut out = vec![0.0; items.len()];
    for (item, _, t) in planned(items, start, m) {
        out[item] = t;
    }
    out
}

/// The time of each planned move with its item and statistics line, in program order.
fn planned(items: &[Item], start: P3, m: &Machine) -> Vec<(usize, Bucket, f64)> {
    let mv = moves(items, start, m);
    let n = mv.len();
    // w[k]: the highest speed at the start of move k (w[n]: the end of the program, at rest)
    let mut w = vec![0.0; n + 1];
    for k in (0..n).rev() {
        let reach = (w[k + 1] * w[k + 1] + 2.0 * mv[k].a * mv[k].len).sqrt();
        let corner = if k == 0 {
            0.0
        } else {
            corner(&mv[k - 1], &mv[k], m.path_tolerance)
        };
        w[k] = corner.min(reach);
    }
    let mut entry = 0.0;
    let mut out = Vec::with_capacity(n);
    for (k, m) in mv.iter().enumerate() {
        let exit = w[k + 1].min((entry * entry + 2.0 * m.a * m.len).sqrt());
        out.push((m.item, m.bucket, trapezoid(m.len, m.v, m.a, entry, exit)));
        entry = exit;
    }
    out
}
