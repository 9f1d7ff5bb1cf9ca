//! The second opinion's lean checker (no moves kept; clamps, depths and stock model on a
//! second reading of the program) gives the report of the checker that keeps every move, on
//! every program of the examples and of the shared drawings (when ../shared is there), in
//! every dialect: as compile checks it, with rapids into a raised stock, cuts below a raised
//! bottom, a clamp across the middle, and the findings and work limits.

mod support;

use millpath_core::{compile_file, Dialect, OsFileSystem, Session, Settings};
use millpath_verify::{
    parse_stock_comment, program_top, Clamp, FindingKind, Limits, Options, Report, Verifier,
};
use std::path::Path;
use support::*;

/// The milling and clean programs `compile` writes for a drawing on disk (its folder's
/// millpath.toml applied); none when it does not compile alone.
fn programs_of(file: &Path, dialect: Dialect) -> Vec<(String, String)> {
    let mut s = Settings::default();
    let dir = file.parent().unwrap();
    if let Ok(text) = std::fs::read_to_string(dir.join("millpath.toml")) {
        let cfg = millpath_core::load::config::parse(&text, dir).unwrap();
        cfg.apply(&mut s, &mut Default::default());
    }
    s.dialect = dialect;
    let mut session = Session::new(s, &OsFileSystem).unwrap();
    compile_file(&mut session, file, "millpath test")
        .outputs
        .into_iter()
        .filter(|o| {
            let p = o.path.to_string_lossy();
            p.ends_with("_Milling.gcode") || p.ends_with("_Clean.gcode")
        })
        .map(|o| (format!("{dialect} {}", o.path.display()), o.content))
        .collect()
}

/// Both checkers' reports, asserted equal to the last bit.
fn same(name: &str, program: &str, o: &Options) -> Report {
    let kept = Verifier::new(o.clone()).read_text(program);
    let lean = Verifier::lean(o.clone()).read_text(program);
    assert_eq!(
        format!("{kept:#?}"),
        format!("{lean:#?}"),
        "{name} with {o:?}"
    );
    kept
}

/// The T, O and BOTTOM of the program's `(MILLPATH-STOCK …)` comment, if it has one.
fn comment(program: &str) -> (Option<f64>, Option<f64>, Option<f64>) {
    program
        .lines()
        .flat_map(|l| l.split('(').skip(1))
        .filter_map(|c| c.split_once(')').map(|(t, _)| t))
        .find_map(|c| parse_stock_comment(c)?.ok())
        .map_or((None, None, None), |p| (p.top, p.tool, p.bottom))
}

#[test]
fn lean_and_kept_checkers_agree_on_every_compiled_program() {
    let mut drawings = files_in(&root().join("examples/plate"), &["dxf"]);
    drawings.extend(files_in(&root().join("examples/text"), &["mpath"]));
    let shared = root().join("../shared");
    let fixtures = files_in(&shared.join("conformance/fixtures"), &["dxf"]);
    if fixtures.is_empty() {
        eprintln!("../shared is not there: only the examples");
    }
    drawings.extend(fixtures);
    let mut programs = Vec::new();
    for dialect in [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl] {
        for f in &drawings {
            programs.extend(programs_of(f, dialect));
        }
    }
    assert!(programs.len() >= 12, "{}", programs.len());
    let (mut hits, mut below, mut rapids, mut capped, mut stopped) = (0, 0, 0, 0, 0);
    for (name, g) in &programs {
        let dialect = match name.split(' ').next() {
            Some("linuxcnc") => millpath_verify::Dialect::LinuxCnc,
            Some("grbl") => millpath_verify::Dialect::Grbl,
            _ => millpath_verify::Dialect::Reference,
        };
        let (t, o, b) = comment(g);
        let top = program_top(g).or(t).unwrap_or(0.0);
        let tool = o.unwrap_or(2.0);
        // as compile checks it
        let plain = Options {
            dialect,
            top: Some(top),
            tool: Some(tool),
            bottom: b,
            limits: Limits {
                max_work: u64::MAX,
                ..Limits::default()
            },
            ..Options::default()
        };
        let r = same(name, g, &plain);
        let Some(s) = r.stock else { continue };
        // a box over the middle of the program's area, the stock raised, the bottom too
        let (cx, cy) = (
            s.x0 + s.cell * s.nx as f64 / 2.0,
            s.y0 + s.cell * s.ny as f64 / 2.0,
        );
        let hard = Options {
            top: Some(top + 2.0),
            bottom: Some(top - 0.2),
            clamps: vec![Clamp {
                name: "middle".into(),
                min: [cx - 3.0, cy - 3.0, -100.0],
                max: [cx + 3.0, cy + 3.0, top],
            }],
            ..plain.clone()
        };
        let r = same(name, g, &hard);
        let count = |code: &str| r.findings.iter().filter(|f| f.code() == code).count();
        hits += count("clamp-hit");
        below += count("below-bottom");
        rapids += count("rapid-into-material");
        for limits in [
            Limits {
                max_findings: 4,
                ..Limits::default()
            },
            Limits {
                max_work: 20_000,
                max_findings: 40,
                ..Limits::default()
            },
        ] {
            let r = same(
                name,
                g,
                &Options {
                    limits,
                    ..hard.clone()
                },
            );
            for f in &r.findings {
                match f.kind {
                    FindingKind::Limit(_) => capped += 1,
                    FindingKind::StockSkipped(_) => stopped += 1,
                    _ => {}
                }
            }
        }
    }
    // every check and limit was reached somewhere
    assert!(
        hits > 0 && below > 0 && rapids > 0 && capped > 0 && stopped > 0,
        "{hits} {below} {rapids} {capped} {stopped}"
    );
}

