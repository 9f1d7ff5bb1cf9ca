//! Time estimates with machine limits (`emit/timing.rs`): programs of a few moves against
//! velocity profiles computed by hand from the formulas (the arithmetic is in the comments;
//! no number here was taken from the code), the statistics lines, and the model line of a
//! compiled program.
//!
//! Unless a test says otherwise: MAX_ACCELERATION 500 mm/s² on every axis (a line accelerates
//! with all of it; the last move of a program with half, A = 250 mm/s², as LinuxCNC's planner
//! keeps its blend condition with nothing to blend into); maximum velocity 6000 mm/min =
//! 100 mm/s on every axis; G64 P0.05; the servo period 1 ms. The same programs, timed by
//! LinuxCNC 2.9's planner (tests/planner_oracle.sh), are in the comments where they are.

mod support;

use millpath_core::diag::{Lang, Msg};
use millpath_core::emit::stats::Stats;
use millpath_core::emit::{Item, Kind, Target};
use millpath_core::geom::{P2, P3};
use millpath_core::machine::{Axes, Machine, TimeModel};
use millpath_core::Settings;
use support::*;

fn machine() -> Machine {
    Machine {
        max_velocity: Axes::all(6000.0),
        max_acceleration: Axes::all(500.0),
        path_tolerance: 0.05,
    }
}

const ORIGIN: P3 = P3 {
    x: 0.0,
    y: 0.0,
    z: 0.0,
};

fn item(kind: Kind, len: f64, feed: f64, target: Target) -> Item {
    Item {
        kind,
        len,
        feed,
        target,
        source: None,
        shape: Default::default(),
    }
}

/// A cut in the XY plane at Z0 from the previous point to (x, y); `len` is its length.
fn cut(x: f64, y: f64, len: f64, feed: f64) -> Item {
    item(
        Kind::Mill,
        len,
        feed,
        Target {
            x: Some(x),
            y: Some(y),
            z: Some(0.0),
            arc: None,
        },
    )
}

fn xy(x: f64, y: f64) -> Target {
    Target {
        x: Some(x),
        y: Some(y),
        ..Target::default()
    }
}

fn stats(items: &[Item], m: &Machine) -> Stats {
    Stats::timed(items, 500.0, ORIGIN, Some(&TimeModel::from(*m)))
}

/// Seconds of milling.
fn mill_seconds(items: &[Item], m: &Machine) -> f64 {
    stats(items, m).mill_min * 60.0
}

fn close(got: f64, want: f64) {
    assert!(
        (got - want).abs() <= 1e-6 * want.max(1.0),
        "got {got}, want {want}"
    );
}

#[test]
fn a_long_line_reaches_the_feed() {
    // one line is the last move: A = 250 mm/s².
    // L = 100 mm at F600 = 10 mm/s; critical distance v²/A = 100/250 = 0.4 mm ≤ 100:
    // t = L/v + v/A = 100/10 + 10/250 = 10 + 0.04 = 10.04 s
    close(
        mill_seconds(&[cut(100.0, 0.0, 100.0, 600.0)], &machine()),
        10.04,
    );
}

#[test]
fn a_short_line_never_reaches_the_feed() {
    // L = 0.2 mm < v²/A = 0.4 mm: a triangle, t = 2·√(L/A) = 2·√(0.2/250) = 2·√0.0008
    // = 2·0.0282842712 = 0.0565685425 s (the peak √(A·L) = √50 = 7.07 mm/s < 10)
    close(
        mill_seconds(&[cut(0.2, 0.0, 0.2, 600.0)], &machine()),
        0.0565685425,
    );
}

