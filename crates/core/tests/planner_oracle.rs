//! The time model against LinuxCNC 2.9's own trajectory planner: every program of the
//! planner oracle (`tests/planner_oracle.sh`) is estimated here and held within 2 % of the
//! planner time recorded in `fixtures/planner_times.tsv`. The synthetic programs are read
//! from `tests/planner/programs`; the examples and shared drawings are compiled as the
//! script compiles them (the shared ones are skipped, with a note, when `../shared` is
//! absent).

mod support;

use millpath_core::emit::stats::Stats;
use millpath_core::emit::Kind;
use millpath_core::load::config::{parse, Have};
use millpath_core::load::fs::MemFileSystem;
use millpath_core::{compile_file, Session, Settings};
use std::path::{Path, PathBuf};
use support::gcode::{items_of, start_of};
use support::root;

/// The allowed distance from the planner's time.
const TOLERANCE: f64 = 0.02;

fn oracle_dir() -> PathBuf {
    root().join("tests/planner")
}

/// The settings of `tests/planner/millpath.toml`.
fn settings() -> Settings {
    let text = std::fs::read_to_string(oracle_dir().join("millpath.toml")).unwrap();
    let mut s = Settings::default();
    parse(&text, Path::new("."))
        .unwrap()
        .apply(&mut s, &mut Have::default());
    s
}

fn seconds(s: &Stats) -> f64 {
    (s.mill_min + s.drill_min + s.sweep_min) * 60.0
}

/// A synthetic program's estimate.
fn synthetic(name: &str, s: &Settings) -> f64 {
    let text = std::fs::read_to_string(oracle_dir().join("programs").join(name)).unwrap();
    let start = start_of(&text, s.sweep_height);
    seconds(&Stats::timed(
        &items_of(&text, [start.x, start.y, start.z]),
        s.sweep_speed,
        start,
        s.time_model().as_ref(),
    ))
}

/// A drawing's estimate, compiled as the oracle script compiles it; `None` without the
/// drawing (the shared data is absent).
fn compiled(name: &str, s: &Settings) -> Option<f64> {
    let (folder, file, pattern) = match name {
        "examples/plate/1234.1P.ngc" => ("examples/plate", "1234.1P.dxf", None),
        "examples/text/2001.ngc" => ("examples/text", "2001.mpath", None),
        "examples/text/2010.ngc" => ("examples/text", "2010.mpath", None),
        "shared/samples/2916.1P.ngc" => ("../shared/samples", "2916.1P.dxf", Some("2916\\.1P")),
        "shared/samples/2051.1P.ngc" => (
            "../shared/samples",
            "2051 Pv Schlüssel.dxf",
            Some("2051\\.1P"),
        ),
        _ => {
            let stem = name
                .strip_prefix("shared/conformance/")?
                .strip_suffix(".ngc")?;
            return compiled_in(
                "../shared/conformance/fixtures",
                &format!("{stem}.dxf"),
                None,
                s,
            );
        }
    };
    compiled_in(folder, file, pattern, s)
}

fn compiled_in(folder: &str, file: &str, pattern: Option<&str>, s: &Settings) -> Option<f64> {
    let dir = root().join(folder);
    if !dir.join(file).exists() {
        return None;
    }
    let mut fs = MemFileSystem::default();
    for f in support::files_in(&dir, &["dxf", "mpath"]) {
        let name = f.file_name().unwrap().to_string_lossy().to_string();
        fs.add(name.as_str(), std::fs::read(&f).unwrap());
    }
    let mut settings = s.clone();
    if let Some(p) = pattern {
        settings.path_pattern = p.to_string();
    }
    let mut session = Session::new(settings, &fs).expect("settings");
    let outcome = compile_file(&mut session, Path::new(file), "planner oracle");
    assert!(
        !outcome.stats.is_empty(),
        "{file}: {:?}",
        session.diags.list
    );
    Some(outcome.stats.iter().map(|(_, st)| seconds(st)).sum())
}

#[test]
fn the_model_keeps_within_two_percent_of_linuxcncs_planner() {
    let s = settings();
    let recorded =
        std::fs::read_to_string(root().join("crates/core/tests/fixtures/planner_times.tsv"))
            .unwrap();
    let mut rows = Vec::new();
    let mut skipped = 0;
    for line in recorded
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
    {
        let (name, planner) = line.split_once('\t').unwrap();
        let planner: f64 = planner.parse().unwrap();
        let estimate = match name.strip_prefix("synthetic/") {
            Some(file) => Some(synthetic(file, &s)),
            None => compiled(name, &s),
        };
        match estimate {
            Some(e) => rows.push((name.to_string(), e, planner)),
            None => skipped += 1,
        }
    }
    let mut table = String::from("program\testimate s\tplanner s\tratio\n");
    for (name, e, p) in &rows {
        table += &format!("{name}\t{e:.3}\t{p:.3}\t{:.4}\n", e / p);
    }
    println!("{table}");
    if skipped > 0 {
        println!("note: {skipped} shared drawings skipped (../shared is absent)");
    }
    assert!(rows.len() >= 12, "{table}");
    let off: Vec<_> = rows
        .iter()
        .filter(|(_, e, p)| ((e / p) - 1.0).abs() > TOLERANCE)
        .collect();
    assert!(off.is_empty(), "beyond 2 %: {off:?}\n{table}");
}

#[test]
fn the_gcode_reader_reads_what_the_programs_say() {
    let items = items_of(
        "G0 X10 (a comment X99)\nG1 Y5 F600\nG2 X15 Y10 I5 J0\nG3 X15 Y10 I-5 J0\n",
        [0.0; 3],
    );
    assert_eq!(items.len(), 4);
    assert_eq!(items[0].kind, Kind::HSweep);
    assert_eq!(items[0].target.x, Some(10.0));
    assert_eq!(items[1].feed, 600.0);
    assert!((items[1].len - 5.0).abs() < 1e-12);
    // a quarter circle of radius 5 clockwise, then a full circle
    let q = std::f64::consts::FRAC_PI_2 * 5.0;
    assert!((items[2].len - q).abs() < 1e-9, "{}", items[2].len);
    assert!((items[3].len - 4.0 * q).abs() < 1e-9, "{}", items[3].len);
}

/// `PLANNER_PROGRAM=FILE cargo test -p millpath-core --test planner_oracle -- --ignored`:
/// the model's time of each line of a program (to set beside the oracle's `--profiles`).
#[test]
#[ignore]
fn print_the_time_of_each_line() {
    let Some(file) = std::env::var_os("PLANNER_PROGRAM") else {
        return;
    };
    let s = settings();
    let text = std::fs::read_to_string(file).unwrap();
    let start = start_of(&text, s.sweep_height);
    let items = items_of(&text, [start.x, start.y, start.z]);
    let times = s.time_model().unwrap().item_times(&items, start);
    let lines: Vec<&str> = text.lines().collect();
    for (it, t) in items.iter().zip(times) {
        let no = it.source.unwrap() as usize;
        println!("{no}\t{t:.4}\t{}", lines[no - 1].trim());
    }
}
