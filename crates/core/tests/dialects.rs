//! Controller dialects: complete `linuxcnc` and `grbl` programs of a small drawing written by
//! hand (header order, plunge feeds, spindle, program end, stock comment), and every `grbl`
//! program of the examples, of drawings of our own and of the shared drawings checked against
//! the words and modal groups GRBL 1.1 accepts. The reference dialect is covered by
//! `output_digests.rs` (unchanged table).

mod support;

use millpath_core::diag::Msg;
use millpath_core::{compile_file, Dialect, OsFileSystem, Session, Settings};
use std::path::Path;
use support::grbl;
use support::*;

/// T2, I1.2, B−0.3, S5: a 20 mm line milled in two passes (0.8 forward, −0.3 back).
const LINE: &str = "path 1000.1P {
  start (0, 0)  O2 T2 I1,2 B-0,3 S5
  end (20, 0)
  mill (0, 0) -> (20, 0)
}
";

fn with(dialect: Dialect) -> Settings {
    Settings {
        dialect,
        ..settings()
    }
}

fn program(text: &str, settings: Settings) -> String {
    let run = compile_with(&[("1000.1P.mpath", text.into())], "1000.1P.mpath", settings);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    run.output("_Milling.gcode").to_string()
}

/// The body of LINE (reference-output.md §7.2: Sx = 5.00001; rapid to T, plunge to 0.8,
/// forward; plunge to −0.3 from 0.8, back; pull up, sweep to the chain end; final Z) with the
/// given plunge words (`G01 Z…` in the reference, `G01 F… Z…` in the other dialects).
fn line_body(plunge: &str) -> String {
    format!(
        "  (Model 1000.1P[1000.1P.mpath])
  (SweepAndDrillSafelyFromTo [0.000 0.000 5.000] [0.000 0.000 0.800] s=5.000 bt=False)
    (DrillOrPullZFromTo 5.000 0.800)
G00 Z2.000
G01 {plunge}Z0.800
  (MillLine s=[0.000 0.000] e=[20.000 0.000] fr=0.800 to=0.800 bt=False)
G01 F150.000 X20.000 Y0.000 Z0.800
  (SweepAndDrillSafelyFromTo [20.000 0.000 0.800] [20.000 0.000 -0.300] s=5.000 bt=False)
    (DrillOrPullZFromTo 0.800 -0.300)
G01 {plunge}Z-0.300
  (MillLine s=[20.000 0.000] e=[0.000 0.000] fr=-0.300 to=-0.300 bt=False)
G01 F150.000 X0.000 Y0.000 Z-0.300
  (SweepAndDrillSafelyFromTo [0.000 0.000 -0.300] [20.000 0.000 5.000] s=5.000 bt=False)
    (DrillOrPullZFromTo -0.300 5.000)
G00 Z5.000
G00 X20.000 Y0.000
G00 Z5.000
"
    )
}

// mill 2·20 = 40 (40/150·1.4 = 0.37 min → 1); drill (2 − 0.8) + (2 + 0.3) = 3.5 → 4;
// sweeps 3.00001 + 5.3 + 20 + 0.00001 = 28.3 → 28 (0.08 min → 1); sum 71.8 → 72; 8 commands
const STATS: &str = "  (Milling length:    40 mm   ca.  1 min)
  (Drill length:     4 mm   ca.  1 min)
  (Sweeps:         28 mm   ca.  1 min)
  (Sum:            72 mm   ca.  1 min)
  (Command count: 8)
";

#[test]
fn reference_writes_f150_before_the_modal_line_and_plunges_without_feed() {
    let expected = "%
(millpath test)
(1000.1P.mpath)
F150
G17 G21 G40 G49 G54 G80 G90 G94
T1
(SweepSafelyTo [0.000 0.000 5.000])
G00 Z5.000
G00 X0.000 Y0.000
"
    .to_string()
        + &line_body("")
        + STATS
        + "M30\n%\n";
    assert_eq!(program(LINE, settings()), expected);
    assert_eq!(program(LINE, with(Dialect::Reference)), expected);
}

#[test]
fn linuxcnc_writes_the_feed_after_the_modal_line_and_on_every_plunge() {
    // default plunge feed: half the feed (150 / 2 = 75)
    let expected = "%
(millpath test)
(1000.1P.mpath)
(MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300)
G17 G21 G40 G49 G54 G80 G90 G94
F150.000
T1
(SweepSafelyTo [0.000 0.000 5.000])
G00 Z5.000
G00 X0.000 Y0.000
"
    .to_string()
        + &line_body("F75.000 ")
        + STATS
        + "M30\n%\n";
    assert_eq!(program(LINE, with(Dialect::LinuxCnc)), expected);
}

