//! The built-in `marlin` post end to end (issue 32): every example and every shared drawing
//! compiled with it is read by `millpath verify --dialect marlin` with no finding, in the
//! shape Marlin reads (`;` comments, one command a line, no `%`, no T word, `G4 S`, the end
//! at one `M5`, also after a spindle), with arcs and with `arcs = "lines"`; probes are refused, located (MP207); a
//! mutated Marlin program is caught; a Marlin post file with absurd values gives a located
//! error and writes nothing.

use std::path::{Path, PathBuf};

mod common;

use common::{copy_text_examples as example, millpath, MACHINE};

/// `../shared` beside the repository (`MILLPATH_SHARED` names it elsewhere, e.g. from a
/// worktree); `None` (the shared rows are skipped, said so) when it is absent.
fn shared() -> Option<PathBuf> {
    let p = std::env::var_os("MILLPATH_SHARED")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared"));
    p.join("conformance/fixtures").is_dir().then_some(p)
}

fn programs(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_string_lossy().ends_with(".gcode"))
        .collect();
    v.sort();
    v
}

/// `verify --dialect marlin FILE`: its exit status and report.
fn verify(dir: &Path, file: &Path) -> (bool, String) {
    let out = millpath(
        dir,
        &["verify", "--dialect", "marlin", file.to_str().unwrap()],
    );
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.success(), text)
}

/// Every line as Marlin reads it: a `;` comment, or one G/M command with its parameters.
fn assert_marlin_shape(name: &str, text: &str) {
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.last(), Some(&"M5"), "{name}: ends with M5");
    let stops = lines.iter().filter(|l| **l == "M5").count();
    assert_eq!(stops, 1, "{name}: M5 once (the spindle's stop is the end)");
    for l in &lines {
        let code = l.trim_start();
        if code.starts_with(';') {
            continue;
        }
        let words: Vec<&str> = code.split(' ').collect();
        assert!(
            words[0].starts_with('G') || words[0].starts_with('M'),
            "{name}: {l}"
        );
        assert!(
            words[1..]
                .iter()
                .all(|w| !w.starts_with(['G', 'M', 'T', '(', '%'])),
            "{name}: one command a line: {l}"
        );
        assert!(!["M30", "M2"].contains(&code), "{name}: {l}");
    }
}

/// Compiles every drawing of `dir` (with `args` before the drawing) and has every program
/// read as Marlin: no error, no warning. Returns how many programs were read.
fn every_program_clean(dir: &Path, post: &str, args: &[&str], drawings: &[&str]) -> usize {
    for d in drawings {
        let mut a = vec!["compile", "--post", post];
        a.extend(args);
        a.push(d);
        // a shared drawing that does not compile alone writes nothing: left out
        millpath(dir, &a);
    }
    let files = programs(dir);
    for f in &files {
        let (ok, report) = verify(dir, f);
        assert!(
            ok && report.contains(" 0 error(s), 0 warning(s)"),
            "{}: {report}",
            f.display()
        );
        assert_marlin_shape(
            &f.display().to_string(),
            &std::fs::read_to_string(f).unwrap(),
        );
    }
    files.len()
}

#[test]
fn every_example_and_shared_drawing_compiled_for_marlin_checks_clean() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    example(d);
    let toml = d.join("millpath.toml");
    let own = std::fs::read_to_string(&toml).unwrap();
    std::fs::write(&toml, format!("{own}spindle_rpm = 255\n")).unwrap();
    assert_eq!(
        every_program_clean(d, "marlin", &[], &["2001.mpath", "2010.mpath"]),
        2
    );
    let text = std::fs::read_to_string(d.join("2010_Milling.gcode")).unwrap();
    assert!(text.contains("\nM3 S255\nG4 S2\n"), "{text}");
    assert!(
        text.ends_with("\nM5\n") && text.matches("M5").count() == 1,
        "{text}"
    );
    assert!(text.contains("\n; tool 1: change it by hand\n"), "{text}");
    // probes: refused at the first one, nothing written
    let out = millpath(d, &["compile", "--post", "marlin", "2020.mpath"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{err}");
    assert!(
        err.contains("MP207") && err.contains("The post marlin cannot write Z probes"),
        "{err}"
    );
    assert!(err.contains("2020.mpath:7:3"), "{err}");
    assert!(!d.join("2020_Clean.gcode").exists());

    // the plate example (a DXF drawing with its own settings)
    let plate = tempfile::tempdir().unwrap();
    let from = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate");
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, plate.path().join(p.file_name().unwrap())).unwrap();
    }
    assert_eq!(
        every_program_clean(plate.path(), "marlin", &[], &["1234.1P.dxf"]),
        1
    );

    let Some(shared) = shared() else {
        eprintln!("../shared is absent: the shared drawings are skipped");
        return;
    };
    let fixtures = tempfile::tempdir().unwrap();
    let mut drawings = Vec::new();
    for folder in ["conformance/fixtures", "samples"] {
        for e in std::fs::read_dir(shared.join(folder)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "dxf") {
                let name = p.file_name().unwrap().to_string_lossy().into_owned();
                std::fs::copy(&p, fixtures.path().join(&name)).unwrap();
                drawings.push(name);
            }
        }
    }
    let names: Vec<&str> = drawings.iter().map(String::as_str).collect();
    let n = every_program_clean(fixtures.path(), "marlin", &MACHINE, &names);
    assert!(n >= 20, "{n} programs of the shared drawings");
    let arcs = programs(fixtures.path())
        .iter()
        .filter(|f| {
            let text = std::fs::read_to_string(f).unwrap();
            text.lines()
                .any(|l| l.starts_with("G2 ") || l.starts_with("G3 "))
        })
        .count();
    assert!(arcs >= 5, "{arcs} programs with arcs");
    // the same drawings with arcs as lines (firmware without ARC_SUPPORT): no G2/G3
    for f in programs(fixtures.path()) {
        std::fs::remove_file(f).unwrap();
    }
    let shown = millpath(d, &["post", "show", "marlin"]).stdout;
    let lines = String::from_utf8(shown)
        .unwrap()
        .replace("name = \"marlin\"", "name = \"router\"")
        .replace("arcs = \"ij\"", "arcs = \"lines\"");
    std::fs::write(fixtures.path().join("router.toml"), lines).unwrap();
    let m = every_program_clean(fixtures.path(), "router.toml", &MACHINE, &names);
    assert_eq!(m, n);
    for f in programs(fixtures.path()) {
        let text = std::fs::read_to_string(&f).unwrap();
        assert!(
            !text
                .lines()
                .any(|l| l.starts_with("G2 ") || l.starts_with("G3 ")),
            "{}",
            f.display()
        );
    }
}

