//! A height map as a setting (issue 21, compile side): `[heightmap]` makes `compile` write a
//! grid probing program, its `_Z.txt` and the nominal `_Clean.gcode` in linuxcnc and grbl;
//! the reference dialect, drawn probes and values out of bounds are refused.

mod common;

use std::path::{Path, PathBuf};

const MACHINE: &str = "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n";

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate/1234.1P.dxf")
}

/// A folder with the plate example and a millpath.toml of `MACHINE` + `extra`.
fn setup(extra: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(example(), dir.path().join("1234.1P.dxf")).unwrap();
    std::fs::write(
        dir.path().join("millpath.toml"),
        format!("{MACHINE}{extra}"),
    )
    .unwrap();
    dir
}

fn read(dir: &Path, name: &str) -> String {
    std::fs::read_to_string(dir.join(name)).unwrap_or_default()
}

fn num(word: &str, letter: char) -> Option<f64> {
    word.strip_prefix(letter)?.parse().ok()
}

/// `(x, y)` of every `_Z.txt` line, and the names in order.
fn z_points(z: &str) -> (Vec<(f64, f64)>, Vec<String>) {
    let mut pts = Vec::new();
    let mut names = Vec::new();
    for line in z.lines() {
        let inner = line.strip_prefix("([").unwrap();
        let (xy, rest) = inner.split_once(']').unwrap();
        let (x, y) = xy.split_once(' ').unwrap();
        pts.push((x.parse().unwrap(), y.parse().unwrap()));
        let name = rest.split_once(") ").unwrap().1;
        assert!(name.ends_with('='), "{line}");
        names.push(name.trim_end_matches('=').to_string());
    }
    (pts, names)
}

/// The XY where each `G38.2` of a probing program probes.
fn probed_points(program: &str) -> Vec<(f64, f64)> {
    let (mut x, mut y) = (0.0, 0.0);
    let mut out = Vec::new();
    for line in program.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.first() == Some(&"G38.2") {
            out.push((x, y));
        }
        for w in &words {
            if let Some(v) = num(w, 'X') {
                x = v;
            }
            if let Some(v) = num(w, 'Y') {
                y = v;
            }
        }
    }
    out
}

/// Rows by ascending Y, X ascending in the first row and alternating after.
fn is_serpentine(pts: &[(f64, f64)]) -> bool {
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut last_y = f64::NEG_INFINITY;
    for &(x, y) in pts {
        if y != last_y {
            if y < last_y {
                return false;
            }
            rows.push(Vec::new());
            last_y = y;
        }
        rows.last_mut().unwrap().push(x);
    }
    rows.iter().enumerate().all(|(j, r)| {
        r.windows(2)
            .all(|w| if j % 2 == 0 { w[0] < w[1] } else { w[0] > w[1] })
    }) && rows.windows(2).all(|w| w[0].len() == w[1].len())
}

/// The banner line (where the set's digest is: line 2, or 1 in GRBL without `%`).
fn is_banner(l: &str) -> bool {
    l.starts_with("(millpath V.")
}

/// The lines of a program but its banner.
fn without_banner(p: &str) -> Vec<&str> {
    p.lines().filter(|l| !is_banner(l)).collect()
}

#[test]
fn compile_writes_a_grid_probing_set_in_linuxcnc_and_grbl() {
    for dialect in ["linuxcnc", "grbl"] {
        let dir = setup("\n[heightmap]\nstep = 10\nmargin = 2\nprobe_depth = 4\n");
        let d = dir.path();
        let (code, text) =
            common::status_and_text(d, &["compile", "--dialect", dialect, "1234.1P.dxf"]);
        assert_eq!(code, 0, "{text}");
        let probing = read(d, "1234.1P_Probing.gcode");
        let z = read(d, "1234.1P_Z.txt");
        let clean = read(d, "1234.1P_Clean.gcode");
        assert!(!d.join("1234.1P_Milling.gcode").exists());
        let (pts, names) = z_points(&z);
        assert!(pts.len() >= 4, "{z}");
        // names from #1000 on, in tour order
        for (k, n) in names.iter().enumerate() {
            assert_eq!(n, &format!("#{}", 1000 + k));
        }
        // the program probes exactly the _Z.txt points, in that (serpentine) order
        assert_eq!(probed_points(&probing), pts, "{dialect}");
        assert!(is_serpentine(&pts), "{pts:?}");
        // every probe goes down at most probe_depth below the top (T3 in the example)
        for l in probing.lines().filter(|l| l.starts_with("G38.2")) {
            assert!(l.starts_with("G38.2 Z-1.000 F"), "{l}");
        }
        let (has_open, has_close) = (
            probing.contains("(PROBEOPEN 1234.1P_probes.txt)\n"),
            probing.contains("(PROBECLOSE)\n"),
        );
        if dialect == "linuxcnc" {
            assert!(has_open && has_close, "{probing}");
        } else {
            // GRBL 1.1: no PROBEOPEN, no parameters, no %
            assert!(!has_open && !has_close && !probing.contains('%'));
            assert!(!probing.contains('#'));
        }
        // the clean program is the nominal program: what compile writes without a height map
        let plain = setup("");
        let (code, text) = common::status_and_text(
            plain.path(),
            &["compile", "--dialect", dialect, "1234.1P.dxf"],
        );
        assert_eq!(code, 0, "{text}");
        let milling = read(plain.path(), "1234.1P_Milling.gcode");
        assert_eq!(without_banner(&clean), without_banner(&milling));
        // one set: the same digest in both banners
        let banner = |p: &str| {
            p.lines()
                .find(|l| is_banner(l))
                .unwrap_or_default()
                .to_string()
        };
        assert!(banner(&clean).contains("set="), "{clean}");
        assert_eq!(banner(&clean), banner(&probing));
        // the grid covers every cutting move: margin 2 around the cuts (10..70 × 10..30)
        let xs: Vec<f64> = pts.iter().map(|p| p.0).collect();
        let ys: Vec<f64> = pts.iter().map(|p| p.1).collect();
        let min = |v: &[f64]| v.iter().cloned().fold(f64::INFINITY, f64::min);
        let max = |v: &[f64]| v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        for (l, h) in [(min(&xs), max(&xs)), (min(&ys), max(&ys))] {
            assert!(l < h);
        }
        assert_eq!((min(&xs), min(&ys)), (8.0, 8.0), "{z}");
        assert_eq!((max(&xs), max(&ys)), (72.0, 32.0), "{z}");
    }
}

