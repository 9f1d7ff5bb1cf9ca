//! A subpath file embedded by several top-level files is read and parsed once per process
//! while it is unchanged, and again as soon as it changes.

mod support;

use millpath_core::load::parse_cache::FileStamp;
use millpath_core::{compile_file, FileSystem, OsFileSystem, Session, Settings};
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use support::*;

/// The disk, counting reads per file.
#[derive(Default)]
struct CountingFs {
    reads: RefCell<HashMap<PathBuf, usize>>,
}

impl CountingFs {
    fn reads_of(&self, p: &Path) -> usize {
        self.reads.borrow().get(p).copied().unwrap_or(0)
    }
}

impl FileSystem for CountingFs {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        *self
            .reads
            .borrow_mut()
            .entry(path.to_path_buf())
            .or_default() += 1;
        OsFileSystem.read(path)
    }
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        OsFileSystem.list_dir(dir)
    }
    fn is_dir(&self, dir: &Path) -> bool {
        OsFileSystem.is_dir(dir)
    }
    fn stamp(&self, path: &Path) -> Option<FileStamp> {
        OsFileSystem.stamp(path)
    }
}

fn part(bottom: &str) -> String {
    let mut d = Drawing::new();
    let l = "2000_1P";
    d.start(l, (0.0, 0.0), &format!("O2 T2 M20x2 I2 B{bottom}"))
        .end(l, (20.0, 0.0))
        .line(l, "CONTINUOUS", (0.0, 0.0), (20.0, 0.0), "");
    d.dxf()
}

fn project(layer: &str) -> String {
    let mut d = Drawing::new();
    d.start(layer, (0.0, 0.0), "O2 T2 M20x2 I2 B0")
        .end(layer, (30.0, 0.0))
        .line(layer, "DASHED", (0.0, 0.0), (10.0, 0.0), "")
        .line(layer, "DASHDOT", (10.0, 0.0), (30.0, 0.0), ">2000.1P");
    d.dxf()
}

/// `check` of one top-level file in its own session.
fn check(fs: &CountingFs, top: &Path) -> Vec<String> {
    check_as(fs, top, false)
}

/// [`check`]; `one_file`: as the command line does (the session serves this file only).
fn check_as(fs: &CountingFs, top: &Path, one_file: bool) -> Vec<String> {
    let settings = Settings {
        check: true,
        ..settings()
    };
    let mut s = Session::new(settings, fs).expect("settings");
    s.one_file = one_file;
    compile_file(&mut s, top, "test");
    s.diags
        .list
        .iter()
        .map(|d| d.message(Default::default()))
        .collect()
}

#[test]
fn a_subpath_file_is_parsed_once_until_it_changes() {
    let dir = tempfile::tempdir().unwrap();
    let part_file = dir.path().join("2000.dxf");
    std::fs::write(&part_file, part("0")).unwrap();
    let tops: Vec<PathBuf> = (1..=3)
        .map(|i| {
            let f = dir.path().join(format!("100{i}.1P.dxf"));
            std::fs::write(&f, project(&format!("100{i}_1P"))).unwrap();
            f
        })
        .collect();
    let fs = CountingFs::default();
    for top in &tops {
        assert_eq!(check(&fs, top), Vec::<String>::new());
    }
    assert_eq!(fs.reads_of(&part_file), 1, "{:?}", fs.reads.borrow());
    // checking the same files again reads nothing
    check(&fs, &tops[0]);
    assert_eq!(fs.reads_of(&tops[0]), 1);
    assert_eq!(fs.reads_of(&part_file), 1);

    // an edit (other length, so even a coarse clock sees it) is read again and counts
    std::fs::write(&part_file, part("3")).unwrap();
    let after = check(&fs, &tops[1]);
    assert_eq!(fs.reads_of(&part_file), 2);
    assert!(
        after.iter().any(|m| m.contains("B=3")),
        "the edited part's error must show: {after:?}"
    );
}

/// One chain of `n` segments as a text drawing.
fn long_chain(n: usize) -> String {
    let mut s = format!("path 3000.1P {{\n  start (0, 0)  O2 T2 I1,2 B-0,3\n  end ({n}, 0)\n");
    for i in 0..n {
        s.push_str(&format!("  mill ({i}, 0) -> ({}, 0)\n", i + 1));
    }
    s.push_str("}\n");
    s
}

/// A drawing too long to be a library that many files embed is not kept after the command
/// line's check of it (its parse would stay beside its model for the rest of the run); a
/// short one is, and so is a long one an editor's sessions read.
#[test]
fn a_drawing_beyond_the_kept_size_is_read_again() {
    use millpath_core::load::parse_cache::MAX_KEPT_SEGMENTS;
    let dir = tempfile::tempdir().unwrap();
    let long = dir.path().join("3000.mpath");
    std::fs::write(&long, long_chain(MAX_KEPT_SEGMENTS + 1)).unwrap();
    let short = dir.path().join("3100.mpath");
    std::fs::write(&short, long_chain(10).replace("3000.1P", "3100.1P")).unwrap();
    let fs = CountingFs::default();
    for _ in 0..2 {
        assert_eq!(check_as(&fs, &long, true), Vec::<String>::new());
        assert_eq!(check_as(&fs, &short, true), Vec::<String>::new());
    }
    assert_eq!(fs.reads_of(&long), 2, "read at each check");
    assert_eq!(fs.reads_of(&short), 1, "kept");
    for _ in 0..2 {
        assert_eq!(check(&fs, &long), Vec::<String>::new());
    }
    assert_eq!(fs.reads_of(&long), 3, "kept for sessions of many files");
}
