//! Hostile input never makes a dangerous program or a dead process (issue: machine safety,
//! items 1, 3, 4, 5): non-finite and absurd numbers are errors with their location, every
//! loop is bounded, and nothing runs the emitter on a model with errors.

mod support;

use millpath_core::diag::Msg;
use millpath_core::Settings;
use std::sync::mpsc;
use std::time::Duration;
use support::*;

fn line_drawing(start_text: &str, line_text: &str) -> Drawing {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), start_text).end(L, (20.0, 0.0)).line(
        L,
        "CONTINUOUS",
        (0.0, 0.0),
        (20.0, 0.0),
        line_text,
    );
    d
}

fn helix_drawing(start_text: &str, helix_text: &str) -> Drawing {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), start_text)
        .end(L, (30.0, 0.0))
        .line(L, "DASHED", (0.0, 0.0), (10.0, 0.0), "")
        .circle(L, "CONTINUOUS", (10.0, 0.0), 3.0, helix_text)
        .line(L, "DASHED", (10.0, 0.0), (30.0, 0.0), "");
    d
}

fn check_settings() -> Settings {
    Settings {
        check: true,
        ..settings()
    }
}

/// Runs `f` on another thread; fails instead of hanging or eating the machine's memory.
fn within<T: Send + 'static>(secs: u64, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(Duration::from_secs(secs))
        .expect("did not finish: an unbounded loop")
}

/// Every number of every G-code line is finite and within ±1e6.
fn assert_sane_gcode(text: &str) {
    for line in text.lines() {
        assert!(
            !line.contains("NaN") && !line.contains("inf"),
            "non-finite number in {line:?}"
        );
        for word in line.split([' ', '(', ')', '[', ']', '=', '+', '*']) {
            let Some(num) = word
                .get(1..)
                .filter(|_| word.starts_with(|c: char| "XYZIJF".contains(c)))
            else {
                continue;
            };
            if let Ok(v) = num.parse::<f64>() {
                assert!(v.abs() <= 1e6, "absurd number {v} in {line:?}");
            }
        }
    }
}

// ---- item 1: NaN, infinities and absurd values are errors, never G-code

#[test]
fn non_finite_parameter_values_are_errors_and_write_nothing() {
    let cases = [
        ("O2 T2 I1 BNaN", ""),
        ("O2 T2 I1 B-0,3 SNaN", ""),
        ("O2 T2 I1 B-0,3 FNaN", ""),
        ("O2 T2 INaN B-0,3", ""),
        ("O2 TNaN I1 B-0,3", ""),
        ("O2 T2 I1 B-0,3", "Binf"),
        ("O2 T2 I1 B-0,3", "F-Infinity"),
        ("O2 T2 I1 B1e999", ""),
    ];
    for (start, text) in cases {
        let run = compile_one(&line_drawing(start, text));
        assert!(
            run.errors().contains(&Msg::NumberNotFinite),
            "{start} / {text}: {:?}",
            run.messages()
        );
        assert!(run.outputs.is_empty(), "{start} / {text} wrote a program");
    }
}

#[test]
fn absurd_depths_are_errors() {
    for (start, text) in [
        ("O2 T2 I1 B-99999999999999999999", ""),
        ("O2 T2 I1 B-0,3", "B-1e7"),
        ("O2 T2 I1 B-0,3 F1e300", ""),
    ] {
        let run = compile_one(&line_drawing(start, text));
        assert!(
            run.errors().contains(&Msg::NumberOutOfRange),
            "{start} / {text}: {:?}",
            run.messages()
        );
        assert!(run.outputs.is_empty());
    }
    // a helix with an absurd depth: an error, not an out-of-memory abort
    let run = within(20, || {
        compile_one(&helix_drawing("O2 T2 I1 B-99999999999999999999", "")).errors()
    });
    assert!(run.contains(&Msg::NumberOutOfRange), "{run:?}");
}

#[test]
fn non_finite_and_absurd_coordinates_are_errors_with_their_element() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 2e6, -9.3e15] {
        let mut d = Drawing::new();
        d.start(L, (0.0, 0.0), "O2 T2 I1 B-0,3")
            .end(L, (20.0, 0.0))
            .line(L, "CONTINUOUS", (0.0, 0.0), (bad, 0.0), "")
            .line(L, "CONTINUOUS", (bad, 0.0), (20.0, 0.0), "");
        let run = within(20, move || compile_one(&d));
        assert!(
            run.errors().contains(&Msg::CoordinateOutOfRange),
            "{bad}: {:?}",
            run.messages()
        );
        let located = run
            .diags
            .iter()
            .find(|d| d.msg == Msg::CoordinateOutOfRange)
            .unwrap();
        assert!(
            matches!(&located.origin, millpath_core::Origin::Entity(e) if e.code_name == "LINE"),
            "{:?}",
            located.origin
        );
        assert!(run.outputs.is_empty());
    }
}

#[test]
fn machine_settings_must_be_finite() {
    for s in [
        Settings {
            feed: f64::NAN,
            ..settings()
        },
        Settings {
            sweep_height: f64::INFINITY,
            ..settings()
        },
        Settings {
            probe_feed: Some(1e9),
            ..settings()
        },
    ] {
        let fs = millpath_core::MemFileSystem::default();
        let errs = match millpath_core::Session::new(s, &fs) {
            Ok(_) => panic!("accepted"),
            Err(e) => e,
        };
        assert_eq!(errs[0].msg, Msg::SettingNotFinite);
    }
}

