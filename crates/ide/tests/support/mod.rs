//! Helpers shared by the in-process editor tests.
#![allow(dead_code)]

use millpath_ide::Workspace;
use std::path::{Path, PathBuf};

/// A temporary workspace folder with machine settings and the given text files.
pub fn workspace(files: &[(&str, &str)]) -> (tempfile::TempDir, Workspace) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n",
    )
    .unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let ws = Workspace {
        roots: vec![dir.path().to_path_buf()],
        ..Workspace::default()
    };
    (dir, ws)
}

/// The byte offset of `needle` in `src`.
pub fn at(src: &str, needle: &str) -> usize {
    src.find(needle).unwrap_or_else(|| panic!("{needle}"))
}

pub fn p(dir: &Path, f: &str) -> PathBuf {
    dir.join(f)
}
