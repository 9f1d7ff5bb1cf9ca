//! The GRBL time model (`emit/timing/grbl/`) on programs of a few moves, against velocity
//! profiles computed by hand (the arithmetic is in the comments), and GRBL's settings in
//! `[machine]`: names, `$` numbers, defaults, the controller chosen by the dialect, and bad
//! values as located errors in English and German.

use millpath_core::diag::{Lang, Msg, Origin};
use millpath_core::emit::timing::grbl::Grbl;
use millpath_core::emit::{Item, Kind, Target};
use millpath_core::geom::{P2, P3};
use millpath_core::load::config::{parse, Have};
use millpath_core::machine::{Axes, TimeModel};
use millpath_core::Settings;
use std::path::{Path, PathBuf};

const ORIGIN: P3 = P3 {
    x: 0.0,
    y: 0.0,
    z: 0.0,
};

fn grbl(g: Grbl) -> TimeModel {
    TimeModel::Grbl {
        settings: g,
        start_dwell: 0.0,
        feed_override: 100.0,
    }
}

fn cut(x: f64, y: f64, feed: f64) -> Item {
    Item {
        kind: Kind::Mill,
        len: 0.0,
        feed,
        target: Target {
            x: Some(x),
            y: Some(y),
            z: Some(0.0),
            arc: None,
        },
        source: None,
        shape: Default::default(),
    }
}

fn seconds(m: &TimeModel, items: &[Item]) -> f64 {
    let t = m.plan(items, ORIGIN);
    t.mill + t.drill + t.sweep
}

#[test]
fn one_line_is_a_trapezoid_at_grbls_defaults() {
    // F600 capped by $110 = 500 mm/min = 8.333 mm/s; a = 10 mm/s²: 0.8333 s and 3.4722 mm to
    // reach it, the same to stop; 10 − 6.9444 = 3.0556 mm at 8.333 mm/s = 0.3667 s
    let t = seconds(&grbl(Grbl::default()), &[cut(10.0, 0.0, 600.0)]);
    assert!((t - (2.0 * 0.833_333 + 0.366_667)).abs() < 1e-5, "{t}");
}

#[test]
fn a_corner_runs_at_the_junction_deviation_speed() {
    let g = Grbl {
        max_rate: Axes::all(6000.0),
        acceleration: Axes::all(100.0),
        junction_deviation: 0.05,
        ..Grbl::default()
    };
    // a right angle: cos θ (GRBL's, of the reversed first direction) = 0, sin(θ/2) = √½;
    // along the change of direction (−1, 1)/√2 each axis allows 100/(1/√2) = 141.42 mm/s²;
    // v² = 141.42 · 0.05 · 0.70711 / (1 − 0.70711) = 17.071 → v = 4.1317 mm/s
    let half = std::f64::consts::FRAC_1_SQRT_2;
    let v: f64 = (141.421_356 * 0.05 * half / (1.0 - half)).sqrt();
    // two 50 mm lines at F1200 (20 mm/s), a = 100 along each axis:
    // up 0 → 20: 0.2 s, 2 mm; down 20 → v: (20 − v)/100 s, (400 − v²)/200 mm; the second
    // line mirrored
    let down = (20.0 - v) / 100.0;
    let d_down = (400.0 - v * v) / 200.0;
    let one = 0.2 + down + (50.0 - 2.0 - d_down) / 20.0;
    let t = seconds(&grbl(g), &[cut(50.0, 0.0, 1200.0), cut(50.0, 50.0, 1200.0)]);
    assert!((t - 2.0 * one).abs() < 1e-4, "{t} vs {}", 2.0 * one);
    // a reversal stops
    let back = seconds(&grbl(g), &[cut(50.0, 0.0, 1200.0), cut(0.0, 0.0, 1200.0)]);
    let alone = 0.2 + 0.2 + (50.0 - 4.0) / 20.0;
    assert!((back - 2.0 * alone).abs() < 1e-6, "{back}");
}

