//! The settings of a run from Python: a dict with `millpath.toml`'s keys, read by the same
//! parser as the file (`load::config`), then what the command line adds to it (the post a
//! `post =` names, the machine values compile requires). Plain Rust, no Python types.

use millpath_core::load::config::{self, Have};
use millpath_core::{FileSystem, Lang, MemFileSystem, Settings};
use std::path::{Path, PathBuf};

/// Where the settings are said to come from: messages about them name this file.
pub const SETTINGS_NAME: &str = "millpath.toml";

/// The settings the TOML text `toml_text` gives (`None`: none given), posts read from
/// `files`. `require_machine`: compile's rule, `feed`, `sweep_speed` and `sweep_height` must
/// be given and > 0. The error is the message in the settings' language.
pub fn settings_of(
    toml_text: Option<&str>,
    files: &MemFileSystem,
    require_machine: bool,
) -> Result<Settings, String> {
    let mut s = Settings::default();
    let mut have = Have::default();
    let file = PathBuf::from(SETTINGS_NAME);
    if let Some(text) = toml_text {
        let cfg = config::parse(text, Path::new(""))
            .map_err(|e| format!("settings ({SETTINGS_NAME}): {e}"))?;
        cfg.apply(&mut s, &mut have);
        if let Some(name) = &cfg.post {
            let read = |p: &Path| {
                files
                    .read(p)
                    .map_err(|e| e.to_string())
                    .map(|b| String::from_utf8_lossy(&b).into_owned())
            };
            let (dialect, post) =
                millpath_core::emit::dialect::select_post(name, Path::new(""), &read, s.lang)
                    .map_err(|e| format!("{SETTINGS_NAME}: post: {e}"))?;
            s.dialect = dialect;
            s.post = post;
        }
        s.settings_file = Some(file.clone());
        if cfg.heightmap.is_some() {
            s.heightmap_file = Some(file.clone());
        }
        if !cfg.clamp.is_empty() {
            s.clamps_file = Some(file.clone());
        }
        if cfg.probe_split.is_some() {
            s.probe_split_file = Some(file);
        }
    }
    if require_machine {
        machine_given(&s, have)?;
    }
    Ok(s)
}

/// compile's rule (as the command line's): the machine values given, each a number > 0.
fn machine_given(s: &Settings, have: Have) -> Result<(), String> {
    let de = s.lang == Lang::De;
    let missing: Vec<&str> = [
        ("feed", have.feed),
        ("sweep_speed", have.sweep_speed),
        ("sweep_height", have.sweep_height),
    ]
    .iter()
    .filter(|(_, h)| !h)
    .map(|(n, _)| *n)
    .collect();
    if !missing.is_empty() {
        return Err(if de {
            format!(
                "Maschinenwerte fehlen: {} (in settings angeben)",
                missing.join(", ")
            )
        } else {
            format!(
                "missing machine settings: {} (give them in settings)",
                missing.join(", ")
            )
        });
    }
    s.machine_values_positive()
}
