//! `millpath.toml`: machine settings found by walking up from the input file.

use millpath_core::Settings;
use serde::Deserialize;
use std::path::{Path, PathBuf};

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
}

pub const FILE_NAME: &str = "millpath.toml";

/// The nearest `millpath.toml` at or above the directory of `input`.
pub fn find(input: &Path) -> Option<PathBuf> {
    let abs = std::fs::canonicalize(input)
        .ok()
        .or_else(|| std::env::current_dir().ok().map(|d| d.join(input)))?;
    let mut dir = abs.parent();
    while let Some(d) = dir {
        let candidate = d.join(FILE_NAME);
        if candidate.is_file() {
            return Some(candidate);
        }
        dir = d.parent();
    }
    None
}

/// Reads and parses a settings file; the error text names the file and the line.
pub fn load(path: &Path) -> Result<FileConfig, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut cfg: FileConfig =
        toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let base = path.parent().unwrap_or(Path::new("."));
    cfg.search_dirs = cfg.search_dirs.iter().map(|d| base.join(d)).collect();
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
            s.lang = millpath_core::Lang::from_name(l);
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn found_by_walking_up_and_relative_dirs_resolved() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join(FILE_NAME), "feed = 150\nsweep_speed = 500\nsweep_height = 15\nsearch_dirs = [\"parts\"]\nrestrictions = [\"L$:L$\"]\n").unwrap();
        let sub = dir.path().join("a/b");
        std::fs::create_dir_all(&sub).unwrap();
        std::fs::write(sub.join("x.dxf"), "").unwrap();
        let found = find(&sub.join("x.dxf")).unwrap();
        let cfg = load(&found).unwrap();
        assert_eq!(cfg.feed, Some(150.0));
        assert!(cfg.search_dirs[0].ends_with("parts"));
        let mut s = Settings::default();
        let mut have = Have::default();
        cfg.apply(&mut s, &mut have);
        assert!(have.feed && have.sweep_speed && have.sweep_height);
        assert_eq!(s.restrictions, vec![("L$".to_string(), "L$".to_string())]);
    }

    #[test]
    fn unknown_keys_and_bad_values_are_errors_with_lines() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join(FILE_NAME);
        std::fs::write(&p, "feed = 150\nfeeed = 3\n").unwrap();
        let e = load(&p).unwrap_err();
        assert!(e.contains("feeed") && e.contains("line 2"), "{e}");
        std::fs::write(&p, "feed = \"fast\"\n").unwrap();
        assert!(load(&p).is_err());
    }
}