#[test]
fn the_buffer_looks_fourteen_blocks_ahead() {
    // 100 collinear blocks of 0.1 mm at F6000 (100 mm/s) and a = 100 mm/s²: GRBL must be
    // able to stop within the 14 blocks behind the running one (1.4 mm), so it never runs
    // faster than √(2 · 100 · 1.4) = 16.73 mm/s, far below the feed
    let g = Grbl {
        max_rate: Axes::all(6000.0),
        acceleration: Axes::all(100.0),
        ..Grbl::default()
    };
    let items: Vec<Item> = (1..=100)
        .map(|k| cut(0.1 * k as f64, 0.0, 6000.0))
        .collect();
    let t = seconds(&grbl(g), &items);
    // the cap: 10 mm at ≤ 16.73 mm/s takes at least 0.598 s; one move would take 0.632 s
    // (a triangle: 2 · √(10/100)); the window also shortens the acceleration at the start
    let cap = (2.0_f64 * 100.0 * 1.4).sqrt();
    assert!(t > 10.0 / cap, "{t}");
    let whole = seconds(&grbl(g), &[cut(10.0, 0.0, 6000.0)]);
    assert!((whole - 2.0 * (0.1_f64).sqrt()).abs() < 1e-9, "{whole}");
    assert!(
        t > whole * 0.99,
        "the window is not faster than one move: {t} {whole}"
    );
}

#[test]
fn arcs_become_chords_by_the_arc_tolerance() {
    // a full circle of radius 5 at F60 (1 mm/s): the chords' junctions allow far more than
    // 1 mm/s, so the time is the chords' length / 1 mm/s plus what the ramps lose (0 → 1 mm/s
    // at 10 mm/s²: 0.1 s for 0.05 mm, 0.05 s more than at full speed, each way). $12 = 0.002: ⌊π·5 / √(0.002·9.998)⌋ = 111 chords of
    // 2·5·sin(π/111) = 0.282963 mm, 31.4089 mm in all
    let arc = Item {
        kind: Kind::Mill,
        len: std::f64::consts::TAU * 5.0,
        feed: 60.0,
        target: Target {
            x: Some(0.0),
            y: Some(0.0),
            z: Some(0.0),
            arc: Some((P2 { x: 5.0, y: 0.0 }, true)),
        },
        source: None,
        shape: Default::default(),
    };
    let t = seconds(&grbl(Grbl::default()), std::slice::from_ref(&arc));
    let chords = 111.0 * 2.0 * 5.0 * (std::f64::consts::PI / 111.0).sin();
    // steps of 0.004 mm move each chord end by up to 0.002 mm
    assert!(
        (t - (chords + 0.1)).abs() < 0.005,
        "{t} vs {}",
        chords + 0.1
    );
    // a coarser tolerance: fewer, longer chords, a shorter way round;
    // ⌊π·5 / √(0.1·9.9)⌋ = 15 chords of 2·5·sin(π/15) = 2.07912 mm: 31.1868 mm
    let coarse = Grbl {
        arc_tolerance: 0.1,
        ..Grbl::default()
    };
    let t2 = seconds(&grbl(coarse), &[arc]);
    let chords2 = 15.0 * 2.0 * 5.0 * (std::f64::consts::PI / 15.0).sin();
    assert!(
        t2 < t && (t2 - (chords2 + 0.1)).abs() < 0.005,
        "{t2} vs {}",
        chords2 + 0.1
    );
}

fn settings_from(text: &str) -> Settings {
    let mut s = Settings {
        settings_file: Some(PathBuf::from("shop/millpath.toml")),
        ..Settings::default()
    };
    parse(text, Path::new("."))
        .unwrap()
        .apply(&mut s, &mut Have::default());
    s
}

#[test]
fn grbl_settings_by_name_and_number() {
    let s = settings_from(
        "dialect = \"grbl\"\n[machine]\n\"$110\" = 5000\ny_max_rate = 4000\n\"$122\" = 50\njunction_deviation = 0.02\n\"$12\" = 0.01\n",
    );
    assert!(s.number_errors().is_empty(), "{:?}", s.number_errors());
    let Some(TimeModel::Grbl { settings: g, .. }) = s.time_model() else {
        panic!("{:?}", s.time_model());
    };
    assert_eq!(
        g.max_rate,
        Axes {
            x: 5000.0,
            y: 4000.0,
            z: 500.0
        }
    );
    assert_eq!(
        g.acceleration,
        Axes {
            x: 10.0,
            y: 10.0,
            z: 50.0
        }
    );
    assert_eq!((g.junction_deviation, g.arc_tolerance), (0.02, 0.01));
    // the line of the statistics names the model, in both languages
    let m = s.time_model().unwrap();
    assert_eq!(
        m.line(Lang::En),
        "Time model: GRBL planner, $110-$112 X5000/Y4000/Z500 mm/min, $120-$122 X10/Y10/Z50 mm/s^2, $11=0.02, $12=0.01"
    );
    assert!(m.line(Lang::De).starts_with("Zeitmodell: GRBL-Planer, "));
    // a name and its number both: refused by the parser, with the line
    let both = parse(
        "[machine]\n\"$110\" = 5000\nx_max_rate = 4000\n",
        Path::new("."),
    );
    let err = both.unwrap_err();
    assert!(
        err.contains("duplicate") && err.contains("x_max_rate"),
        "{err}"
    );
}

