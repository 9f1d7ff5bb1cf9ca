//! The exact estimated time (h:mm:ss) beside the reference's whole-minute statistics:
//! `compile`'s summary and `check --format json` give the same figure, the statistics'
//! "ca. N min" is that figure rounded up, and the reference command line prints none.

mod common;

use common::millpath;
use std::path::Path;

fn plate(dir: &Path, machine: &str) {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate/1234.1P.dxf");
    std::fs::copy(example, dir.join("1234.1P.dxf")).unwrap();
    std::fs::write(
        dir.join("millpath.toml"),
        format!("feed = 300\nsweep_speed = 1000\nsweep_height = 10\n{machine}"),
    )
    .unwrap();
}

/// `h:mm:ss` as seconds.
fn seconds_of(hms: &str) -> u64 {
    let p: Vec<u64> = hms.split(':').map(|v| v.parse().unwrap()).collect();
    assert_eq!(p.len(), 3, "{hms}");
    assert!(p[1] < 60 && p[2] < 60, "{hms}");
    p[0] * 3600 + p[1] * 60 + p[2]
}

/// The exact time `check --format json` reports for the plate (seconds, h:mm:ss).
fn checked(dir: &Path) -> (f64, String) {
    let o = millpath(dir, &["check", "--format", "json", "1234.1P.dxf"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let times = v["times"].as_array().unwrap();
    assert_eq!(times.len(), 1, "{v}");
    assert_eq!(times[0]["path"], "1234.1P");
    assert!(times[0]["file"].as_str().unwrap().ends_with("1234.1P.dxf"));
    (
        times[0]["seconds"].as_f64().unwrap(),
        times[0]["time"].as_str().unwrap().to_string(),
    )
}

/// The summary's exact time and the Sum line's whole minutes after `compile`.
fn compiled(dir: &Path, lang: &str) -> (String, u64) {
    let o = millpath(dir, &["compile", "--lang", lang, "1234.1P.dxf"]);
    assert!(o.status.success());
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    let label = if lang == "de" {
        "Geschätzte Zeit: "
    } else {
        "Estimated time: "
    };
    let time = err
        .lines()
        .find_map(|l| l.trim().strip_prefix(label))
        .unwrap_or_else(|| panic!("{err}"))
        .to_string();
    let sum = if lang == "de" { "Summe:" } else { "Sum:" };
    let minutes = err
        .split(sum)
        .nth(1)
        .and_then(|r| r.split("ca.").nth(1))
        .and_then(|r| r.split_whitespace().next())
        .and_then(|m| m.parse().ok())
        .unwrap_or_else(|| panic!("{err}"));
    (time, minutes)
}

#[test]
fn compile_and_check_give_the_same_exact_time() {
    for machine in [
        "",
        "[machine]\nmax_velocity = 3000\nmax_acceleration = 500\npath_tolerance = 0.05\n",
    ] {
        let dir = tempfile::tempdir().unwrap();
        plate(dir.path(), machine);
        let (seconds, time) = checked(dir.path());
        assert!(seconds > 0.0 && seconds.is_finite());
        assert_eq!(
            seconds_of(&time),
            seconds.round() as u64,
            "{time} {seconds}"
        );
        for lang in ["en", "de"] {
            let (summary, minutes) = compiled(dir.path(), lang);
            assert_eq!(summary, time, "{machine}");
            // the statistics keep the reference's whole minutes: the exact time rounded up
            assert_eq!(minutes, (seconds / 60.0).ceil() as u64, "{seconds}");
        }
    }
}

#[test]
fn the_machine_model_is_faster_than_the_reference_formula() {
    let reference = tempfile::tempdir().unwrap();
    plate(reference.path(), "");
    let machine = tempfile::tempdir().unwrap();
    plate(
        machine.path(),
        "[machine]\nmax_velocity = 3000\nmax_acceleration = 500\n",
    );
    let (r, _) = checked(reference.path());
    let (m, _) = checked(machine.path());
    // the reference pads every move by 1.4; LinuxCNC's planner at these limits does not
    assert!(m < r / 1.2, "{m} {r}");
}

#[test]
fn the_reference_command_line_prints_no_exact_time() {
    let dir = tempfile::tempdir().unwrap();
    plate(dir.path(), "");
    let o = millpath(
        dir.path(),
        &["pathdxf2gcode", "/f150", "/v500", "/s15", "1234.1P.dxf"],
    );
    assert!(o.status.success());
    assert!(!String::from_utf8_lossy(&o.stderr).contains("Estimated time"));
}