#[test]
fn a_mutated_marlin_program_is_caught() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    example(d);
    let out = millpath(
        d,
        &[
            "compile",
            "--post",
            "marlin",
            "--spindle-rpm",
            "255",
            "2010.mpath",
        ],
    );
    assert!(out.status.success());
    let good = std::fs::read_to_string(d.join("2010_Milling.gcode")).unwrap();
    let first_cut = good
        .lines()
        .find(|l| l.starts_with("G1 F") && l.contains(" X"))
        .unwrap();
    let rest = first_cut.strip_prefix("G1 ").unwrap();
    let deepest = good
        .lines()
        .filter(|l| l.starts_with("G1 ") && l.contains(" Z"))
        .max_by(|a, b| {
            let z = |l: &str| -> f64 { l.rsplit_once(" Z").unwrap().1.parse().unwrap() };
            z(b).total_cmp(&z(a))
        })
        .unwrap();
    let mutations: Vec<(&str, String)> = vec![
        // a ( ) comment: Marlin without PAREN_COMMENTS reads it as words
        (
            "parens",
            good.replacen("; SweepSafelyTo", "(SweepSafelyTo)", 1),
        ),
        // two commands on a line: Marlin runs only the first
        (
            "second command",
            good.replacen("\nG4 S2\n", "\nG4 S2 M5\n", 1),
        ),
        // the spindle dwell in P (milliseconds in Marlin): 2 ms
        ("dwell in P", good.replacen("\nG4 S2\n", "\nG4 P2\n", 1)),
        // M30 deletes a file on the SD card
        ("M30", format!("{}M30\n", good.trim_end_matches("M5\n"))),
        // a move without its G: Marlin's motion is not modal
        ("no G", good.replacen(first_cut, rest, 1)),
        // a % line
        ("percent", format!("%\n{good}")),
        // a cut 5 mm deeper than drawn: below the stock bottom
        (
            "too deep",
            good.replacen(
                deepest,
                &{
                    let (head, z) = deepest.rsplit_once(" Z").unwrap();
                    format!("{head} Z{:.3}", z.parse::<f64>().unwrap() - 5.0)
                },
                1,
            ),
        ),
    ];
    for (what, text) in mutations {
        assert_ne!(text, good, "{what}: the mutation changed the program");
        std::fs::write(d.join("mutated.gcode"), &text).unwrap();
        let (ok, report) = verify(d, Path::new("mutated.gcode"));
        // an error, or (the dwell in milliseconds) a warning
        let caught = !ok || !report.contains(" 0 error(s), 0 warning(s)");
        assert!(caught, "{what}: not caught: {report}");
        assert!(
            report.contains("mutated.gcode:"),
            "{what}: located: {report}"
        );
    }
}

#[test]
fn a_marlin_post_with_absurd_values_gives_a_located_error() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    example(d);
    let shown = String::from_utf8(millpath(d, &["post", "show", "marlin"]).stdout).unwrap();
    let line_of = |needle: &str| {
        shown
            .lines()
            .position(|l| l.starts_with(needle))
            .unwrap_or_else(|| panic!("{needle}"))
            + 1
    };
    // what is replaced, by what, the key named and the error's line below the replaced one
    let cases = [
        ("decimals = 3", "decimals = 1e300", "format.decimals", 0),
        (
            "max_line_length = 95",
            "max_line_length = 1e300",
            "format.max_line_length",
            0,
        ),
        ("arcs = \"ij\"", "arcs = \"spline\"", "format.arcs", 0),
        (
            "arcs = \"ij\"",
            "arcs = \"lines\"\nchord_tolerance = nan",
            "format.chord_tolerance",
            1,
        ),
        (
            "dwell = \"G4 S{seconds}\"",
            "dwell = \"G4 S{millis}\"",
            "templates.dwell",
            0,
        ),
        (
            "family = \"marlin\"",
            "family = \"reprap\"",
            "post.family",
            0,
        ),
    ];
    for (from, to, key, below) in cases {
        let text = shown
            .replace("name = \"marlin\"", "name = \"router\"")
            .replacen(from, to, 1);
        assert_ne!(text, shown);
        std::fs::write(d.join("router.toml"), &text).unwrap();
        for lang in ["en", "de"] {
            let out = millpath(
                d,
                &[
                    "compile",
                    "--lang",
                    lang,
                    "--post",
                    "router.toml",
                    "2001.mpath",
                ],
            );
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success(), "{to}: {err}");
            let at = format!("router.toml:{}:", line_of(from) + below);
            assert!(err.contains(&at) && err.contains(key), "{to}: {err}");
            assert!(
                !d.join("2001_Milling.gcode").exists(),
                "{to}: nothing written"
            );
        }
    }
}
