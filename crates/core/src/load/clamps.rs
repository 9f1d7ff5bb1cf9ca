//! `[[clamp]]` in `millpath.toml`: keep-out boxes (clamps, fixtures) the tool must never
//! touch. The check itself is the independent checker's (`millpath_verify::Clamp`), run on
//! every written program (`second_opinion.rs`); here are the settings and their bounds.
//!
//! `[[clamp]]` keep-out boxes of millpath.toml: names (`clamp N`), bounds (≤ 64, finite, `min <
//! max`) located at the file; the check itself is verify's (`clamps.rs`), run on every written
//! program by `second_opinion.rs` (also in the editor's quick check).

use crate::args;
use crate::diag::{Diagnostic, FileRef, Msg, Origin};
use crate::params::{fmt_num, MAX_MAGNITUDE};
use millpath_verify::{Clamp, MAX_CLAMPS};
use serde::Deserialize;
use std::path::PathBuf;

/// One `[[clamp]]`: `name` (default `clamp N`), `min = [x, y, z]`, `max = [x, y, z]` (mm).
#[derive(Debug, Deserialize, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ClampConfig {
    pub name: Option<String>,
    pub min: [f64; 3],
    pub max: [f64; 3],
}

/// The boxes of the file, named (`clamp 1`, `clamp 2`, … where no name is given).
pub fn clamps(list: &[ClampConfig]) -> Vec<Clamp> {
    list.iter()
        .enumerate()
        .map(|(i, c)| Clamp {
            name: c
                .name
                .clone()
                .filter(|n| !n.trim().is_empty())
                .unwrap_or_else(|| format!("clamp {}", i + 1)),
            min: c.min,
            max: c.max,
        })
        .collect()
}

/// Too many boxes, coordinates not finite or beyond ±[`MAX_MAGNITUDE`], `min ≥ max`;
/// located at the settings file (`None`: the editor's or the options' settings).
pub fn errors(clamps: &[Clamp], file: Option<&PathBuf>) -> Vec<Diagnostic> {
    let origin = || match file {
        Some(p) => Origin::File(FileRef::new(p.clone())),
        None => Origin::Options,
    };
    let mut errors = Vec::new();
    if clamps.len() > MAX_CLAMPS {
        errors.push(Diagnostic::error(
            Msg::ClampTooMany,
            origin(),
            args![clamps.len(), MAX_CLAMPS],
        ));
    }
    for (i, c) in clamps.iter().enumerate().take(MAX_CLAMPS) {
        let mut finite = true;
        for (end, values) in [("min", c.min), ("max", c.max)] {
            for (axis, v) in ["x", "y", "z"].iter().zip(values) {
                if !(v.is_finite() && v.abs() <= MAX_MAGNITUDE) {
                    finite = false;
                    let shown = if v.is_finite() {
                        format!("{v:e}")
                    } else {
                        v.to_string()
                    };
                    errors.push(Diagnostic::error(
                        Msg::SettingNotFinite,
                        origin(),
                        args![
                            format!("clamp[{}].{end}.{axis} ({})", i + 1, c.name),
                            shown,
                            MAX_MAGNITUDE
                        ],
                    ));
                }
            }
        }
        if !finite {
            continue;
        }
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            if c.min[k] >= c.max[k] {
                errors.push(Diagnostic::error(
                    Msg::ClampEmpty,
                    origin(),
                    args![c.name, axis, fmt_num(c.min[k]), fmt_num(c.max[k])],
                ));
            }
        }
    }
    errors
}
