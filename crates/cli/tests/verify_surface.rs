//! `millpath verify` on programs adjusted to a height map, and `--surface FILE`: the surface
//! as measured on the machine (a probe log, a filled-in `_Z.txt`) replaces the program's own
//! record, so a program adjusted with the log of another surface is found. The probe points
//! are those of the probing program `compile` writes for `[heightmap]`; the adjusted program
//! is written here by hand as adjust-z's contract says (record after the stock comment, Z =
//! nominal + offset at every point below the safe height, cuts split at the grid lines).

mod common;

use common::status_and_text;
use millpath_verify::HeightMap;
use std::path::{Path, PathBuf};

const TOML: &str = "dialect = \"linuxcnc\"\nfeed = 300\nsweep_speed = 1000\nsweep_height = 10\n\
                    probe_feed = 50\n[heightmap]\nstep = 10\nmargin = 2\n";

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// 2001.mpath compiled with `[heightmap]` in a fresh folder: the folder and the probe points
/// of its probing program (the XY of the G00 before each G38).
fn compiled() -> (tempfile::TempDir, Vec<(f64, f64)>) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        repo().join("examples/text/2001.mpath"),
        dir.path().join("2001.mpath"),
    )
    .unwrap();
    std::fs::write(dir.path().join("millpath.toml"), TOML).unwrap();
    let (status, text) = status_and_text(dir.path(), &["compile", "2001.mpath"]);
    assert_eq!(status, 0, "{text}");
    let probing = std::fs::read_to_string(dir.path().join("2001_Probing.gcode")).unwrap();
    let (mut x, mut y) = (0.0, 0.0);
    let mut points = Vec::new();
    for line in probing.lines() {
        let word = |l: char| {
            line.split_whitespace()
                .find_map(|w| w.strip_prefix(l)?.parse::<f64>().ok())
        };
        if line.starts_with("G38") {
            points.push((x, y));
        } else if line.starts_with("G00") {
            x = word('X').unwrap_or(x);
            y = word('Y').unwrap_or(y);
        }
    }
    assert_eq!(points.len(), 8, "{probing}");
    (dir, points)
}

fn tilted(x: f64, y: f64) -> f64 {
    3.0 + 0.01 * x + 0.02 * y
}
fn falling(x: f64, _y: f64) -> f64 {
    3.2 - 0.01 * x
}

/// LinuxCNC's PROBEOPEN log of `surface` at `points`.
fn linuxcnc_log(points: &[(f64, f64)], surface: fn(f64, f64) -> f64) -> String {
    points
        .iter()
        .map(|&(x, y)| format!("{x:.6} {y:.6} {:.6} 0 0 0 0 0 0\n", surface(x, y)))
        .collect()
}

/// 2001's slot (5,0) → (25,0) at −0.2, adjusted to `surface` measured at `points`.
fn adjusted(points: &[(f64, f64)], surface: fn(f64, f64) -> f64) -> String {
    let pts: Vec<(f64, f64, f64)> = points.iter().map(|&(x, y)| (x, y, surface(x, y))).collect();
    let map = HeightMap::from_points(&pts, 3.0, 0.01).unwrap();
    let z = |nominal: f64, x: f64| nominal + map.offset(x, 0.0).unwrap();
    let mut p = vec![
        "%".to_string(),
        "(2001.mpath)".into(),
        "(MILLPATH-STOCK T=3.000 O=2.000 BOTTOM=-0.200)".into(),
    ];
    p.extend(map.comment_lines());
    p.extend(
        [
            "G17 G21 G40 G49 G54 G80 G90 G94",
            "F300.000",
            "T1",
            "G00 Z10.000",
            "G00 X5.000 Y0.000",
        ]
        .map(String::from),
    );
    p.push(format!("G00 Z{:.3}", z(3.0, 5.0)));
    p.push(format!("G01 F150.000 Z{:.3}", z(-0.2, 5.0)));
    for x in map
        .xs()
        .iter()
        .copied()
        .filter(|x| *x > 5.0 && *x < 25.0)
        .chain([25.0])
    {
        p.push(format!("G01 F300.000 X{x:.3} Y0.000 Z{:.3}", z(-0.2, x)));
    }
    p.extend(["G00 Z10.000", "G00 X30.000 Y0.000", "M30", "%"].map(String::from));
    p.join("\n") + "\n"
}

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

