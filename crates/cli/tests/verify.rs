//! `millpath verify` end to end: every program we compile from the examples and from the
//! shared drawings (when ../shared is there; skipped with a message otherwise) passes the
//! independent checker with the drawing's material top T and tool diameter O; a broken
//! program fails with `file:line:` findings.

mod common;

use common::{millpath, MACHINE};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn shared() -> Option<PathBuf> {
    let p = repo().join("../shared");
    if p.join("conformance/fixtures").is_dir() {
        Some(p)
    } else {
        eprintln!("skipped: ../shared is not there (only the examples are verified)");
        None
    }
}

fn files(dir: &Path, ext: &str) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.to_ascii_lowercase().ends_with(ext))
        .collect()
}

fn copy(from: &Path, to: &Path, exts: &[&str]) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        let name = p
            .file_name()
            .unwrap()
            .to_string_lossy()
            .to_ascii_lowercase();
        if exts.iter().any(|x| name.ends_with(x)) {
            std::fs::copy(&p, to.join(p.file_name().unwrap())).unwrap();
        }
    }
}

/// A number of a parameter token: `T2`, `O0,5`, `B-0,3`.
fn param(start_line: &str, letter: char) -> Option<f64> {
    start_line.split_whitespace().find_map(|t| {
        let v = t.strip_prefix(letter)?;
        v.replace(',', ".").parse::<f64>().ok()
    })
}

