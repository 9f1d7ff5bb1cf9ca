//! Every output byte of every shared drawing and every example stays as it was: a digest of
//! what each file and each of its paths compiles to (G-code of every path, compile outputs,
//! diagnostics, check statistics) is compared with `output_digests.txt`. Restructuring the
//! compiler must not change a byte; an intended change of output regenerates the table with
//! `MILLPATH_UPDATE_DIGESTS=1 cargo test -p millpath-core --test output_digests` and shows up
//! in review as a changed line per drawing.

use millpath_core::diag::Lang;
use millpath_core::emit::{generate, Output};
use millpath_core::{compile_file, OsFileSystem, Session, Settings};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// FNV-1a, 64 bit: stable across platforms and Rust versions (std's hasher is not promised to be).
/// Messages name files by the path given, which holds the checkout's folder: that part is
/// replaced, so the table holds wherever the repository is cloned.
fn fnv(data: &str) -> u64 {
    let data = data.replace(&*root().to_string_lossy(), "<root>");
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in data.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// (label, file): the examples always, the shared drawings when ../shared is there.
fn drawings() -> (Vec<(String, PathBuf)>, bool) {
    let mut v = Vec::new();
    for dir in ["examples/plate", "examples/text"] {
        let mut files: Vec<PathBuf> = std::fs::read_dir(root().join(dir))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| {
                p.extension()
                    .is_some_and(|e| e.eq_ignore_ascii_case("dxf") || e == "mpath")
            })
            .collect();
        files.sort();
        for f in files {
            v.push((
                format!("{dir}/{}", f.file_name().unwrap().to_string_lossy()),
                f,
            ));
        }
    }
    let shared = root().join("../shared");
    let present = shared.join("conformance/fixtures").is_dir();
    if present {
        for dir in ["conformance/fixtures", "samples"] {
            let mut files: Vec<PathBuf> = std::fs::read_dir(shared.join(dir))
                .unwrap()
                .map(|e| e.unwrap().path())
                .collect();
            files.sort();
            for f in files {
                let name = f.file_name().unwrap().to_string_lossy().into_owned();
                v.push((format!("shared/{dir}/{name}"), f));
            }
        }
    } else {
        eprintln!("../shared is absent: only the examples are compared");
    }
    (v, present)
}

fn settings(check: bool) -> Settings {
    Settings {
        check,
        ..Settings::default()
    }
}

/// Digest lines of one drawing: every path's G-code, the file's compile, its check.
fn digests(label: &str, file: &Path, out: &mut BTreeMap<String, String>) {
    let fs = OsFileSystem;
    // every path alone, through the library (multi-path files cannot be compiled whole)
    let mut s = Session::new(settings(false), &fs).unwrap();
    let mut names = s.load_file(file);
    names.sort();
    for name in names {
        let text = match s.build_top(&name) {
            Err(d) => format!("abort {}", d.message(Lang::En)),
            Ok(None) => "none".to_string(),
            Ok(Some(model)) => {
                let fname = file.file_name().unwrap().to_string_lossy();
                match generate(&model, &fname, "digest", 500.0, Lang::En) {
                    Err(e) => format!(
                        "{:?}",
                        e.iter().map(|d| d.message(Lang::En)).collect::<Vec<_>>()
                    ),
                    Ok(g) => match g.output {
                        Output::Milling(m) => m,
                        Output::Probing {
                            probing,
                            z_txt,
                            clean,
                        } => {
                            format!("{probing}\u{0}{z_txt}\u{0}{clean}")
                        }
                    },
                }
            }
        };
        out.insert(
            format!("{label} path {name}"),
            format!("{:016x}", fnv(&text)),
        );
    }
    // the file as `compile` sees it
    let mut s = Session::new(settings(false), &fs).unwrap();
    let outcome = compile_file(&mut s, file, "digest");
    let mut text = String::new();
    for o in &outcome.outputs {
        let _ = write!(
            text,
            "{}\u{0}{}\u{0}",
            o.path.file_name().unwrap().to_string_lossy(),
            o.content
        );
    }
    for d in &s.diags.list {
        let _ = writeln!(text, "{}", d.message(Lang::En));
    }
    out.insert(format!("{label} compile"), format!("{:016x}", fnv(&text)));
    // and as `check` sees it
    let mut s = Session::new(settings(true), &fs).unwrap();
    let outcome = compile_file(&mut s, file, "digest");
    let mut text = String::new();
    for (name, st) in &outcome.stats {
        let _ = writeln!(text, "{name} {:?}", st.lines(Lang::En));
    }
    for d in &s.diags.list {
        let _ = writeln!(text, "{}", d.message(Lang::En));
    }
    out.insert(format!("{label} check"), format!("{:016x}", fnv(&text)));
}

#[test]
fn outputs_are_unchanged() {
    let (files, shared_present) = drawings();
    let mut now = BTreeMap::new();
    for (label, f) in &files {
        digests(label, f, &mut now);
    }
    let table = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/output_digests.txt");
    if std::env::var_os("MILLPATH_UPDATE_DIGESTS").is_some() {
        assert!(shared_present, "regenerate only with ../shared present");
        let text: String = now.iter().map(|(k, v)| format!("{k}\t{v}\n")).collect();
        std::fs::write(&table, text).unwrap();
        return;
    }
    let expected: BTreeMap<String, String> = std::fs::read_to_string(&table)
        .unwrap()
        .lines()
        .filter_map(|l| l.split_once('\t'))
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .filter(|(k, _)| shared_present || !k.starts_with("shared/"))
        .collect();
    assert!(expected.len() > 10, "table too small: {}", expected.len());
    let changed: Vec<&String> = expected
        .keys()
        .chain(now.keys())
        .filter(|k| expected.get(*k) != now.get(*k))
        .collect();
    assert!(changed.is_empty(), "outputs changed: {changed:#?}");
}