#[test]
fn a_program_is_judged_against_the_surface_measured_on_the_machine() {
    let (dir, points) = compiled();
    let d = dir.path();
    write(d, "2001_Milling.gcode", &adjusted(&points, tilted));
    write(d, "tilted.txt", &linuxcnc_log(&points, tilted));
    write(d, "falling.txt", &linuxcnc_log(&points, falling));
    let verify = |extra: &[&str]| {
        let mut args = vec!["verify", "--dialect", "linuxcnc", "2001_Milling.gcode"];
        args.extend_from_slice(extra);
        status_and_text(d, &args)
    };
    // its own record, and the same surface from the log: clean
    let (status, text) = verify(&[]);
    assert_eq!(status, 0, "{text}");
    assert!(text.contains("on a height map of 4×2 points"), "{text}");
    let (status, text) = verify(&["--surface", "tilted.txt"]);
    assert_eq!(status, 0, "{text}");
    // another board: found, with the line of the cut
    let (status, text) = verify(&["--surface", "falling.txt"]);
    assert_eq!(status, 1, "{text}");
    assert!(
        text.contains("2001_Milling.gcode:") && text.contains("below the deepest drawn depth"),
        "{text}"
    );
    let (_, de) = verify(&["--surface", "falling.txt", "--lang", "de"]);
    assert!(de.contains("unter der tiefsten gezeichneten Tiefe"), "{de}");
    // the nominal program run on that board without adjustment: found as well
    let (status, text) = status_and_text(
        d,
        &[
            "verify",
            "--dialect",
            "linuxcnc",
            "2001_Clean.gcode",
            "--surface",
            "falling.txt",
        ],
    );
    assert_eq!(status, 1, "{text}");
    // the same surface as a filled-in _Z.txt (each point's XY in its comment), as GRBL's
    // console (machine coordinates and the work offset), as an adjusted program
    let z_txt: String = std::fs::read_to_string(d.join("2001_Z.txt"))
        .unwrap()
        .lines()
        .zip(&points)
        .map(|(l, &(x, y))| format!("{l}{:.3}\n", falling(x, y)))
        .collect();
    write(d, "falling_Z.txt", &z_txt);
    let grbl: String = std::iter::once("[G54:-100.000,-50.000,-20.000]\n".to_string())
        .chain(points.iter().map(|&(x, y)| {
            format!(
                "[PRB:{:.3},{:.3},{:.3}:1]\nok\n",
                x - 100.0,
                y - 50.0,
                falling(x, y) - 20.0
            )
        }))
        .collect();
    write(d, "falling_grbl.txt", &grbl);
    write(d, "falling_Milling.gcode", &adjusted(&points, falling));
    for file in ["falling_Z.txt", "falling_grbl.txt", "falling_Milling.gcode"] {
        let (status, text) = verify(&["--surface", file]);
        assert_eq!(status, 1, "{file}: {text}");
        assert!(
            text.contains("below the deepest drawn depth"),
            "{file}: {text}"
        );
    }
    let (status, text) = status_and_text(
        d,
        &[
            "verify",
            "--dialect",
            "linuxcnc",
            "falling_Milling.gcode",
            "--surface",
            "falling_grbl.txt",
        ],
    );
    assert_eq!(status, 0, "{text}");
}