/// Random hostile values in every parameter: whatever compiles is sane G-code.
#[test]
fn no_generated_program_holds_a_non_finite_or_absurd_number() {
    let values = [
        "NaN", "inf", "-inf", "1e999", "1e300", "-1e300", "0", "-0", "1e-300", "999999", "1000001",
        "-2", "0,5", "2", "1e6", "-1e6", "x", "", "=Z",
    ];
    let keys = ["T", "O", "I", "B", "D", "S", "F", "W", "A"];
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = |n: usize| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % n as u64) as usize
    };
    let mut compiled = 0;
    for _ in 0..300 {
        let mut start = String::from("O2 T2 I1 B-0,3");
        for _ in 0..1 + next(3) {
            let k = keys[next(keys.len())];
            let v = values[next(values.len())];
            start = start
                .split(' ')
                .filter(|t| !t.starts_with(k))
                .collect::<Vec<_>>()
                .join(" ");
            start.push_str(&format!(" {k}{v}"));
        }
        let line_text = if next(2) == 0 {
            format!("{}{}", keys[next(keys.len())], values[next(values.len())])
        } else {
            String::new()
        };
        for d in [
            line_drawing(&start, &line_text),
            helix_drawing(&start, &line_text),
        ] {
            let run = within(20, move || compile_one(&d));
            for o in &run.outputs {
                assert_sane_gcode(&o.content);
                compiled += 1;
            }
        }
    }
    assert!(compiled > 20, "too few programs compiled: {compiled}");
}

// ---- item 3: a helix with I0 or a negative I in check mode (and so in the editor)

#[test]
fn helix_with_zero_or_negative_infeed_is_checked_without_hanging() {
    for i in ["I0", "I-1", "I-0,001"] {
        let text = format!("O2 T2 {i} B-0,1");
        let errors = within(20, move || {
            compile_with(
                &[("1000.1P.dxf", helix_drawing(&text, "").dxf())],
                "1000.1P.dxf",
                check_settings(),
            )
            .errors()
        });
        assert!(errors.contains(&Msg::MustBePositive), "{i}: {errors:?}");
    }
    // the same I on the helix itself
    let errors = within(20, || {
        compile_with(
            &[("1000.1P.dxf", helix_drawing("O2 T2 I1 B-0,1", "I-1").dxf())],
            "1000.1P.dxf",
            check_settings(),
        )
        .errors()
    });
    assert!(errors.contains(&Msg::MustBePositive), "{errors:?}");
}

#[test]
fn tiny_infeed_is_refused_not_milled_forever() {
    // 0.00001 mm per pass over 2 mm: 200,000 passes
    let run = within(20, || {
        compile_one(&line_drawing("O2 T2 I0,00001 B0", "")).errors()
    });
    assert!(run.contains(&Msg::TooManyPasses), "{run:?}");
    let run = within(20, || {
        compile_one(&helix_drawing("O2 T2 I0,00001 B0", "")).errors()
    });
    assert!(run.contains(&Msg::TooManyPasses), "{run:?}");
}

// ---- item 4: support bars along a very long segment

#[test]
fn bars_along_a_long_segment_are_bounded() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1 B0 D1 P0,01 U0,01")
        .end(L, (900_000.0, 0.0))
        .line(L, "BORDER", (0.0, 0.0), (900_000.0, 0.0), "");
    let errors = within(20, move || compile_one(&d).errors());
    assert!(errors.contains(&Msg::TooManyBars), "{errors:?}");
    // a 1e9 mm segment is out of range before any bar is made
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1 B0 D1 P1 U5")
        .end(L, (1e9, 0.0))
        .line(L, "BORDER", (0.0, 0.0), (1e9, 0.0), "");
    let errors = within(20, move || compile_one(&d).errors());
    assert!(errors.contains(&Msg::CoordinateOutOfRange), "{errors:?}");
}

// ---- item 5: coordinates that overflowed the traversal grid

#[test]
fn huge_coordinates_do_not_overflow_the_traversal() {
    let mut d = Drawing::new();
    d.start(L, (9.3e15, 0.0), "O2 T2 I1 B0")
        .end(L, (9.3e15 + 20.0, 0.0))
        .line(L, "CONTINUOUS", (9.3e15, 0.0), (9.3e15 + 20.0, 0.0), "");
    let errors = within(20, move || compile_one(&d).errors());
    assert!(errors.contains(&Msg::CoordinateOutOfRange), "{errors:?}");
}

// ---- a drawing file too large to read

#[test]
fn a_file_larger_than_the_limit_is_an_error_not_an_exhausted_memory() {
    use millpath_core::load::fs::MAX_FILE_BYTES;
    use millpath_core::{compile_file, OsFileSystem, Session};
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("9000.dxf");
    // sparse: no disk space taken, but the size the reader sees
    std::fs::File::create(&path)
        .unwrap()
        .set_len(MAX_FILE_BYTES + 1)
        .unwrap();
    let fs = OsFileSystem;
    let errors = within(20, move || {
        let mut session = Session::new(settings(), &fs).expect("settings");
        compile_file(&mut session, &path, "millpath test");
        session.diags.list.iter().map(|d| d.msg).collect::<Vec<_>>()
    });
    assert_eq!(errors.first(), Some(&Msg::FileTooLarge), "{errors:?}");
}

#[test]
fn passes_within_the_depth_tolerance_count_against_the_bound() {
    // W = B at 800,000 mm: the pass estimate says 2 a segment, but the levels stay `ge` the
    // bottom within its tolerance (0.8 mm) for 8,000 passes; 300 segments are more passes
    // than a program may have
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T900000 S950000 W800000 I0,0001 B800000")
        .end(L, (300.0, 0.0));
    for i in 0..300 {
        let x = f64::from(i);
        d.line(L, "CONTINUOUS", (x, 0.0), (x + 1.0, 0.0), "");
    }
    let errors = within(20, move || compile_one(&d).errors());
    assert!(errors.contains(&Msg::TooManyMoves), "{errors:?}");
}
