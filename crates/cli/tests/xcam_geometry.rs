//! The xcam post's geometry (issue 32): every example and every shared drawing is compiled
//! with `--post xcam` and with `--post linuxcnc`; each `.NCC` file's cutting geometry is
//! rebuilt from its contours (each `G0` start, its `G1` plunges and lines and `G5` arcs) and
//! drillings (`B`: the point and `Z - TI`) and compared with the linuxcnc program's cutting
//! moves: its passes (runs of `G01`/`G02`/`G03` moves between rapids, each from the point the
//! tool stood at) and its drill elements' plunges. Every point, end and
//! arc centre agrees within 0.001 mm, arcs turn the same way, and nothing is left over on
//! either side. Drawings with probes are refused by xcam (MP207) and counted apart.
//!
//! The examples always run; the shared drawings are skipped with a message when `../shared`
//! is absent. The reading of both files here is the test's own (not verify's NCC reader).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

mod common;

use common::millpath;

const TOLERANCE: f64 = 0.001;

/// What the shared drawings need (the examples bring their own millpath.toml).
const SHARED_BASE: &str = "feed = 300\nsweep_speed = 1000\nsweep_height = 25\n";

/// Drawings with several path layers, compiled one path at a time.
const SHARED_PATHS: &[(&str, &str)] = &[
    ("2916.1P.dxf", "2916.2P"),
    ("2051 Pv Schlüssel.dxf", "2051.2P"),
    ("8998.dxf", "8998.2P"),
    ("8999.21P.dxf", "8999.21S"),
];

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn shared() -> Option<PathBuf> {
    let p = std::env::var_os("MILLPATH_SHARED")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo().join("../shared"));
    p.join("conformance/fixtures").is_dir().then_some(p)
}

fn copy_files(from: &Path, to: &Path) {
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        if p.is_file() {
            std::fs::copy(&p, to.join(p.file_name().unwrap())).unwrap();
        }
    }
}

/// A cutting element: where it ends and, for an arc, its centre and whether it turns
/// clockwise.
#[derive(Debug, Clone, PartialEq)]
struct Cut {
    to: [f64; 3],
    arc: Option<([f64; 2], bool)>,
}

/// A pass: where the tool stands when it starts, and its elements.
#[derive(Debug, Default, Clone)]
struct Pass {
    start: [f64; 3],
    cuts: Vec<Cut>,
}

#[derive(Debug, Default)]
struct Geometry {
    passes: Vec<Pass>,
    /// Drillings: the point and the bottom.
    drills: Vec<[f64; 3]>,
}

/// The words of a G-code line (comments left out).
fn words(line: &str) -> BTreeMap<char, f64> {
    let code = line.split(['(', ';']).next().unwrap_or("");
    code.split_whitespace()
        .filter_map(|w| {
            let letter = w.chars().next()?;
            Some((letter, w[1..].parse().ok()?))
        })
        .collect()
}

/// The linuxcnc program's passes (runs of feed moves between rapids) and drill plunges (the
/// `G01` after a `(Drill l=…)` comment, which xcam writes as a `B`).
fn from_gcode(text: &str) -> Geometry {
    let mut g = Geometry::default();
    let mut at = [f64::NAN; 3];
    let mut open: Option<Pass> = None;
    let mut in_drill = false;
    for line in text.lines() {
        let comment = line.trim_start().strip_prefix('(').unwrap_or("");
        if comment.starts_with("Drill l=") {
            in_drill = true;
        } else if comment.starts_with("SweepAndDrill") || comment.starts_with("Mill") {
            in_drill = false;
        }
        let w = words(line);
        let Some(&code) = w.get(&'G') else { continue };
        let mut to = at;
        for (k, l) in ['X', 'Y', 'Z'].into_iter().enumerate() {
            if let Some(v) = w.get(&l) {
                to[k] = *v;
            }
        }
        let feed = code == 1.0 || code == 2.0 || code == 3.0;
        if feed && in_drill {
            g.drills.push(to);
            in_drill = false;
        } else if feed {
            let pass = open.get_or_insert_with(|| Pass {
                start: at,
                cuts: Vec::new(),
            });
            let arc = (code != 1.0).then(|| ([at[0] + w[&'I'], at[1] + w[&'J']], code == 2.0));
            pass.cuts.push(Cut { to, arc });
        } else if let Some(p) = open.take() {
            g.passes.push(p);
        }
        at = to;
    }
    g.passes.extend(open);
    g
}

