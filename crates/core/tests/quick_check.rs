//! The editor's quick check skips the order of fast milling (its chains' passes go level by
//! level in list order): its diagnostics must still be exactly `millpath check`'s, less the
//! second opinion (which the quick check never runs). Held on the examples, every shared
//! drawing and drawings made to fail in the emitter, in every dialect.

mod support;

use millpath_core::diag::{Diagnostic, Msg};
use millpath_core::{compile_file, Dialect, FileSystem, MemFileSystem, OsFileSystem, Session};
use std::path::{Path, PathBuf};
use support::*;

fn diagnostics(fs: &dyn FileSystem, file: &Path, dialect: Dialect, quick: bool) -> Vec<String> {
    let settings = millpath_core::Settings {
        dialect,
        check: true,
        quick_check: quick,
        ..settings()
    };
    let Ok(mut session) = Session::new(settings, fs) else {
        return vec!["settings refused".into()];
    };
    compile_file(&mut session, file, "millpath test");
    session
        .diags
        .list
        .iter()
        .filter(|d| !matches!(d.msg, Msg::SecondOpinion | Msg::ClampHit))
        .map(describe)
        .collect()
}

fn describe(d: &Diagnostic) -> String {
    format!("{:?} {:?} {:?} {:?}", d.severity, d.msg, d.args, d.origin)
}

fn assert_same(fs: &dyn FileSystem, file: &Path) {
    for dialect in [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl] {
        let full = diagnostics(fs, file, dialect, false);
        let quick = diagnostics(fs, file, dialect, true);
        assert_eq!(quick, full, "{} in {dialect:?}", file.display());
    }
}

fn drawings() -> Vec<PathBuf> {
    let root = root();
    let mut files = Vec::new();
    for dir in ["examples/plate", "examples/text"] {
        files.extend(files_in(&root.join(dir), &["dxf", "mpath"]));
    }
    let shared = root.join("../shared");
    if shared.is_dir() {
        files.extend(files_in(&shared.join("conformance/fixtures"), &["dxf"]));
        files.extend(files_in(&shared.join("samples"), &["dxf"]));
    } else {
        eprintln!("../shared is absent: the shared drawings are skipped");
    }
    files
}

#[test]
fn the_quick_check_reports_what_check_reports_on_every_drawing() {
    let files = drawings();
    assert!(files.len() >= 3, "{files:?}");
    for f in &files {
        assert_same(&OsFileSystem, f);
    }
}

/// A zig-zag chain of `n` mill lines with the start text `params`, and extra elements.
fn chain(n: usize, params: &str, extra: &str) -> String {
    let mut s = format!("path 1000.1P {{\n  start (0, 0)  {params}\n  end ({n}, 0)\n{extra}");
    for i in 0..n {
        let (y0, y1) = if i % 2 == 0 { (0, 5) } else { (5, 0) };
        let y1 = if i + 1 == n { 0 } else { y1 };
        s.push_str(&format!("  mill ({i}, {y0}) -> ({}, {y1})\n", i + 1));
    }
    s.push_str("}\n");
    s
}

#[test]
fn the_quick_check_reports_what_check_reports_where_the_emitter_refuses() {
    let cases = [
        // fine: many passes, reversed and forward segments
        chain(400, "O2 T3 I0,1 B-0,2", ""),
        // a value beyond the sane range only in a sum (T + O)
        chain(20, "O9e12 T9e12 I1e12 B0", ""),
        // a missing depth on one segment of the chain
        chain(20, "O2 T3 I1", ""),
        // too many passes for one segment
        chain(20, "O2 T3 I0,000001 B-5", ""),
        // a program beyond two million lines (refused before any pass is emitted)
        chain(400, "O2 T3 I0,0006 B-0,2", ""),
        // 130,000 passes: the quick order's sweeps might reach the bound, so the true order
        // is emitted
        chain(50, "O2 T3 I0,002 B-0,2", ""),
    ];
    for (k, text) in cases.iter().enumerate() {
        let mut fs = MemFileSystem::default();
        fs.add("1000.mpath", text.clone().into_bytes());
        let file = Path::new("1000.mpath");
        assert_same(&fs, file);
        if k == 4 {
            let d = diagnostics(&fs, file, Dialect::LinuxCnc, true);
            assert!(
                d.iter().any(|m| m.contains("TooManyMoves")),
                "case {k}: {d:?}"
            );
        }
    }
}
