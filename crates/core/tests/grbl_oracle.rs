//! The GRBL time model against GRBL 1.1h's own firmware on its simulator: every program of
//! the GRBL oracle (`tests/grbl_oracle.sh`) under each of its machines (`tests/grbl/machines`:
//! a slow stiff router, a fast light machine, GRBL's defaults) is estimated here and held
//! within 2 % of the motion time recorded in `fixtures/grbl_times.tsv`, every row. The
//! simulator the oracle builds (`tests/grbl/build_sim.sh`) holds its clock while GRBL's main
//! loop is behind, so a busy computer no longer stalls its steppers; the sender still counts
//! stalls (the fourth column) and a recorded row with any fails here. The synthetic programs
//! are read from `tests/planner/programs`; the examples and shared drawings are compiled as
//! the script compiles them (the shared ones are skipped, with a note, when `../shared` is
//! absent).

mod support;

use millpath_core::geom::P3;
use millpath_core::load::config::{parse, Have};
use millpath_core::load::fs::MemFileSystem;
use millpath_core::{compile_file, Session, Settings};
use std::path::Path;
use support::gcode::{items_of, start_of};
use support::root;

/// The allowed distance from GRBL's time.
const TOLERANCE: f64 = 0.02;

/// The settings of `tests/grbl/machines/NAME.toml`.
fn settings(machine: &str) -> Settings {
    let file = root().join(format!("tests/grbl/machines/{machine}.toml"));
    let text = std::fs::read_to_string(file).unwrap();
    let mut s = Settings::default();
    parse(&text, Path::new("."))
        .unwrap()
        .apply(&mut s, &mut Have::default());
    s
}

/// The estimated motion time (s) of a program's text (what the oracle measures).
fn of_text(text: &str, s: &Settings) -> f64 {
    let start = start_of(text, s.sweep_height);
    let model = s.time_model().expect("a GRBL machine");
    let t = model.plan(&items_of(text, [start.x, start.y, start.z]), start);
    t.mill + t.drill + t.sweep
}

/// The estimated motion time (s) of a probing program: GRBL's probe cycle starts and ends at
/// rest (it waits for the planner to empty first, and its move runs out without contact), so
/// the moves before each probe, the probe move (at its feed) and those after are planned apart,
/// each from rest where the one before ended.
fn probing_estimate(text: &str, s: &Settings) -> f64 {
    let model = s.time_model().expect("a GRBL machine");
    let start = start_of(text, s.sweep_height);
    let mut at = [start.x, start.y, start.z];
    let plan = |chunk: &str, at: &mut [f64; 3]| {
        let items = items_of(chunk, *at);
        let from = P3 {
            x: at[0],
            y: at[1],
            z: at[2],
        };
        if let Some(last) = items.last() {
            let t = last.target;
            *at = [
                t.x.unwrap_or(at[0]),
                t.y.unwrap_or(at[1]),
                t.z.unwrap_or(at[2]),
            ];
        }
        let t = model.plan(&items, from);
        t.mill + t.drill + t.sweep
    };
    let (mut total, mut chunk) = (0.0, String::new());
    for line in text.lines() {
        if line.contains("G38") {
            total += plan(&chunk, &mut at);
            chunk.clear();
            let probe = line.replace("G38.3", "G01").replace("G38.2", "G01");
            total += plan(&probe, &mut at);
        } else {
            chunk.push_str(line);
            chunk.push('\n');
        }
    }
    total + plan(&chunk, &mut at)
}

/// A row of `tests/grbl/drawings.tsv`: the drawing of a program, its path pattern, sweep
/// height and output (`Milling`, `Clean` or `Probing`).
struct Drawing {
    file: std::path::PathBuf,
    pattern: Option<String>,
    sweep_height: Option<f64>,
    output: String,
}

fn drawing_of(name: &str) -> Drawing {
    let table = std::fs::read_to_string(root().join("tests/grbl/drawings.tsv")).unwrap();
    let row = table
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split('\t').collect::<Vec<_>>())
        .find(|f| f[0] == name)
        .unwrap_or_else(|| panic!("{name} is not in tests/grbl/drawings.tsv"));
    let file = match row[1].strip_prefix("shared/") {
        Some(rest) => root().join("../shared").join(rest),
        None => root().join(row[1]),
    };
    Drawing {
        file,
        pattern: (row[2] != "-").then(|| row[2].to_string()),
        sweep_height: (row[3] != "-").then(|| row[3].parse().unwrap()),
        output: row[4].to_string(),
    }
}

