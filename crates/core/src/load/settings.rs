//! Machine settings and options of a run.
//!
//! `Settings` of a run (`/f /v /s /z /c /d /n /p /e /x`, language, dialect, plunge feed, spindle,
//! machine limits for the time estimates, `[heightmap]` with its bounds located at the
//! millpath.toml or the options; `probe_split` ≥ 0.5 mm, refused in the reference dialect).

use crate::args;
use crate::diag::Lang;
use crate::diag::{Diagnostic, Msg, Origin};
use crate::machine::{
    Axes, Dialect, GrblValues, Machine, Planner, TimeModel, DEFAULT_PATH_TOLERANCE,
    DEFAULT_SPINDLE_DWELL, FEED_OVERRIDE_RANGE, NO_FEED_OVERRIDE,
};
use crate::params::MAX_MAGNITUDE;
use crate::probe::heightmap::Heightmap;
use std::path::PathBuf;

/// The shortest `probe_split` (mm): shorter pieces would not follow a board any better
/// (probes are millimetres apart) and only multiply the program's lines.
pub const MIN_PROBE_SPLIT: f64 = 0.5;

/// Machine settings and options of a run.
#[derive(Debug, Clone)]
pub struct Settings {
    /// `/f`: default feed (mm/min).
    pub feed: f64,
    /// `/v`: sweep speed (mm/min), statistics only.
    pub sweep_speed: f64,
    /// `/s`: sweep height of the top-level path.
    pub sweep_height: f64,
    /// `/z`: probe feed; `None` or ≤ 0 means `/f`.
    pub probe_feed: Option<f64>,
    /// `/c`: check every path, write nothing.
    pub check: bool,
    /// The reference's command line (`pathdxf2gcode`): its messages, and its `/c` (every
    /// path generated even after errors, no file-level errors, S = T+O). Otherwise check
    /// mode reports what `compile` would.
    pub reference_check: bool,
    /// Check mode knows the sweep height `compile` would use (options or millpath.toml):
    /// the top-level default S is then `/s`, as in `compile`, not T+O.
    pub check_sweep_height: bool,
    /// The editor's check, answered while typing: each path is planned as compile plans it
    /// (every emitter error, the statistics; cancellable between elements and passes) but not
    /// written out and not given to the second opinion, whose stock simulation would take
    /// the answer past a frame on a large drawing. `millpath check` and `compile` review.
    pub quick_check: bool,
    /// `compile`'s command line: the milling (or clean) program is written to a temporary
    /// file beside its output while it is generated ([`crate::OutputFile::staged`]), never
    /// held whole; the caller renames it into place with the set.
    pub stage_outputs: bool,
    /// `/d`: further search directories, in order.
    pub search_dirs: Vec<PathBuf>,
    pub path_pattern: String,
    pub file_pattern: String,
    /// `/e parent:child` restrictions, in order.
    pub restrictions: Vec<(String, String)>,
    /// `/x`: debug output of text assignments.
    pub debug_pattern: Option<String>,
    pub lang: Lang,
    /// The controller the programs are written for (`reference`: byte-identical to
    /// PathDxf2GCode).
    pub dialect: Dialect,
    /// A post file (`post = "posts/mymachine.toml"`, `--post FILE`) that writes the text
    /// instead of the dialect's built-in post; the dialect is then the post's family's.
    pub post: Option<std::sync::Arc<millpath_post::Post>>,
    /// Feed of plunges in the `linuxcnc` and `grbl` dialects; `None`: half the feed of the
    /// element (a set value is never faster than the element's feed either).
    pub plunge_feed: Option<f64>,
    /// Spindle speed (`linuxcnc`, `grbl`): `M3 S…` before the first move, `M5` at the end.
    pub spindle_rpm: Option<f64>,
    /// Seconds to wait after the spindle start (`G4 P…`; 0: no wait).
    pub spindle_dwell: f64,
    /// The operator's feed override (percent) the time estimates assume
    /// (`--feed-override`, `feed_override`; 100: none).
    pub feed_override: f64,
    /// Maximum velocity per axis (mm/min) for the time estimates; `None`: `/v` on every axis.
    pub max_velocity: Option<Axes>,
    /// MAX_ACCELERATION per axis (mm/s²). Set: the statistics use the LinuxCNC planner time model
    /// (`emit/timing.rs`); `None`: the reference's model.
    pub max_acceleration: Option<Axes>,
    /// G64 P (mm): how far a blended corner may leave the path, for the time estimates.
    pub path_tolerance: f64,
    /// `controller` of `[machine]`: whose planner times the programs; `None`: the dialect's.
    pub planner: Option<Planner>,
    /// GRBL's settings given in `[machine]` (`$110` …) for its planner.
    pub grbl: GrblValues,
    /// How DXF geometry is read: as the reference, or also polylines, blocks, line-type
    /// aliases and units (`--extended`, `input = "extended"`).
    pub input: crate::InputMode,
    /// `[heightmap]`: the probing set is a grid over the cuts (linuxcnc and grbl).
    pub heightmap: Option<Heightmap>,
    /// Where the `[heightmap]` was given (its errors are located there); `None`: options.
    pub heightmap_file: Option<PathBuf>,
    /// `--heightmap-step` / `--heightmap-margin` given on the command line.
    pub heightmap_options: (bool, bool),
    /// `probe_split` (mm): with drawn probes, cutting moves longer than this are written in
    /// pieces, each with the probe correction of its own start (linuxcnc and grbl).
    pub probe_split: Option<f64>,
    /// Where `probe_split` was given (its errors are located there); `None`: `--probe-split`.
    pub probe_split_file: Option<PathBuf>,
    /// `[[clamp]]`: keep-out boxes; every written program is checked against them.
    pub clamps: Vec<millpath_verify::Clamp>,
    /// Where the clamps were given (their errors are located there).
    pub clamps_file: Option<PathBuf>,
    /// The toolpath view's cut part: cell edge in mm (`cut_cell`, `render --cut-cell`);
    /// `None`: the checker's.
    pub cut_cell: Option<f64>,
    /// `check` fails with more warnings than this (`max_warnings`, `--max-warnings`).
    pub max_warnings: Option<u32>,
    /// The millpath.toml these settings were read from; `None`: none (options, an editor).
    pub settings_file: Option<PathBuf>,
    /// Settings the command line gave (`feed`, `probe_feed`, …): their errors are located at
    /// the options, the others' at [`Settings::settings_file`].
    pub option_keys: Vec<&'static str>,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            feed: 150.0,
            sweep_speed: 500.0,
            sweep_height: 15.0,
            probe_feed: None,
            check: false,
            reference_check: false,
            quick_check: false,
            stage_outputs: false,
            check_sweep_height: false,
            search_dirs: Vec::new(),
            path_pattern: crate::load::names::DEFAULT_PATH_PATTERN.into(),
            file_pattern: crate::load::names::DEFAULT_FILE_PATTERN.into(),
            restrictions: Vec::new(),
            debug_pattern: None,
            lang: Lang::En,
            dialect: Dialect::Reference,
            post: None,
            plunge_feed: None,
            spindle_rpm: None,
            spindle_dwell: DEFAULT_SPINDLE_DWELL,
            feed_override: NO_FEED_OVERRIDE,
            max_velocity: None,
            max_acceleration: None,
            path_tolerance: DEFAULT_PATH_TOLERANCE,
            planner: None,
            grbl: GrblValues::default(),
            input: crate::InputMode::Reference,
            heightmap: None,
            heightmap_file: None,
            heightmap_options: (false, false),
            probe_split: None,
            probe_split_file: None,
            clamps: Vec::new(),
            clamps_file: None,
            cut_cell: None,
            max_warnings: None,
            settings_file: None,
            option_keys: Vec::new(),
        }
    }
}

