//! `compile` writes the program to a temporary file as it generates it (it never holds a
//! long program whole) and renames it into place with the set: the files are those compile
//! wrote before, byte for byte (the text form is core's `compile_file` without staging), no
//! temporary file is left after a success or a refusal, and the probing set's digest is
//! stamped into the staged program.

mod common;

use common::{status_and_text, MACHINE};
use millpath_core::{compile_file, MemFileSystem, Session, Settings};
use std::path::{Path, PathBuf};

/// The files of a folder (hidden ones included), sorted.
fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

const DRAWINGS: [&str; 3] = ["2001.mpath", "2010.mpath", "2020.mpath"];

/// What core's compile gives for a drawing in memory (no staging): (file name, text).
/// `all`: the drawings beside it (a subpath comes from another file).
fn in_memory(name: &str, all: &[(&str, String)], dialect: &str) -> Vec<(String, String)> {
    let mut fs = MemFileSystem::default();
    for (n, text) in all {
        fs.add(PathBuf::from(n), text.as_bytes().to_vec());
    }
    let settings = Settings {
        feed: 150.0,
        sweep_speed: 500.0,
        sweep_height: 15.0,
        dialect: millpath_core::Dialect::from_name(dialect).unwrap(),
        ..Settings::default()
    };
    let mut session = Session::new(settings, &fs).unwrap();
    let outcome = compile_file(&mut session, Path::new(name), &millpath_core::banner());
    assert!(!session.diags.has_errors(), "{:?}", session.diags.list);
    outcome
        .outputs
        .into_iter()
        .map(|o| {
            assert!(o.staged.is_none());
            (o.path.display().to_string(), o.content)
        })
        .collect()
}

#[test]
fn the_staged_files_are_the_texts_and_nothing_is_left_beside_them() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/text");
    let all: Vec<(&str, String)> = DRAWINGS
        .iter()
        .map(|n| (*n, std::fs::read_to_string(root.join(n)).unwrap()))
        .collect();
    for dialect in ["reference", "linuxcnc", "grbl"] {
        for name in DRAWINGS {
            let dir = tempfile::tempdir().unwrap();
            for (n, text) in &all {
                std::fs::write(dir.path().join(n), text).unwrap();
            }
            let mut args = vec!["compile", "--dialect", dialect, name];
            args.extend(MACHINE);
            let (status, out) = status_and_text(dir.path(), &args);
            assert_eq!(status, 0, "{dialect} {name}: {out}");
            let want = in_memory(name, &all, dialect);
            let mut names: Vec<String> = want.iter().map(|(n, _)| n.clone()).collect();
            names.extend(DRAWINGS.map(String::from));
            names.sort();
            // the outputs and the drawing, no temporary file
            assert_eq!(files(dir.path()), names, "{dialect} {name}");
            for (file, content) in &want {
                let written = std::fs::read_to_string(dir.path().join(file)).unwrap();
                assert!(written == *content, "{dialect} {name}: {file} differs");
            }
        }
    }
}

#[test]
fn a_program_refused_after_it_was_staged_leaves_nothing() {
    // the second opinion refuses it once the whole program is written: a clamp on the cut
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("3001.mpath"),
        "path 3001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2 S10\n  end (60, 0)\n  \
         sweep (0, 0) -> (10, 0)\n  mill (10, 0) -> (50, 0)\n  sweep (50, 0) -> (60, 0)\n}\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 100\nsweep_speed = 500\nsweep_height = 10\ndialect = \"linuxcnc\"\n\
         [[clamp]]\nname = \"stop\"\nmin = [29.0, -2.0, -5.0]\nmax = [31.0, 2.0, 5.0]\n",
    )
    .unwrap();
    let (status, out) = status_and_text(dir.path(), &["compile", "3001.mpath"]);
    assert_eq!(status, 1, "{out}");
    assert!(out.contains("'stop'"), "{out}");
    assert_eq!(files(dir.path()), ["3001.mpath", "millpath.toml"]);
}
