//! `probe_split = L` (issue 21): with drawn probes, linuxcnc and grbl write every cutting
//! line and arc longer than L as pieces of at most L, each corrected with the weights of its
//! own start (reference-output.md §12.4); the statistics count the pieces; settings errors
//! are located; the reference dialect refuses it; a move needing too many pieces is refused
//! at its element.

mod support;

use millpath_core::diag::Msg;
use millpath_core::{Dialect, Origin, Session, Settings};
use support::*;

/// A 60 mm groove, one pass at −0.2, a probe at each end.
const GROOVE: &str = "path 1000.1P {
  start (0, 0)  O2 T3 I5 B-0,2 S10
  end (60, 0)
  mill (0, 0) -> (60, 0)
  probe (0, 0)
  probe (60, 0)
}
";

fn split(dialect: Dialect, l: Option<f64>) -> Settings {
    Settings {
        dialect,
        probe_split: l,
        probe_feed: Some(50.0),
        ..settings()
    }
}

fn clean(text: &str, s: Settings) -> String {
    let run = compile_with(&[("1000.1P.mpath", text.into())], "1000.1P.mpath", s);
    assert!(run.errors().is_empty(), "{:?}", run.messages());
    run.output("_Clean.gcode").to_string()
}

/// The cutting moves (`G01 … X…`, `G02`, `G03`) of a program.
fn cuts(g: &str) -> Vec<&str> {
    g.lines()
        .filter(|l| {
            l.starts_with("G02")
                || l.starts_with("G03")
                || l.starts_with("G01 F") && l.contains(" X")
        })
        .collect()
}

fn word(line: &str, w: char) -> f64 {
    line.split([' ', '('])
        .find_map(|t| t.strip_prefix(w))
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no {w} in {line}"))
}

/// §12.4's weights of two probes at x on the groove, printed F3, in the program's order
/// (descending weight).
fn expression(z: f64, x: f64) -> String {
    let (w1, w2) = (1.0 / (x + 0.001), 1.0 / (60.0 - x + 0.001));
    let (a, b) = (w1 / (w1 + w2), w2 / (w1 + w2));
    let terms = if b > a {
        format!("+{b:.3}*[#52-3.000]+{a:.3}*[#51-3.000]")
    } else {
        format!("+{a:.3}*[#51-3.000]+{b:.3}*[#52-3.000]")
    };
    format!("Z{z:.3}(={z:.3}{terms})")
}

#[test]
fn a_groove_is_milled_in_pieces_each_corrected_at_its_start() {
    for dialect in [Dialect::LinuxCnc, Dialect::Grbl] {
        let g = clean(GROOVE, split(dialect, Some(10.0)));
        let c = cuts(&g);
        assert_eq!(c.len(), 6, "{dialect}: {g}");
        for (k, line) in c.iter().enumerate() {
            let (x0, x1) = (10.0 * k as f64, 10.0 * (k + 1) as f64);
            assert_eq!(word(line, 'X'), x1, "{line}");
            assert!(line.ends_with(&expression(-0.2, x0)), "piece {k}: {line}");
        }
        // the statistics count the pieces, and say how many moves were split
        let commands = g
            .lines()
            .filter(|l| l.starts_with('G') || l.starts_with('M'))
            .count();
        let body_commands = g
            .lines()
            .skip_while(|l| !l.contains("(Model "))
            .take_while(|l| !l.contains("Milling length"))
            .filter(|l| l.starts_with('G'))
            .count();
        assert!(
            g.contains(&format!("(Command count: {body_commands})")),
            "{body_commands} of {commands}: {g}"
        );
        assert!(
            g.contains("(Split for probes: 1 moves into 6 pieces)"),
            "{g}"
        );
    }
}

#[test]
fn without_the_setting_or_without_probes_nothing_changes() {
    let whole = clean(GROOVE, split(Dialect::LinuxCnc, None));
    let c = cuts(&whole);
    assert_eq!(c.len(), 1, "{whole}");
    assert!(c[0].ends_with(&expression(-0.2, 0.0)), "{}", c[0]);
    assert!(!whole.contains("Split for probes"));
    // a move no longer than L stays whole
    let g = clean(GROOVE, split(Dialect::LinuxCnc, Some(60.0)));
    assert_eq!(cuts(&g).len(), 1);
    // no probes: no expressions to apply along the move, the program is the same
    let plain = GROOVE
        .replace("  probe (0, 0)\n", "")
        .replace("  probe (60, 0)\n", "");
    let program = |l| {
        let run = compile_with(
            &[("1000.1P.mpath", plain.clone())],
            "1000.1P.mpath",
            split(Dialect::LinuxCnc, l),
        );
        assert!(run.errors().is_empty(), "{:?}", run.messages());
        run.output("_Milling.gcode").to_string()
    };
    assert_eq!(program(Some(5.0)), program(None));
}