/// An NCC line's `NAME=value` pairs (numbers only; strings are kept as text).
fn pairs(line: &str) -> (String, BTreeMap<String, String>) {
    let mut parts = line.split(' ');
    let command = parts.next().unwrap_or("").to_string();
    let values = parts
        .filter_map(|p| p.split_once('='))
        .map(|(k, v)| (k.to_string(), v.trim_matches('"').to_string()))
        .collect();
    (command, values)
}

fn num(v: &BTreeMap<String, String>, k: &str, line: &str) -> f64 {
    let t = v.get(k).unwrap_or_else(|| panic!("{k} missing: {line}"));
    assert!(t.contains('.'), "{k}={t}: a number with a decimal point");
    t.parse().unwrap()
}

/// The `.NCC` file's contours as passes (in the order their millings come) and drillings.
fn from_ncc(text: &str) -> Geometry {
    assert!(text.ends_with("\r\n"), "CR LF");
    let body = text.strip_suffix("\r\n").unwrap();
    assert!(!body
        .split("\r\n")
        .any(|l| l.contains('\n') || l.contains('\r')));
    let mut lines = body.split("\r\n");
    assert!(
        lines.next().unwrap().starts_with("H DX="),
        "the header first"
    );
    let mut g = Geometry::default();
    let mut contours: BTreeMap<String, Pass> = BTreeMap::new();
    let mut current: Option<String> = None;
    for line in lines {
        let (command, v) = pairs(line);
        let point = |v: &BTreeMap<String, String>| {
            [num(v, "X", line), num(v, "Y", line), num(v, "Z", line)]
        };
        match command.as_str() {
            "COM" => {}
            "G0" => {
                let name = v["N"].clone();
                let pass = Pass {
                    start: point(&v),
                    cuts: Vec::new(),
                };
                assert!(contours.insert(name.clone(), pass).is_none(), "{line}");
                current = Some(name);
            }
            "G1" | "G5" => {
                let arc = (command == "G5").then(|| {
                    let dir = &v["DIR"];
                    assert!(dir == "1" || dir == "-1", "{line}");
                    ([num(&v, "I", line), num(&v, "J", line)], dir == "1")
                });
                let c = contours.get_mut(current.as_ref().unwrap()).unwrap();
                c.cuts.push(Cut { to: point(&v), arc });
            }
            "GIN" => {
                assert_eq!(v["DFC"], "1", "depth from the contour: {line}");
                g.passes.push(contours[&v["N"]].clone());
                current = None;
            }
            "B" => {
                let p = point(&v);
                g.drills.push([p[0], p[1], p[2] - num(&v, "TI", line)]);
            }
            other => panic!("unexpected command {other}: {line}"),
        }
    }
    g
}