impl Settings {
    /// `--heightmap-step` and `--heightmap-margin` over the `[heightmap]` of the settings
    /// file: the step keeps the table's other keys (or makes a grid of its own), the margin
    /// widens the grid. `false` when a margin has no grid to widen (it changes nothing then).
    pub fn override_heightmap(&mut self, step: Option<f64>, margin: Option<f64>) -> bool {
        if let Some(step) = step {
            let hm = self.heightmap.unwrap_or(Heightmap::with_step(step));
            self.heightmap = Some(Heightmap { step, ..hm });
            self.heightmap_options.0 = true;
        }
        if let Some(margin) = margin {
            let Some(hm) = self.heightmap.as_mut() else {
                return false;
            };
            hm.margin = margin;
            self.heightmap_options.1 = true;
        }
        true
    }

    /// compile's rule for the machine values (the command line's and the Python package's):
    /// feed, sweep speed and sweep height each a number > 0, else the message naming it.
    pub fn machine_values_positive(&self) -> Result<(), String> {
        for (name, v) in [
            ("feed", self.feed),
            ("sweep_speed", self.sweep_speed),
            ("sweep_height", self.sweep_height),
        ] {
            if v.is_nan() || v <= 0.0 {
                return Err(match self.lang {
                    Lang::De => format!("{name} muss > 0 sein (ist {v})"),
                    Lang::En => format!("{name} must be > 0 (is {v})"),
                });
            }
        }
        Ok(())
    }