#[test]
fn a_square_slows_down_at_its_three_corners() {
    // 100 mm sides at F600 (v = 10 mm/s), from rest back to rest, three 90° corners, each
    // a blend arc (the kink would allow 10·0.1/21 = 0.05 mm/s, a parabolic blend rates
    // half of √½·2·√(250·0.05/√½) = 2.97 mm/s). θ = 45° (half the angle between the sides),
    // φ = 90° (the turn). Within the tolerance: h = P/(1 − sin θ) = 0.05/0.2928932188 =
    // 0.1707106781, d = cos θ·h = 0.1207106781 mm (≪ 50 mm, half a side), R = tan θ·d =
    // 0.1207106781 mm. Speed √(0.866·a·R) = √(433.0127019·0.1207106781) = 7.2297480509
    // mm/s < 10; the radius that speed needs, v²/(0.866·a) = R. The arc: R·φ = 0.1896118898
    // mm at 7.2297480509 mm/s = 0.0262266248 s; each side loses d at each blended end.
    // Side 1 (0 → 7.2297, a = 500): 10/500 + (10 − 7.2297480509)/500 + (99.8792893219 −
    // 100/1000 − (100 − 52.2692604)/1000)/10 = 9.9986963618 s. Sides 2, 3 (7.2297 → 7.2297,
    // 99.7585786438 mm): 9.9773927235 s. Side 4 (7.2297 → 0, the last move: a = 250):
    // 10.0094637914 s. Total 9.9986963618 + 2·9.9773927235 + 10.0094637914 + 3·0.0262266248
    // = 40.0416254747 s (LinuxCNC: 40.042 s).
    let square = [
        cut(100.0, 0.0, 100.0, 600.0),
        cut(100.0, 100.0, 100.0, 600.0),
        cut(0.0, 100.0, 100.0, 600.0),
        cut(0.0, 0.0, 100.0, 600.0),
    ];
    close(mill_seconds(&square, &machine()), 40.0416254747);
    // a tighter tolerance slows down more: P0.01 → d = R = 0.0241421356 mm, speed
    // √(433.0127019·0.0241421356) = 3.2332416204 mm/s, arcs of 0.0379223780 mm:
    // 10.0121646883 + 2·10.0043293767 + 10.0267435902 + 3·0.0117289032 = 40.0827537415 s
    let tight = Machine {
        path_tolerance: 0.01,
        ..machine()
    };
    close(mill_seconds(&square, &tight), 40.0827537415);
}

#[test]
fn collinear_pieces_do_not_slow_down() {
    // ten 10 mm pieces on one straight line: tangent joins, no slowing down; all but the
    // last accelerate with 500 mm/s²: the first 10/500 + (10 − 0.1)/10 = 1.01 s, eight at
    // 1 s, the last 10/250 + (10 − 0.2)/10 = 1.02 s: 10.03 s (LinuxCNC: 10.039 s)
    let pieces: Vec<Item> = (1..=10)
        .map(|k| cut(10.0 * k as f64, 0.0, 10.0, 600.0))
        .collect();
    close(mill_seconds(&pieces, &machine()), 10.03);
    // 100 pieces of 1 mm along a 45° diagonal: each from rest to rest would take 0.11 s
    // (11 s for all); straight on they make one line. F600 still rules (the axes allow 141
    // mm/s); along the diagonal the acceleration is 500/cos 45° = 707.1067812 mm/s² (each
    // axis takes 500): the first 10/707.1067812 + (1 − 100/1414.2135624)/10 = 0.1070710678 s,
    // 98 at 0.1 s, the last (at 353.5533906) 10/353.5533906 + (1 − 100/707.1067812)/10
    // = 0.1141421356 s: 10.0212132034 s
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let diagonal: Vec<Item> = (1..=100)
        .map(|k| cut(k as f64 * s, k as f64 * s, 1.0, 600.0))
        .collect();
    close(mill_seconds(&diagonal, &machine()), 10.0212132034);
}

