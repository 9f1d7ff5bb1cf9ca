//! Controller dialects. `reference` writes what PathDxf2GCode writes, byte for byte
//! (reference-output.md §4). `linuxcnc` and `grbl` write programs those controllers run as
//! drawn: the feed after the modal line (LinuxCNC's G94 resets the feed, so the reference's
//! `F150` before it leaves the first plunge without a feed), a feed on every plunge, the
//! optional spindle start and stop, a stock comment for verifiers, and — for GRBL, which has
//! no `%` program delimiters — no `%` lines.

use crate::emit::comment::comment_line;
use crate::emit::timing::TimeModel;
use crate::front::drawing::Style;
use crate::geom::{f3, P3};
use crate::load::settings::Settings;
use crate::model::{Element, Model};
use crate::params::fmt_num;
use crate::probe::heightmap::Heightmap;
use serde::Deserialize;

/// The controller a program is written for.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Dialect {
    /// PathDxf2GCode's output, byte-identical (the default).
    #[default]
    Reference,
    /// LinuxCNC (rs274ngc).
    #[serde(rename = "linuxcnc")]
    LinuxCnc,
    /// GRBL 1.1.
    Grbl,
}

impl Dialect {
    pub const ALL: [Dialect; 3] = [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl];

    pub fn name(self) -> &'static str {
        match self {
            Dialect::Reference => "reference",
            Dialect::LinuxCnc => "linuxcnc",
            Dialect::Grbl => "grbl",
        }
    }

    pub fn from_name(name: &str) -> Option<Dialect> {
        Dialect::ALL
            .into_iter()
            .find(|d| d.name().eq_ignore_ascii_case(name.trim()))
    }
}

impl std::fmt::Display for Dialect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What the program writer needs to know about the controller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Controller {
    pub dialect: Dialect,
    /// Feed of plunges (mm/min); `None`: half the element's feed.
    pub plunge_feed: Option<f64>,
    /// Spindle speed; `None`: the program does not switch the spindle.
    pub spindle_rpm: Option<f64>,
    /// Seconds to wait after the spindle start.
    pub spindle_dwell: f64,
    /// The time model and machine of the estimates; `None`: the reference's time model.
    pub machine: Option<TimeModel>,
    /// `[heightmap]`: the probing set is a grid over the cuts (its probe feed resolved).
    pub heightmap: Option<Heightmap>,
    /// `probe_split` (mm): with drawn probes, cutting moves are written in pieces of at most
    /// this length, each corrected at its own start (`emit/probe_split.rs`).
    pub probe_split: Option<f64>,
    /// The height map is the drawing's own (`K`), for the messages that name where it came from.
    pub heightmap_in_drawing: bool,
}

impl Default for Controller {
    fn default() -> Self {
        Controller::reference()
    }
}

impl Controller {
    /// PathDxf2GCode's programs.
    pub fn reference() -> Controller {
        Controller {
            dialect: Dialect::Reference,
            plunge_feed: None,
            spindle_rpm: None,
            spindle_dwell: DEFAULT_SPINDLE_DWELL,
            machine: None,
            heightmap: None,
            probe_split: None,
            heightmap_in_drawing: false,
        }
    }

    pub fn of(s: &Settings) -> Controller {
        Controller {
            dialect: s.dialect,
            plunge_feed: s.plunge_feed,
            spindle_rpm: s.spindle_rpm,
            spindle_dwell: s.spindle_dwell,
            machine: s.time_model(),
            heightmap: s.heightmap.map(|h| Heightmap {
                probe_feed: Some(h.probe_feed.unwrap_or(s.probe_feed())),
                ..h
            }),
            probe_split: s.probe_split,
            heightmap_in_drawing: false,
        }
    }

    /// [`Controller::of`] for a compiled model: a height map said in its drawing (`K`) over
    /// the `[heightmap]` of millpath.toml, and `--heightmap-step`/`--heightmap-margin` over
    /// both. The drawing is the part's own truth; the file gives what `K` cannot say (area,
    /// probe feed and depth) and a margin `K` leaves out; an option is this run's choice.
    pub fn for_model(s: &Settings, model: &Model) -> Controller {
        let mut c = Controller::of(s);
        if let Some(k) = model.params.heightmap {
            let base = c.heightmap.unwrap_or(Heightmap {
                probe_feed: Some(s.probe_feed()),
                ..Heightmap::with_step(k.step)
            });
            let (step_option, margin_option) = s.heightmap_options;
            c.heightmap = Some(Heightmap {
                step: if step_option { base.step } else { k.step },
                margin: match (margin_option, k.margin) {
                    (false, Some(m)) => m,
                    _ => base.margin,
                },
                ..base
            });
            c.heightmap_in_drawing = true;
        }
        c
    }

    /// The feed written on a plunge of an element milled at `element_feed`: `None` in the
    /// reference dialect (no F word, the modal feed applies); else `plunge_feed`, but never
    /// faster than the element's own feed, or — without `plunge_feed` — half the element's
    /// feed.
    pub fn plunge(&self, element_feed: f64) -> Option<f64> {
        if self.dialect == Dialect::Reference {
            return None;
        }
        Some(match self.plunge_feed {
            Some(p) => p.min(element_feed),
            None => element_feed / 2.0,
        })
    }

