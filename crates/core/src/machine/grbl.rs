//! GRBL's settings that decide its motion (`[machine]` with `controller = "grbl"`), as
//! settings: the values given and the machine they make. The planner that uses them is
//! `emit/timing/grbl/`.

use super::limits::Axes;

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