#[test]
fn an_arc_is_limited_by_its_centripetal_acceleration() {
    // half circle R = 2 mm, counter-clockwise from (2, 0) to (−2, 0) around (0, 0), F3000
    // (50 mm/s): the controller caps an arc at √(0.866·a·R) = √(433.0127019·2) =
    // 29.4283095638 mm/s. As the last move it keeps half of a for itself (250), and of that
    // the tangential half (125 mm/s²; the planner never finalises the last move, so the
    // share stays 0.5). L = 2π = 6.2831853072 mm < v²/125 = 6.93 mm: a triangle, peak
    // √(125·L) = 28.0249560820 mm/s, t = 2·28.0249560820/125 = 0.4483992973 s (LinuxCNC:
    // 0.447 s)
    let start = P3 {
        x: 2.0,
        y: 0.0,
        z: 0.0,
    };
    let arc = item(
        Kind::Mill,
        std::f64::consts::PI * 2.0,
        3000.0,
        Target {
            x: Some(-2.0),
            y: Some(0.0),
            z: Some(0.0),
            arc: Some((P2 { x: 0.0, y: 0.0 }, true)),
        },
    );
    let s = Stats::timed(&[arc], 500.0, start, Some(&machine().into()));
    close(s.mill_min * 60.0, 0.4483992973);
}

#[test]
fn an_arc_continuing_a_line_tangentially_keeps_its_speed() {
    // a 100 mm line along +X into a quarter circle R = 100 turning left (tangent at the
    // joint, no slowing down), F600: the arc's cap √(433·100) = 208 mm/s is above 10 mm/s.
    // The line accelerates with 500: 10/500 + (100 − 0.1)/10 = 10.01 s; the arc, the last
    // move, decelerates with 250·0.5 = 125: 10/125 + (50π − 0.4)/10 = 15.7479632679 s;
    // 25.7579632679 s (LinuxCNC: 25.758 s)
    let arc = item(
        Kind::Mill,
        50.0 * std::f64::consts::PI,
        600.0,
        Target {
            x: Some(200.0),
            y: Some(100.0),
            z: Some(0.0),
            arc: Some((P2 { x: 100.0, y: 100.0 }, true)),
        },
    );
    close(
        mill_seconds(&[cut(100.0, 0.0, 100.0, 600.0), arc], &machine()),
        25.7579632679,
    );
}

#[test]
fn sweeps_and_plunges_use_the_axis_limits() {
    let m = Machine {
        max_velocity: Axes {
            x: 6000.0,
            y: 3000.0,
            z: 300.0,
        },
        max_acceleration: Axes {
            x: 500.0,
            y: 500.0,
            z: 200.0,
        },
        path_tolerance: 0.05,
    };
    // a 1000 mm sweep along X at V_x = 100 mm/s: 1000/100 + 100/250 = 10.4 s
    let along_x = item(Kind::HSweep, 1000.0, 0.0, xy(1000.0, 0.0));
    close(
        Stats::timed(&[along_x], 500.0, ORIGIN, Some(&m.into())).sweep_min * 60.0,
        10.4,
    );
    // a 45° sweep of 100 mm: X may go 100/0.7071 = 141.4 mm/s, Y only 50/0.7071
    // = 70.7106781187 mm/s; both axes accelerate with 250 mm/s², so along the move
    // A = 250/0.7071067812 = 353.5533906 mm/s²; L ≥ v²/A = 5000/353.55 = 14.1 mm:
    // t = 100/70.7106781187 + 70.7106781187/353.5533906 = 1.4142135624 + 0.2
    // = 1.6142135624 s
    let d = 100.0 * std::f64::consts::FRAC_1_SQRT_2;
    let diagonal = item(Kind::HSweep, 100.0, 0.0, xy(d, d));
    close(
        Stats::timed(&[diagonal], 500.0, ORIGIN, Some(&m.into())).sweep_min * 60.0,
        1.6142135624,
    );
    // a 5 mm plunge at F600 (10 mm/s) but V_z = 5 mm/s, A_z = 100 mm/s²: v²/A = 0.25 ≤ 5:
    // t = 5/5 + 5/100 = 1.05 s
    let plunge = item(
        Kind::Drill,
        5.0,
        600.0,
        Target {
            z: Some(-5.0),
            ..Target::default()
        },
    );
    close(
        Stats::timed(&[plunge], 500.0, ORIGIN, Some(&m.into())).drill_min * 60.0,
        1.05,
    );
}