    /// `%` lines around the program (LinuxCNC and the reference; GRBL 1.1 rejects them).
    fn percent(&self) -> bool {
        self.dialect != Dialect::Grbl
    }

    /// The lines before the body: `start` is the first sweep height; `spindle` is false for
    /// the probing program (the probe touches with a standing spindle).
    pub(crate) fn prologue(
        &self,
        banner: &str,
        file_name: &str,
        model: &Model,
        start: f64,
        spindle: bool,
    ) -> Vec<String> {
        let mut v = Vec::new();
        if self.percent() {
            v.push("%".into());
        }
        v.push(comment_line(self.dialect, 0, banner));
        v.push(comment_line(self.dialect, 0, file_name));
        if self.dialect == Dialect::Reference {
            v.push("F150".into());
            v.push("G17 G21 G40 G49 G54 G80 G90 G94".into());
            v.push("T1".into());
        } else {
            v.push(stock_comment(model));
            v.push("G17 G21 G40 G49 G54 G80 G90 G94".into());
            v.push(format!("F{}", f3(model.params.f)));
            v.push("T1".into());
            if let (true, Some(rpm)) = (spindle, self.spindle_rpm) {
                v.push(format!("M3 S{}", fmt_num(rpm)));
                if self.spindle_dwell > 0.0 {
                    v.push(format!("G4 P{}", fmt_num(self.spindle_dwell)));
                }
            }
        }
        let p = P3 {
            x: 0.0,
            y: 0.0,
            z: start,
        };
        v.push(comment_line(self.dialect, 0, &format!("SweepSafelyTo {p}")));
        v.push(format!("G00 Z{}", f3(start)));
        v.push("G00 X0.000 Y0.000".into());
        v
    }

    /// The lines after the body (and the statistics).
    pub(crate) fn epilogue(&self, spindle: bool) -> Vec<String> {
        let mut v = Vec::new();
        if spindle && self.dialect != Dialect::Reference && self.spindle_rpm.is_some() {
            v.push("M5".into());
        }
        v.push("M30".into());
        if self.percent() {
            v.push("%".into());
        }
        v
    }
}

/// Seconds the program waits after starting the spindle, unless set.
pub const DEFAULT_SPINDLE_DWELL: f64 = 2.0;

/// `(MILLPATH-STOCK T=<top> O=<tool diameter> BOTTOM=<lowest drawn depth>)`: what an
/// independent verifier needs to know about the stock and the tool.
pub fn stock_comment(model: &Model) -> String {
    // the same figures the compiler's own second opinion uses
    let (top, tool, bottom) = crate::second_opinion::stock_of(model);
    format!(
        "(MILLPATH-STOCK T={} O={} BOTTOM={})",
        f3(top),
        f3(tool),
        f3(bottom.unwrap_or(top))
    )
}

/// The lowest Z a model's elements ask for (`h` + B or D), subpaths with their H included.
pub fn lowest_depth(model: &Model, h: f64, depth: usize) -> Option<f64> {
    let pick = |style: Style, b: Option<f64>, d: Option<f64>| match style {
        Style::Mark => d,
        Style::Mill | Style::Support => b,
    };
    let mut lowest: Option<f64> = None;
    let mut take = |z: Option<f64>| {
        if let Some(z) = z {
            lowest = Some(lowest.map_or(z, |l: f64| l.min(z)));
        }
    };
    for e in &model.elements {
        match e {
            Element::Chain(c) => c
                .segs
                .iter()
                .for_each(|s| take(pick(s.style, s.b, s.d).map(|z| h + z))),
            Element::Drill(d) => take(pick(d.style, d.b, d.d).map(|z| h + z)),
            Element::Helix(x) => {
                let z = match (x.style, &x.bars) {
                    (Style::Support, None) => x.d,
                    (style, _) => pick(style, x.b, x.d),
                };
                take(z.map(|z| h + z));
            }
            Element::Subpath(emb) => {
                if let (Some(t), true) = (&emb.target, depth < 10) {
                    take(lowest_depth(t, h + emb.h, depth + 1));
                }
            }
            Element::Sweep(_) => {}
        }
    }
    lowest
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for d in Dialect::ALL {
            assert_eq!(Dialect::from_name(d.name()), Some(d));
        }
        assert_eq!(Dialect::from_name("LinuxCNC"), Some(Dialect::LinuxCnc));
        assert_eq!(Dialect::from_name("mach3"), None);
        assert_eq!(Dialect::default(), Dialect::Reference);
    }

    #[test]
    fn plunge_feeds() {
        let mut c = Controller::reference();
        assert_eq!(c.plunge(150.0), None);
        c.dialect = Dialect::LinuxCnc;
        assert_eq!(c.plunge(60.0), Some(30.0));
        c.plunge_feed = Some(100.0);
        assert_eq!(c.plunge(150.0), Some(100.0));
        assert_eq!(c.plunge(60.0), Some(60.0), "never faster than the element");
    }
}