#[test]
fn bad_surface_files_are_located_errors() {
    let (dir, points) = compiled();
    let d = dir.path();
    write(d, "2001_Milling.gcode", &adjusted(&points, tilted));
    let log = linuxcnc_log(&points, tilted);
    let lines: Vec<&str> = log.lines().collect();
    let cases: Vec<(&str, String, &str, &str)> = vec![
        // a point missing: the grid point named
        (
            "missing.txt",
            lines[..7].iter().map(|l| format!("{l}\n")).collect(),
            "missing.txt: error: the measurements do not form a full grid of probe points: no height at X",
            "keine Höhe bei X",
        ),
        // a point twice: the second measurement's line
        (
            "twice.txt",
            format!("{log}{}\n", lines[2]),
            "twice.txt:9: error: the measurements do not form a full grid of probe points: two heights at",
            "zwei Höhen bei",
        ),
        (
            "nan.txt",
            log.replacen(lines[3], "13.000000 2.000000 nan 0 0 0 0 0 0", 1),
            "--> nan.txt:4",
            "--> nan.txt:4",
        ),
        ("junk.txt", "hello\nworld\n".into(), "--> junk.txt:1", "--> junk.txt:1"),
        (
            "cut.txt",
            log.trim_end().to_string(),
            "--> cut.txt:8",
            "--> cut.txt:8",
        ),
        ("empty.txt", String::new(), "empty.txt", "empty.txt"),
        (
            "record.gcode",
            "(MILLPATH-SURFACE T=3.000 NX=2 NY=1)\n(MILLPATH-SURFACE-X I=0 0 inf)\n".into(),
            "record.gcode:2: error: 'inf' is not a sane number",
            "record.gcode:2: Fehler: 'inf' ist keine brauchbare Zahl",
        ),
    ];
    for (name, text, en, de) in cases {
        write(d, name, &text);
        for (lang, want) in [("en", en), ("de", de)] {
            let (status, out) = status_and_text(
                d,
                &[
                    "verify",
                    "2001_Milling.gcode",
                    "--surface",
                    name,
                    "--lang",
                    lang,
                ],
            );
            assert_eq!(status, 2, "{name} {lang}: {out}");
            assert!(out.contains(want), "{name} {lang}: {out}");
            assert!(!out.contains("panicked"), "{out}");
        }
    }
    // a file that is not there, a tolerance out of range, a program without T
    let (status, out) = status_and_text(
        d,
        &["verify", "2001_Milling.gcode", "--surface", "nothere.txt"],
    );
    assert_eq!(status, 2, "{out}");
    assert!(out.contains("nothere.txt"), "{out}");
    write(d, "tilted.txt", &log);
    let (status, out) = status_and_text(
        d,
        &[
            "verify",
            "2001_Milling.gcode",
            "--surface",
            "tilted.txt",
            "--tolerance",
            "5",
        ],
    );
    assert_eq!(status, 2, "{out}");
    write(d, "bare.gcode", "G00 Z10\nG00 X5 Y0\nM30\n");
    let (status, out) = status_and_text(d, &["verify", "bare.gcode", "--surface", "tilted.txt"]);
    assert_eq!(status, 2, "{out}");
    assert!(out.contains("give --top"), "{out}");
    let (status, out) = status_and_text(
        d,
        &[
            "verify",
            "bare.gcode",
            "--surface",
            "tilted.txt",
            "--top",
            "3",
            "--tool",
            "2",
        ],
    );
    assert_eq!(status, 0, "{out}");
    // --tolerance only with --surface
    let (status, _) = status_and_text(d, &["verify", "bare.gcode", "--tolerance", "0.1"]);
    assert_eq!(status, 2);
}

#[test]
fn render_draws_the_measured_surface_or_the_probe_grid() {
    let (dir, points) = compiled();
    let d = dir.path();
    write(d, "tilted.txt", &linuxcnc_log(&points, tilted));
    let (status, text) = status_and_text(
        d,
        &[
            "render",
            "2001.mpath",
            "--svg",
            "m.svg",
            "--html",
            "m.html",
            "--surface",
            "tilted.txt",
        ],
    );
    assert_eq!(status, 0, "{text}");
    // three cells, coloured from the lowest (blue) to the highest (yellow) mean height
    let svg = std::fs::read_to_string(d.join("m.svg")).unwrap();
    let fills: Vec<&str> = svg
        .lines()
        .filter(|l| l.starts_with("<rect"))
        .filter_map(|l| l.split("fill=\"").nth(1)?.split('"').next())
        .collect();
    assert_eq!(fills.len(), 3, "{svg}");
    assert_ne!(fills[0], fills[2]);
    let html = std::fs::read_to_string(d.join("m.html")).unwrap();
    assert!(
        html.contains(r#""measured":true"#),
        "no surface in the page data"
    );
    // without --surface: the probe grid of [heightmap] at the nominal top
    let (status, _) = status_and_text(d, &["render", "2001.mpath", "--svg", "g.svg"]);
    assert_eq!(status, 0);
    let svg = std::fs::read_to_string(d.join("g.svg")).unwrap();
    assert_eq!(svg.matches("fill=\"#8a8f98\"").count(), 8, "{svg}");
    // a bad file: located, nothing written
    write(d, "junk.txt", "hello\n");
    let (status, text) = status_and_text(
        d,
        &[
            "render",
            "2001.mpath",
            "--svg",
            "j.svg",
            "--surface",
            "junk.txt",
            "--lang",
            "de",
        ],
    );
    assert_eq!(status, 2, "{text}");
    assert!(
        text.contains("junk.txt:1") && text.contains("Antast-Protokoll"),
        "{text}"
    );
    assert!(!d.join("j.svg").exists());
}
