//! The operator's feed override in the estimate (issue 33): `--feed-override PERCENT` on
//! `compile` and `check`, or `feed_override` in millpath.toml, times the plate through the same
//! planner (GRBL's and LinuxCNC's) with the feeds scaled and the rapids and ramps kept; the
//! statistics line names it; out of 1–1000 % it is a located error in English and German, as
//! is a bad `$` value of `[machine]`.

mod common;

use common::millpath;
use std::path::Path;

const GRBL: &str = "dialect = \"grbl\"\n[machine]\n\"$110\" = 4000\n\"$111\" = 4000\n\"$112\" = 1000\n\"$120\" = 200\n\"$121\" = 200\n\"$122\" = 100\n";
const LINUXCNC: &str = "[machine]\nmax_velocity = 4000\nmax_acceleration = 200\n";

/// The plate example with `settings` (feeds of 300 mm/min, sweeps at 1000).
fn plate(dir: &Path, settings: &str) {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate/1234.1P.dxf");
    std::fs::copy(example, dir.join("1234.1P.dxf")).unwrap();
    std::fs::write(
        dir.join("millpath.toml"),
        format!("feed = 300\nsweep_speed = 1000\nsweep_height = 10\n{settings}"),
    )
    .unwrap();
}

/// The estimate `check --format json` gives (seconds), with `args` before the drawing.
fn checked(dir: &Path, args: &[&str]) -> f64 {
    let mut all = vec!["check", "--format", "json"];
    all.extend(args);
    all.push("1234.1P.dxf");
    let o = millpath(dir, &all);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&o.stderr)));
    v["times"][0]["seconds"].as_f64().unwrap()
}

/// `compile`'s standard error.
fn compiled(dir: &Path, args: &[&str]) -> (bool, String) {
    let mut all = vec!["compile"];
    all.extend(args);
    all.push("1234.1P.dxf");
    let o = millpath(dir, &all);
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stderr).to_string(),
    )
}

#[test]
fn the_estimate_follows_the_override_through_either_planner() {
    for machine in [GRBL, LINUXCNC] {
        let dir = tempfile::tempdir().unwrap();
        plate(dir.path(), machine);
        let plain = checked(dir.path(), &[]);
        let same = checked(dir.path(), &["--feed-override", "100"]);
        let faster = checked(dir.path(), &["--feed-override", "200"]);
        let slower = checked(dir.path(), &["--feed-override", "50"]);
        assert_eq!(plain, same, "{machine}");
        // twice the feed: less time, but more than half (the sweeps and the ramps stay)
        assert!(
            faster < plain && faster > plain / 2.0,
            "{machine}: {faster} {plain}"
        );
        // half the feed: more time, but less than twice
        assert!(
            slower > plain && slower < plain * 2.0,
            "{machine}: {slower} {plain}"
        );
        // compile says the same and names the override in the statistics line
        let (ok, err) = compiled(dir.path(), &["--feed-override", "200"]);
        assert!(ok, "{err}");
        assert!(err.contains(", feed override 200 %"), "{err}");
        let (_, de) = compiled(dir.path(), &["--feed-override", "200", "--lang", "de"]);
        assert!(de.contains(", Vorschub-Override 200 %"), "{de}");
        let (_, none) = compiled(dir.path(), &[]);
        assert!(!none.contains("override"), "{none}");
        // millpath.toml's feed_override: the same estimate as the option
        plate(dir.path(), &format!("feed_override = 200\n{machine}"));
        assert_eq!(checked(dir.path(), &[]), faster, "{machine}");
        // and the option wins over it
        assert_eq!(
            checked(dir.path(), &["--feed-override", "100"]),
            plain,
            "{machine}"
        );
    }
}

#[test]
fn an_override_out_of_bounds_is_a_located_error() {
    let dir = tempfile::tempdir().unwrap();
    plate(dir.path(), GRBL);
    for value in ["0", "1000.5", "-10", "nan", "inf", "1e300"] {
        for (lang, at) in [("en", "--> Options"), ("de", "--> Optionen")] {
            let (ok, err) = compiled(
                dir.path(),
                &["--lang", lang, &format!("--feed-override={value}")],
            );
            assert!(!ok, "{value}: {err}");
            assert!(err.contains("feed_override="), "{value}: {err}");
            assert!(err.contains(at), "{value} {lang}: {err}");
        }
    }
    // within the bounds: fine, the bounds included
    for value in ["1", "1000", "87.5"] {
        let (ok, err) = compiled(dir.path(), &["--feed-override", value]);
        assert!(ok, "{value}: {err}");
    }
    // in millpath.toml: located there, in both languages; check refuses it too
    plate(dir.path(), &format!("feed_override = 1200\n{GRBL}"));
    let (ok, err) = compiled(dir.path(), &[]);
    assert!(!ok && err.contains("feed_override=1200"), "{err}");
    assert!(err.contains("millpath.toml"), "{err}");
    let (_, de) = compiled(dir.path(), &["--lang", "de"]);
    assert!(
        de.contains("muss ein Prozentwert von 1 bis 1000 sein"),
        "{de}"
    );
    let o = millpath(dir.path(), &["check", "1234.1P.dxf"]);
    assert!(!o.status.success());
}

#[test]
fn a_bad_dollar_value_is_a_located_error() {
    for (value, name) in [
        ("\"$120\" = -5", "x_acceleration ($120)"),
        ("\"$121\" = nan", "y_acceleration ($121)"),
        ("\"$110\" = 1e300", "x_max_rate ($110)"),
        ("\"$112\" = -inf", "z_max_rate ($112)"),
        ("\"$11\" = -0.01", "junction_deviation ($11)"),
        ("\"$12\" = 0", "arc_tolerance ($12)"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        plate(
            dir.path(),
            &format!("dialect = \"grbl\"\n[machine]\n{value}\n"),
        );
        for lang in ["en", "de"] {
            let (ok, err) = compiled(dir.path(), &["--lang", lang]);
            assert!(!ok, "{value}: {err}");
            assert!(err.contains(name), "{value}: {err}");
            assert!(err.contains("millpath.toml"), "{value}: {err}");
        }
        // nothing was written
        assert!(
            !dir.path().join("1234.1P_Milling.gcode").exists(),
            "{value}"
        );
    }
}
