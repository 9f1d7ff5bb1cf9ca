//! verify's GRBL rules held against GRBL 1.1h's own parser (`gvalidate`, built from
//! `../shared/grbl` by its `build.sh`; the test is skipped with a message when that is
//! absent). 600 mutated programs of the `grbl` dialect: wherever GRBL refuses a line, verify
//! must report an error at that line. GRBL stops at its first refused line, so each program
//! gives one comparison.
//!
//! Differences by design, counted and printed, not failed:
//! * GRBL's validator starts at X0 Y0 Z0; verify does not assume where a machine starts, so a
//!   move before the first position is known is not simulated (a warning), and an arc there
//!   is not checked;
//! * verify reads a program up to its end (M2/M30) and warns about code after it; GRBL goes
//!   on with what a sender streams;
//! * GRBL's validator has no workpiece, so a probe never touches and ends at its target: a
//!   second probe to the same target is refused (`error:33`); on a machine the first stops
//!   at the contact, and verify does not know where;
//! * lines GRBL accepts and verify refuses: what verify checks beyond a parser (rapids into
//!   material, a missing program end, absurd values, feeds).

use millpath_verify::{verify, Dialect, FindingKind, Options, Severity};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

use common::{mutate, Rng};

/// A program as the `grbl` dialect writes it: spindle with its start dwell, sweeps, plunges,
/// lines, arcs, a helix, a probe and its dwell, the spindle stopped, the end.
const GOOD: &str = "(millpath V.0.1.0)\n(MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300)\n\
G17 G21 G40 G49 G54 G80 G90 G94\nF300.000\nT1\nM3 S12000\nG4 P1.5\n\
G00 Z10.000\nG00 X0.000 Y0.000\nG00 X10.000 Y-0.050\nG00 Z4.000\n\
G02 F150.000 I0 J0.050 X10.000 Y0.050 Z1.400\nG02 F150.000 I0 J-0.050 X10.000 Y-0.050 Z-0.300\n\
G00 X10.000 Y0.000\nG00 Z5.000\nG00 X20.000 Y0.000\nG00 Z2.000(=2.000+0.794*[#51-2.000])\n\
G01 F150.000 Z0.800\nG01 F300.000 X30.000 Y5.000 Z0.800\n\
G03 F300.000 I-5.000 J0.000 X20.000 Y5.000 Z0.800\nG01 F300.000 X20.000 Y0.000 Z0.800\n\
G00 Z5.000\nG00 X40.000 Y5.000\nG00 Z3.000\nG38.3 Z0 F50.000\nG04 P4\nG00 Z10.000\n\
M5\nM30\n";

/// Letters, digits and signs a program has, and what a damaged one may get.
const ALPHABET: &[u8] = b"GMXYZIJKRFPNST0123456789.-+ ()[];%#=eE$/\t";

const PROGRAMS: usize = 600;

/// The workspace root (two levels above this crate).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// gvalidate, built into target/grbl on first use; `None` without ../shared/grbl.
fn gvalidate() -> Option<PathBuf> {
    let root = root();
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"));
    let tools = target.join("grbl");
    let exe = tools.join("gvalidate");
    if exe.exists() {
        return Some(exe);
    }
    let build = root.join("../shared/grbl/build.sh");
    if !build.exists() {
        return None;
    }
    std::fs::create_dir_all(&tools).unwrap();
    let ok = Command::new("bash")
        .arg(&build)
        .arg(&tools)
        .status()
        .expect("bash runs");
    assert!(ok.success(), "building GRBL's tools failed");
    Some(exe)
}

/// GRBL's first refused line (1-based) and its answer, or `None` when it accepts all.
fn grbl_refuses(exe: &Path, dir: &Path, text: &str) -> Option<(usize, String)> {
    let file = dir.join("program.gcode");
    std::fs::write(&file, text).unwrap();
    // a program pause (M0, M1) makes GRBL wait for the operator: what it answered by then
    let out = Command::new("timeout")
        .arg("5")
        .arg(exe)
        .arg("program.gcode")
        .current_dir(dir)
        .output()
        .expect("gvalidate runs");
    let answers = String::from_utf8_lossy(&out.stdout);
    // one answer a line: `ok`, or the error that stops it; messages and reports are none
    let mut line = 0;
    for a in answers.lines() {
        if a == "ok" {
            line += 1;
        } else if a.starts_with("error:") || a.starts_with("ALARM:") {
            return Some((line + 1, a.to_string()));
        }
    }
    None
}

