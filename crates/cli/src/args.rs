//! Command-line argument types shared by several commands, and the settings they give.
//!
//! Options shared by commands (`MachineArgs`, `NameArgs`, formats, languages) and `settings_for`:
//! millpath.toml, then the options.

use crate::config;
use clap::ValueEnum;
use millpath_core::{Lang, Settings};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Clone, Default)]
pub struct MachineArgs {
    /// Feed for milling moves, mm/min (or `feed` in millpath.toml)
    #[arg(long, short = 'f', value_parser = crate::numbers::decimal)]
    pub feed: Option<f64>,
    /// Sweep speed for time estimates, mm/min (or `sweep_speed`)
    #[arg(long, short = 'v', value_parser = crate::numbers::decimal)]
    pub sweep_speed: Option<f64>,
    /// Sweep height of the top-level path, mm (or `sweep_height`)
    #[arg(long, short = 's', value_parser = crate::numbers::decimal)]
    pub sweep_height: Option<f64>,
    /// Probe feed, mm/min (default: the feed)
    #[arg(long, short = 'z', value_parser = crate::numbers::decimal)]
    pub probe_feed: Option<f64>,
    /// Further directory to search for subpaths (repeatable)
    #[arg(long = "search-dir", short = 'd')]
    pub search_dirs: Vec<PathBuf>,
    /// Path-name pattern
    #[arg(long)]
    pub path_pattern: Option<String>,
    /// File-name pattern
    #[arg(long)]
    pub file_pattern: Option<String>,
    /// PARENT:CHILD — paths matching PARENT may only embed subpaths matching CHILD
    #[arg(long = "restrict", short = 'e')]
    pub restrictions: Vec<String>,
    /// Show which element each text matching REGEX was assigned to
    #[arg(long)]
    pub debug_texts: Option<String>,
    /// Message language
    #[arg(long, value_enum)]
    pub lang: Option<LangArg>,
    /// Settings file (default: nearest millpath.toml above the first input)
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Controller the programs are written for (or `dialect`; default reference)
    #[arg(long, value_parser = dialect_parser())]
    pub dialect: Option<millpath_core::Dialect>,
    /// Post that writes the programs: a built-in name (`millpath post list`) or a post file
    /// (or `post` in millpath.toml; over --dialect)
    #[arg(long, value_name = "NAME|FILE")]
    pub post: Option<String>,
    /// Plunge feed in linuxcnc/grbl, mm/min (or `plunge_feed`; default half the feed)
    #[arg(long, value_parser = crate::numbers::decimal)]
    pub plunge_feed: Option<f64>,
    /// Spindle speed in linuxcnc/grbl: M3 S… at the start, M5 at the end (or `spindle_rpm`)
    #[arg(long, value_parser = crate::numbers::decimal)]
    pub spindle_rpm: Option<f64>,
    /// Seconds to wait after the spindle start (or `spindle_dwell`; default 2)
    #[arg(long, value_parser = crate::numbers::decimal)]
    pub spindle_dwell: Option<f64>,
    /// Feed override (percent, 1–1000) the time estimate assumes: the feeds scale, the
    /// rapids and the acceleration phases do not (or `feed_override`; default 100)
    #[arg(long, value_name = "PERCENT", value_parser = crate::numbers::decimal)]
    pub feed_override: Option<f64>,
    /// Read polylines, blocks, line-type names of other CAD programs and $INSUNITS (or
    /// `input = "extended"`; default: as PathDxf2GCode, with a warning for what it ignores)
    #[arg(long)]
    pub extended: bool,
    /// Probe a grid over the cuts with points every STEP mm (or `step` in `[heightmap]`;
    /// linuxcnc and grbl)
    #[arg(long, value_name = "STEP", value_parser = crate::numbers::decimal)]
    pub heightmap_step: Option<f64>,
    /// Margin added around the cuts for the height map, mm (or `margin` in `[heightmap]`;
    /// default 0)
    #[arg(long, value_name = "MM", value_parser = crate::numbers::decimal)]
    pub heightmap_margin: Option<f64>,
    /// With drawn probes, mill moves longer than L mm in pieces, each corrected at its own
    /// start (or `probe_split`; linuxcnc and grbl)
    #[arg(long, value_name = "L", value_parser = crate::numbers::decimal)]
    pub probe_split: Option<f64>,
}

/// The settings the conversions use: path and file names, the message language.
#[derive(clap::Args, Clone, Default)]
pub struct NameArgs {
    /// Path-name pattern
    #[arg(long)]
    pub path_pattern: Option<String>,
    /// File-name pattern
    #[arg(long)]
    pub file_pattern: Option<String>,
    /// Message language
    #[arg(long, value_enum)]
    pub lang: Option<LangArg>,
    /// Settings file (default: nearest millpath.toml above the input)
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Polylines and blocks become plain elements (or `input = "extended"`)
    #[arg(long)]
    pub extended: bool,
}

