//! Which planner times a program: LinuxCNC's (`Machine`) or GRBL's (`Grbl`), chosen by the
//! controller of `[machine]` (or the dialect), and the statistics line that names it. The
//! planners themselves are `emit/timing/` (LinuxCNC) and `emit/timing/grbl/`.

use super::grbl::Grbl;
use super::limits::{Axes, Machine};
use crate::diag::Lang;
use crate::params::fmt_num;

/// The planner that times the programs (`controller` in `[machine]`; by default the
/// dialect's: GRBL's for `grbl`, LinuxCNC's otherwise).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
pub enum Planner {
    #[serde(rename = "linuxcnc")]
    LinuxCnc,
    #[serde(rename = "grbl")]
    Grbl,
}

/// The operator's feed override (percent) the estimates assume when none is given.
pub const NO_FEED_OVERRIDE: f64 = 100.0;

/// The bounds of the feed override (percent): GRBL's own are 10–200, LinuxCNC's up to its
/// MAX_FEED_OVERRIDE; these keep the estimate meaningful for any of them.
pub const FEED_OVERRIDE_RANGE: (f64, f64) = (1.0, 1000.0);

/// A time model with its machine. `feed_override` (percent; 100: none) is the operator's
/// override the estimate assumes: it scales the feeds of the cuts within the machine's
/// limits, not the rapids, and the planner keeps its acceleration phases.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TimeModel {
    /// LinuxCNC 2.9's trajectory planner.
    LinuxCnc {
        machine: Machine,
        feed_override: f64,
    },
    /// GRBL 1.1's planner; `start_dwell`: the seconds the program waits after starting the
    /// spindle (`G4`, counted with the moves).
    Grbl {
        settings: Grbl,
        start_dwell: f64,
        feed_override: f64,
    },
}

impl From<Machine> for TimeModel {
    fn from(machine: Machine) -> TimeModel {
        TimeModel::LinuxCnc {
            machine,
            feed_override: NO_FEED_OVERRIDE,
        }
    }
}

impl TimeModel {
    /// Seconds the program waits beside its moves (the spindle's start dwell).
    pub fn dwell(&self) -> f64 {
        match self {
            TimeModel::LinuxCnc { .. } => 0.0,
            TimeModel::Grbl { start_dwell, .. } => *start_dwell,
        }
    }

    /// The operator's feed override (percent) the estimate assumes.
    pub fn feed_override(&self) -> f64 {
        match self {
            TimeModel::LinuxCnc { feed_override, .. } | TimeModel::Grbl { feed_override, .. } => {
                *feed_override
            }
        }
    }

    /// The statistics line naming the model, e.g. `Time model: GRBL planner, $110–$112
    /// X5000/Y5000/Z1000 mm/min, $120–$122 X500/Y500/Z200 mm/s^2, $11 0.01, $12 0.002`, and
    /// the feed override when there is one (`, feed override 120 %`).
    pub fn line(&self, lang: Lang) -> String {
        let line = self.model_line(lang);
        let f = self.feed_override();
        if f == NO_FEED_OVERRIDE {
            return line;
        }
        match lang {
            Lang::En => format!("{line}, feed override {} %", fmt_num(f)),
            Lang::De => format!("{line}, Vorschub-Override {} %", fmt_num(f)),
        }
    }

    fn model_line(&self, lang: Lang) -> String {
        let axes = |a: &Axes| format!("X{}/Y{}/Z{}", fmt_num(a.x), fmt_num(a.y), fmt_num(a.z));
        match self {
            TimeModel::LinuxCnc { machine: m, .. } => {
                let label = match lang {
                    Lang::En => "Time model: LinuxCNC planner",
                    Lang::De => "Zeitmodell: LinuxCNC-Planer",
                };
                format!(
                    "{label}, v={} mm/min, a={} mm/s^2, G64 P{}",
                    axes(&m.max_velocity),
                    axes(&m.max_acceleration),
                    fmt_num(m.path_tolerance)
                )
            }
            TimeModel::Grbl { settings: g, .. } => {
                let label = match lang {
                    Lang::En => "Time model: GRBL planner",
                    Lang::De => "Zeitmodell: GRBL-Planer",
                };
                format!(
                    "{label}, $110-$112 {} mm/min, $120-$122 {} mm/s^2, $11={}, $12={}",
                    axes(&g.max_rate),
                    axes(&g.acceleration),
                    fmt_num(g.junction_deviation),
                    fmt_num(g.arc_tolerance)
                )
            }
        }
    }
}
