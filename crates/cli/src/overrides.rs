//! The command line's machine options as settings over each file's own `millpath.toml`, for
//! commands that compile through the editor's workspace (`diff`): the workspace reads every
//! version's `millpath.toml` itself (a git revision's from that revision) and puts these on
//! top, as it puts an editor's settings. `--config FILE` is the first layer of them.

use crate::args::MachineArgs;
use crate::config;
use millpath_core::load::config::FileConfig;
use millpath_core::{InputMode, Lang};
use millpath_history::Options;
use std::path::{Path, PathBuf};

/// The settings the options give; `None` when none is given (each file's own settings
/// alone). `--heightmap-step` and `--heightmap-margin` go over each version's own
/// `[heightmap]` as `compile` takes them (the step keeps its other keys, a margin alone
/// widens its grid).
pub fn overrides(m: &MachineArgs, lang: Lang) -> Result<Option<Options>, String> {
    let cwd = std::env::current_dir().unwrap_or_default();
    let mut c = match &m.config {
        Some(p) => {
            let mut c = config::load_in(p, lang)?;
            c.base_dir = absolute(&cwd, &c.base_dir);
            c.search_dirs = c.search_dirs.iter().map(|d| absolute(&cwd, d)).collect();
            c
        }
        None => FileConfig {
            base_dir: cwd.clone(),
            ..FileConfig::default()
        },
    };
    let given = m.config.is_some();
    let mut any = given;
    let mut set = |slot: &mut Option<f64>, v: Option<f64>| {
        if v.is_some() {
            *slot = v;
            any = true;
        }
    };
    set(&mut c.feed, m.feed);
    set(&mut c.sweep_speed, m.sweep_speed);
    set(&mut c.sweep_height, m.sweep_height);
    set(&mut c.probe_feed, m.probe_feed);
    set(&mut c.plunge_feed, m.plunge_feed);
    set(&mut c.spindle_rpm, m.spindle_rpm);
    set(&mut c.spindle_dwell, m.spindle_dwell);
    set(&mut c.feed_override, m.feed_override);
    set(&mut c.probe_split, m.probe_split);
    if let Some(d) = m.dialect {
        // the option's dialect over a `post` of the --config file, as in settings_for
        c.dialect = Some(d);
        c.post = None;
        any = true;
    }
    if let Some(p) = &m.post {
        c.post = Some(p.clone());
        c.base_dir = cwd.clone();
        any = true;
    }
    if m.extended {
        c.input = Some(InputMode::Extended);
        any = true;
    }
    let heightmap = (m.heightmap_step, m.heightmap_margin);
    any |= heightmap != (None, None);
    if !m.search_dirs.is_empty() {
        c.search_dirs
            .extend(m.search_dirs.iter().map(|d| absolute(&cwd, d)));
        any = true;
    }
    if m.path_pattern.is_some() || m.file_pattern.is_some() || !m.restrictions.is_empty() {
        c.path_pattern = m.path_pattern.clone().or(c.path_pattern);
        c.file_pattern = m.file_pattern.clone().or(c.file_pattern);
        c.restrictions.extend(m.restrictions.iter().cloned());
        any = true;
    }
    Ok(any.then_some(Options {
        config: c,
        heightmap,
    }))
}

fn absolute(base: &Path, p: &Path) -> PathBuf {
    if p.is_absolute() {
        p.to_path_buf()
    } else {
        base.join(p)
    }
}