#[test]
fn the_controller_follows_the_dialect_unless_given() {
    // linuxcnc limits in the grbl dialect: GRBL's planner with them as $110/$120
    let s = settings_from(
        "dialect = \"grbl\"\n[machine]\nmax_velocity = 3000\nmax_acceleration = 200\n",
    );
    let Some(TimeModel::Grbl { settings: g, .. }) = s.time_model() else {
        panic!("{:?}", s.time_model());
    };
    assert_eq!((g.max_rate.x, g.acceleration.z), (3000.0, 200.0));
    // the same in the linuxcnc dialect: LinuxCNC's planner
    let s = settings_from(
        "dialect = \"linuxcnc\"\n[machine]\nmax_velocity = 3000\nmax_acceleration = 200\n",
    );
    assert!(matches!(s.time_model(), Some(TimeModel::LinuxCnc { .. })));
    // controller = "grbl" alone: GRBL's defaults, whatever the dialect
    let s = settings_from("[machine]\ncontroller = \"grbl\"\n");
    assert_eq!(
        s.time_model(),
        Some(TimeModel::Grbl {
            settings: Grbl::default(),
            start_dwell: 0.0,
            feed_override: 100.0,
        })
    );
    // grbl without any machine value: the reference's model, as before
    assert_eq!(settings_from("dialect = \"grbl\"\n").time_model(), None);
    // the spindle's start dwell counts
    let s = settings_from("dialect = \"grbl\"\nspindle_rpm = 10000\nspindle_dwell = 3\n[machine]\ncontroller = \"grbl\"\n");
    assert_eq!(s.time_model().unwrap().dwell(), 3.0);
}

#[test]
fn bad_grbl_values_are_located_errors() {
    for (text, msg, name) in [
        (
            "\"$120\" = -5",
            Msg::MustBePositive,
            "x_acceleration ($120)",
        ),
        (
            "\"$11\" = nan",
            Msg::SettingNotFinite,
            "junction_deviation ($11)",
        ),
        (
            "z_max_rate = 1e300",
            Msg::SettingNotFinite,
            "z_max_rate ($112)",
        ),
        ("\"$12\" = 0", Msg::MustBePositive, "arc_tolerance ($12)"),
    ] {
        let s = settings_from(&format!("dialect = \"grbl\"\n[machine]\n{text}\n"));
        let errors = s.number_errors();
        assert_eq!(errors.len(), 1, "{text}: {errors:?}");
        let e = &errors[0];
        assert_eq!(e.msg, msg, "{text}");
        assert!(
            matches!(&e.origin, Origin::File(f) if f.path.ends_with("millpath.toml")),
            "{text}: {:?}",
            e.origin
        );
        assert!(
            e.message(Lang::En).contains(name),
            "{}",
            e.message(Lang::En)
        );
        assert!(
            e.message(Lang::De).contains(name),
            "{}",
            e.message(Lang::De)
        );
        assert_ne!(e.message(Lang::En), e.message(Lang::De));
    }
    // an unknown key: the parser names it and its line
    let err = parse("[machine]\n\"$999\" = 1\n", Path::new(".")).unwrap_err();
    assert!(err.contains("$999") && err.contains("line 2"), "{err}");
}

/// A sweep (rapid) in the XY plane at Z0 to (x, y).
fn sweep(x: f64, y: f64) -> Item {
    Item {
        kind: Kind::HSweep,
        ..cut(x, y, 0.0)
    }
}