/// A program's estimate: a synthetic one read, a drawing compiled as the oracle script
/// compiles it (tests/grbl/drawings.tsv); `None` without the drawing. A milling program's is
/// the compiler's own estimate; a probing program (which the compiler does not estimate: the
/// contact is not known) is read back and planned with each probe move at its feed to its
/// full depth, as GRBL's G38.3 without contact goes.
fn estimate(name: &str, s: &Settings) -> Option<f64> {
    if let Some(file) = name.strip_prefix("synthetic/") {
        let text =
            std::fs::read_to_string(root().join("tests/planner/programs").join(file)).unwrap();
        return Some(of_text(&text, s));
    }
    let d = drawing_of(name);
    if !d.file.exists() {
        return None;
    }
    let dir = d.file.parent().unwrap();
    let file = d.file.file_name().unwrap().to_string_lossy().to_string();
    let mut fs = MemFileSystem::default();
    for f in support::files_in(dir, &["dxf", "mpath"]) {
        let n = f.file_name().unwrap().to_string_lossy().to_string();
        fs.add(n.as_str(), std::fs::read(&f).unwrap());
    }
    let mut settings = s.clone();
    if let Some(p) = &d.pattern {
        settings.path_pattern = p.clone();
    }
    if let Some(h) = d.sweep_height {
        settings.sweep_height = h;
    }
    let mut session = Session::new(settings.clone(), &fs).expect("settings");
    let outcome = compile_file(&mut session, Path::new(&file), "grbl oracle");
    assert!(
        !outcome.stats.is_empty(),
        "{file}: {:?}",
        session.diags.list
    );
    if d.output == "Probing" {
        let program = outcome
            .outputs
            .iter()
            .find(|o| o.path.to_string_lossy().ends_with("_Probing.gcode"))
            .expect("a probing program");
        return Some(probing_estimate(&program.content, &settings));
    }
    // the compiler's own estimate, moves only (the oracle counts dwells apart)
    Some(
        outcome
            .stats
            .iter()
            .map(|(_, st)| st.seconds() - st.dwell)
            .sum(),
    )
}

#[test]
fn the_model_keeps_within_two_percent_of_grbls_planner() {
    let recorded =
        std::fs::read_to_string(root().join("crates/core/tests/fixtures/grbl_times.tsv")).unwrap();
    let mut rows = Vec::new();
    let mut skipped = 0;
    for line in recorded
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
    {
        let f: Vec<&str> = line.split('\t').collect();
        let (machine, name, grbl): (&str, &str, f64) = (f[0], f[1], f[2].parse().unwrap());
        // stalls of the simulator's steppers in that run (none recorded: not known clean)
        let stalls: usize = f.get(3).map_or(usize::MAX, |v| v.parse().unwrap());
        // and the time they took (shown beside: GRBL's time without them)
        let stalled: f64 = f.get(4).map_or(0.0, |v| v.parse().unwrap());
        match estimate(name, &settings(machine)) {
            Some(e) => rows.push((
                machine.to_string(),
                name.to_string(),
                e,
                grbl,
                stalls,
                stalled,
            )),
            None => skipped += 1,
        }
    }
    let mut table = String::from("machine\tprogram\tGRBL s\tmillpath s\tratio\tstalls\n");
    for (m, name, e, g, stalls, _) in &rows {
        let stalls = match *stalls {
            usize::MAX => "?".to_string(),
            n => n.to_string(),
        };
        table += &format!("{m}\t{name}\t{g:.3}\t{e:.3}\t{:.4}\t{stalls}\n", e / g);
    }
    println!("{table}");
    if skipped > 0 {
        println!("note: {skipped} shared drawings skipped (../shared is absent)");
    }
    // the examples alone (without ../shared) are still rows under every machine
    assert!(rows.len() >= 9, "too few rows: {}\n{table}", rows.len());
    let unclean: Vec<_> = rows.iter().filter(|r| r.4 != 0).collect();
    assert!(
        unclean.is_empty(),
        "recorded with stalls: {unclean:?}\n{table}"
    );
    let off: Vec<_> = rows
        .iter()
        .filter(|(_, _, e, g, _, _)| ((e / g) - 1.0).abs() > TOLERANCE)
        .collect();
    assert!(off.is_empty(), "beyond 2 %: {off:?}\n{table}");
}

/// `GRBL_ORACLE_LIST=1 cargo test -p millpath-core --test grbl_oracle -- --ignored
/// --nocapture`: the model's estimate of every candidate program under every machine (to
/// choose programs the simulator can time in reasonable wall time).
#[test]
#[ignore]
fn print_the_estimates() {
    let mut names: Vec<String> = std::fs::read_dir(root().join("tests/planner/programs"))
        .unwrap()
        .map(|e| format!("synthetic/{}", e.unwrap().file_name().to_string_lossy()))
        .collect();
    names.sort();
    let table = std::fs::read_to_string(root().join("tests/grbl/drawings.tsv")).unwrap();
    names.extend(
        table
            .lines()
            .filter(|l| !l.starts_with('#'))
            .map(|l| l.split('\t').next().unwrap().to_string()),
    );
    for m in ["router", "light", "defaults"] {
        let s = settings(m);
        for n in &names {
            println!("{m}\t{n}\t{:?}", estimate(n, &s));
        }
    }
}

/// `GRBL_PROGRAM=FILE GRBL_MACHINE=router cargo test -p millpath-core --test grbl_oracle --
/// --ignored --nocapture print_the_time_of_each_line`: the model's time of each line of a
/// program (to set beside the blocks of the simulator's step file).
#[test]
#[ignore]
fn print_the_time_of_each_line() {
    let Some(file) = std::env::var_os("GRBL_PROGRAM") else {
        return;
    };
    let machine = std::env::var("GRBL_MACHINE").unwrap_or_else(|_| "defaults".into());
    let s = settings(&machine);
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