    /// Where an error of setting `name` is located: millpath.toml, unless an option gave it.
    fn origin_of(&self, name: &str) -> Origin {
        match &self.settings_file {
            Some(p) if !self.option_keys.contains(&name) => {
                Origin::File(crate::diag::FileRef::new(p.clone()))
            }
            _ => Origin::Options,
        }
    }

    /// Machine values that are not finite or beyond ±[`MAX_MAGNITUDE`], whichever way they
    /// came (options, `millpath.toml` where `nan` and `inf` are valid floats, an editor).
    pub fn number_errors(&self) -> Vec<Diagnostic> {
        let mut values = vec![
            ("feed", self.feed),
            ("sweep_speed", self.sweep_speed),
            ("sweep_height", self.sweep_height),
        ];
        values.extend(self.probe_feed.map(|z| ("probe_feed", z)));
        values.extend(self.plunge_feed.map(|v| ("plunge_feed", v)));
        values.extend(self.spindle_rpm.map(|v| ("spindle_rpm", v)));
        values.push(("spindle_dwell", self.spindle_dwell));
        values.push(("feed_override", self.feed_override));
        values.extend(self.cut_cell.map(|v| ("cut_cell", v)));
        let machine = self.machine_values();
        values.extend(machine.iter().cloned());
        let finite = |v: f64| v.is_finite() && v.abs() <= MAX_MAGNITUDE;
        let mut errors: Vec<Diagnostic> = values
            .into_iter()
            .filter(|(_, v)| !finite(*v))
            .map(|(name, v)| {
                // 1e300 as written, not as three hundred digits
                let shown = if v.is_finite() {
                    format!("{v:e}")
                } else {
                    v.to_string()
                };
                Diagnostic::error(
                    Msg::SettingNotFinite,
                    self.origin_of(name),
                    args![name, shown, MAX_MAGNITUDE],
                )
            })
            .collect();
        // the controller settings must also make sense as what they are
        let mut positive = vec![
            ("plunge_feed", self.plunge_feed),
            ("spindle_rpm", self.spindle_rpm),
            ("cut_cell", self.cut_cell),
        ];
        positive.extend(machine.iter().map(|(name, v)| (*name, Some(*v))));
        for (name, v) in positive {
            if let Some(v) = v.filter(|v| finite(*v) && *v <= 0.0) {
                errors.push(Diagnostic::error(
                    Msg::MustBePositive,
                    self.origin_of(name),
                    args![name, crate::params::fmt_num(v)],
                ));
            }
        }
        // feeds and speeds that round to nothing in the program or the estimate
        let mut feeds = vec![("feed", self.feed), ("sweep_speed", self.sweep_speed)];
        feeds.extend(self.probe_feed.map(|z| ("probe_feed", z)));
        feeds.extend(self.plunge_feed.map(|v| ("plunge_feed", v)));
        errors.extend(
            feeds.into_iter().filter_map(|(name, v)| {
                crate::params::feed_too_small(name, v, &self.origin_of(name))
            }),
        );
        if finite(self.spindle_dwell) && self.spindle_dwell < 0.0 {
            errors.push(Diagnostic::error(
                Msg::OptionNegative,
                self.origin_of("spindle_dwell"),
                args!["spindle_dwell", crate::params::fmt_num(self.spindle_dwell)],
            ));
        }
        let (least, most) = FEED_OVERRIDE_RANGE;
        if finite(self.feed_override) && !(least..=most).contains(&self.feed_override) {
            errors.push(Diagnostic::error(
                Msg::FeedOverrideRange,
                self.origin_of("feed_override"),
                args![
                    crate::params::fmt_num(self.feed_override),
                    crate::params::fmt_num(least),
                    crate::params::fmt_num(most)
                ],
            ));
        }
        errors.extend(self.heightmap_errors());
        errors.extend(self.probe_split_errors());
        errors.extend(self.post_errors());
        errors.extend(crate::load::clamps::errors(
            &self.clamps,
            self.clamps_file.as_ref(),
        ));
        if self.max_velocity.is_some()
            && self.max_acceleration.is_none()
            && self.planner() == Planner::LinuxCnc
        {
            errors.push(Diagnostic::error(
                Msg::MachineNeedsAcceleration,
                // `[machine]` of millpath.toml (an editor's settings: the options)
                self.origin_of("max_velocity"),
                vec![],
            ));
        }
        errors
    }

