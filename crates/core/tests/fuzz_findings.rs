//! Bugs the structure-aware fuzz target (`fuzz/fuzz_targets/drawing.rs`) found, each pinned
//! by the smallest drawing that showed it.

mod support;

use millpath_core::diag::{FileRef, Msg, Severity};
use millpath_core::load::names::{Patterns, DEFAULT_FILE_PATTERN, DEFAULT_PATH_PATTERN};
use millpath_core::machine::Dialect;
use std::path::PathBuf;
use support::*;

fn patterns() -> Patterns {
    Patterns::new(DEFAULT_PATH_PATTERN, DEFAULT_FILE_PATTERN).unwrap()
}

fn to_dxf(name: &str, text: &str) -> Result<String, Vec<millpath_core::Diagnostic>> {
    millpath_core::convert::text_to_dxf(text, &FileRef::new(PathBuf::from(name)), &patterns())
}

const PART: &str = "path 2001.1P {
  start (0, 0)  T3 O2 M3 I1 B1
  end (10, 0)
  mill (0, 0) -> (10, 0)
}
";

/// A subpath raised (or lowered) by H has its own material top. The second opinion's stock
/// was one block as high as the highest top, so the project's own approach to T was a "rapid
/// into material": linuxcnc and grbl refused the valid program. The block is now as high as
/// the lowest top.
#[test]
fn a_raised_or_lowered_subpath_is_no_rapid_into_material() {
    for h in ["H1", "H-0,5"] {
        let top = format!(
            "path 1000.1P {{
  start (0, 0)  T3 O2 M3 I1 B1
  end (30, 0)
  mill (0, 0) -> (10, 0)
  sub (10, 0) -> (20, 0)  >2001.1P {h}
  mill (20, 0) -> (30, 0)
}}
"
        );
        for dialect in [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl] {
            let run = compile_with(
                &[
                    ("1000.mpath", top.clone()),
                    ("2001.mpath", PART.to_string()),
                ],
                "1000.mpath",
                millpath_core::Settings {
                    dialect,
                    ..settings()
                },
            );
            assert!(
                !run.diags.iter().any(|d| d.msg == Msg::SecondOpinion),
                "{h} {dialect}: {:?}",
                run.messages()
            );
            assert!(!run.outputs.is_empty(), "{h} {dialect}: nothing written");
            if dialect != Dialect::Reference {
                // the stock comment a standalone `verify` reads says the same top
                let lowest = if h == "H1" { "T=3.000" } else { "T=2.500" };
                assert!(
                    run.output("_Milling.gcode").contains(lowest),
                    "{h} {dialect}"
                );
            }
        }
    }
}

/// text2dxf wrote texts beyond ASCII as UTF-8 into a file that declares ANSI_1252: read back,
/// `Größe` became `GrÃ¶ÃŸe` (in the G-code comment of a Q). They are `\U+XXXX` escapes now,
/// also at the very end of a text, where readers decode an escape only when a character
/// follows (the writer adds an empty MTEXT group).
#[test]
fn texts_beyond_ascii_survive_text2dxf() {
    for q in ["QGröße", "QMaß", "QÆ€"] {
        let text = format!(
            "path 1000.1P {{
  start (0, 0)  T3 O2 I1 B1
  end (20, 0)
  mill (0, 0) -> (20, 0)  {q}
}}
"
        );
        let dxf = to_dxf("1000.mpath", &text).expect("converts");
        assert!(dxf.is_ascii(), "{q}: the DXF holds bytes beyond ASCII");
        let from_text = compile(&[("1000.mpath", text.clone())], "1000.mpath");
        let from_dxf = compile(&[("1000.dxf", dxf)], "1000.dxf");
        let comment = format!("(Q:{})", &q[1..]);
        let g = from_text.output("_Milling.gcode");
        assert!(g.contains(&comment), "{q}: {g}");
        assert_eq!(
            g.replace(".mpath", ".dxf"),
            from_dxf.output("_Milling.gcode"),
            "{q}"
        );
    }
}

/// A DXF cannot attach a text to a HIDDEN line (`move`) or an end marker, so the text
/// language silently dropped what was written there (`move … S20` moved at the path's sweep
/// height) while the DXF of the same text reported the loose text. Now it is an error at the
/// parameters, and text2dxf refuses to convert it.
#[test]
fn parameters_on_a_move_or_an_end_marker_are_refused() {
    for (line, words) in [
        ("  move (0, 0) -> (20, 0)  S20\n  end (20, 0)\n", "S20"),
        (
            "  sweep (0, 0) -> (20, 0)\n  end (20, 0)  N1 F100\n",
            "N1 F100",
        ),
    ] {
        let text = format!("path 1000.1P {{\n  start (0, 0)  T3 O2 I1 B1\n{line}}}\n");
        let run = compile(&[("1000.mpath", text.clone())], "1000.mpath");
        let d = run
            .diags
            .iter()
            .find(|d| d.msg == Msg::NoTextHere)
            .unwrap_or_else(|| panic!("{line}: {:?}", run.messages()));
        assert_eq!(d.severity, Severity::Error);
        assert!(
            d.message(Default::default()).contains(words),
            "{:?}",
            run.messages()
        );
        assert!(run.outputs.is_empty());
        let refusal = to_dxf("1000.mpath", &text).expect_err("refused");
        assert!(refusal.iter().any(|d| d.msg == Msg::NoTextHere));
    }
}

/// A `bars helix` in a turned subpath: its bar profile was turned with the subpath while the
/// helix's semicircles end at the circle's south point in output coordinates, so the first
/// bar arc began away from the tool (the second opinion: "arc radius differs at start and
/// end"; linuxcnc and grbl refused). The profile now starts where the tool is.
#[test]
fn a_bars_helix_in_a_turned_subpath_starts_its_bars_where_the_tool_is() {
    let part = "path 2001.1P {
  start (0, 0)  T3 O2 M3 I1 B-0,2 D1 P2 U5
  bars helix (0, 0) d8
  sweep (0, 0) -> (10, 0)
  end (10, 0)
}
";
    for to in ["(10, 0)", "(0, 10)", "(-10, 0)", "(6, -8)"] {
        let top = format!(
            "path 1000.1P {{
  start (0, 0)  T3 O2 M3 I1 B-0,2
  end {to}
  sub (0, 0) -> {to}  >2001.1P
}}
"
        );
        for dialect in [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl] {
            let run = compile_with(
                &[
                    ("1000.mpath", top.clone()),
                    ("2001.mpath", part.to_string()),
                ],
                "1000.mpath",
                millpath_core::Settings {
                    dialect,
                    ..settings()
                },
            );
            assert!(
                !run.diags.iter().any(|d| d.msg == Msg::SecondOpinion),
                "{to} {dialect}: {:?}",
                run.messages()
            );
            let g = run.output("_Milling.gcode");
            assert!(g.contains("Support.Bar"), "{to} {dialect}: no bars");
        }
    }
}