fn deviation(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[derive(Debug, Default)]
struct Counts {
    drawings: usize,
    refused: usize,
    passes: usize,
    cuts: usize,
    drills: usize,
    max_deviation: f64,
}

/// Compares one program pair, adding to `n`.
fn compare(name: &str, gcode: &str, ncc: &str, n: &mut Counts) {
    let (a, b) = (from_gcode(gcode), from_ncc(ncc));
    assert_eq!(a.passes.len(), b.passes.len(), "{name}: passes");
    assert_eq!(a.drills.len(), b.drills.len(), "{name}: drillings");
    let mut worst = 0.0_f64;
    for (k, (p, q)) in a.passes.iter().zip(&b.passes).enumerate() {
        worst = worst.max(deviation(&p.start, &q.start));
        assert_eq!(p.cuts.len(), q.cuts.len(), "{name}: pass {}", k + 1);
        for (c, d) in p.cuts.iter().zip(&q.cuts) {
            worst = worst.max(deviation(&c.to, &d.to));
            match (c.arc, d.arc) {
                (None, None) => {}
                (Some((cc, cw)), Some((dc, dw))) => {
                    assert_eq!(cw, dw, "{name}: pass {} turns otherwise", k + 1);
                    worst = worst.max(deviation(&cc, &dc));
                }
                _ => panic!("{name}: pass {}: a line against an arc", k + 1),
            }
        }
        n.cuts += p.cuts.len();
    }
    for (p, q) in a.drills.iter().zip(&b.drills) {
        worst = worst.max(deviation(p, q));
    }
    assert!(worst <= TOLERANCE + 1e-9, "{name}: deviation {worst}");
    n.drawings += 1;
    n.passes += a.passes.len();
    n.drills += a.drills.len();
    n.max_deviation = n.max_deviation.max(worst);
}

/// Compiles `args` in copies of `from` (with `toml` as millpath.toml when given) with both
/// posts and compares every milling program.
fn job(from: &[PathBuf], toml: Option<&str>, args: &[&str], n: &mut Counts) {
    let dirs = [tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap()];
    for (dir, post) in dirs.iter().zip(["linuxcnc", "xcam"]) {
        for f in from {
            copy_files(f, dir.path());
        }
        if let Some(t) = toml {
            std::fs::write(dir.path().join("millpath.toml"), t).unwrap();
        }
        let mut all = vec!["compile", "--post", post];
        all.extend(args);
        millpath(dir.path(), &all);
    }
    let mut found = 0;
    for e in std::fs::read_dir(dirs[0].path()).unwrap() {
        let p = e.unwrap().path();
        let file = p.file_name().unwrap().to_string_lossy().into_owned();
        let ncc_path = |end: &str| {
            let stem = file.strip_suffix(end).unwrap();
            dirs[1].path().join(format!("{stem}_Milling.NCC"))
        };
        if file.ends_with("_Clean.gcode") {
            // a probing set: refused by xcam, nothing written
            assert!(!ncc_path("_Clean.gcode").exists(), "{file}");
            n.refused += 1;
            continue;
        }
        let Some(_) = file.strip_suffix("_Milling.gcode") else {
            continue;
        };
        let gcode = std::fs::read_to_string(&p).unwrap();
        let ncc = std::fs::read_to_string(ncc_path("_Milling.gcode"))
            .unwrap_or_else(|e| panic!("{file}: no .NCC beside it: {e}"));
        compare(&file, &gcode, &ncc, n);
        found += 1;
    }
    assert!(found > 0 || n.refused > 0, "{args:?}: nothing compiled");
}

#[test]
fn every_ncc_contour_is_the_linuxcnc_cut_within_a_micron() {
    let mut n = Counts::default();
    for example in ["plate", "text"] {
        job(
            &[repo().join("examples").join(example)],
            None,
            &["."],
            &mut n,
        );
    }
    let examples = (n.drawings, n.passes);
    match shared() {
        None => eprintln!("skipped the shared drawings: ../shared is not there"),
        Some(s) => {
            let from = [s.join("conformance/fixtures"), s.join("samples")];
            job(&from, Some(SHARED_BASE), &["."], &mut n);
            for (file, path) in SHARED_PATHS {
                job(
                    &from,
                    Some(SHARED_BASE),
                    &["--path-pattern", path, file],
                    &mut n,
                );
            }
        }
    }
    eprintln!(
        "xcam geometry: {} programs ({} of them examples, {} passes), {} refused probing sets; \
         {} contours with {} elements, {} drillings; largest deviation {:.6} mm",
        n.drawings, examples.0, examples.1, n.refused, n.passes, n.cuts, n.drills, n.max_deviation
    );
    assert!(n.passes > 0 && n.drills > 0 && n.cuts > n.passes);
}