#[test]
fn the_feed_override_scales_the_feeds_not_the_rapids_nor_the_ramps() {
    let g = Grbl {
        max_rate: Axes::all(6000.0),
        acceleration: Axes::all(100.0),
        ..Grbl::default()
    };
    let at = |percent: f64, items: &[Item]| {
        let m = TimeModel::Grbl {
            settings: g,
            start_dwell: 0.0,
            feed_override: percent,
        };
        seconds(&m, items)
    };
    // 100 mm at F600 (10 mm/s), a = 100 mm/s²: 0.1 s and 0.5 mm to reach it, the same to
    // stop; 99 mm at 10 mm/s: 10.1 s
    let line = [cut(100.0, 0.0, 600.0)];
    assert!(
        (at(100.0, &line) - 10.1).abs() < 1e-6,
        "{}",
        at(100.0, &line)
    );
    // at 200 %: 20 mm/s, 0.2 s and 2 mm each way, 96 mm at 20 mm/s: 5.2 s (not 10.1 / 2:
    // the ramps do not get shorter)
    assert!(
        (at(200.0, &line) - 5.2).abs() < 1e-6,
        "{}",
        at(200.0, &line)
    );
    // at 50 %: 5 mm/s, 0.05 s and 0.125 mm each way, 99.75 mm at 5 mm/s: 20.05 s
    assert!(
        (at(50.0, &line) - 20.05).abs() < 1e-6,
        "{}",
        at(50.0, &line)
    );
    // the axes' rate caps an override: F3000 at 1000 % would be 500 mm/s, $110 allows 100
    let fast = [cut(100.0, 0.0, 3000.0)];
    assert_eq!(at(1000.0, &fast), at(200.0, &fast));
    // a rapid does not follow the feed override: 100 mm at $110 = 100 mm/s, a = 100: 1 s
    // and 50 mm to reach it, the same to stop (a triangle: 2 s)
    let rapid = [sweep(100.0, 0.0)];
    for percent in [1.0, 50.0, 100.0, 1000.0] {
        assert!((at(percent, &rapid) - 2.0).abs() < 1e-6, "{percent}");
    }
    // the line of the statistics names the override, in both languages; none at 100 %
    let m = TimeModel::Grbl {
        settings: g,
        start_dwell: 0.0,
        feed_override: 120.0,
    };
    assert!(
        m.line(Lang::En).ends_with(", feed override 120 %"),
        "{}",
        m.line(Lang::En)
    );
    assert!(
        m.line(Lang::De).ends_with(", Vorschub-Override 120 %"),
        "{}",
        m.line(Lang::De)
    );
    assert!(!grbl(g).line(Lang::En).contains("override"));
}

#[test]
fn the_feed_override_comes_from_millpath_toml_within_its_bounds() {
    let s = settings_from(
        "dialect = \"grbl\"\nfeed_override = 120\n[machine]\ncontroller = \"grbl\"\n",
    );
    assert!(s.number_errors().is_empty(), "{:?}", s.number_errors());
    assert_eq!(s.time_model().unwrap().feed_override(), 120.0);
    // and reaches LinuxCNC's planner the same way
    let s = settings_from("feed_override = 80\n[machine]\nmax_acceleration = 200\n");
    assert!(matches!(
        s.time_model(),
        Some(TimeModel::LinuxCnc { feed_override, .. }) if feed_override == 80.0
    ));
    for (value, msg) in [
        ("0", Msg::FeedOverrideRange),
        ("0.5", Msg::FeedOverrideRange),
        ("-20", Msg::FeedOverrideRange),
        ("1000.5", Msg::FeedOverrideRange),
        ("nan", Msg::SettingNotFinite),
        ("inf", Msg::SettingNotFinite),
        ("1e300", Msg::SettingNotFinite),
    ] {
        let s = settings_from(&format!("feed_override = {value}\n"));
        let errors = s.number_errors();
        assert_eq!(errors.len(), 1, "{value}: {errors:?}");
        let e = &errors[0];
        assert_eq!(e.msg, msg, "{value}");
        assert!(
            matches!(&e.origin, Origin::File(f) if f.path.ends_with("millpath.toml")),
            "{value}: {:?}",
            e.origin
        );
        assert!(e.message(Lang::En).contains("feed_override"));
        assert!(e.message(Lang::De).contains("feed_override"));
        assert_ne!(e.message(Lang::En), e.message(Lang::De));
    }
    // the bounds themselves are fine
    for value in ["1", "1000"] {
        let s = settings_from(&format!("feed_override = {value}\n"));
        assert!(s.number_errors().is_empty(), "{value}");
    }
}