#[test]
fn grbl_has_no_percent_lines_and_switches_the_spindle() {
    let s = Settings {
        spindle_rpm: Some(12000.0),
        plunge_feed: Some(100.0),
        ..with(Dialect::Grbl)
    };
    let expected = "(millpath test)
(1000.1P.mpath)
(MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300)
G17 G21 G40 G49 G54 G80 G90 G94
F150.000
T1
M3 S12000
G4 P2
(SweepSafelyTo [0.000 0.000 5.000])
G00 Z5.000
G00 X0.000 Y0.000
"
    .to_string()
        + &line_body("F100.000 ")
        + STATS
        + "M5\nM30\n";
    assert_eq!(program(LINE, s), expected);
}

#[test]
fn plunge_feed_follows_the_feed_and_never_exceeds_the_element_feed() {
    // --feed 60: mill moves F60, plunges at half of it
    let g = program(
        LINE,
        Settings {
            feed: 60.0,
            ..with(Dialect::LinuxCnc)
        },
    );
    assert!(g.contains("\nF60.000\n"), "{g}");
    assert!(g.contains("\nG01 F30.000 Z0.800\n"), "{g}");
    assert!(g.contains("\nG01 F30.000 Z-0.300\n"), "{g}");
    assert!(g.contains("\nG01 F60.000 X20.000 Y0.000 Z0.800\n"), "{g}");
    // a plunge feed above the element's own F (here F40 on the drill) takes the element's
    let text = "path 1000.1P {
  start (0, 0)  O2 T2 I1,2 B-0,3 S5
  end (20, 0)
  sweep (0, 0) -> (10, 0)
  drill (10, 0) d2  F40
  sweep (10, 0) -> (20, 0)
}
";
    let s = Settings {
        plunge_feed: Some(100.0),
        ..with(Dialect::Grbl)
    };
    let g = program(text, s);
    assert!(g.contains("\nG01 F40.000 Z-0.300\n"), "{g}");
    // the spindle dwell is left out when 0, the spindle lines only with a speed
    let g = program(
        LINE,
        Settings {
            spindle_rpm: Some(8000.5),
            spindle_dwell: 0.0,
            ..with(Dialect::LinuxCnc)
        },
    );
    assert!(g.contains("\nT1\nM3 S8000.5\n(SweepSafelyTo"), "{g}");
    assert!(g.ends_with("  (Command count: 8)\nM5\nM30\n%\n"), "{g}");
}

#[test]
fn invalid_controller_settings_are_option_errors() {
    let fs = millpath_core::MemFileSystem::default();
    for (s, msg) in [
        (
            Settings {
                plunge_feed: Some(0.0),
                ..settings()
            },
            Msg::MustBePositive,
        ),
        (
            Settings {
                spindle_rpm: Some(-1.0),
                ..settings()
            },
            Msg::MustBePositive,
        ),
        (
            Settings {
                spindle_dwell: -2.0,
                ..settings()
            },
            Msg::OptionNegative,
        ),
        (
            Settings {
                plunge_feed: Some(f64::INFINITY),
                ..settings()
            },
            Msg::SettingNotFinite,
        ),
        (
            Settings {
                spindle_dwell: f64::NAN,
                ..settings()
            },
            Msg::SettingNotFinite,
        ),
    ] {
        let errs = match Session::new(s, &fs) {
            Ok(_) => panic!("accepted"),
            Err(e) => e,
        };
        assert_eq!(errs.iter().map(|d| d.msg).collect::<Vec<_>>(), [msg]);
    }
}

#[test]
fn stock_comment_names_the_lowest_depth_including_subpaths_with_h() {
    // the project mills down to 1.5 itself; the slot (B−0.2) embedded with H1 goes to 0.8;
    // the mark D2.5 is higher
    let part = std::fs::read_to_string(root().join("examples/text/2001.mpath")).unwrap();
    let project = "path 2011.1P {
  start (0, 0)  M10x3 O2 T4 I1,5 B1,5 D2,5
  end (50, 0)
  sweep (0, 0) -> (10, 10)
  sub (10, 10) -> (40, 10)  >2001.1P H1 T3
  sweep (40, 10) -> (40, 20)
  mark (40, 20) -> (10, 20)
  sweep (10, 20) -> (10, 30)
  mill (10, 30) -> (40, 30)
  sweep (40, 30) -> (50, 0)
}
";
    let run = compile_with(
        &[("2001.mpath", part), ("2011.mpath", project.into())],
        "2011.mpath",
        with(Dialect::LinuxCnc),
    );
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let g = run.output("_Milling.gcode");
    assert!(
        g.contains("\n(MILLPATH-STOCK T=4.000 O=2.000 BOTTOM=0.800)\n"),
        "{g}"
    );
}

