//! Which files a command works on.
//!
//! Which files a command works on (folders searched once each by canonical path: symlink loops, ≤
//! 64 levels; `.dxf` completion, conversion inputs).

use crate::args::{patterns_for, MachineArgs};
use crate::report;
use millpath_core::complete_input;
use millpath_core::diag::{Diagnostic, Msg, Origin};
use millpath_core::Lang;
use std::path::{Path, PathBuf};

/// The files `compile` compiles: a folder gives every drawing below it (never `folder.dxf`);
/// a name without extension gets `.dxf` as in the reference.
pub fn compile_inputs(files: &[String]) -> Result<Vec<PathBuf>, String> {
    let mut inputs = Vec::new();
    for f in files {
        let p = Path::new(f);
        if p.is_dir() {
            let before = inputs.len();
            collect_files(&[p.to_path_buf()], is_drawing, &mut inputs);
            if inputs.len() == before {
                return Err(f.clone());
            }
        } else {
            inputs.push(complete_input(f));
        }
    }
    Ok(inputs)
}

/// Folders below a given one that are searched at most (a bound for any tree).
const MAX_DEPTH: usize = 64;

/// Files given, and below directories given the files `accept` takes, sorted. Each folder
/// and each file found in one is taken once, by its canonical path: a symbolic link back
/// to a folder above (a loop) or beside is no error and reads nothing twice.
pub fn collect_files(paths: &[PathBuf], accept: fn(&Path) -> bool, out: &mut Vec<PathBuf>) {
    let mut seen = Seen::default();
    for p in paths {
        if p.is_dir() {
            walk(p, accept, out, &mut seen, 0);
        } else {
            out.push(p.clone());
        }
    }
}

#[derive(Default)]
struct Seen {
    dirs: std::collections::HashSet<PathBuf>,
    files: std::collections::HashSet<PathBuf>,
}

fn walk(
    dir: &Path,
    accept: fn(&Path) -> bool,
    out: &mut Vec<PathBuf>,
    seen: &mut Seen,
    depth: usize,
) {
    let canonical = dunce::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
    if depth > MAX_DEPTH || !seen.dirs.insert(canonical) {
        return;
    }
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|r| r.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    entries.sort();
    let (dirs, files): (Vec<PathBuf>, Vec<PathBuf>) = entries.into_iter().partition(|e| e.is_dir());
    for f in files.into_iter().filter(|f| accept(f)) {
        let key = dunce::canonicalize(&f).unwrap_or_else(|_| f.clone());
        if seen.files.insert(key) {
            out.push(f);
        }
    }
    for d in &dirs {
        walk(d, accept, out, seen, depth + 1);
    }
}

pub fn is_drawing(f: &Path) -> bool {
    f.extension().is_some_and(|e| e.eq_ignore_ascii_case("dxf"))
        || millpath_core::load::fs::is_text_file(f)
}

/// Settings, patterns and the input bytes of a conversion; `Err(exit status)` after reporting.
pub fn conversion_input(
    file: &Path,
    m: &MachineArgs,
) -> Result<
    (
        std::sync::Arc<millpath_core::load::names::Patterns>,
        Lang,
        Vec<u8>,
    ),
    u8,
> {
    let (patterns, lang) = patterns_for(m, file).map_err(|e| {
        let lang = crate::args::lang_of(m, Some(file));
        eprintln!(
            "{}: {e}",
            report::severity_word(millpath_core::diag::Severity::Error, lang)
        );
        2
    })?;
    let bytes = std::fs::read(file).map_err(|e| {
        let d = Diagnostic::error(
            Msg::CannotRead,
            Origin::Input,
            millpath_core::args![file.display(), e],
        );
        eprintln!("{}", report::human(&d, lang));
        1
    })?;
    Ok((patterns, lang, bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn a_symlink_loop_gives_each_file_once() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::create_dir(d.join("sub")).unwrap();
        std::fs::write(d.join("a.mpath"), "").unwrap();
        std::fs::write(d.join("sub/b.dxf"), "").unwrap();
        std::os::unix::fs::symlink(d, d.join("sub/loop")).unwrap();
        std::os::unix::fs::symlink(d.join("sub"), d.join("twin")).unwrap();
        std::os::unix::fs::symlink(d.join("a.mpath"), d.join("sub/same.mpath")).unwrap();
        let mut out = Vec::new();
        collect_files(&[d.to_path_buf()], is_drawing, &mut out);
        assert_eq!(out, vec![d.join("a.mpath"), d.join("sub/b.dxf")]);
    }

    #[test]
    fn deep_trees_are_bounded() {
        let dir = tempfile::tempdir().unwrap();
        let mut p = dir.path().to_path_buf();
        for _ in 0..(MAX_DEPTH + 5) {
            p.push("d");
        }
        std::fs::create_dir_all(&p).unwrap();
        std::fs::write(p.join("deep.mpath"), "").unwrap();
        std::fs::write(dir.path().join("top.mpath"), "").unwrap();
        let mut out = Vec::new();
        collect_files(&[dir.path().to_path_buf()], is_drawing, &mut out);
        assert_eq!(out, vec![dir.path().join("top.mpath")]);
    }
}
