//! Machine settings and options of a run.

use crate::args;
use crate::diag::Lang;
use crate::diag::{Diagnostic, Msg, Origin};
use crate::params::MAX_MAGNITUDE;
use std::path::PathBuf;

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
    /// `/d`: further search directories, in order.
    pub search_dirs: Vec<PathBuf>,
    pub path_pattern: String,
    pub file_pattern: String,
    /// `/e parent:child` restrictions, in order.
    pub restrictions: Vec<(String, String)>,
    /// `/x`: debug output of text assignments.
    pub debug_pattern: Option<String>,
    pub lang: Lang,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            feed: 150.0,
            sweep_speed: 500.0,
            sweep_height: 15.0,
            probe_feed: None,
            check: false,
            search_dirs: Vec::new(),
            path_pattern: crate::load::names::DEFAULT_PATH_PATTERN.into(),
            file_pattern: crate::load::names::DEFAULT_FILE_PATTERN.into(),
            restrictions: Vec::new(),
            debug_pattern: None,
            lang: Lang::En,
        }
    }
}

impl Settings {
    /// Machine values that are not finite or beyond ±[`MAX_MAGNITUDE`], whichever way they
    /// came (options, `millpath.toml` where `nan` and `inf` are valid floats, an editor).
    pub fn number_errors(&self) -> Vec<Diagnostic> {
        let mut values = vec![
            ("feed", self.feed),
            ("sweep_speed", self.sweep_speed),
            ("sweep_height", self.sweep_height),
        ];
        values.extend(self.probe_feed.map(|z| ("probe_feed", z)));
        values
            .into_iter()
            .filter(|(_, v)| !(v.is_finite() && v.abs() <= MAX_MAGNITUDE))
            .map(|(name, v)| {
                Diagnostic::error(
                    Msg::SettingNotFinite,
                    Origin::Options,
                    args![name, v, MAX_MAGNITUDE],
                )
            })
            .collect()
    }
    pub fn probe_feed(&self) -> f64 {
        match self.probe_feed {
            Some(z) if z > 0.0 => z,
            _ => self.feed,
        }
    }
}
