//! `millpath.toml`: machine settings of a folder tree. Parsing and applying only; finding
//! the file is the caller's (the CLI walks the file system, the language server its view).
//!
//! `millpath.toml` parsing (`[machine]`: `max_velocity`, `max_acceleration`, `path_tolerance`;
//! `[heightmap]`: `step`, `margin`, `area`, `probe_feed`, `probe_depth`; `probe_split`).

use crate::machine::{Axes, Dialect, GrblValues};
use crate::probe::heightmap::Heightmap;
use crate::Settings;
use serde::Deserialize;
use std::path::{Path, PathBuf};

pub const FILE_NAME: &str = "millpath.toml";

#[derive(Debug, Default, Deserialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FileConfig {
    pub feed: Option<f64>,
    pub sweep_speed: Option<f64>,
    pub sweep_height: Option<f64>,
    pub probe_feed: Option<f64>,
    /// Relative to the directory of the `millpath.toml`.
    #[serde(default)]
    pub search_dirs: Vec<PathBuf>,
    pub path_pattern: Option<String>,
    pub file_pattern: Option<String>,
    /// `parent:child` regex pairs, like `/e`.
    #[serde(default)]
    pub restrictions: Vec<String>,
    pub lang: Option<String>,
    /// `reference` (default), `linuxcnc` or `grbl`.
    pub dialect: Option<Dialect>,
    /// A built-in post's name or a post file (relative to this file's folder); over
    /// `dialect`. Read by the caller ([`crate::emit::dialect::select_post`]).
    pub post: Option<String>,
    /// The folder a relative `post` file is found in.
    #[serde(skip)]
    pub base_dir: PathBuf,
    pub plunge_feed: Option<f64>,
    pub spindle_rpm: Option<f64>,
    pub spindle_dwell: Option<f64>,
    /// The operator's feed override (percent) the time estimates assume.
    pub feed_override: Option<f64>,
    /// `[machine]`: limits for the time estimates.
    pub machine: Option<MachineConfig>,
    /// `reference` (default) or `extended`: polylines, blocks, line-type aliases, units.
    pub input: Option<crate::InputMode>,
    /// `[heightmap]`: probe a grid over the cuts (linuxcnc and grbl).
    pub heightmap: Option<HeightmapConfig>,
    /// With drawn probes, moves longer than this (mm) are milled in pieces, each corrected
    /// at its own start (linuxcnc and grbl).
    pub probe_split: Option<f64>,
    /// `[[clamp]]`: keep-out boxes the tool must never touch (`load/clamps.rs`).
    #[serde(default)]
    pub clamp: Vec<crate::load::clamps::ClampConfig>,
    /// The toolpath view's cut part: its cell edge (mm); default the checker's (O/8).
    pub cut_cell: Option<f64>,
    /// `check` fails when it finds more warnings than this (as `--max-warnings`); a whole
    /// number ≥ 0 (a negative or NaN value is the TOML reader's error, at its line).
    pub max_warnings: Option<u32>,
}

/// `[heightmap]`: `step` (mm, required), `margin` (mm, default 0), `area = [xmin, ymin,
/// xmax, ymax]` (instead of the cuts' extent plus margin), `probe_feed` (mm/min, default the
/// probe feed), `probe_depth` (mm below the nominal top, default 5).
#[derive(Debug, Deserialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct HeightmapConfig {
    pub step: f64,
    pub margin: Option<f64>,
    pub area: Option<[f64; 4]>,
    pub probe_feed: Option<f64>,
    pub probe_depth: Option<f64>,
}

impl HeightmapConfig {
    pub fn heightmap(&self) -> Heightmap {
        let d = Heightmap::with_step(self.step);
        Heightmap {
            margin: self.margin.unwrap_or(d.margin),
            area: self.area,
            probe_feed: self.probe_feed,
            probe_depth: self.probe_depth.unwrap_or(d.probe_depth),
            ..d
        }
    }
}

/// `[machine]`: `max_velocity` (mm/min) and `max_acceleration` (mm/s²), each one number for
/// every axis or `{ x = …, y = …, z = … }`, and `path_tolerance` (G64 P, mm); `controller`
/// (`linuxcnc` or `grbl`: whose planner times the programs) and GRBL's settings by their
/// names or `$` numbers (`x_max_rate` or `"$110"`, …).
#[derive(Debug, Default, Deserialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MachineConfig {
    pub max_velocity: Option<AxesValue>,
    pub max_acceleration: Option<AxesValue>,
    pub path_tolerance: Option<f64>,
    pub controller: Option<crate::emit::timing::Planner>,
    #[serde(alias = "$11")]
    pub junction_deviation: Option<f64>,
    #[serde(alias = "$12")]
    pub arc_tolerance: Option<f64>,
    #[serde(alias = "$100")]
    pub x_steps_per_mm: Option<f64>,
    #[serde(alias = "$101")]
    pub y_steps_per_mm: Option<f64>,
    #[serde(alias = "$102")]
    pub z_steps_per_mm: Option<f64>,
    #[serde(alias = "$110")]
    pub x_max_rate: Option<f64>,
    #[serde(alias = "$111")]
    pub y_max_rate: Option<f64>,
    #[serde(alias = "$112")]
    pub z_max_rate: Option<f64>,
    #[serde(alias = "$120")]
    pub x_acceleration: Option<f64>,
    #[serde(alias = "$121")]
    pub y_acceleration: Option<f64>,
    #[serde(alias = "$122")]
    pub z_acceleration: Option<f64>,
}