impl NameArgs {
    pub fn machine(&self) -> MachineArgs {
        MachineArgs {
            path_pattern: self.path_pattern.clone(),
            file_pattern: self.file_pattern.clone(),
            lang: self.lang,
            config: self.config.clone(),
            extended: self.extended,
            ..MachineArgs::default()
        }
    }
}

/// `-o -` means standard output.
pub fn stdout_dash(output: Option<PathBuf>) -> Option<PathBuf> {
    output.filter(|p| p.as_os_str() != "-")
}

pub fn dialect_parser() -> impl clap::builder::TypedValueParser<Value = millpath_core::Dialect> {
    use clap::builder::TypedValueParser;
    let names = millpath_core::Dialect::ALL.map(|d| d.name());
    clap::builder::PossibleValuesParser::new(names)
        .map(|s| millpath_core::Dialect::from_name(&s).unwrap_or_default())
}

#[derive(Clone, Copy, ValueEnum)]
pub enum LangArg {
    En,
    De,
}

#[derive(Clone, Copy, ValueEnum, Default, PartialEq)]
pub enum Format {
    #[default]
    Human,
    Json,
    Github,
    Sarif,
}

#[derive(Clone, Copy, ValueEnum, Default, PartialEq)]
pub enum DialectArg {
    #[default]
    Reference,
    Linuxcnc,
    Grbl,
    // the rs274 family (LinuxCNC, Mach3, UCCNC, Centroid), read as linuxcnc
    Rs274,
    // Marlin firmware on a router
    Marlin,
    // xCAM's exchange format (.NCC files)
    Xcam,
}

#[derive(Clone, Copy, ValueEnum, Default, PartialEq)]
pub enum VerifyFormat {
    #[default]
    Human,
    Json,
}

pub fn to_lang(l: LangArg) -> Lang {
    match l {
        LangArg::En => Lang::En,
        LangArg::De => Lang::De,
    }
}

/// Settings: millpath.toml (nearest above the first input, or --config), then the flags.
pub fn settings_for(
    m: &MachineArgs,
    first_input: Option<&Path>,
    require_machine: bool,
) -> Result<Settings, String> {
    let mut s = Settings::default();
    let mut have = config::Have::default();
    let lang = lang_of(m, first_input);
    let de = lang == Lang::De;
    let cfg_path = m
        .config
        .clone()
        .or_else(|| first_input.and_then(config::find));
    if let Some(p) = cfg_path {
        let cfg = config::load_in(&p, lang)?;
        cfg.apply(&mut s, &mut have);
        if let Some(name) = &cfg.post {
            let at = format!("{}: post", p.display());
            select_post(&mut s, name, &cfg.base_dir, lang).map_err(|e| format!("{at}: {e}"))?;
        }
        s.settings_file = Some(p.clone());
        if cfg.heightmap.is_some() {
            s.heightmap_file = Some(p.clone());
        }
        if !cfg.clamp.is_empty() {
            s.clamps_file = Some(p.clone());
        }
        if cfg.probe_split.is_some() {
            s.probe_split_file = Some(p);
        }
    }
    heightmap_options(m, &mut s, de)?;
    // the settings the options give: their errors are located there, not at millpath.toml
    for (key, given) in [
        ("feed", m.feed.is_some()),
        ("sweep_speed", m.sweep_speed.is_some()),
        ("sweep_height", m.sweep_height.is_some()),
        ("probe_feed", m.probe_feed.is_some()),
        ("plunge_feed", m.plunge_feed.is_some()),
        ("spindle_rpm", m.spindle_rpm.is_some()),
        ("spindle_dwell", m.spindle_dwell.is_some()),
        ("feed_override", m.feed_override.is_some()),
    ] {
        if given {
            s.option_keys.push(key);
        }
    }
    if let Some(v) = m.feed {
        s.feed = v;
        have.feed = true;
    }
    if let Some(v) = m.sweep_speed {
        s.sweep_speed = v;
        have.sweep_speed = true;
    }
    if let Some(v) = m.sweep_height {
        s.sweep_height = v;
        have.sweep_height = true;
    }
    if m.probe_feed.is_some() {
        s.probe_feed = m.probe_feed;
    }
    if m.probe_split.is_some() {
        s.probe_split = m.probe_split;
        s.probe_split_file = None;
    }
    s.search_dirs.extend(m.search_dirs.iter().cloned());
    if let Some(p) = &m.path_pattern {
        s.path_pattern = p.clone();
    }
    if let Some(p) = &m.file_pattern {
        s.file_pattern = p.clone();
    }
    for r in &m.restrictions {
        let (a, b) = r.split_once(':').ok_or_else(|| {
            if de {
                format!("--restrict {r}: Form PARENT:CHILD erwartet")
            } else {
                format!("--restrict {r}: expected PARENT:CHILD")
            }
        })?;
        s.restrictions.push((a.to_string(), b.to_string()));
    }
    s.debug_pattern = m.debug_texts.clone();
    if let Some(d) = m.dialect {
        s.dialect = d;
        s.post = None;
    }
    if let Some(name) = &m.post {
        select_post(&mut s, name, Path::new(""), lang).map_err(|e| format!("--post: {e}"))?;
        // its errors are located at the option
        s.option_keys.push("post");
    }
    if m.plunge_feed.is_some() {
        s.plunge_feed = m.plunge_feed;
    }
    if m.spindle_rpm.is_some() {
        s.spindle_rpm = m.spindle_rpm;
    }
    if let Some(v) = m.spindle_dwell {
        s.spindle_dwell = v;
    }
    if let Some(v) = m.feed_override {
        s.feed_override = v;
    }
    if let Some(l) = m.lang {
        s.lang = to_lang(l);
    }
    if m.extended {
        s.input = millpath_core::InputMode::Extended;
    }
    if require_machine {
        let missing: Vec<&str> = [
            ("--feed / feed", have.feed),
            ("--sweep-speed / sweep_speed", have.sweep_speed),
            ("--sweep-height / sweep_height", have.sweep_height),
        ]
        .iter()
        .filter(|(_, h)| !h)
        .map(|(n, _)| *n)
        .collect();
        if !missing.is_empty() {
            return Err(match s.lang {
                Lang::En => format!(
                    "missing machine settings: {} (give them as options or in millpath.toml)",
                    missing.join(", ")
                ),
                Lang::De => format!(
                    "Maschinenwerte fehlen: {} (als Option oder in millpath.toml angeben)",
                    missing.join(", ")
                ),
            });
        }
        s.machine_values_positive()?;
    }
    Ok(s)
}