#[test]
fn verify_refuses_every_line_grbl_refuses() {
    let Some(exe) = gvalidate() else {
        eprintln!("skipped: ../shared/grbl is absent (GRBL's parser is built from it)");
        return;
    };
    let dir = std::env::temp_dir().join(format!("millpath-grbl-parser-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let options = Options {
        dialect: Dialect::Grbl,
        top: Some(2.0),
        tool: Some(2.0),
        ..Default::default()
    };
    // the base program is good for both
    assert_eq!(grbl_refuses(&exe, &dir, GOOD), None);
    let clean = verify(GOOD, &options);
    assert!(
        clean.findings.iter().all(|f| f.severity != Severity::Error),
        "{:#?}",
        clean.findings
    );

    let mut rng = Rng(0x6772_626C_3333);
    let lines: Vec<&str> = GOOD.lines().collect();
    let (mut refused, mut agreed) = (0, 0);
    let mut missed = Vec::new();
    let mut stricter: BTreeMap<String, usize> = BTreeMap::new();
    let mut designed: BTreeMap<&str, usize> = BTreeMap::new();
    for _ in 0..PROGRAMS {
        let mut prog: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        for _ in 0..1 + rng.below(3) {
            mutate(&mut prog, &mut rng, ALPHABET);
        }
        let text = prog.join("\n") + "\n";
        let report = verify(&text, &options);
        let errors: Vec<usize> = report
            .findings
            .iter()
            .filter(|f| f.severity == Severity::Error)
            .filter_map(|f| f.line)
            .collect();
        let grbl = grbl_refuses(&exe, &dir, &text);
        let first_grbl = grbl.as_ref().map_or(usize::MAX, |(l, _)| *l);
        if let Some((line, answer)) = &grbl {
            refused += 1;
            let shown = text.lines().nth(line - 1).unwrap_or("");
            let by_design = report.findings.iter().find_map(|f| match f.kind {
                FindingKind::UnknownPosition { .. } if f.line == Some(*line) => {
                    Some("a move before the position is known")
                }
                FindingKind::AfterProgramEnd if f.line.is_some_and(|l| l <= *line) => {
                    Some("code after the program end")
                }
                _ => None,
            });
            let by_design = by_design.or_else(|| {
                (shown.contains("G38") && answer == "error:33")
                    .then_some("a probe to where the validator's last probe ended")
            });
            if errors.contains(line) {
                agreed += 1;
            } else if let Some(why) = by_design {
                *designed.entry(why).or_default() += 1;
            } else {
                missed.push(format!("line {line} `{shown}`: GRBL {answer}"));
                // GRBL_PARSER_KEEP=DIR: the programs of the differences, to look at
                if let Some(keep) = std::env::var_os("GRBL_PARSER_KEEP") {
                    let file = Path::new(&keep).join(format!("missed-{}.gcode", missed.len()));
                    std::fs::write(file, &text).unwrap();
                }
            }
        }
        // verify refusing a line GRBL took (before GRBL's first refusal): by design
        for f in report
            .findings
            .iter()
            .filter(|f| f.severity == Severity::Error)
        {
            if f.line.is_some_and(|l| l < first_grbl) {
                // the kind, and a syntax error's own kind
                let kind = format!("{:?}", f.kind);
                let mut parts = kind.split(['(', ' ', '{']).filter(|p| !p.is_empty());
                let kind = match (parts.next(), parts.next()) {
                    (Some("Syntax"), Some(inner)) => format!("Syntax {inner}"),
                    (Some(k), _) => k.to_string(),
                    _ => String::new(),
                };
                *stricter.entry(kind).or_default() += 1;
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    eprintln!(
        "{PROGRAMS} mutated programs: GRBL refused a line in {refused}, verify refused that \
         line in {agreed}"
    );
    eprintln!("GRBL refused, verify did not, by design: {designed:?}");
    eprintln!("verify stricter than GRBL (lines GRBL accepts), by finding: {stricter:?}");
    assert!(
        refused >= PROGRAMS / 4,
        "too few refusals to mean much: {refused}"
    );
    assert!(
        missed.is_empty(),
        "lines GRBL refuses and verify does not ({}):\n{}",
        missed.len(),
        missed.join("\n")
    );
}
