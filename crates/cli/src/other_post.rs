//! A post change leaves no program of the earlier post beside the new one (issue 32):
//! compiling with `post = "xcam"` after `linuxcnc` writes `NAME_Milling.NCC`, and the old
//! `NAME_Milling.gcode` would still look current to an operator. Each `NAME_Milling.EXT`
//! of the same drawing with another extension is
//! - removed, with a warning, when it is provably a program compile wrote for this drawing
//!   (millpath's banner and the drawing's file name in its first lines) and holds no
//!   measurements;
//! - kept, with a warning at its line, when it holds measured heights (an adjusted program:
//!   a set digest, `MILLPATH-PROBES` or `MILLPATH-SURFACE`): nothing the user made is lost;
//! - left alone otherwise (not provably ours: a file of the user's own).

use millpath_core::diag::{Diagnostic, FileRef, Msg, Origin};
use millpath_core::probe::adjustz;
use std::path::{Path, PathBuf};

/// Lines read from the head of a program: the banner, the file name and the records an
/// adjusted program carries after the stock comment.
const HEAD_LINES: usize = 24;

/// What to do with a program of another post.
pub enum Found {
    /// Remove the file and report the warning.
    Stale(PathBuf, Diagnostic),
    /// Keep it; report the warning.
    Measured(Diagnostic),
}

/// The programs `PREFIX_Milling.EXT` of other posts beside `written` (`None`: this compile
/// wrote no milling program), except those with an extension in `skip` (handled by their
/// own rules). `drawing`: the drawing's file name. The caller removes the stale ones.
pub fn find(prefix: &Path, drawing: &str, written: Option<&Path>, skip: &[&str]) -> Vec<Found> {
    let wrote = written
        .and_then(Path::file_name)
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let now = if wrote.is_empty() {
        "—".to_string()
    } else {
        wrote.clone()
    };
    let mut found = Vec::new();
    for path in candidates(prefix) {
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        let ext = name.rsplit('.').next().unwrap_or_default();
        if name.eq_ignore_ascii_case(&wrote) || skip.iter().any(|s| s.eq_ignore_ascii_case(ext)) {
            continue;
        }
        let head = millpath_core::stage::file_head(&path, HEAD_LINES);
        if !is_ours(&head, drawing) {
            continue;
        }
        let args = millpath_core::args![path.display(), now];
        found.push(match measured_line(&head) {
            Some(line) => Found::Measured(Diagnostic::warning(
                Msg::OtherPostProgramKept,
                Origin::FileLine {
                    file: path.display().to_string().into(),
                    line,
                },
                args,
            )),
            None => Found::Stale(
                path.clone(),
                Diagnostic::warning(
                    Msg::OtherPostProgramRemoved,
                    Origin::File(FileRef::new(path.clone())),
                    args,
                ),
            ),
        });
    }
    found
}

/// Files named `PREFIX_Milling.EXT` (one extension of letters and digits), sorted.
fn candidates(prefix: &Path) -> Vec<PathBuf> {
    let Some(stem) = prefix
        .file_name()
        .map(|s| format!("{}_Milling.", s.to_string_lossy()))
    else {
        return Vec::new();
    };
    let dir = match prefix.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Vec::new();
    };
    let mut found: Vec<PathBuf> = entries
        .filter_map(Result::ok)
        .filter(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name.strip_prefix(&stem).is_some_and(|ext| {
                !ext.is_empty() && ext.len() <= 16 && ext.bytes().all(|b| b.is_ascii_alphanumeric())
            })
        })
        .map(|e| prefix.with_file_name(e.file_name()))
        .collect();
    found.sort();
    found
}

/// Written by millpath's compile for this drawing: the banner and the drawing's file name
/// among its first lines (every post writes both as comments).
fn is_ours(head: &str, drawing: &str) -> bool {
    let lines: Vec<&str> = head.lines().take(4).collect();
    lines.iter().any(|l| l.contains("millpath V."))
        && !drawing.is_empty()
        && lines.iter().any(|l| l.contains(drawing))
}

/// The 1-based line that shows measured heights: a set digest (a program adjusted from a
/// probing set), the measured probes or the measured surface.
fn measured_line(head: &str) -> Option<usize> {
    if adjustz::stored_digest(head).is_some() {
        return Some(millpath_core::digest::banner_index(head) + 1);
    }
    head.lines()
        .position(|l| l.contains("MILLPATH-PROBES") || l.contains("MILLPATH-SURFACE"))
        .map(|i| i + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ours_and_measured_are_read_from_the_head() {
        let plain = "%\n(millpath V.0.1.0)\n(2001.mpath)\nG0 Z5\n";
        assert!(is_ours(plain, "2001.mpath"));
        assert!(!is_ours(plain, "2002.mpath"));
        assert!(!is_ours("(my own)\n(2001.mpath)\n", "2001.mpath"));
        assert_eq!(measured_line(plain), None);
        let adjusted = "%\n(millpath V.0.1.0 set=0123456789abcdef)\n(2001.mpath)\n";
        assert_eq!(measured_line(adjusted), Some(2));
        let surface = "(millpath V.0.1.0)\n(2001.mpath)\n(MILLPATH-STOCK T=2)\n(MILLPATH-SURFACE T=2.000 NX=3 NY=2)\n";
        assert_eq!(measured_line(surface), Some(4));
    }
}
