//! Statistics: lengths, times and command count (reference-output.md §14). The times are the
//! reference's (length / F · 1.4) unless machine limits are set: then they come from the
//! model of LinuxCNC's planner in `timing/`, and a sixth line names that model.
//!
//! Statistics (reference-output.md §14); with machine limits the times come from `timing/` and a
//! sixth line names the model; a line `Split for probes: N moves into M pieces` when `probe_split`
//! split moves; `hms` and `time_line`: the exact time as `h:mm:ss` for every place beside the
//! statistics.

use crate::diag::Lang;
use crate::emit::timing::TimeModel;
use crate::emit::{Item, Kind};
use crate::geom::P3;

#[derive(Debug, Clone, Default, PartialEq)]
pub struct Stats {
    pub mill: f64,
    pub mill_min: f64,
    pub drill: f64,
    pub drill_min: f64,
    pub sweep: f64,
    pub sweep_min: f64,
    pub count: usize,
    /// The time model and machine the times were estimated with; `None`: the reference's
    /// model.
    pub machine: Option<TimeModel>,
    /// Seconds the program waits beside its moves (the spindle's start dwell in the GRBL
    /// model), part of [`Stats::seconds`].
    pub dwell: f64,
    /// `probe_split`: cutting moves split for the probes, and the pieces they became (each
    /// piece is one command of `count`).
    pub split: (usize, usize),
}

const TICKS_PER_MINUTE: f64 = 600_000_000.0;

impl Stats {
    pub fn of(items: &[Item], sweep_speed: f64) -> Stats {
        let mut s = Stats::default();
        for it in items {
            s.add(it, sweep_speed);
        }
        s.scaled()
    }

    /// Adds one move to sums that [`Stats::scaled`] turns into statistics (in program order:
    /// the sums are the same bit for bit as [`Stats::of`]'s).
    pub(crate) fn add(&mut self, it: &Item, sweep_speed: f64) {
        match it.kind {
            Kind::Mill => {
                self.mill += it.len;
                self.mill_min += it.len / it.feed;
            }
            Kind::Drill => {
                self.drill += it.len;
                self.drill_min += it.len / it.feed;
            }
            Kind::HSweep | Kind::VSweep => {
                self.sweep += it.len;
                self.sweep_min += it.len / sweep_speed;
            }
            Kind::Comment => return,
        }
        self.count += 1;
    }

    /// The reference's times from the sums of [`Stats::add`].
    pub(crate) fn scaled(mut self) -> Stats {
        self.mill_min *= 1.4;
        self.drill_min *= 1.4;
        self.sweep_min *= 1.4;
        self
    }

    /// [`Stats::of`], with the times of a planner model when `machine` is set (the tool
    /// starting at rest at `start`).
    pub fn timed(
        items: &[Item],
        sweep_speed: f64,
        start: P3,
        machine: Option<&TimeModel>,
    ) -> Stats {
        let mut s = Stats::of(items, sweep_speed);
        if let Some(m) = machine {
            let t = m.plan(items, start);
            s.dwell = m.dwell();
            s.mill_min = t.mill / 60.0;
            s.drill_min = t.drill / 60.0;
            s.sweep_min = t.sweep / 60.0;
            s.machine = Some(*m);
        }
        s
    }

    /// The estimated time of the whole program in seconds (the sum of the three lines'
    /// times, unrounded).
    pub fn seconds(&self) -> f64 {
        (self.mill_min + self.drill_min + self.sweep_min) * 60.0 + self.dwell
    }

    /// The exact estimate for the summaries beside the reference's statistics, e.g.
    /// `Estimated time: 0:02:05` (the statistics lines keep their whole minutes).
    pub fn time_line(&self, lang: Lang) -> String {
        let label = match lang {
            Lang::En => "Estimated time:",
            Lang::De => "Geschätzte Zeit:",
        };
        format!("{label} {}", hms(self.seconds()))
    }

    /// The line after the five naming the time model, e.g. `Time model: LinuxCNC planner,
    /// v=X5000/Y5000/Z1000 mm/min, a=X500/Y500/Z200 mm/s^2, G64 P0.05`; `None` for the
    /// reference's model (whose output has five lines).
    pub fn model_line(&self, lang: Lang) -> Option<String> {
        Some(self.machine?.line(lang))
    }

