//! Time estimates for a GRBL controller: the model of GRBL 1.1's planner (planner.c,
//! motion_control.c), held within 2 % of GRBL's own firmware run on its simulator by
//! `tests/grbl_oracle.sh` and the test `grbl_oracle`. In mm and seconds.
//!
//! * **Blocks** (`blocks.rs`): arcs become chords by the arc tolerance `$12`, end points are
//!   rounded to whole steps; a block's top speed and acceleration are the axis limits
//!   (`$110–$112`, `$120–$122`) along it, its speed the feed (a rapid: that top speed).
//! * **Planner** (`planner.rs`): the junction speed from the junction deviation `$11`; the
//!   buffer's look-ahead of 14 blocks behind the running one; a trapezoid per block.
//!
//! GRBL does not stop between rapids and cuts: the moves flow on unless a junction reverses.

mod blocks;
mod planner;

pub use planner::BUFFER_BLOCKS;

use super::{Axes, Bucket};
use crate::emit::Item;
use crate::geom::P3;

/// GRBL's settings that decide its motion, with their `$` numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grbl {
    /// `$110–$112`: maximum rate per axis (mm/min); rapids run at it.
    pub max_rate: Axes,
    /// `$120–$122`: acceleration per axis (mm/s²).
    pub acceleration: Axes,
    /// `$11`: junction deviation (mm).
    pub junction_deviation: f64,
    /// `$12`: arc tolerance (mm): arcs are cut into chords within it.
    pub arc_tolerance: f64,
    /// `$100–$102`: steps per mm (end points are rounded to whole steps).
    pub steps_per_mm: Axes,
}

impl Default for Grbl {
    /// GRBL 1.1h's defaults (defaults.h, DEFAULTS_GENERIC).
    fn default() -> Self {
        Grbl {
            max_rate: Axes::all(500.0),
            acceleration: Axes::all(10.0),
            junction_deviation: 0.01,
            arc_tolerance: 0.002,
            steps_per_mm: Axes::all(250.0),
        }
    }
}

/// The time of the planned blocks of each item with the item and statistics line, in program order, the
/// tool starting at rest at `start`; `feed_override` is the operator's factor on the feeds
/// (1: none).
pub(super) fn planned(
    items: &[Item],
    start: P3,
    g: &Grbl,
    feed_override: f64,
) -> Vec<(usize, Bucket, f64)> {
    let mut planner = planner::Planner::new(g);
    blocks::blocks(items, start, g, feed_override, |b| planner.push(b));
    planner.finish()
}

/// GRBL settings as given (`[machine]` in millpath.toml); what is not given is GRBL's
/// default, or the generic `max_velocity`/`max_acceleration`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct GrblValues {
    /// `$110–$112` (mm/min).
    pub max_rate: [Option<f64>; 3],
    /// `$120–$122` (mm/s²).
    pub acceleration: [Option<f64>; 3],
    /// `$11` (mm).
    pub junction_deviation: Option<f64>,
    /// `$12` (mm).
    pub arc_tolerance: Option<f64>,
    /// `$100–$102`.
    pub steps_per_mm: [Option<f64>; 3],
}

impl GrblValues {
    /// The given values with their names, e.g. `x_acceleration ($120)`, for the checks.
    pub fn named(&self) -> Vec<(&'static str, f64)> {
        let mut v = Vec::new();
        let mut axes = |names: [&'static str; 3], values: [Option<f64>; 3]| {
            v.extend(
                names
                    .into_iter()
                    .zip(values)
                    .filter_map(|(n, x)| Some((n, x?))),
            );
        };
        axes(
            [
                "x_max_rate ($110)",
                "y_max_rate ($111)",
                "z_max_rate ($112)",
            ],
            self.max_rate,
        );
        axes(
            [
                "x_acceleration ($120)",
                "y_acceleration ($121)",
                "z_acceleration ($122)",
            ],
            self.acceleration,
        );
        axes(
            [
                "x_steps_per_mm ($100)",
                "y_steps_per_mm ($101)",
                "z_steps_per_mm ($102)",
            ],
            self.steps_per_mm,
        );
        v.extend(
            self.junction_deviation
                .map(|x| ("junction_deviation ($11)", x)),
        );
        v.extend(self.arc_tolerance.map(|x| ("arc_tolerance ($12)", x)));
        v
    }

    pub fn any(&self) -> bool {
        !self.named().is_empty()
    }

    /// The machine: the given values, else `rate`/`acc` (the generic limits), else GRBL's
    /// defaults.
    pub fn machine(&self, rate: Option<Axes>, acc: Option<Axes>) -> Grbl {
        let d = Grbl::default();
        let axes = |given: [Option<f64>; 3], generic: Option<Axes>, default: Axes| {
            let generic = generic.unwrap_or(default);
            Axes {
                x: given[0].unwrap_or(generic.x),
                y: given[1].unwrap_or(generic.y),
                z: given[2].unwrap_or(generic.z),
            }
        };
        Grbl {
            max_rate: axes(self.max_rate, rate, d.max_rate),
            acceleration: axes(self.acceleration, acc, d.acceleration),
            junction_deviation: self.junction_deviation.unwrap_or(d.junction_deviation),
            arc_tolerance: self.arc_tolerance.unwrap_or(d.arc_tolerance),
            steps_per_mm: axes(self.steps_per_mm, None, d.steps_per_mm),
        }
    }
}