/// In linuxcnc the probing program of drawn probes opens LinuxCNC's probe log itself, around
/// the probes only, named after the drawing (its `R` suffix included); grbl has no such
/// command, and the reference dialect stays PathDxf2GCode's program.
#[test]
fn linuxcnc_probing_program_opens_the_probe_log() {
    let text = "path 1000.1P {
  start (0, 0)  O2 T2 I1,2 B-0,3 S5 R_B
  end (20, 0)
  mill (0, 0) -> (20, 0)
  probe (5, 5)
  probe (15, 5)
}
";
    let probing = |d: Dialect| {
        let s = Settings {
            probe_feed: Some(50.0),
            ..with(d)
        };
        let run = compile_with(&[("1000.1P.mpath", text.into())], "1000.1P.mpath", s);
        assert!(run.diags.is_empty(), "{:?}", run.messages());
        run.output("_Probing.gcode").to_string()
    };
    let lc = probing(Dialect::LinuxCnc);
    assert!(
        lc.contains(
            "G00 X0.000 Y0.000\n(PROBEOPEN 1000.1P_B_probes.txt)\nG00 X5.000 Y5.000\nG00 Z4.000\n\
             G38.3 Z0 F50.000\nG04 P4\nG00 Z5.000\nG00 X15.000 Y5.000\nG00 Z4.000\n\
             G38.3 Z0 F50.000\nG04 P4\nG00 Z5.000\n(PROBECLOSE)\nG00 X0.000 Y0.000\nG00 Z5.000\nM30\n"
        ),
        "{lc}"
    );
    for d in [Dialect::Grbl, Dialect::Reference] {
        let g = probing(d);
        assert!(!g.contains("PROBE"), "{d}: {g}");
    }
}

/// `probe_split` pieces (lines and sub-arcs) in grbl use only what GRBL 1.1 accepts.
#[test]
fn split_moves_in_grbl_use_only_words_grbl_accepts() {
    let text = "path 1000.1P {
  start (0, 0)  O2 T2 I1,2 B-0,3 S5
  end (40, 0)
  mill (0, 0) -> (20, 0) ccw around (10, 0)
  mill (20, 0) -> (40, 0)
  probe (5, 5)
  probe (35, 5)
}
";
    let s = Settings {
        probe_feed: Some(50.0),
        probe_split: Some(3.0),
        ..with(Dialect::Grbl)
    };
    let run = compile_with(&[("1000.1P.mpath", text.into())], "1000.1P.mpath", s);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let clean = run.output("_Clean.gcode");
    // the half circle (31.4 mm) in 11 sub-arcs, forth (G03) and back (G02)
    let arcs = |g: &str| clean.lines().filter(|l| l.starts_with(g)).count();
    assert_eq!((arcs("G03 "), arcs("G02 ")), (11, 11), "{clean}");
    if let Err(e) = grbl::check_program(clean) {
        panic!("{e}\n{clean}");
    }
}