#[test]
fn a_change_between_sweep_and_cut_is_a_stop() {
    // a 100 mm sweep along X (100 mm/s, stopping with all of 500 mm/s²: 1 + 0.2 = 1.2 s)
    // then a 100 mm cut straight on at F600 (the last move: 10.04 s): no blend between G00
    // and G01, each from rest to rest (LinuxCNC: 1.201 s and 10.038 s)
    let sweep = item(Kind::HSweep, 100.0, 0.0, xy(100.0, 0.0));
    let s = stats(&[sweep, cut(200.0, 0.0, 100.0, 600.0)], &machine());
    close(s.sweep_min * 60.0, 1.2);
    close(s.mill_min * 60.0, 10.04);
}

#[test]
fn totals_and_minutes_are_formatted_as_before() {
    // 3000 mm at F600: 300 + 0.04 = 300.04 s = 5.0006666667 min → ceil 6 (the reference's
    // model: 3000/600·1.4 = 7 min)
    let items = [cut(3000.0, 0.0, 3000.0, 600.0)];
    let s = stats(&items, &machine());
    let en = s.lines(Lang::En);
    assert_eq!(en[0], "Milling length:  3000 mm   ca.  6 min");
    assert_eq!(en[2], "Sweeps:          0 mm   ca.  0 min");
    assert_eq!(en[3], "Sum:          3000 mm   ca.  6 min");
    assert_eq!(en[4], "Command count: 1");
    assert_eq!(
        s.model_line(Lang::En).unwrap(),
        "Time model: LinuxCNC planner, v=X6000/Y6000/Z6000 mm/min, a=X500/Y500/Z500 mm/s^2, G64 P0.05"
    );
    assert_eq!(
        s.model_line(Lang::De).unwrap(),
        "Zeitmodell: LinuxCNC-Planer, v=X6000/Y6000/Z6000 mm/min, a=X500/Y500/Z500 mm/s^2, G64 P0.05"
    );
    let reference = Stats::timed(&items, 500.0, ORIGIN, None);
    assert_eq!(reference, Stats::of(&items, 500.0));
    assert_eq!(
        reference.lines(Lang::En)[0],
        "Milling length:  3000 mm   ca.  7 min"
    );
    assert_eq!(reference.model_line(Lang::En), None);
}

/// T2, I1.2, B−0.3, S5: a 20 mm line milled in two passes.
const LINE: &str = "path 1000.1P {
  start (0, 0)  O2 T2 I1,2 B-0,3 S5
  end (20, 0)
  mill (0, 0) -> (20, 0)
}
";

fn program(settings: Settings) -> String {
    let run = compile_with(&[("1000.1P.mpath", LINE.into())], "1000.1P.mpath", settings);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    run.output("_Milling.gcode").to_string()
}

#[test]
fn a_compiled_program_names_its_time_model() {
    let plain = program(settings());
    assert!(!plain.contains("Time model"), "{plain}");
    let timed = program(Settings {
        max_acceleration: Some(Axes {
            x: 500.0,
            y: 500.0,
            z: 200.0,
        }),
        ..settings()
    });
    // the five lines, then the model (the velocity defaults to /v on every axis), then M30
    let lines: Vec<&str> = timed.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.starts_with("  (Command count:"))
        .unwrap();
    assert_eq!(
        lines[at + 1],
        "  (Time model: LinuxCNC planner, v=X500/Y500/Z500 mm/min, a=X500/Y500/Z200 mm/s^2, G64 P0.05)"
    );
    assert_eq!(lines[at + 2], "M30");
    // everything above the statistics times is the same program
    let cut = |p: &str| p[..p.find("  (Milling length:").unwrap()].to_string();
    assert_eq!(cut(&plain), cut(&timed));
}