    /// `[heightmap]` values out of bounds, located at the settings file or the options, and
    /// a height map in the reference dialect (PathDxf2GCode's programs have none).
    fn heightmap_errors(&self) -> Vec<Diagnostic> {
        let Some(hm) = &self.heightmap else {
            return Vec::new();
        };
        let file = || match &self.heightmap_file {
            Some(p) => Origin::File(crate::diag::FileRef::new(p.clone())),
            None => Origin::Options,
        };
        let at = |name: &str| match (name, self.heightmap_options) {
            ("step", (true, _)) => ("--heightmap-step".to_string(), Origin::Options),
            ("margin", (_, true)) => ("--heightmap-margin".to_string(), Origin::Options),
            _ => (format!("heightmap.{name}"), file()),
        };
        let mut errors = hm.errors(&at);
        // a probe feed that rounds to nothing in the program
        if let Some(v) = hm.probe_feed.filter(|v| v.is_finite() && *v > 0.0) {
            errors.extend(crate::params::feed_too_small(
                "heightmap.probe_feed",
                v,
                &file(),
            ));
        }
        if self.dialect == Dialect::Reference {
            errors.push(Diagnostic::error(
                Msg::HeightmapReferenceDialect,
                file(),
                vec![],
            ));
        }
        errors
    }

    /// `probe_split` not finite, below [`MIN_PROBE_SPLIT`], or in the reference dialect
    /// (refused, not ignored: the run was asked to follow the surface and would not),
    /// located at the settings file or the option.
    fn probe_split_errors(&self) -> Vec<Diagnostic> {
        let Some(v) = self.probe_split else {
            return Vec::new();
        };
        let (name, origin) = match &self.probe_split_file {
            Some(p) => (
                "probe_split",
                Origin::File(crate::diag::FileRef::new(p.clone())),
            ),
            None => ("--probe-split", Origin::Options),
        };
        let mut errors = Vec::new();
        if !(v.is_finite() && v.abs() <= MAX_MAGNITUDE) {
            let shown = if v.is_finite() {
                format!("{v:e}")
            } else {
                v.to_string()
            };
            errors.push(Diagnostic::error(
                Msg::SettingNotFinite,
                origin.clone(),
                args![name, shown, MAX_MAGNITUDE],
            ));
        } else if v < MIN_PROBE_SPLIT {
            errors.push(Diagnostic::error(
                Msg::ProbeSplitTooSmall,
                origin.clone(),
                args![
                    name,
                    crate::params::fmt_num(v),
                    crate::params::fmt_num(MIN_PROBE_SPLIT)
                ],
            ));
        }
        if self.dialect == Dialect::Reference {
            errors.push(Diagnostic::error(
                Msg::ProbeSplitReferenceDialect,
                origin,
                args![name],
            ));
        }
        errors
    }

