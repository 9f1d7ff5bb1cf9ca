//! The drawings below the workspace folders, found by a bounded walk (as `check .` walks):
//! each folder and file once by its canonical path (symbolic link loops), at most
//! [`MAX_DEPTH`] levels and [`MAX_FILES`] files; hidden folders and `target` skipped.

use millpath_core::load::fs::is_text_file;
use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// Folder levels below a workspace folder that are searched at most.
pub const MAX_DEPTH: usize = 64;
/// Drawings taken at most (a workspace larger than this is cut, in walk order).
pub const MAX_FILES: usize = 20_000;

/// The drawings found, sorted per folder; `truncated` when [`MAX_FILES`] cut the walk.
#[derive(Debug, Default)]
pub struct Walk {
    pub files: Vec<PathBuf>,
    pub truncated: bool,
}

/// Text files and DXF drawings below `roots`.
pub fn drawing_files(roots: &[PathBuf]) -> Walk {
    let mut w = Walk::default();
    let mut seen = Seen::default();
    for r in roots {
        walk(r, &mut w, &mut seen, 0);
    }
    w
}

pub(crate) fn is_drawing(p: &Path) -> bool {
    is_text_file(p) || p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dxf"))
}

#[derive(Default)]
struct Seen {
    dirs: HashSet<PathBuf>,
    files: HashSet<PathBuf>,
}

fn walk(dir: &Path, w: &mut Walk, seen: &mut Seen, depth: usize) {
    if depth > MAX_DEPTH || w.truncated {
        return;
    }
    let canonical = std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
    if !seen.dirs.insert(canonical) {
        return;
    }
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for e in entries {
        let hidden = e
            .file_name()
            .is_some_and(|n| n.to_string_lossy().starts_with('.') || n == "target");
        if e.is_dir() {
            if !hidden {
                walk(&e, w, seen, depth + 1);
            }
        } else if is_drawing(&e) {
            let key = std::fs::canonicalize(&e).unwrap_or_else(|_| e.clone());
            if !seen.files.insert(key) {
                continue;
            }
            if w.files.len() >= MAX_FILES {
                w.truncated = true;
                return;
            }
            w.files.push(e);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn a_symlink_loop_gives_each_drawing_once() {
        let d = tempfile::tempdir().unwrap();
        let sub = d.path().join("sub");
        std::fs::create_dir(&sub).unwrap();
        std::fs::write(sub.join("a.mpath"), "").unwrap();
        std::fs::write(sub.join("b.DXF"), "").unwrap();
        std::fs::write(sub.join("c.txt"), "").unwrap();
        std::os::unix::fs::symlink(d.path(), sub.join("loop")).unwrap();
        std::os::unix::fs::symlink(sub.join("a.mpath"), d.path().join("link.mpath")).unwrap();
        let w = drawing_files(&[d.path().to_path_buf()]);
        assert_eq!(w.files.len(), 2, "{:?}", w.files);
        assert!(!w.truncated);
    }
}