    /// The line after the others when `probe_split` split moves, e.g. `Split for probes: 4
    /// moves into 26 pieces`; `None` otherwise (the reference's five lines stay five).
    pub fn split_line(&self, lang: Lang) -> Option<String> {
        let (moves, pieces) = self.split;
        (moves > 0).then(|| match lang {
            Lang::En => format!("Split for probes: {moves} moves into {pieces} pieces"),
            Lang::De => format!("Für Messpunkte geteilt: {moves} Bewegungen in {pieces} Stücke"),
        })
    }

    /// The five statistics texts, e.g. `Fräslänge:     115 mm   ca.  2 min`.
    pub fn lines(&self, lang: Lang) -> [String; 5] {
        let labels = match lang {
            Lang::En => [
                "Milling length:",
                "Drill length:",
                "Sweeps:",
                "Sum:",
                "Command count:",
            ],
            Lang::De => [
                "Fräslänge:",
                "Bohrungen:",
                "Leerfahrten:",
                "Summe:",
                "Befehlszahl:",
            ],
        };
        let ticks = |m: f64| (m * TICKS_PER_MINUTE).trunc();
        let (tm, td, ts) = (
            ticks(self.mill_min),
            ticks(self.drill_min),
            ticks(self.sweep_min),
        );
        let minutes = |t: f64| (t / TICKS_PER_MINUTE).ceil();
        let line = |l: &str, len: f64, t: f64| {
            format!("{l:<12} {:>5.0} mm   ca.{:>3.0} min", len, minutes(t))
        };
        [
            line(labels[0], self.mill, tm),
            line(labels[1], self.drill, td),
            line(labels[2], self.sweep, ts),
            line(labels[3], self.mill + self.drill + self.sweep, tm + td + ts),
            format!("{:<12} {}", labels[4], self.count),
        ]
    }
}

/// A duration as `h:mm:ss`, rounded to the second (`0:00:00` for what is not a finite
/// positive number; hours are not wrapped).
pub fn hms(seconds: f64) -> String {
    let s = if seconds.is_finite() && seconds > 0.0 {
        // beyond a hundred years nothing is meaningful; keep the cast exact
        seconds.round().min(3.2e9) as u64
    } else {
        0
    };
    format!("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_times() {
        assert_eq!(hms(0.0), "0:00:00");
        assert_eq!(hms(0.49), "0:00:00");
        assert_eq!(hms(0.5), "0:00:01");
        assert_eq!(hms(125.4), "0:02:05");
        assert_eq!(hms(3600.0 * 27.0 + 61.0), "27:01:01");
        assert_eq!(hms(f64::NAN), "0:00:00");
        assert_eq!(hms(-3.0), "0:00:00");
        assert_eq!(hms(f64::INFINITY), "0:00:00");
        let s = Stats {
            mill_min: 1.0,
            drill_min: 0.5,
            sweep_min: 0.6,
            ..Stats::default()
        };
        assert!((s.seconds() - 126.0).abs() < 1e-9);
        assert_eq!(s.time_line(Lang::En), "Estimated time: 0:02:06");
        assert_eq!(s.time_line(Lang::De), "Geschätzte Zeit: 0:02:06");
    }

    #[test]
    fn statistics_lines() {
        let s = Stats {
            mill: 115.374,
            mill_min: 115.374 / 150.0 * 1.4,
            drill: 3.5,
            drill_min: 3.5 / 150.0 * 1.4,
            sweep: 65.99,
            sweep_min: 65.99 / 500.0 * 1.4,
            count: 8,
            machine: None,
            dwell: 0.0,
            split: (0, 0),
        };
        assert_eq!(s.split_line(Lang::En), None, "the reference's five lines");
        let split = Stats {
            split: (4, 26),
            ..s.clone()
        };
        assert_eq!(
            split.split_line(Lang::En).as_deref(),
            Some("Split for probes: 4 moves into 26 pieces")
        );
        assert_eq!(
            split.split_line(Lang::De).as_deref(),
            Some("Für Messpunkte geteilt: 4 Bewegungen in 26 Stücke")
        );
        let de = s.lines(Lang::De);
        assert_eq!(de[0], "Fräslänge:     115 mm   ca.  2 min");
        assert_eq!(de[4], "Befehlszahl: 8");
        let en = s.lines(Lang::En);
        assert_eq!(en[0], "Milling length:   115 mm   ca.  2 min");
        assert_eq!(en[1], "Drill length:     4 mm   ca.  1 min");
        assert_eq!(en[3], "Sum:           185 mm   ca.  2 min");
        assert_eq!(
            Stats::default().lines(Lang::De)[1],
            "Bohrungen:       0 mm   ca.  0 min"
        );
    }
}
