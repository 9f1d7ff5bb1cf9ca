//! The byte-identity proof of issue 32: the programs of the `linuxcnc` and `grbl` posts (and
//! the reference dialect) stay what they were when the dialects were code. For every example,
//! every shared drawing and every setting that reaches the output (spindle and dwell, plunge
//! feed, `[machine]`, `[heightmap]`, `probe_split`, `[[clamp]]`), each file of the set is
//! compiled and hashed (SHA-256), and so is adjust-z's program of each probing set filled with
//! measured heights. The hashes are in `posts/identity.tsv` (recorded from the binary before
//! the posts existed; hashes only, never copies of shared data).
//!
//! The examples' rows always run; the shared drawings' rows are skipped with a message when
//! `../shared` is absent. `MILLPATH_RECORD_IDENTITY=1` writes the manifest instead of
//! comparing (only ever to record a deliberate change of output).

use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

const MANIFEST: &str = "tests/posts/identity.tsv";

/// Each setting: its name and the lines of millpath.toml (top-level keys, then tables).
const SETTINGS: &[(&str, &str)] = &[
    ("reference", ""),
    ("linuxcnc", "dialect = \"linuxcnc\"\n"),
    ("grbl", "dialect = \"grbl\"\n"),
    (
        "linuxcnc-spindle",
        "dialect = \"linuxcnc\"\nspindle_rpm = 12000\nspindle_dwell = 3\nplunge_feed = 100\n",
    ),
    (
        "grbl-spindle",
        "dialect = \"grbl\"\nspindle_rpm = 9000.5\nspindle_dwell = 0\nplunge_feed = 40\n",
    ),
    (
        "linuxcnc-machine",
        "dialect = \"linuxcnc\"\n[machine]\nmax_velocity = 3000\nmax_acceleration = { x = 200, y = 150, z = 80 }\npath_tolerance = 0.02\n",
    ),
    // recorded before GRBL had a time model of its own: the grbl dialect's `[machine]` now
    // times with GRBL's planner (issue 33), so the LinuxCNC planner is named to keep the bytes
    (
        "grbl-machine",
        "dialect = \"grbl\"\nspindle_rpm = 10000\n[machine]\ncontroller = \"linuxcnc\"\nmax_velocity = 2500\nmax_acceleration = 300\n",
    ),
    (
        "linuxcnc-heightmap",
        "dialect = \"linuxcnc\"\n[heightmap]\nstep = 7\nmargin = 1.5\n",
    ),
    (
        "grbl-heightmap",
        "dialect = \"grbl\"\nspindle_rpm = 8000\n[heightmap]\nstep = 12\nprobe_depth = 3\nprobe_feed = 40\n",
    ),
    ("linuxcnc-split", "dialect = \"linuxcnc\"\nprobe_split = 4\n"),
    (
        "grbl-split",
        "dialect = \"grbl\"\nprobe_split = 2.5\nplunge_feed = 60\n",
    ),
    (
        "linuxcnc-clamp",
        "dialect = \"linuxcnc\"\n[[clamp]]\nname = \"vice\"\nmin = [-500, -500, -50]\nmax = [-400, -400, 50]\n",
    ),
    (
        "grbl-clamp",
        "dialect = \"grbl\"\n[[clamp]]\nmin = [-500, -500, -50]\nmax = [-400, -400, 50]\n[[clamp]]\nname = \"stop\"\nmin = [600, 600, -50]\nmax = [700, 700, 50]\n",
    ),
];

/// What the shared drawings need besides the setting (the examples bring their own file).
const SHARED_BASE: &str = "feed = 300\nsweep_speed = 1000\nsweep_height = 25\n";

/// Drawings with several path layers, compiled one path at a time.
const SHARED_PATHS: &[(&str, &str)] = &[
    ("2916.1P.dxf", "2916.1P"),
    ("2916.1P.dxf", "2916.2P"),
    ("2051 Pv Schlüssel.dxf", "2051.1P"),
    ("2051 Pv Schlüssel.dxf", "2051.2P"),
    ("8998.dxf", "8998.1P"),
    ("8998.dxf", "8998.2P"),
    ("8999.21P.dxf", "8999.21P"),
    ("8999.21P.dxf", "8999.21S"),
];

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `../shared` beside the repository (`MILLPATH_SHARED` names it elsewhere, e.g. from a
/// worktree).
fn shared() -> Option<PathBuf> {
    let p = std::env::var_os("MILLPATH_SHARED")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo().join("../shared"));
    p.join("conformance/fixtures").is_dir().then_some(p)
}

fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

fn copy_files(from: &Path, to: &Path) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(from)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file())
        .collect();
    entries.sort();
    for p in entries {
        std::fs::copy(&p, to.join(p.file_name().unwrap())).unwrap();
    }
}

fn is_output(name: &str) -> bool {
    name.ends_with(".gcode") || name.ends_with("_Z.txt")
}