/// A zigzag of 40 cuts over a box: clamp hits on many lines, in every dialect.
fn zigzag() -> String {
    let mut t =
        String::from("path 3001.1P {\n  start (0, 0)  O2 T2 I1,2 B-0,3 S5\n  end (41, 0)\n");
    for i in 0..40 {
        t += &format!(
            "  mill ({i}, {}) -> ({}, {})\n",
            (i % 2) * 5,
            i + 1,
            ((i + 1) % 2) * 5
        );
    }
    t += "  mill (40, 0) -> (41, 0)\n}\n";
    t
}

/// The diagnostics' messages (with the lines and texts the checker names) and whether the
/// program was written.
fn review_as(dir: &Path, settings: Settings) -> (Vec<String>, bool) {
    let _ = std::fs::remove_file(dir.join("3001_Milling.gcode"));
    let mut session = Session::new(settings, &OsFileSystem).unwrap();
    let out = compile_file(&mut session, &dir.join("3001.mpath"), "millpath test");
    for o in &out.outputs {
        // a staged program is already in its temporary file: the command line renames it
        if let Some(staged) = &o.staged {
            let _ = std::fs::remove_file(staged);
        }
    }
    let messages = session
        .diags
        .list
        .iter()
        .map(|d| format!("{:?} {}", d.severity, d.message(Default::default())))
        .collect();
    (messages, !out.outputs.is_empty())
}

#[test]
fn check_kept_text_and_staged_file_give_the_same_review() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("3001.mpath"), zigzag()).unwrap();
    for dialect in [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl] {
        for clamps in [
            vec![],
            vec![Clamp {
                name: "bar".into(),
                min: [10.0, 1.0, -5.0],
                max: [30.0, 2.0, 0.5],
            }],
        ] {
            let base = Settings {
                dialect,
                clamps: clamps.clone(),
                ..settings()
            };
            let kept = review_as(dir.path(), base.clone());
            let staged = review_as(
                dir.path(),
                Settings {
                    stage_outputs: true,
                    ..base.clone()
                },
            );
            let check = review_as(
                dir.path(),
                Settings {
                    check: true,
                    ..base
                },
            );
            assert_eq!(kept, staged, "{dialect}");
            assert_eq!(kept.0, check.0, "{dialect}");
            let hits = kept.0.iter().filter(|m| m.contains("'bar'")).count();
            if clamps.is_empty() {
                assert!(kept.0.is_empty() && kept.1, "{dialect}: {:?}", kept.0);
            } else {
                // every pass of the cuts through the box, each with its G-code line's text
                assert!(hits >= 20, "{dialect}: {:?}", kept.0);
                assert!(kept
                    .0
                    .iter()
                    .all(|m| m.contains("G01") || m.contains("G00")));
                assert!(!kept.1, "{dialect}: a clamp hit refuses the program");
            }
        }
    }
}