#[test]
fn machine_settings_are_checked() {
    let bad = Settings {
        max_velocity: Some(Axes {
            x: 5000.0,
            y: 0.0,
            z: f64::NAN,
        }),
        path_tolerance: -1.0,
        ..settings()
    };
    let errors: Vec<Msg> = bad.number_errors().iter().map(|d| d.msg).collect();
    assert!(errors.contains(&Msg::SettingNotFinite), "{errors:?}");
    assert_eq!(
        errors.iter().filter(|m| **m == Msg::MustBePositive).count(),
        2,
        "{errors:?}"
    );
    assert!(
        errors.contains(&Msg::MachineNeedsAcceleration),
        "{errors:?}"
    );
    assert!(Settings::default().number_errors().is_empty());
    assert_eq!(Settings::default().machine(), None);
}

#[test]
fn millpath_toml_machine_table() {
    use millpath_core::load::config::{parse, Have};
    use std::path::Path;
    let cfg = parse(
        "feed = 150\n[machine]\nmax_velocity = { x = 5000, y = 5000, z = 1000 }\nmax_acceleration = 400\npath_tolerance = 0.02\n",
        Path::new("."),
    )
    .unwrap();
    let mut s = Settings::default();
    cfg.apply(&mut s, &mut Have::default());
    assert_eq!(
        s.machine(),
        Some(Machine {
            max_velocity: Axes {
                x: 5000.0,
                y: 5000.0,
                z: 1000.0
            },
            max_acceleration: Axes::all(400.0),
            path_tolerance: 0.02,
        })
    );
    // unknown axes and keys are errors with their line
    let e = parse(
        "[machine]\nmax_velocity = { x = 1, y = 2, w = 3 }\n",
        Path::new("."),
    )
    .unwrap_err();
    assert!(e.contains("line 2"), "{e}");
    let e = parse("[machine]\nmax_accel = 3\n", Path::new(".")).unwrap_err();
    assert!(e.contains("max_accel"), "{e}");
    // without the table nothing changes
    let mut s = Settings::default();
    parse("feed = 150\n", Path::new("."))
        .unwrap()
        .apply(&mut s, &mut Have::default());
    assert_eq!(s.machine(), None);
}

