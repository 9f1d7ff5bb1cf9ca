//! The reference tool's recorded outputs (../shared/conformance) against our binary, and
//! `check` over every shared drawing. Skips with a message when ../shared is absent.

use std::path::{Path, PathBuf};
use std::process::Command;

fn shared() -> Option<PathBuf> {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared");
    if p.join("conformance/cases").is_dir() {
        Some(p)
    } else {
        eprintln!("skipped: ../shared/conformance is not there");
        None
    }
}

fn drop_banner(text: &str) -> String {
    let text = text.replace("\r\n", "\n");
    let mut lines: Vec<&str> = text.trim().split('\n').collect();
    if lines.len() > 1 && lines[0] == "%" && lines[1].starts_with('(') {
        lines.remove(1);
    }
    lines.join("\n")
}

fn copy_dxfs(from: &Path, to: &Path) {
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dxf")) {
            std::fs::copy(&p, to.join(p.file_name().unwrap())).unwrap();
        }
    }
}

#[test]
fn reference_cases_are_reproduced_byte_for_byte() {
    let Some(shared) = shared() else { return };
    let cases = shared.join("conformance/cases");
    let mut names: Vec<PathBuf> = std::fs::read_dir(&cases)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    names.sort();
    let mut failures = Vec::new();
    for case in &names {
        let spec: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(case.join("args.json")).unwrap())
                .unwrap();
        let work = tempfile::tempdir().unwrap();
        copy_dxfs(&shared.join("conformance/fixtures"), work.path());
        let args: Vec<String> = spec["args"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a.as_str().unwrap().to_string())
            .collect();
        let out = Command::new(env!("CARGO_BIN_EXE_millpath"))
            .arg("pathdxf2gcode")
            .args(&args)
            .args(["/l", "de"])
            .current_dir(work.path())
            .output()
            .unwrap();
        let code = out.status.code().unwrap_or(-1) as i64;
        let want = spec["expected_exit"]["value"].as_i64().unwrap();
        let exit_ok = if spec["expected_exit"]["op"] == "==" {
            code == want
        } else {
            code != want
        };
        if !exit_ok {
            failures.push(format!(
                "{}: exit {code}: {}",
                case.display(),
                String::from_utf8_lossy(&out.stderr)
            ));
        }
        for f in spec["expected_files"].as_array().unwrap() {
            let name = f["file"].as_str().unwrap();
            let produced = std::fs::read_to_string(work.path().join(name)).unwrap_or_default();
            let expected = std::fs::read_to_string(case.join(name)).unwrap();
            if drop_banner(&produced) != drop_banner(&expected) {
                failures.push(format!("{}: {name} differs", case.display()));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
    assert!(names.len() >= 12);
}

#[test]
fn check_over_every_shared_drawing_never_panics_and_locates_errors() {
    let Some(shared) = shared() else { return };
    let out = Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(["check", "--format", "json"])
        .arg(shared.join("conformance/fixtures"))
        .arg(shared.join("samples"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(matches!(out.status.code(), Some(0) | Some(1)));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["files"], 38);
    for d in v["diagnostics"].as_array().unwrap() {
        assert!(
            d["location"]["file"].is_string(),
            "diagnostic without a file: {d}"
        );
    }
    // the two samples and the drawings the reference tests expect to pass are clean
    for clean in [
        "2051 Pv Schlüssel.dxf",
        "2916.1P.dxf",
        "8999.21P.dxf",
        "8998.31-8998.34P.dxf",
        "8999.16P.dxf",
    ] {
        assert!(
            !v["diagnostics"]
                .as_array()
                .unwrap()
                .iter()
                .any(|d| d["location"]["file"].as_str().unwrap().ends_with(clean)),
            "{clean}"
        );
    }
}