/// Sets the dialect and post `name` selects (a built-in's name, or a file relative to `base`).
fn select_post(s: &mut Settings, name: &str, base: &Path, lang: Lang) -> Result<(), String> {
    let read = |p: &Path| std::fs::read_to_string(p).map_err(|e| e.to_string());
    let (dialect, post) = millpath_core::emit::dialect::select_post(name, base, &read, lang)?;
    s.dialect = dialect;
    s.post = post;
    Ok(())
}

/// `--heightmap-step` and `--heightmap-margin` over the `[heightmap]` of the settings file; a
/// margin alone has no grid to widen.
fn heightmap_options(m: &MachineArgs, s: &mut Settings, de: bool) -> Result<(), String> {
    if s.override_heightmap(m.heightmap_step, m.heightmap_margin) {
        return Ok(());
    }
    Err(if de {
        "--heightmap-margin braucht --heightmap-step oder eine [heightmap] in millpath.toml".into()
    } else {
        "--heightmap-margin needs --heightmap-step or a [heightmap] in millpath.toml".into()
    })
}

/// The message language, known before the first message: `--lang`, else `lang` of the
/// settings file the command reads (`--config`, or the nearest millpath.toml of the first
/// input) even when that file has other errors, else English.
pub fn lang_for(flag: Option<LangArg>, config: Option<&Path>, first_input: Option<&Path>) -> Lang {
    if let Some(l) = flag {
        return to_lang(l);
    }
    config
        .map(Path::to_path_buf)
        .or_else(|| first_input.and_then(config::find_for))
        .and_then(|p| config::lang_in(&p))
        .unwrap_or_default()
}

pub fn lang_of(m: &MachineArgs, first_input: Option<&Path>) -> Lang {
    lang_for(m.lang, m.config.as_deref(), first_input)
}

pub fn patterns_for(
    m: &MachineArgs,
    input: &Path,
) -> Result<(std::sync::Arc<millpath_core::load::names::Patterns>, Lang), String> {
    let s = settings_for(m, Some(input), false)?;
    let p = millpath_core::load::names::Patterns::shared(&s.path_pattern, &s.file_pattern)
        .map_err(|(c, p, e)| match s.lang {
            Lang::En => format!("invalid /{c} pattern '{p}': {e}"),
            Lang::De => format!("ungültiges /{c}-Muster '{p}': {e}"),
        })?;
    Ok((p, s.lang))
}