#[test]
fn probing_programs_follow_the_dialect_without_spindle() {
    let text = "path 1000.1P {
  start (0, 0)  O2 T2 I1,2 B-0,3 S5
  end (20, 0)
  mill (0, 0) -> (20, 0)
  probe (5, 5)
  probe (15, 5)  H1
}
";
    let s = Settings {
        spindle_rpm: Some(10000.0),
        probe_feed: Some(50.0),
        ..with(Dialect::Grbl)
    };
    let run = compile_with(&[("1000.1P.mpath", text.into())], "1000.1P.mpath", s);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let probing = run.output("_Probing.gcode");
    // the banner line carries the probing set's digest (grbl has no `%`: it is line 1)
    let (banner, probing) = probing.split_once('\n').unwrap();
    assert!(
        banner.starts_with("(millpath test set=")
            && banner.len() == "(millpath test set=)".len() + 16,
        "{banner}"
    );
    assert_eq!(
        probing,
        "(1000.1P.mpath)
(MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300)
G17 G21 G40 G49 G54 G80 G90 G94
F150.000
T1
(SweepSafelyTo [0.000 0.000 5.000])
G00 Z5.000
G00 X0.000 Y0.000
G00 X5.000 Y5.000
G00 Z4.000
G38.3 Z0 F50.000
G04 P4
G00 Z5.000
G00 X15.000 Y5.000
G00 Z5.000
G38.3 Z0 F50.000
G04 P4
G00 Z5.000
G00 X0.000 Y0.000
G00 Z5.000
M30
"
    );
    let clean = run.output("_Clean.gcode");
    assert!(clean.contains("\nM3 S10000\nG4 P2\n"), "{clean}");
    assert!(
        clean.contains("\nG01 F75.000 Z0.800(=0.800+"),
        "plunges keep their probe expressions: {clean}"
    );
    assert!(clean.ends_with("M5\nM30\n"));
    for (name, g) in [("probing", probing), ("clean", clean)] {
        if let Err(e) = grbl::check_program(g) {
            panic!("{name}: {e}\n{g}");
        }
    }
}

/// The G-code files `compile` writes for a drawing on disk, with the settings of its
/// `millpath.toml` (if any) and the given dialect; `None` when it does not compile alone.
fn compile_disk(file: &Path, dialect: Dialect) -> Option<Vec<(String, String)>> {
    let mut s = Settings::default();
    let toml = file.parent().unwrap().join("millpath.toml");
    if let Ok(text) = std::fs::read_to_string(&toml) {
        let cfg = millpath_core::load::config::parse(&text, file.parent().unwrap()).unwrap();
        cfg.apply(&mut s, &mut Default::default());
    }
    s.dialect = dialect;
    let fs = OsFileSystem;
    let mut session = Session::new(s, &fs).unwrap();
    let outcome = compile_file(&mut session, file, "millpath test");
    if outcome.outputs.is_empty() {
        return None;
    }
    Some(
        outcome
            .outputs
            .into_iter()
            .filter(|o| o.path.to_string_lossy().ends_with(".gcode"))
            .map(|o| (o.path.display().to_string(), o.content))
            .collect(),
    )
}

#[test]
fn every_grbl_program_uses_only_words_grbl_accepts() {
    let mut programs: Vec<(String, String)> = Vec::new();
    // the examples must compile
    for f in files_in(&root().join("examples/plate"), &["dxf"])
        .into_iter()
        .chain(files_in(&root().join("examples/text"), &["mpath"]))
    {
        let out = compile_disk(&f, Dialect::Grbl)
            .unwrap_or_else(|| panic!("{} does not compile", f.display()));
        programs.extend(out);
    }
    // drawings of our own: every element kind (bars on lines and helixes, marks, drills,
    // helixes, arcs, sweepless chains, subpaths with H, probes), with spindle
    let own = [
        "path 1000.1P {
  start (0, 0)  O2 T3 I1,2 B-0,3 D1 P6 U30 S8
  end (100, 0)
  sweep (0, 0) -> (10, 0)  N1
  bars helix (10, 0) d8
  bars (10, 0) -> (60, 0)
  mark (60, 0) -> (60, 10)
  mill arc (60, 20) r10 from 270 to 360
  sweep (70, 20) -> (80, 20)
  drill (80, 20) d2
  mark drill (80, 20) d2
  sweep (80, 20) -> (90, 20)
  helix (90, 20) d6
  sweep (90, 20) -> (90, 0)
  mill (90, 0) -> (100, 0)  W2
  probe (50, 30)
  probe (20, 30)  L2
}
",
        "path 1000.1P {
  start (0, 0)  M10x3 O2 T4 I1,5 B1,5
  end (50, 0)
  sweep (0, 0) -> (10, 10)
  sub (10, 10) -> (40, 10)  >2001.1P H1 T3
  sweep (40, 10) -> (50, 0)
}
",
    ];
    let part = std::fs::read_to_string(root().join("examples/text/2001.mpath")).unwrap();
    for (i, text) in own.iter().enumerate() {
        let run = compile_with(
            &[
                ("1000.1P.mpath", text.to_string()),
                ("2001.mpath", part.clone()),
            ],
            "1000.1P.mpath",
            Settings {
                spindle_rpm: Some(18000.0),
                ..with(Dialect::Grbl)
            },
        );
        assert!(run.errors().is_empty(), "own {i}: {:?}", run.messages());
        assert!(!run.outputs.is_empty(), "own {i}");
        for o in run.outputs {
            if o.path.to_string_lossy().ends_with(".gcode") {
                programs.push((format!("own {i} {}", o.path.display()), o.content));
            }
        }
    }
    // and every shared drawing that compiles alone, when ../shared is there
    let shared = root().join("../shared");
    for dir in ["conformance/fixtures", "samples"] {
        for f in files_in(&shared.join(dir), &["dxf"]) {
            programs.extend(compile_disk(&f, Dialect::Grbl).unwrap_or_default());
        }
    }
    assert!(programs.len() >= 8, "{}", programs.len());
    for (name, g) in &programs {
        if let Err(e) = grbl::check_program(g) {
            panic!("{name}: {e}");
        }
    }
    // the table was really exercised: arcs, helixes, plunges, probes, dwells, spindle
    for w in [
        "G00 Z", "G00 X", "G01 F", "G02 ", "G03 ", "G38.3 ", "G04 ", "M3 S", "G4 P", "M5", "M30",
    ] {
        assert!(
            programs
                .iter()
                .any(|(_, g)| g.lines().any(|l| l.starts_with(w))),
            "no {w} in any program"
        );
    }
}