/// T and O of the compiled path, read from its `start` line in the path's text form.
fn top_and_tool(dir: &Path, source: &str, gcode: &str) -> Option<(f64, f64)> {
    let name = gcode
        .lines()
        .find_map(|l| l.trim().strip_prefix("(Model "))?
        .split('[')
        .next()?
        .to_string();
    let text = if source.ends_with(".mpath") {
        std::fs::read_to_string(dir.join(source)).ok()?
    } else {
        let out = millpath(dir, &["dxf2text", source]);
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let mut in_path = false;
    for l in text.lines() {
        let t = l.trim();
        if t.starts_with("path ") {
            in_path = t.trim_start_matches("path ").trim_end_matches('{').trim() == name;
        } else if in_path && t.starts_with("start ") {
            let params = t.split_once(')')?.1;
            return Some((param(params, 'T')?, param(params, 'O')?));
        }
    }
    None
}

struct Figures {
    programs: usize,
    with_stock: usize,
    warnings: u64,
    notes: usize,
    volume: f64,
}

/// Compiles each drawing on its own (failures skipped) and verifies what it wrote.
fn compile_and_verify(dir: &Path, sources: &[String], machine: &[&str], fig: &mut Figures) {
    for src in sources {
        let before = files(dir, ".gcode");
        let mut args = vec!["compile"];
        args.extend_from_slice(machine);
        args.push(src);
        if !millpath(dir, &args).status.success() {
            eprintln!("  {src}: does not compile alone, skipped");
            continue;
        }
        let written: Vec<String> = files(dir, ".gcode").difference(&before).cloned().collect();
        // the probing file has no Model comment: it takes the values of its companion
        let to = written
            .iter()
            .find_map(|g| top_and_tool(dir, src, &std::fs::read_to_string(dir.join(g)).unwrap()));
        for g in &written {
            let mut args: Vec<String> = ["verify", "--dialect", "reference", "--format", "json"]
                .map(String::from)
                .to_vec();
            if let Some((t, o)) = to {
                args.extend([
                    "--top".into(),
                    t.to_string(),
                    "--tool".into(),
                    o.to_string(),
                ]);
            }
            args.push(g.clone());
            let argv: Vec<&str> = args.iter().map(String::as_str).collect();
            let out = millpath(dir, &argv);
            let v: serde_json::Value = serde_json::from_slice(&out.stdout)
                .unwrap_or_else(|e| panic!("{g}: {e}: {}", String::from_utf8_lossy(&out.stdout)));
            let file = &v["files"][0];
            assert_eq!(
                v["errors"],
                0,
                "{g} (T/O {to:?}): {}",
                serde_json::to_string_pretty(file).unwrap()
            );
            assert_eq!(out.status.code(), Some(0), "{g}");
            fig.programs += 1;
            fig.warnings += file["warnings"].as_u64().unwrap();
            fig.notes += file["findings"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|f| f["severity"] == "note")
                .count();
            if let Some(vol) = file["removed_volume_mm3"].as_f64() {
                fig.with_stock += 1;
                fig.volume += vol;
            }
            eprintln!(
                "  {g}: T/O {to:?}, {} moves, {} warning(s), removed {:.1} mm³",
                file["moves"],
                file["warnings"],
                file["removed_volume_mm3"].as_f64().unwrap_or(0.0)
            );
        }
    }
}

#[test]
fn every_compiled_program_passes_the_checker() {
    let work = tempfile::tempdir().unwrap();
    let mut fig = Figures {
        programs: 0,
        with_stock: 0,
        warnings: 0,
        notes: 0,
        volume: 0.0,
    };
    // the examples, with their millpath.toml
    let text = work.path().join("text");
    copy(&repo().join("examples/text"), &text, &[".mpath", ".toml"]);
    let sources: Vec<String> = files(&text, ".mpath").into_iter().collect();
    compile_and_verify(&text, &sources, &[], &mut fig);
    let plate = work.path().join("plate");
    copy(&repo().join("examples/plate"), &plate, &[".dxf", ".toml"]);
    compile_and_verify(&plate, &["1234.1P.dxf".into()], &[], &mut fig);
    assert_eq!(fig.programs, 5, "2001, 2010, 2020 (clean + probing), 1234");
    assert_eq!(fig.with_stock, 5);
    // every shared drawing that compiles alone
    if let Some(shared) = shared() {
        let fx = work.path().join("fixtures");
        copy(&shared.join("conformance/fixtures"), &fx, &[".dxf"]);
        let sources: Vec<String> = files(&fx, ".dxf").into_iter().collect();
        compile_and_verify(&fx, &sources, &MACHINE, &mut fig);
        assert!(fig.programs >= 30, "{}", fig.programs);
    }
    eprintln!(
        "verified {} programs ({} with the stock model): 0 errors, {} warnings, {} notes, removed {:.0} mm³ in all",
        fig.programs, fig.with_stock, fig.warnings, fig.notes, fig.volume
    );
}

#[test]
fn a_broken_program_fails_with_file_and_line() {
    let work = tempfile::tempdir().unwrap();
    let dir = work.path();
    copy(&repo().join("examples/text"), dir, &[".mpath", ".toml"]);
    assert!(millpath(dir, &["compile", "2001.mpath"]).status.success());
    let good = std::fs::read_to_string(dir.join("2001_Milling.gcode")).unwrap();
    // clean with T and O; the reference's header fails LinuxCNC's feed rule
    let out = millpath(
        dir,
        &["verify", "--top", "3", "--tool", "2", "2001_Milling.gcode"],
    );
    assert_eq!(out.status.code(), Some(0));
    assert!(
        out.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("removed volume"));
    let out = millpath(
        dir,
        &["verify", "--dialect", "linuxcnc", "2001_Milling.gcode"],
    );
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let g01 = good.lines().position(|l| l.starts_with("G01")).unwrap() + 1;
    assert!(
        stdout.contains(&format!(
            "2001_Milling.gcode:{g01}: error: G01 without a feed rate (G94 on line 5 resets the feed rate in LinuxCNC: give F after it)"
        )),
        "{stdout}"
    );
    // a rapid through the material instead of the pull-up after the last pass, in German
    let last_pull = good.rfind("G00 Z10.000\n  (SweepAndDrill").unwrap();
    let broken = format!(
        "{}G00 X25.000 Y5.000\n{}",
        &good[..last_pull],
        &good[last_pull..]
    );
    std::fs::write(dir.join("broken.gcode"), &broken).unwrap();
    let line = broken[..last_pull].lines().count() + 1;
    let out = millpath(
        dir,
        &[
            "verify",
            "--top",
            "3",
            "--tool",
            "2",
            "--lang",
            "de",
            "broken.gcode",
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.starts_with(&format!(
            "broken.gcode:{line}: Fehler: Eilgang (G00) ins Material: die Werkzeugspitze fährt 3.200 mm unter der Materialoberfläche"
        )),
        "{stdout}"
    );
    assert!(stdout.contains("    | G00 X25.000 Y5.000"), "{stdout}");
    // unreadable file and bad options
    assert_eq!(
        millpath(dir, &["verify", "missing.gcode"]).status.code(),
        Some(1)
    );
    assert_eq!(
        millpath(dir, &["verify", "--tool", "0", "2001_Milling.gcode"])
            .status
            .code(),
        Some(2)
    );
    assert_eq!(
        millpath(dir, &["verify", "--dialect", "fanuc", "2001_Milling.gcode"])
            .status
            .code(),
        Some(2)
    );
}