    /// A post file whose family the second opinion cannot read; what it cannot write of
    /// these settings: a height map, a spindle speed, a dwell (the built-in posts write what
    /// their dialect allows).
    fn post_errors(&self) -> Vec<Diagnostic> {
        let Some(post) = &self.post else {
            return Vec::new();
        };
        // the second opinion reads every program: a family it cannot read is refused here
        if let Err(family) = crate::machine::Reading::of(self.dialect, post) {
            return vec![Diagnostic::error(
                Msg::PostNotVerifiable,
                self.origin_of("post"),
                args![post.name.clone(), family.name()],
            )];
        }
        let asks = [
            (
                self.heightmap.is_some(),
                "[heightmap]",
                (false, true, false, false),
            ),
            (
                self.spindle_rpm.is_some(),
                "spindle_rpm",
                (false, false, true, false),
            ),
            (
                self.spindle_rpm.is_some() && self.spindle_dwell > 0.0,
                "spindle_dwell",
                (false, false, false, true),
            ),
        ];
        asks.into_iter()
            .filter(|(asked, _, _)| *asked)
            .filter_map(|(_, what, (p, g, s, d))| {
                let missing = post.missing_for(p, g, s, d)?;
                let origin = match (what, &self.heightmap_file) {
                    ("[heightmap]", Some(f)) => Origin::File(crate::diag::FileRef::new(f.clone())),
                    ("[heightmap]", None) => Origin::Options,
                    (key, _) => self.origin_of(key),
                };
                Some(Diagnostic::error(
                    Msg::PostCannot,
                    origin,
                    args![post.name.clone(), what, missing.key()],
                ))
            })
            .collect()
    }

    /// The machine limits as named values (`max_velocity.x` …, `path_tolerance`).
    fn machine_values(&self) -> Vec<(&'static str, f64)> {
        let mut v = Vec::new();
        if let Some(a) = self.max_velocity {
            v.extend(
                ["max_velocity.x", "max_velocity.y", "max_velocity.z"]
                    .into_iter()
                    .zip(a.values().map(|(_, v)| v)),
            );
        }
        if let Some(a) = self.max_acceleration {
            v.extend(
                [
                    "max_acceleration.x",
                    "max_acceleration.y",
                    "max_acceleration.z",
                ]
                .into_iter()
                .zip(a.values().map(|(_, v)| v)),
            );
        }
        v.push(("path_tolerance", self.path_tolerance));
        v.extend(self.grbl.named());
        v
    }

    /// Whose planner times the programs: `controller`, else GRBL's for the `grbl` dialect,
    /// else LinuxCNC's.
    pub fn planner(&self) -> Planner {
        self.planner.unwrap_or(match self.dialect {
            Dialect::Grbl => Planner::Grbl,
            _ => Planner::LinuxCnc,
        })
    }

    /// The time model of the estimates: LinuxCNC's when `max_acceleration` is set; GRBL's
    /// when any machine value is (GRBL's defaults for the others) or `controller = "grbl"`;
    /// `None`: the reference's model.
    pub fn time_model(&self) -> Option<TimeModel> {
        match self.planner() {
            Planner::LinuxCnc => self.machine().map(|machine| TimeModel::LinuxCnc {
                machine,
                feed_override: self.feed_override,
            }),
            Planner::Grbl => {
                let given = self.planner.is_some()
                    || self.grbl.any()
                    || self.max_velocity.is_some()
                    || self.max_acceleration.is_some();
                // the program waits after starting the spindle (dialect.rs's prologue)
                let dwell = self.spindle_rpm.is_some() && self.dialect != Dialect::Reference;
                given.then(|| TimeModel::Grbl {
                    settings: self.grbl.machine(self.max_velocity, self.max_acceleration),
                    start_dwell: if dwell {
                        self.spindle_dwell.max(0.0)
                    } else {
                        0.0
                    },
                    feed_override: self.feed_override,
                })
            }
        }
    }

    /// The machine limits of the time estimates: set when `max_acceleration` is (the maximum
    /// velocity defaults to `/v` on every axis).
    pub fn machine(&self) -> Option<Machine> {
        Some(Machine {
            max_acceleration: self.max_acceleration?,
            max_velocity: self.max_velocity.unwrap_or(Axes::all(self.sweep_speed)),
            path_tolerance: self.path_tolerance,
        })
    }

    pub fn probe_feed(&self) -> f64 {
        match self.probe_feed {
            Some(z) if z > 0.0 => z,
            _ => self.feed,
        }
    }
}
