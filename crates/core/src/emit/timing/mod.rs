//! Time estimates that know the machine. GRBL's planner has its own module (`grbl/`), and
//! `model.rs` chooses between the two (`TimeModel`); the rest of this module is the velocity
//! profile LinuxCNC 2.9's trajectory planner (src/emc/tp: tp.c, tc.c, blendmath.c; the limits
//! from emccanon.cc) gives a program, held within 2 % of the real planner by `tests/planner_oracle.sh` and the test
//! `planner_oracle`. Used by the statistics when machine limits are set (`[machine]` in
//! `millpath.toml`); without them the statistics keep the reference's model (length / F ·
//! 1.4, reference-output.md §14). In mm, seconds, and the servo period of 1 ms.
//!
//! * **Limits of a move** (`segments.rs`): a line runs at min(F, `min_i(V_i/|u_i|)`) and
//!   accelerates with `min_i(A_i/|u_i|)` along its unit direction `u`, the *full* axis
//!   acceleration (sweeps: the axis limits alone). An arc takes the slower in-plane axis,
//!   caps its in-plane speed at `√(0.866·a·r)` and the climb of a helix by Z, and the planner
//!   caps it once more on the helix's effective radius `r + h²/r` (h: the climb).
//! * **Joins** (`corners.rs`): a change between sweep and cut, and a reversal within 2°,
//!   stop. A join whose kink the axes can take in one servo cycle (within 10 % of their
//!   acceleration) is tangent. Otherwise the planner takes the fastest of a circular blend
//!   arc, the kink at a reduced speed, and a parabolic blend: the arc stays within the path
//!   tolerance P (also within a quarter of either move) and uses at most half of the next move
//!   and what is left of the previous; its speed is `√(0.866·a·R)`, its radius then no
//!   larger than that speed needs (or a parabolic blend of the same speed would use), and it
//!   takes the time of its own length, accelerating along it with a/2. A rest of a line shorter
//!   than 4 cycles goes into the arc.
//! * **Profile** (`profile.rs`): the moves, shortened by their arcs, and the arcs are pieces
//!   with a speed cap (also at most their length per cycle) and an acceleration: lines the
//!   full one, arcs what is left of it beside the sideways `v²/R` (a/2 at the cap), halved
//!   next to a parabolic blend and on the last move (the planner keeps its blend condition
//!   with nothing to blend into). A backward pass limits each piece's entry speed by what the
//!   rest can still brake from, a forward pass by what it can reach; each piece takes its
//!   trapezoid, or a constant ramp when it is a cut shorter than 10 ms (100 Hz) that flows
//!   tangentially into the next. Linear in the number of moves, every loop bounded by them.
//!
//! Moves without length take no time and do not break a blend (nor do comments).

mod corners;
pub mod grbl;
mod model;
mod plan;
mod profile;
mod segments;

pub use model::{Planner, TimeModel};
pub use plan::{item_times, plan, Times};

/// LinuxCNC's servo period (s): the planner's time step.
const CYCLE: f64 = 0.001;

#[derive(Debug, Clone, Copy)]
enum Bucket {
    Mill,
    Drill,
    Sweep,
}

impl Bucket {
    /// The statistics line of a move and whether it is a rapid; `None` for a comment.
    fn of(kind: crate::emit::Kind) -> Option<(Bucket, bool)> {
        use crate::emit::Kind;
        match kind {
            Kind::Mill => Some((Bucket::Mill, false)),
            Kind::Drill => Some((Bucket::Drill, false)),
            Kind::HSweep | Kind::VSweep => Some((Bucket::Sweep, true)),
            Kind::Comment => None,
        }
    }
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