/// A probing set's `_Z.txt` filled in: each value the line's nominal top (`T=` in its
/// comment) plus a small offset that differs from point to point.
fn fill_z(text: &str) -> String {
    let mut out = String::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim_end().ends_with('=') {
            let top = line
                .split("T=")
                .nth(1)
                .and_then(|r| r.split(')').next())
                .and_then(|v| v.parse::<f64>().ok())
                .unwrap_or(0.0);
            let offset = ((i * 37 % 11) as f64 - 5.0) * 0.01;
            out.push_str(&format!("{}{:.3}\n", line.trim_end(), top + offset));
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// Runs one compile in `dir`, hashes its outputs (and adjust-z's of each filled probing set)
/// into `rows` under `setting`/`job`, and removes them.
fn run_job(
    dir: &Path,
    setting: &str,
    job: &str,
    args: &[&str],
    rows: &mut BTreeMap<String, String>,
) {
    let bin = env!("CARGO_BIN_EXE_millpath");
    let out = Command::new(bin)
        .arg("compile")
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    let key = |file: &str| format!("{setting}\t{job}\t{file}");
    rows.insert(key("exit"), out.status.code().unwrap_or(-1).to_string());
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| is_output(n))
        .collect();
    names.sort();
    for n in &names {
        rows.insert(key(n), sha256(&std::fs::read(dir.join(n)).unwrap()));
    }
    for clean in names.iter().filter(|n| n.ends_with("_Clean.gcode")) {
        let base = clean.trim_end_matches("_Clean.gcode");
        let z = dir.join(format!("{base}_Z.txt"));
        std::fs::write(&z, fill_z(&std::fs::read_to_string(&z).unwrap())).unwrap();
        let out = Command::new(bin)
            .args(["adjust-z", "--max", "2", clean])
            .current_dir(dir)
            .output()
            .unwrap();
        let adjusted = format!("adjusted/{base}");
        rows.insert(
            key(&format!("{adjusted}/exit")),
            out.status.code().unwrap_or(-1).to_string(),
        );
        let milling = dir.join(format!("{base}_Milling.gcode"));
        if let Ok(bytes) = std::fs::read(&milling) {
            rows.insert(key(&format!("{adjusted}_Milling.gcode")), sha256(&bytes));
        }
    }
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if is_output(&p.file_name().unwrap().to_string_lossy()) {
            std::fs::remove_file(p).unwrap();
        }
    }
}

/// Every row this machine can make (shared rows only when `../shared` is there).
fn compute(shared: Option<&Path>) -> BTreeMap<String, String> {
    let mut rows = BTreeMap::new();
    for (setting, toml) in SETTINGS {
        for example in ["plate", "text"] {
            let work = tempfile::tempdir().unwrap();
            let from = repo().join("examples").join(example);
            copy_files(&from, work.path());
            let own = std::fs::read_to_string(from.join("millpath.toml")).unwrap();
            std::fs::write(work.path().join("millpath.toml"), format!("{own}{toml}")).unwrap();
            run_job(
                work.path(),
                setting,
                &format!("examples/{example}"),
                &["."],
                &mut rows,
            );
        }
        if let Some(shared) = shared {
            let work = tempfile::tempdir().unwrap();
            copy_files(&shared.join("conformance/fixtures"), work.path());
            copy_files(&shared.join("samples"), work.path());
            std::fs::write(
                work.path().join("millpath.toml"),
                format!("{SHARED_BASE}{toml}"),
            )
            .unwrap();
            run_job(work.path(), setting, "shared/all", &["."], &mut rows);
            for (file, path) in SHARED_PATHS {
                let job = format!("shared/{path}");
                let args = ["--path-pattern", path, file];
                run_job(work.path(), setting, &job, &args, &mut rows);
            }
        }
    }
    rows
}

#[test]
fn linuxcnc_and_grbl_programs_are_byte_identical() {
    let shared = shared();
    if shared.is_none() {
        eprintln!("skipped the shared drawings' rows: ../shared is not there");
    }
    let rows = compute(shared.as_deref());
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(MANIFEST);
    if std::env::var_os("MILLPATH_RECORD_IDENTITY").is_some() {
        assert!(shared.is_some(), "record with ../shared present");
        let text: String = rows.iter().map(|(k, v)| format!("{k}\t{v}\n")).collect();
        std::fs::write(&manifest, text).unwrap();
        return;
    }
    let want: BTreeMap<String, String> = std::fs::read_to_string(&manifest)
        .unwrap()
        .lines()
        .filter_map(|l| l.rsplit_once('\t'))
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .filter(|(k, _)| shared.is_some() || !k.split('\t').nth(1).unwrap().starts_with("shared/"))
        .collect();
    let mut diffs = Vec::new();
    for (k, v) in &want {
        match rows.get(k) {
            None => diffs.push(format!("missing now: {k}")),
            Some(got) if got != v => diffs.push(format!("changed: {k}")),
            _ => {}
        }
    }
    for k in rows.keys().filter(|k| !want.contains_key(*k)) {
        diffs.push(format!("new: {k}"));
    }
    assert!(
        diffs.is_empty(),
        "{} of {} rows differ:\n{}",
        diffs.len(),
        want.len(),
        diffs.join("\n")
    );
    // the proof covers what it says: every setting, probing sets and adjusted programs
    let files = |part: &str| want.keys().filter(|k| k.contains(part)).count();
    assert!(files("_Milling.gcode") > 0 && files("_Probing.gcode") > 0);
    assert!(files("_Z.txt") > 0 && files("adjusted/") > 0);
    eprintln!("{} rows identical", want.len());
}