/// Random programs of lines, arcs, helixes and sweeps (a fixed linear congruential sequence):
/// every estimate is finite, no faster than the whole length at the highest speed allowed,
/// and the moves' own times add up to the statistics'.
#[test]
fn random_programs_get_sane_times() {
    use millpath_core::emit::timing::{item_times, plan};
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = move || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..200 {
        let mut items = Vec::new();
        let (mut x, mut y, mut z) = (0.0f64, 0.0f64, 0.0f64);
        let mut length = 0.0;
        for _ in 0..(1 + (next() * 60.0) as usize) {
            let feed = 50.0 + next() * 5000.0;
            let kind = next();
            if kind < 0.5 {
                // a line or a sweep, sometimes tiny, sometimes straight back
                let scale = if next() < 0.2 { 1e-3 } else { 20.0 };
                let (nx, ny, nz) = (
                    x + (next() - 0.5) * scale,
                    y + (next() - 0.5) * scale,
                    z + if next() < 0.3 {
                        (next() - 0.5) * 5.0
                    } else {
                        0.0
                    },
                );
                let d = ((nx - x).powi(2) + (ny - y).powi(2) + (nz - z).powi(2)).sqrt();
                let k = if kind < 0.15 {
                    Kind::HSweep
                } else {
                    Kind::Mill
                };
                items.push(item(
                    k,
                    d,
                    feed,
                    Target {
                        x: Some(nx),
                        y: Some(ny),
                        z: Some(nz),
                        arc: None,
                    },
                ));
                (x, y, z) = (nx, ny, nz);
                length += d;
            } else {
                // an arc or helix around a centre beside the tool, any sweep
                let r = 0.05 + next() * 30.0;
                let a0 = next() * std::f64::consts::TAU;
                let sweep = 0.01 + next() * std::f64::consts::TAU;
                let ccw = next() < 0.5;
                let c = P2 {
                    x: x - r * a0.cos(),
                    y: y - r * a0.sin(),
                };
                let a1 = if ccw { a0 + sweep } else { a0 - sweep };
                let nz = z + if next() < 0.4 { -next() * 3.0 } else { 0.0 };
                let (nx, ny) = (c.x + r * a1.cos(), c.y + r * a1.sin());
                items.push(item(
                    Kind::Mill,
                    r * sweep,
                    feed,
                    Target {
                        x: Some(nx),
                        y: Some(ny),
                        z: Some(nz),
                        arc: Some((c, ccw)),
                    },
                ));
                length += ((r * sweep).powi(2) + (nz - z).powi(2)).sqrt();
                (x, y, z) = (nx, ny, nz);
            }
        }
        let m = Machine {
            max_velocity: Axes {
                x: 1000.0 + next() * 9000.0,
                y: 1000.0 + next() * 9000.0,
                z: 500.0 + next() * 3000.0,
            },
            max_acceleration: Axes {
                x: 50.0 + next() * 2000.0,
                y: 50.0 + next() * 2000.0,
                z: 20.0 + next() * 1000.0,
            },
            path_tolerance: next() * 0.5,
        };
        let t = plan(&items, ORIGIN, &m);
        let total = t.mill + t.drill + t.sweep;
        assert!(total.is_finite() && total >= 0.0, "{total}");
        // nothing moves faster than the fastest axis along any direction (√3·max V)
        let fastest =
            3f64.sqrt() * m.max_velocity.x.max(m.max_velocity.y).max(m.max_velocity.z) / 60.0;
        // (moves below the program's 0.001 mm take no time)
        let length = (length - items.len() as f64 * 1e-3).max(0.0);
        assert!(
            total >= length / fastest * (1.0 - 1e-9),
            "{total} < {length}/{fastest}"
        );
        let each = item_times(&items, ORIGIN, &m);
        assert!(each.iter().all(|t| t.is_finite() && *t >= 0.0));
        let sum: f64 = each.iter().sum();
        assert!(
            (sum - total).abs() <= 1e-9 * total.max(1.0),
            "{sum} {total}"
        );
    }
}

#[test]
fn the_feed_override_is_the_feeds_scaled_in_linuxcncs_planner() {
    // LinuxCNC's feed override scales the requested speed of the feed moves (within the
    // axes' limits) and leaves the traverses alone: a program at 150 % is planned as the same
    // program with 1.5 × its feeds, and its rapids take the same time at any override
    let program = |scale: f64| {
        vec![
            item(Kind::HSweep, 30.0, 0.0, xy(0.0, 30.0)),
            cut(40.0, 30.0, 40.0, 1200.0 * scale),
            cut(40.0, 0.0, 30.0, 900.0 * scale),
            cut(0.0, 0.0, 40.0, 3000.0 * scale),
            item(Kind::HSweep, 30.0, 0.0, xy(0.0, 30.0)),
        ]
    };
    let at = |percent: f64, items: &[Item]| {
        let m = TimeModel::LinuxCnc {
            machine: machine(),
            feed_override: percent,
        };
        m.plan(items, ORIGIN)
    };
    for percent in [1.0, 50.0, 150.0, 1000.0] {
        let over = at(percent, &program(1.0));
        let scaled = at(100.0, &program(percent / 100.0));
        assert!(
            (over.mill - scaled.mill).abs() < 1e-9,
            "{percent}: {over:?} {scaled:?}"
        );
        assert!((over.sweep - scaled.sweep).abs() < 1e-9, "{percent}");
        // the cuts speed up (until the axes' 100 mm/s cap), the sweeps do not
        let plain = at(100.0, &program(1.0));
        if percent > 100.0 {
            assert!(over.mill < plain.mill, "{percent}");
        }
        assert!((over.sweep - plain.sweep).abs() < 1e-9, "{percent}");
    }
    // at 1000 % every feed is above the axes' 100 mm/s: what 2000 % gives as well
    let capped = at(1000.0, &program(1.0)).mill;
    assert!((capped - at(2000.0, &program(1.0)).mill).abs() < 1e-9);
}