impl MachineConfig {
    /// The GRBL settings given.
    fn grbl(&self) -> GrblValues {
        GrblValues {
            max_rate: [self.x_max_rate, self.y_max_rate, self.z_max_rate],
            acceleration: [
                self.x_acceleration,
                self.y_acceleration,
                self.z_acceleration,
            ],
            junction_deviation: self.junction_deviation,
            arc_tolerance: self.arc_tolerance,
            steps_per_mm: [
                self.x_steps_per_mm,
                self.y_steps_per_mm,
                self.z_steps_per_mm,
            ],
        }
    }
}

/// One number for every axis, or one per axis.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq)]
#[serde(untagged)]
pub enum AxesValue {
    All(f64),
    Each(Axes),
}

impl AxesValue {
    pub fn axes(self) -> Axes {
        match self {
            AxesValue::All(v) => Axes::all(v),
            AxesValue::Each(a) => a,
        }
    }
}

/// Parses a settings file; relative search directories are taken relative to `base_dir`.
/// The error text names the line.
pub fn parse(text: &str, base_dir: &Path) -> Result<FileConfig, String> {
    let mut cfg: FileConfig = toml::from_str(text).map_err(|e| e.to_string())?;
    cfg.base_dir = base_dir.to_path_buf();
    cfg.search_dirs = cfg.search_dirs.iter().map(|d| base_dir.join(d)).collect();
    Ok(cfg)
}

impl FileConfig {
    /// Applies the file's values to settings (command-line values are applied afterwards).
    pub fn apply(&self, s: &mut Settings, have: &mut Have) {
        if let Some(v) = self.feed {
            s.feed = v;
            have.feed = true;
        }
        if let Some(v) = self.sweep_speed {
            s.sweep_speed = v;
            have.sweep_speed = true;
        }
        if let Some(v) = self.sweep_height {
            s.sweep_height = v;
            have.sweep_height = true;
        }
        if self.probe_feed.is_some() {
            s.probe_feed = self.probe_feed;
        }
        s.search_dirs.extend(self.search_dirs.iter().cloned());
        if let Some(p) = &self.path_pattern {
            s.path_pattern = p.clone();
        }
        if let Some(p) = &self.file_pattern {
            s.file_pattern = p.clone();
        }
        for r in &self.restrictions {
            if let Some((a, b)) = r.split_once(':') {
                s.restrictions.push((a.to_string(), b.to_string()));
            }
        }
        if let Some(l) = &self.lang {
            s.lang = crate::Lang::from_name(l);
        }
        if let Some(d) = self.dialect {
            s.dialect = d;
        }
        if self.plunge_feed.is_some() {
            s.plunge_feed = self.plunge_feed;
        }
        if self.spindle_rpm.is_some() {
            s.spindle_rpm = self.spindle_rpm;
        }
        if let Some(v) = self.spindle_dwell {
            s.spindle_dwell = v;
        }
        if let Some(v) = self.feed_override {
            s.feed_override = v;
        }
        if let Some(i) = self.input {
            s.input = i;
        }
        if let Some(h) = &self.heightmap {
            s.heightmap = Some(h.heightmap());
        }
        if self.probe_split.is_some() {
            s.probe_split = self.probe_split;
        }
        if self.max_warnings.is_some() {
            s.max_warnings = self.max_warnings;
        }
        if self.cut_cell.is_some() {
            s.cut_cell = self.cut_cell;
        }
        if !self.clamp.is_empty() {
            s.clamps = crate::load::clamps::clamps(&self.clamp);
        }
        if let Some(m) = &self.machine {
            if let Some(v) = m.max_velocity {
                s.max_velocity = Some(v.axes());
            }
            if let Some(a) = m.max_acceleration {
                s.max_acceleration = Some(a.axes());
            }
            if let Some(p) = m.path_tolerance {
                s.path_tolerance = p;
            }
            if m.controller.is_some() {
                s.planner = m.controller;
            }
            s.grbl = m.grbl();
        }
    }
}

/// Which required machine settings were given.
#[derive(Debug, Default, Clone, Copy)]
pub struct Have {
    pub feed: bool,
    pub sweep_speed: bool,
    pub sweep_height: bool,
}