#[test]
fn a_height_maps_grbl_programs_use_only_words_grbl_accepts() {
    // arcs, a helix, a drill: every kind of cut widens the grid; the grid's probes G38.2
    let text = "path 1000.1P {
  start (0, 0)  O2 T3 I1,2 B-0,3 S8
  end (60, 0)
  sweep (0, 0) -> (10, 20)
  mill arc (20, 20) r10 from 180 to 360
  sweep (30, 20) -> (40, 20)
  helix (40, 20) d6
  sweep (40, 20) -> (50, 20)
  drill (50, 20) d2
  sweep (50, 20) -> (60, 0)
}
";
    let hm = millpath_core::probe::heightmap::Heightmap {
        margin: 1.0,
        ..millpath_core::probe::heightmap::Heightmap::with_step(5.0)
    };
    let s = Settings {
        heightmap: Some(hm),
        ..with(Dialect::Grbl)
    };
    let run = compile_with(&[("1000.1P.mpath", text.into())], "1000.1P.mpath", s);
    assert!(run.errors().is_empty(), "{:?}", run.messages());
    let probing = run.output("_Probing.gcode");
    assert!(probing.contains("\nG38.2 Z-2.000 F150.000\n"), "{probing}");
    // cuts from x 10 (the arc's start) to 50 (the drill), y 10 (the arc's lowest point, not
    // an end) to 22 (the helix: Ø6 − O2 around y 20), plus the margin 1
    assert!(
        probing.contains("(MILLPATH-HEIGHTMAP X0=9.000 Y0=9.000 X1=51.000 Y1=23.000"),
        "{probing}"
    );
    for (name, g) in [("probing", probing), ("clean", run.output("_Clean.gcode"))] {
        if let Err(e) = grbl::check_program(g) {
            panic!("{name}: {e}\n{g}");
        }
    }
}

#[test]
fn the_grbl_checker_rejects_what_grbl_rejects() {
    for bad in [
        "%",
        "G01 Z#51",
        "G01 Z[1+2]",
        "O100 sub",
        "G01 Z1 (unclosed",
        "G41 D1",
        "G81 X1 Y1 Z-1 R1",
        "M6 T1",
        "G0 G1 X1",
        "G10 L1 P1",
        "M3 M5",
        "G01 X1 X2",
        "G01 A5",
        "G38.1 Z0",
        "X1.2.3",
        "G02 F150.000 X12345.678 Y12345.678 Z12345.678 I12345.678 J12345.678 K12345.678 R12345.678",
    ] {
        assert!(grbl::check_line(bad).is_err(), "{bad} accepted");
    }
    for good in [
        "",
        "(a comment with # and [ ])",
        "; G00 X1 Y1",
        "G00 X1.000 Y-0.000 (tail)",
        "G01 F75.000 Z0.800(=0.800+0.794*[#51-2.000])",
        "G17 G21 G40 G49 G54 G80 G90 G94",
        "G38.3 Z0 F50.000",
        "G04 P4",
        "G10 L20 P1 X0",
        "g02 f150 i0 j5 x1 y2 z3",
        "M3 S12000",
        "G91.1 G43.1 Z1",
        "M56 P1",
        "N10 G28",
    ] {
        if let Err(e) = grbl::check_line(good) {
            panic!("{good}: {e}");
        }
    }
}