#[test]
fn the_options_give_a_height_map_without_the_table() {
    let dir = setup("");
    let d = dir.path();
    let args = [
        "compile",
        "--dialect",
        "grbl",
        "--heightmap-step",
        "20",
        "--heightmap-margin",
        "0",
        "1234.1P.dxf",
    ];
    let (code, text) = common::status_and_text(d, &args);
    assert_eq!(code, 0, "{text}");
    let (pts, _) = z_points(&read(d, "1234.1P_Z.txt"));
    // 10..70 by 20: 10 30 50 70; 10..30: 10 30
    assert_eq!(pts.len(), 8, "{pts:?}");
    // a margin alone has no grid
    let (code, text) =
        common::status_and_text(d, &["compile", "--heightmap-margin", "2", "1234.1P.dxf"]);
    assert_ne!(code, 0);
    assert!(text.contains("--heightmap-margin needs"), "{text}");
}

#[test]
fn refusals_write_nothing_and_name_the_setting() {
    let cases = [
        // the reference dialect has no height map
        (
            "\n[heightmap]\nstep = 10\n",
            "reference",
            "needs the linuxcnc or grbl dialect",
        ),
        (
            "\n[heightmap]\nstep = 0\n",
            "linuxcnc",
            "heightmap.step=0 mm is below",
        ),
        (
            "\n[heightmap]\nstep = -2\n",
            "grbl",
            "heightmap.step=-2 mm is below",
        ),
        (
            "\n[heightmap]\nstep = nan\n",
            "grbl",
            "heightmap.step=NaN must be a finite",
        ),
        (
            "\n[heightmap]\nstep = 10\nmargin = -1\n",
            "grbl",
            "heightmap.margin=-1 must be >= 0",
        ),
        (
            "\n[heightmap]\nstep = 0.5\nmargin = 30\n",
            "grbl",
            "probe points, more than 4000",
        ),
        (
            "\n[heightmap]\nstep = 10\narea = [0, 0, 50, 50]\n",
            "grbl",
            "outside heightmap.area",
        ),
        ("\n[heightmap]\nmargin = 2\n", "grbl", "step"),
    ];
    for (extra, dialect, expect) in cases {
        let dir = setup(extra);
        let d = dir.path();
        let (code, text) =
            common::status_and_text(d, &["compile", "--dialect", dialect, "1234.1P.dxf"]);
        assert_ne!(code, 0, "{extra}: {text}");
        assert!(text.contains(expect), "{extra}: {text}");
        for f in ["_Probing.gcode", "_Z.txt", "_Clean.gcode", "_Milling.gcode"] {
            assert!(!d.join(format!("1234.1P{f}")).exists(), "{extra}: {f}");
        }
    }
    // a settings error is located at the settings file
    let dir = setup("\n[heightmap]\nstep = 0\n");
    let (_, text) =
        common::status_and_text(dir.path(), &["compile", "--dialect", "grbl", "1234.1P.dxf"]);
    assert!(text.contains("millpath.toml"), "{text}");
    // German
    let (_, text) = common::status_and_text(
        dir.path(),
        &[
            "compile",
            "--lang",
            "de",
            "--dialect",
            "grbl",
            "1234.1P.dxf",
        ],
    );
    assert!(
        text.contains("kleiner als der kleinste Rasterabstand"),
        "{text}"
    );
}

#[test]
fn drawn_probes_and_a_height_map_are_refused_together() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("2020.mpath"),
        "path 2020.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (60, 0)\n  mill (0, 0) -> (60, 0)\n  probe (10, 5)\n}\n",
    )
    .unwrap();
    std::fs::write(
        d.join("millpath.toml"),
        format!("{MACHINE}dialect = \"linuxcnc\"\n[heightmap]\nstep = 10\n"),
    )
    .unwrap();
    let (code, text) = common::status_and_text(d, &["compile", "2020.mpath"]);
    assert_ne!(code, 0, "{text}");
    assert!(text.contains("has drawn Z probes (#51)"), "{text}");
    assert!(!d.join("2020_Probing.gcode").exists());
    // check reports what compile would
    let (code, text) = common::status_and_text(d, &["check", "2020.mpath"]);
    assert_ne!(code, 0, "{text}");
    assert!(text.contains("has drawn Z probes"), "{text}");
}
