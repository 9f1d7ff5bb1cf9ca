//! `--dialect`, `--plunge-feed`, `--spindle-rpm` and their `millpath.toml` keys end to end;
//! the reference command line (`pathdxf2gcode`) always writes the reference dialect.

mod common;

use common::millpath;
use std::path::Path;

fn plate(dir: &Path) {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate/1234.1P.dxf");
    std::fs::copy(example, dir.join("1234.1P.dxf")).unwrap();
}

fn milling(dir: &Path) -> String {
    std::fs::read_to_string(dir.join("1234.1P_Milling.gcode")).unwrap()
}

const MACHINE: [&str; 6] = [
    "--feed",
    "60",
    "--sweep-speed",
    "500",
    "--sweep-height",
    "10",
];

#[test]
fn dialect_option_plunges_at_half_the_feed() {
    let dir = tempfile::tempdir().unwrap();
    plate(dir.path());
    let mut args = vec!["compile", "--dialect", "linuxcnc"];
    args.extend(MACHINE);
    args.push("1234.1P.dxf");
    let o = millpath(dir.path(), &args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let g = milling(dir.path());
    assert!(
        g.starts_with("%\n(millpath V.")
            && g.contains(
                "(1234.1P.dxf)\n(MILLPATH-STOCK T=3.000 O=2.000 BOTTOM=-0.200)\nG17 G21 G40 G49 G54 G80 G90 G94\nF60.000\nT1\n(SweepSafelyTo"
            ),
        "{g}"
    );
    let plunges: Vec<&str> = g
        .lines()
        .filter(|l| l.starts_with("G01") && !l.contains(" X"))
        .collect();
    assert!(!plunges.is_empty());
    assert!(
        plunges.iter().all(|l| l.starts_with("G01 F30.000 Z")),
        "{plunges:?}"
    );
    assert!(g.ends_with("M30\n%\n"));
    // the reference dialect: F150 whatever the feed, plunges without F
    let mut args = vec!["compile"];
    args.extend(MACHINE);
    args.push("1234.1P.dxf");
    assert!(millpath(dir.path(), &args).status.success());
    let g = milling(dir.path());
    assert!(g.contains("(1234.1P.dxf)\nF150\nG17"), "{g}");
    assert!(!g.contains("MILLPATH-STOCK"));
}

#[test]
fn settings_file_keys_and_their_checks() {
    let dir = tempfile::tempdir().unwrap();
    plate(dir.path());
    let toml = dir.path().join("millpath.toml");
    std::fs::write(
        &toml,
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\ndialect = \"grbl\"\nplunge_feed = 100\nspindle_rpm = 12000\nspindle_dwell = 3\n",
    )
    .unwrap();
    let o = millpath(dir.path(), &["compile", "1234.1P.dxf"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let g = milling(dir.path());
    assert!(g.starts_with("(millpath V."), "no % in GRBL: {g}");
    assert!(
        g.contains("\nF300.000\nT1\nM3 S12000\nG4 P3\n(SweepSafelyTo"),
        "{g}"
    );
    assert!(g.contains("\nG01 F100.000 Z1.500\n"), "{g}");
    assert!(g.ends_with("  (Command count: 39)\nM5\nM30\n"), "{g}");
    // options override the file
    let o = millpath(
        dir.path(),
        &[
            "compile",
            "--dialect",
            "reference",
            "--spindle-rpm",
            "9000",
            "1234.1P.dxf",
        ],
    );
    assert!(o.status.success());
    assert!(milling(dir.path()).contains("(1234.1P.dxf)\nF150\n"));
    // the reference command line ignores the file's dialect (it reads no millpath.toml)
    std::fs::remove_file(dir.path().join("1234.1P_Milling.gcode")).unwrap();
    let o = millpath(
        dir.path(),
        &["pathdxf2gcode", "/f300", "/v1000", "/s10", "1234.1P"],
    );
    assert_eq!(o.status.code(), Some(0));
    assert!(milling(dir.path()).contains("(1234.1P.dxf)\nF150\n"));
    // unknown dialects and non-positive values are refused before anything is written
    std::fs::write(
        &toml,
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\ndialect = \"mach3\"\n",
    )
    .unwrap();
    let o = millpath(dir.path(), &["compile", "1234.1P.dxf"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("mach3") && err.contains("linuxcnc"), "{err}");
    std::fs::write(
        &toml,
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\nplunge_feed = 0\n",
    )
    .unwrap();
    let o = millpath(dir.path(), &["compile", "1234.1P.dxf"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("plunge_feed=0 must be > 0"));
    let o = millpath(
        dir.path(),
        &[
            "compile",
            "--dialect",
            "fanuc",
            "--feed",
            "1",
            "1234.1P.dxf",
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("grbl"));
}