#[test]
fn arcs_become_sub_arcs_and_ramps_keep_their_slope() {
    // a half circle of radius 15 (47.1 mm) with support bars ramping up and down
    let text = "path 1000.1P {
  start (0, 0)  O2 T3 I5 B-0,2 S10
  end (30, 0)
  mill (0, 0) -> (30, 0) ccw around (15, 0)
  probe (0, 0)
  probe (30, 0)
}
";
    let g = clean(text, split(Dialect::LinuxCnc, Some(5.0)));
    let c = cuts(&g);
    assert_eq!(c.len(), 10, "{g}");
    assert!(c.iter().all(|l| l.starts_with("G03")), "{g}");
    // every piece ends on the circle, the last at the arc's end
    for l in &c {
        let (x, y) = (word(l, 'X'), word(l, 'Y'));
        assert!(((x - 15.0).hypot(y) - 15.0).abs() < 0.001, "{l}");
    }
    assert!(c[9].starts_with("G03 F150.000 I") && c[9].contains(" X30.000 Y0.000 "));
    // a drawn ramp (bars: Down/Up pieces) keeps its Z along the pieces: Z falls evenly
    let bars = "path 1000.1P {
  start (0, 0)  O2 T3 I5 B-0,2 D1 P4 U20 S10
  end (60, 0)
  bars (0, 0) -> (60, 0)
  probe (0, 0)
  probe (60, 0)
}
";
    let whole = clean(bars, split(Dialect::LinuxCnc, None));
    let pieces = clean(bars, split(Dialect::LinuxCnc, Some(0.5)));
    let (cw, cp) = (cuts(&whole), cuts(&pieces));
    assert!(cp.len() > cw.len(), "{pieces}");
    // both end at the same points with the same nominal depths (the Z before the expression)
    let ends = |c: &[&str]| -> Vec<(String, String)> {
        c.iter()
            .map(|l| {
                let z = l.split(" Z").nth(1).unwrap().split('(').next().unwrap();
                (
                    l.split(" Z")
                        .next()
                        .unwrap()
                        .split(" X")
                        .nth(1)
                        .unwrap()
                        .to_string(),
                    z.to_string(),
                )
            })
            .collect()
    };
    let (ew, ep) = (ends(&cw), ends(&cp));
    for e in &ew {
        assert!(ep.contains(e), "{e:?} not among the pieces' ends");
    }
}

#[test]
fn a_move_that_needs_too_many_pieces_is_refused_at_its_element() {
    let text = "path 1000.1P {
  start (0, 0)  O2 T3 I5 B-0,2 S10
  end (6000, 0)
  mill (0, 0) -> (6000, 0)
  probe (0, 0)
}
";
    let run = compile_with(
        &[("1000.1P.mpath", text.into())],
        "1000.1P.mpath",
        split(Dialect::LinuxCnc, Some(0.5)),
    );
    assert_eq!(
        run.errors(),
        [Msg::ProbeSplitTooManyPieces],
        "{:?}",
        run.messages()
    );
    assert!(
        matches!(run.diags[0].origin, Origin::Span { line: 4, .. }),
        "{:?}",
        run.diags[0].origin
    );
    assert!(
        run.messages()[0].contains("12000 moves, more than 10000"),
        "{:?}",
        run.messages()
    );
    assert!(run.outputs.is_empty());
    // a larger L is fine
    let run = compile_with(
        &[("1000.1P.mpath", text.into())],
        "1000.1P.mpath",
        split(Dialect::LinuxCnc, Some(1.0)),
    );
    assert!(run.errors().is_empty(), "{:?}", run.messages());
}

#[test]
fn settings_errors_are_located_and_the_reference_dialect_refuses() {
    let fs = millpath_core::MemFileSystem::default();
    let toml = std::path::PathBuf::from("shop/millpath.toml");
    let at_file = |v: f64, d: Dialect| Settings {
        probe_split: Some(v),
        probe_split_file: Some(toml.clone()),
        ..split(d, None)
    };
    for (v, want) in [
        (0.1, Msg::ProbeSplitTooSmall),
        (f64::NAN, Msg::SettingNotFinite),
        (f64::INFINITY, Msg::SettingNotFinite),
        (-3.0, Msg::ProbeSplitTooSmall),
    ] {
        let errors = Session::new(at_file(v, Dialect::LinuxCnc), &fs)
            .err()
            .expect("refused");
        assert_eq!(errors.len(), 1, "{v}");
        assert_eq!(errors[0].msg, want, "{v}");
        assert!(matches!(&errors[0].origin, Origin::File(f) if f.path == toml));
        assert!(
            errors[0]
                .message(millpath_core::Lang::En)
                .contains("probe_split="),
            "{v}"
        );
    }
    assert!(Session::new(at_file(0.5, Dialect::Grbl), &fs).is_ok());
    // the reference dialect writes PathDxf2GCode's moves: refused, not ignored
    let errors = Session::new(at_file(5.0, Dialect::Reference), &fs)
        .err()
        .expect("refused");
    assert_eq!(errors[0].msg, Msg::ProbeSplitReferenceDialect);
    assert!(matches!(&errors[0].origin, Origin::File(_)));
    // from the command line: named and located as the option, in German too
    let option = Settings {
        probe_split: Some(0.2),
        ..split(Dialect::LinuxCnc, None)
    };
    let errors = Session::new(option, &fs).err().expect("refused");
    assert_eq!(errors[0].origin, Origin::Options);
    assert_eq!(
        errors[0].message(millpath_core::Lang::De),
        "--probe-split=0.2 mm ist kürzer als das kürzeste Teilstück, 0.5 mm"
    );
}
