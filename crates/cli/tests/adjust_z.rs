//! adjust-z end to end: it never writes a dangerous `_Milling.gcode` (one test per rule of
//! docs/differences.md), and good input still gives the reference's bytes.

mod common;

use common::millpath;
use std::path::{Path, PathBuf};
use std::process::Output;
use std::time::{Duration, SystemTime};

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

const CLEAN: &str = "%\n(p.dxf)\nG00 Z5.000\nG01 Z0.800(=0.800+0.794*[#51-2.000]+0.206*[#52-2.000])\nG01 F150.000 X10.000 Y0.000 Z0.800(=0.800+0.206*[#51-2.000]+0.794*[#52-2.000])\nG00 Z5.000\nM30\n%\n";
const Z: &str = "([0.000 0.000]/T=2.000) #51=2,1\n([10.000 0.000]/T=2.000) #52=2.2\n";

/// A folder with `p_Clean.gcode` and `p_Z.txt`.
fn part(clean: &str, z: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("p_Clean.gcode"), clean).unwrap();
    std::fs::write(dir.path().join("p_Z.txt"), z).unwrap();
    dir
}

fn milling(dir: &Path) -> PathBuf {
    dir.join("p_Milling.gcode")
}

/// Runs both spellings; each must refuse with exit 1, name `context` and write nothing.
fn refused(clean: &str, z: &str, context: &str) -> String {
    let dir = part(clean, z);
    let o = millpath(dir.path(), &["pathgcodeadjustz", "/m0,5", "p"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains(context), "{}", stderr(&o));
    assert!(!milling(dir.path()).exists());
    let o = millpath(dir.path(), &["adjust-z", "--max", "0.5", "p_Clean.gcode"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(!milling(dir.path()).exists());
    stderr(&o)
}

#[test]
fn good_input_gives_the_adjusted_program() {
    let dir = part(CLEAN, Z);
    let o = millpath(dir.path(), &["pathgcodeadjustz", "/m0,5", "p"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(milling(dir.path())).unwrap(),
        CLEAN
            .replace("Z0.800(=0.800+0.794", "Z0.921(==0.800+0.794")
            .replace("Z0.800(=0.800+0.206", "Z0.979(==0.800+0.206")
    );
}

/// The reference's recorded `_Clean.gcode` of TestMethod19 (skips without ../shared).
#[test]
fn recorded_reference_program_is_adjusted_as_before() {
    let case = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/conformance/cases/TestMethod19_ZProbes");
    let Ok(clean) = std::fs::read_to_string(case.join("8999.19P_Clean.gcode")) else {
        eprintln!("skipped: ../shared/conformance is not there");
        return;
    };
    let z = std::fs::read_to_string(case.join("8999.19P_Z.txt")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("8999.19P_Clean.gcode"), &clean).unwrap();
    std::fs::write(
        dir.path().join("8999.19P_Z.txt"),
        z.replace("#51=", "#51=2.1").replace("#52=", "#52=2,2"),
    )
    .unwrap();
    let o = millpath(
        dir.path(),
        &["pathgcodeadjustz", "/m", "0,5", "8999.19P.dxf"],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let got = std::fs::read_to_string(dir.path().join("8999.19P_Milling.gcode")).unwrap();
    let want = clean
        .replace("Z2.000(=2.000+", "Z2.121(==2.000+")
        .replace("Z0.800(=0.800+", "Z0.921(==0.800+")
        .replace("Z-0.300(=-0.300+", "Z-0.121(==-0.300+")
        .replace("Z5.000(=5.000+", "Z5.121(==5.000+");
    assert_eq!(got, want);
}

// 1
#[test]
fn non_finite_or_insane_measurements_are_refused() {
    for bad in ["NaN", "inf", "Infinity", "1e999", "5e6"] {
        let e = refused(
            CLEAN,
            &Z.replace("#51=2,1", &format!("#51={bad}")),
            "p_Z.txt:1",
        );
        assert!(e.contains(&format!("'{bad}' for #51")), "{e}");
    }
    refused(CLEAN, &Z.replace("T=2.000) #52", "T=NaN) #52"), "p_Z.txt:2");
    // numbers inside expressions too
    let huge = format!("1{}", "0".repeat(400));
    let clean = CLEAN.replace(
        "Z5.000\nM30",
        &format!("Z5.000\nG00 Z{huge}(={huge}+1.000*[#51-2.000])\nM30"),
    );
    refused(&clean, Z, "p_Clean.gcode:7");
    let clean = CLEAN.replace(
        "Z5.000\nM30",
        "Z5.000\nG00 Z1.000(=1.000/0+1.000*[#51-2.000])\nM30",
    );
    refused(&clean, Z, "p_Clean.gcode:7");
}

// 2
#[test]
fn max_must_be_a_finite_positive_number() {
    let dir = part(CLEAN, &Z.replace("#51=2,1", "#51=9.9"));
    for bad in ["NaN", "inf", "0", "1e999"] {
        let o = millpath(dir.path(), &["adjust-z", "--max", bad, "p_Clean.gcode"]);
        assert_eq!(o.status.code(), Some(2), "--max {bad}: {}", stderr(&o));
        assert!(stderr(&o).contains("--max value"), "{}", stderr(&o));
        assert!(!milling(dir.path()).exists());
        let o = millpath(dir.path(), &["pathgcodeadjustz", "/m", bad, "p"]);
        assert_eq!(o.status.code(), Some(2), "/m {bad}: {}", stderr(&o));
        assert!(!milling(dir.path()).exists());
    }
}

// 3
#[test]
fn nominal_heights_come_from_the_clean_program() {
    let e = refused(
        CLEAN,
        &Z.replace("T=2.000) #51=2,1", "T=-50) #51=-50"),
        "p_Z.txt:1",
    );
    assert!(
        e.contains("T=-50 for #51 differs from its nominal height 2.000 in p_Clean.gcode:4"),
        "{e}"
    );
    let e = refused(CLEAN, Z.lines().next().unwrap(), "p_Clean.gcode:4");
    assert!(
        e.contains("Probe #52 (nominal height 2.000) has no measured value in p_Z.txt"),
        "{e}"
    );
}

// 4
#[test]
fn incomplete_clean_programs_are_refused() {
    let no_m30 = CLEAN.replace("M30\n", "");
    let cases = [
        "",
        &CLEAN[..CLEAN.len() / 2],
        &no_m30,
        &CLEAN[..CLEAN.len() - 2],
    ];
    for clean in cases {
        let e = refused(clean, Z, "p_Clean.gcode");
        assert!(e.contains("is not a complete program"), "{clean:?}: {e}");
    }
}

fn set_mtime(path: &Path, t: SystemTime) {
    std::fs::File::options()
        .write(true)
        .open(path)
        .unwrap()
        .set_modified(t)
        .unwrap();
}

// 5
#[test]
fn a_refusal_removes_an_outdated_milling_program() {
    let dir = part(CLEAN, &Z.replace("#51=2,1", "#51=9.9"));
    let hour_ago = SystemTime::now() - Duration::from_secs(3600);
    std::fs::write(milling(dir.path()), "%\nG01 Z0.800\nM30\n%\n").unwrap();
    set_mtime(&milling(dir.path()), hour_ago);
    let o = millpath(dir.path(), &["adjust-z", "--max", "0.5", "p_Clean.gcode"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(!milling(dir.path()).exists(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("Removed p_Milling.gcode: it is not newer than p_Clean.gcode"),
        "{}",
        stderr(&o)
    );
    // German, reference form
    std::fs::write(milling(dir.path()), "old").unwrap();
    set_mtime(&milling(dir.path()), hour_ago);
    let o = millpath(dir.path(), &["pathgcodeadjustz", "/m0.5", "/lde", "p"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(!milling(dir.path()).exists());
    assert!(
        stderr(&o).contains("++++ Input: p_Milling.gcode entfernt"),
        "{}",
        stderr(&o)
    );
    // a program newer than both inputs was made from them: it stays
    let dir = part(CLEAN, Z);
    set_mtime(&dir.path().join("p_Clean.gcode"), hour_ago);
    set_mtime(&dir.path().join("p_Z.txt"), hour_ago);
    std::fs::write(milling(dir.path()), "current").unwrap();
    let o = millpath(dir.path(), &["adjust-z", "--max", "0.001", "p"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        std::fs::read_to_string(milling(dir.path())).unwrap(),
        "current"
    );
    // without inputs (a part without probes) compile's _Milling.gcode stays
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(milling(dir.path()), "compiled").unwrap();
    let o = millpath(dir.path(), &["adjust-z", "--max", "0.5", "p.dxf"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(milling(dir.path()).exists());
    // a part refused because another part of the run failed: the same rule
    let dir = part(CLEAN, Z);
    std::fs::write(milling(dir.path()), "old").unwrap();
    set_mtime(&milling(dir.path()), hour_ago);
    let o = millpath(dir.path(), &["adjust-z", "--max", "0.5", "p", "q"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(!milling(dir.path()).exists());
}

// 6
#[test]
fn too_far_message_names_measured_and_nominal_value() {
    let dir = part(CLEAN, &Z.replace("#51=2,1", "#51=9,9"));
    let o = millpath(dir.path(), &["pathgcodeadjustz", "/m0,5", "p"]);
    assert!(
        stderr(&o)
            .contains("**** p_Z.txt:1: Value 9,9 for #51 differs from 2.000 by more than /m=0.5"),
        "{}",
        stderr(&o)
    );
    let o = millpath(dir.path(), &["adjust-z", "--max", "0.5", "p"]);
    assert!(
        stderr(&o).contains("Value 9,9 for #51 differs from 2.000 by more than --max=0.5"),
        "{}",
        stderr(&o)
    );
}

// 7
#[test]
fn z_lines_must_have_the_form_comment_name_value() {
    refused(CLEAN, &Z.replace("#51=2,1", "#51=2.1=9"), "p_Z.txt:1");
    let e = refused(CLEAN, &format!("{Z}2.1=9\n"), "p_Z.txt:3");
    assert!(e.contains("Line does not have format"), "{e}");
    refused(CLEAN, &Z.replace("#52=2.2", "52=2.2"), "p_Z.txt:2");
}

// 8
#[test]
fn unknown_probes_in_the_z_file_are_errors() {
    let e = refused(CLEAN, &format!("{Z}([0 0]/T=2.000) #99=2\n"), "p_Z.txt:3");
    assert!(e.contains("#99 is not a probe of p_Clean.gcode"), "{e}");
}

// 9
#[test]
fn bad_expressions_are_errors_not_crashes() {
    let with = |line: &str| CLEAN.replace("Z5.000\nM30", &format!("Z5.000\n{line}\nM30"));
    let e = refused(
        &with("G01 Z1.000(=1.000+1.000*[#53-2.000])"),
        Z,
        "p_Clean.gcode:7",
    );
    assert!(e.contains("#53"), "{e}");
    refused(
        &with("G01 Z1.000(=1..0+1.000*[#51-2.000])"),
        Z,
        "p_Clean.gcode:7",
    );
    // deep nesting within the line limit, and a line of 100,000 `(`
    let deep = format!(
        "G01 Z1.000(=1.000+{}1{})",
        "(".repeat(3000),
        ")".repeat(3000)
    );
    let e = refused(&with(&deep), Z, "p_Clean.gcode:7");
    assert!(e.contains("nested deeper than"), "{e}");
    let e = refused(
        &with(&format!("G01 Z1.000(={})", "(".repeat(100_000))),
        Z,
        "p_Clean.gcode:7",
    );
    assert!(e.contains("Line longer than"), "{e}");
}
