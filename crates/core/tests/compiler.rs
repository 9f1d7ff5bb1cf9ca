//! Behaviour of the compiler on drawings of our own making.

mod support;

use millpath_core::diag::{Lang, Msg, Origin};
use support::*;

/// The walk-through of reference-output.md §19: one line, T2 I1.2 B−0.3, S5.
#[test]
fn single_line_matches_the_specified_walkthrough() {
    let mut d = Drawing::new();
    d.start(L, (10.0, 20.0), "M2x20 O2 T2 I1,2 B-0,3")
        .end(L, (67.687, 20.0))
        .line(L, "CONTINUOUS", (10.0, 20.0), (67.687, 20.0), "");
    let run = compile_with(
        &[("1000.1P.dxf", d.dxf())],
        "1000.1P.dxf",
        millpath_core::Settings {
            sweep_height: 5.0,
            ..settings()
        },
    );
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let g = run.output("1000.1P_Milling.gcode");
    let lines: Vec<&str> = g.lines().collect();
    assert_eq!(
        &lines[..4],
        ["%", "(millpath test)", "(1000.1P.dxf)", "F150"]
    );
    assert_eq!(lines[6], "(SweepSafelyTo [0.000 0.000 5.000])");
    assert_eq!(
        run.body(),
        [
            "  (SweepAndDrillSafelyFromTo [0.000 0.000 5.000] [0.000 0.000 0.800] s=5.000 bt=False)",
            "    (DrillOrPullZFromTo 5.000 0.800)",
            "G00 Z2.000",
            "G01 Z0.800",
            "  (MillLine s=[0.000 0.000] e=[57.687 0.000] fr=0.800 to=0.800 bt=False)",
            "G01 F150.000 X57.687 Y0.000 Z0.800",
            "  (SweepAndDrillSafelyFromTo [57.687 0.000 0.800] [57.687 0.000 -0.300] s=5.000 bt=False)",
            "    (DrillOrPullZFromTo 0.800 -0.300)",
            "G01 Z-0.300",
            "  (MillLine s=[57.687 0.000] e=[0.000 0.000] fr=-0.300 to=-0.300 bt=False)",
            "G01 F150.000 X0.000 Y0.000 Z-0.300",
            "  (SweepAndDrillSafelyFromTo [0.000 0.000 -0.300] [57.687 0.000 5.000] s=5.000 bt=False)",
            "    (DrillOrPullZFromTo -0.300 5.000)",
            "G00 Z5.000",
            "G00 X57.687 Y0.000",
            "G00 Z5.000",
        ]
    );
    // §14 worked check, English labels
    assert!(
        g.contains("  (Milling length:   115 mm   ca.  2 min)"),
        "{g}"
    );
    assert!(g.contains("  (Drill length:     4 mm   ca.  1 min)"));
    assert!(g.contains("  (Sweeps:         66 mm   ca.  1 min)"));
    assert!(g.contains("  (Sum:           185 mm   ca.  2 min)"));
    assert!(g.contains("  (Command count: 8)"));
    assert!(g.ends_with("M30\n%\n"));
}

#[test]
fn german_labels() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1,2 B-0,3")
        .end(L, (50.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (50.0, 0.0), "");
    let run = compile_with(
        &[("1000.1P.dxf", d.dxf())],
        "1000.1P.dxf",
        millpath_core::Settings {
            lang: Lang::De,
            ..settings()
        },
    );
    let g = run.output("_Milling.gcode");
    for label in [
        "(Fräslänge:",
        "(Bohrungen:",
        "(Leerfahrten:",
        "(Summe:",
        "(Befehlszahl:",
    ] {
        assert!(g.contains(label), "{label}");
    }
}

#[test]
fn sweeps_chain_end_is_optimised_away() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 I0,6 B-0,1 S20")
        .end(L, (80.0, 10.0))
        .line(L, "DASHED", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "CONTINUOUS", (10.0, 0.0), (60.0, 0.0), "")
        .line(L, "DASHED", (60.0, 0.0), (80.0, 10.0), "");
    let run = compile_one(&d);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let body = run.body();
    // path S20 beats /s15; the first sweep starts with a pull to S (start offset)
    assert_eq!(body[1], "    (DrillOrPullZFromTo 20.000 20.000)");
    assert!(
        body.contains(&"; G00 X60.000 Y0.000".to_string()),
        "{body:?}"
    );
    assert!(body.contains(&"G00 X80.000 Y10.000".to_string()));
    // passes 0.4 and -0.1 (T1, I0.6)
    assert!(body.contains(&"G01 Z0.400".to_string()) && body.contains(&"G01 Z-0.100".to_string()));
}

#[test]
fn arcs_use_i_j_and_direction() {
    let mut d = Drawing::new();
    // a quarter arc drawn ccw from (10,0) to (0,10) around the origin, traversed from (0,10)
    d.start(L, (0.0, 10.0), "O2 T1 I2 B0")
        .end(L, (10.0, 0.0))
        .arc(L, "CONTINUOUS", (0.0, 0.0), 10.0, 0.0, 90.0, "");
    let run = compile_one(&d);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let moves = run.moves();
    // traversed backwards: clockwise G02, centre relative to the start; the start's x is
    // 10·cos 90° ≈ 6e-16, so I prints as -0.000 exactly like the reference
    assert!(
        moves
            .iter()
            .any(|m| m == "G02 F150.000 I-0.000 J-10.000 X10.000 Y-10.000 Z0.000"),
        "{moves:?}"
    );
    let body = run.body().join("\n");
    assert!(body.contains("(MillArc l=[0.000 -10.000] r=10.000 a0=90.000 a1=0.000 fr=0.000 to=0.000 p0=[0.000 0.000] p1=[10.000 -10.000] bt=False)"), "{body}");
}

#[test]
fn traversal_prefers_numbered_segments() {
    // star at (10,0): the numbered long branch N1 (out) / N2 (back) comes before the
    // unnumbered short sweep to the end. The two texts sit off the middle of the two
    // coincident lines, each nearest to its own (by the reference's line metric): in the
    // middle both would be equally near both, and the file order would decide (MP132).
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 I2 B0")
        .end(L, (10.0, 5.0))
        .line(L, "DASHED", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "DASHED", (10.0, 0.0), (10.0, 5.0), "")
        .line(L, "CONTINUOUS", (10.0, 0.0), (40.0, 0.0), "")
        .line(L, "DASHED", (40.0, 0.0), (10.0, 0.0), "");
    d.w.text(L, (20.0, 0.0), 0.5, "N1")
        .text(L, (30.0, 0.0), 0.5, "N2");
    let run = compile_one(&d);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let body = run.body().join("\n");
    let mill = body
        .find("MillLine s=[10.000 0.000] e=[40.000 0.000]")
        .expect("numbered branch");
    let back = body
        .find("[40.000 0.000 15.000] [10.000 0.000 15.000]")
        .expect("return sweep");
    let last = body.find("G00 X10.000 Y5.000").expect("sweep to the end");
    assert!(mill < back && back < last, "{body}");
    // without N the shorter unnumbered sweep wins and the branch is never reached
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 I2 B0")
        .end(L, (10.0, 5.0))
        .line(L, "DASHED", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "DASHED", (10.0, 0.0), (10.0, 5.0), "")
        .line(L, "DASHED", (10.0, 0.0), (40.0, 0.0), "")
        .line(L, "DASHED", (40.0, 0.0), (10.0, 0.0), "");
    assert_eq!(compile_one(&d).errors(), [Msg::NotReached]);
}

#[test]
fn drills_and_helixes() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1,2 B-0,1")
        .end(L, (30.0, 0.0))
        .line(L, "DASHED", (0.0, 0.0), (10.0, 0.0), "")
        .circle(L, "CONTINUOUS", (10.0, 0.0), 1.0, "")
        .circle(L, "CONTINUOUS", (10.0, 0.0), 3.0, "")
        .line(L, "DASHED", (10.0, 0.0), (30.0, 0.0), "");
    let run = compile_one(&d);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let body = run.body();
    let drill = body
        .iter()
        .position(|l| l == "  (Drill l=[10.000 0.000])")
        .expect("drill first");
    let helix = body
        .iter()
        .position(|l| l == "  (MillHelix l=[10.000 0.000] r=3.000)")
        .expect("helix");
    assert!(drill < helix);
    assert_eq!(
        body[drill + 1..drill + 4],
        [
            "    (DrillOrPullZFromTo 15.000 -0.100)",
            "G00 Z2.000",
            "G01 Z-0.100"
        ]
    );
    // helix: approach T+O, semicircles 1.4/0.8, 0.2/-0.1, -0.1/-0.1 (T2, I1.2, B-0.1, r'=2)
    let semis: Vec<&String> = body.iter().filter(|l| l.starts_with("G02")).collect();
    assert_eq!(semis.len(), 6);
    assert_eq!(semis[0], "G02 F150.000 I0 J2.000 X10.000 Y2.000 Z1.400");
    assert_eq!(semis[1], "G02 F150.000 I0 J-2.000 X10.000 Y-2.000 Z0.800");
    assert_eq!(semis[5], "G02 F150.000 I0 J-2.000 X10.000 Y-2.000 Z-0.100");
    let labels: Vec<&String> = body
        .iter()
        .filter(|l| l.contains("MillSemiCircle"))
        .collect();
    assert_eq!(
        labels,
        [
            "    (MillSemiCircle l=2.000)",
            "    (MillSemiCircle l=0.800)",
            "    (MillSemiCircle l=-0.400)"
        ]
    );
    // R=3 > O=2: pull up to S, then back to the centre
    assert!(body.contains(&"G00 Z15.000".to_string()));
}

#[test]
fn helix_larger_than_a_and_circle_smaller_than_o() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1 B0 A5")
        .end(L, (20.0, 0.0))
        .circle(L, "CONTINUOUS", (0.0, 0.0), 3.0, "")
        .circle(L, "CONTINUOUS", (0.0, 0.0), 0.5, "")
        .line(L, "DASHED", (0.0, 0.0), (20.0, 0.0), "");
    let run = compile_one(&d);
    assert!(run.errors().contains(&Msg::HelixTooLarge));
    assert!(run.errors().contains(&Msg::DiameterSmallerThanO));
    assert!(run.outputs.is_empty());
}

#[test]
fn support_bars_on_a_border_line() {
    // 100 mm, P6 U30 → n = floor(100/36) = 2 → 3 bars
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T3 I2 B-0,5 D1 P6 U30")
        .end(L, (100.0, 0.0))
        .line(L, "BORDER", (0.0, 0.0), (100.0, 0.0), "");
    let run = compile_one(&d);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let g = run.output("_Milling.gcode");
    // passes: 1 (plain, at D), -0.5 (profile) → one profile with 3 bars
    assert_eq!(g.matches("Support.Bar").count(), 3, "{g}");
    assert_eq!(g.matches("Support.Between").count(), 2);
    // the profile starts with the rapid back up to bar height
    let body = run.body();
    let bar = body.iter().position(|l| l == "  (Support.Bar)").unwrap();
    assert_eq!(
        body[bar + 1..bar + 3],
        ["    (DrillOrPullZFromTo -0.500 1.000)", "G00 Z1.000"]
    );
}

#[test]
fn missing_bar_values_abort_the_file() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T3 I2 B-0,5 D1 P6")
        .end(L, (100.0, 0.0))
        .line(L, "BORDER", (0.0, 0.0), (100.0, 0.0), "");
    let run = compile_one(&d);
    assert_eq!(run.messages(), ["U value missing"]);
    assert!(run.outputs.is_empty());
}

#[test]
fn sweepless_milling_runs_and_back_milling() {
    // open chain of two lines, W1 I0,5 B0 T2: runs at 1, 0.5, 0 with back-milling between
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I0,5 B0 W1")
        .end(L, (20.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "CONTINUOUS", (10.0, 0.0), (20.0, 0.0), "");
    let run = compile_one(&d);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let moves = run.moves();
    let mills: Vec<&String> = moves.iter().filter(|m| m.starts_with("G01 F")).collect();
    // 3 runs × 2 segments + 2 back-millings × 2 segments
    assert_eq!(mills.len(), 10, "{moves:?}");
    assert_eq!(mills[0], "G01 F150.000 X10.000 Y0.000 Z1.000");
    assert_eq!(mills[2], "G01 F150.000 X10.000 Y0.000 Z1.000");
    assert_eq!(mills[3], "G01 F150.000 X0.000 Y0.000 Z1.000");
    assert_eq!(mills[9], "G01 F150.000 X20.000 Y0.000 Z0.000");
    // no SweepAndDrill comments: sweepless milling only moves in Z between passes
    assert_eq!(
        run.body()
            .iter()
            .filter(|l| l.contains("SweepAndDrillSafelyFromTo"))
            .count(),
        0
    );
}

fn part_file() -> String {
    // 2000.1P: a 20 mm line from (100,100) to (100,120), O2 T2 M20x2
    let mut d = Drawing::new();
    let l = "2000_1P";
    d.start(l, (100.0, 100.0), "O2 T2 M20x2 I2 B0 :B0~1")
        .end(l, (100.0, 120.0))
        .line(l, "CONTINUOUS", (100.0, 100.0), (100.0, 120.0), "B=B");
    d.dxf()
}

fn project(embed_text: &str, len: f64) -> String {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 M20x2 I2 B0")
        .end(L, (len + 10.0, 0.0))
        .line(L, "DASHED", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "DASHDOT", (10.0, 0.0), (10.0 + len, 0.0), embed_text);
    d.dxf()
}

#[test]
fn subpath_is_placed_rotated_with_variables_and_h() {
    let files = [
        ("1000.1P.dxf", project(">2000.1P :B0,5 H1", 20.0)),
        ("2000.dxf", part_file()),
    ];
    let run = compile(&files, "1000.1P.dxf");
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let body = run.body().join("\n");
    assert!(body.contains("(START Subpath 2000.1P[2000.dxf] t=[ [100.000 100.000]=>[10.000 0.000] / [100.000 120.000]=>[30.000 0.000] ])"), "{body}");
    // B = 0.5 from the variable, raised by H1: bottom 1.5; T raised to 3
    assert!(body.contains("G01 Z1.500"), "{body}");
    assert!(body.contains("G00 Z3.000"));
    // subpath sweep height = H + T + O = 5
    assert!(body.contains("s=5.000"));
}

#[test]
fn subpath_errors() {
    // wrong size
    let run = compile(
        &[
            ("1000.1P.dxf", project(">2000.1P :B0,5", 25.0)),
            ("2000.dxf", part_file()),
        ],
        "1000.1P.dxf",
    );
    assert!(
        run.errors().contains(&Msg::SizeMismatch),
        "{:?}",
        run.messages()
    );
    // not found
    let run = compile(
        &[
            ("1000.1P.dxf", project(">2000.7P", 20.0)),
            ("2000.dxf", part_file()),
        ],
        "1000.1P.dxf",
    );
    assert_eq!(
        run.messages(),
        ["Could not find path 2000.7P in file(s) 2000.dxf"]
    );
    // value outside the definition, material mismatch
    let run = compile(
        &[
            ("1000.1P.dxf", project(">2000.1P :B5 M30x2", 20.0)),
            ("2000.dxf", part_file()),
        ],
        "1000.1P.dxf",
    );
    assert!(
        run.errors().contains(&Msg::ValueNotInDefinition),
        "{:?}",
        run.messages()
    );
    assert!(run.errors().contains(&Msg::MMismatch));
    // missing value, extra assignment
    let run = compile(
        &[
            ("1000.1P.dxf", project(">2000.1P :Q1", 20.0)),
            ("2000.dxf", part_file()),
        ],
        "1000.1P.dxf",
    );
    assert!(
        run.errors().contains(&Msg::MissingValues)
            && run.errors().contains(&Msg::MissingDefinitions)
    );
    // invalid target name aborts
    let run = compile(
        &[
            ("1000.1P.dxf", project(">xyz", 20.0)),
            ("2000.dxf", part_file()),
        ],
        "1000.1P.dxf",
    );
    assert!(run.errors().contains(&Msg::InvalidPathName));
    // restriction by E
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 M20x2 I2 B0 E[Q]$")
        .end(L, (30.0, 0.0))
        .line(L, "DASHED", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "DASHDOT", (10.0, 0.0), (30.0, 0.0), ">2000.1P :B0,5");
    let run = compile(
        &[("1000.1P.dxf", d.dxf()), ("2000.dxf", part_file())],
        "1000.1P.dxf",
    );
    assert_eq!(run.errors(), [Msg::Forbidden]);
}

#[test]
fn endless_recursion_stops_at_nesting_depth() {
    let mut d = Drawing::new();
    for (me, other) in [("3000_1P", "3000.2P"), ("3000_2P", "3000.1P")] {
        d.start(me, (0.0, 0.0), "O2 T2 M1 I2 B0")
            .end(me, (20.0, 0.0))
            .line(me, "DASHDOT", (0.0, 0.0), (20.0, 0.0), &format!(">{other}"));
    }
    let run = compile_with(
        &[("3000.dxf", d.dxf())],
        "3000.dxf",
        millpath_core::Settings {
            check: true,
            ..settings()
        },
    );
    assert!(
        run.errors().contains(&Msg::NestingTooDeep),
        "{:?}",
        run.messages()
    );
}

#[test]
fn z_probes_produce_probing_z_and_clean_files() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1,2 B-0,3 S5")
        .end(L, (40.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (40.0, 0.0), "")
        .circle(L, "PHANTOM", (10.0, 10.0), 3.0, "")
        .circle(L, "DASHDOT", (30.0, 10.0), 3.0, "Lleft H1")
        .circle(L, "DOT", (50.0, 10.0), 3.0, "");
    let run = compile_with(
        &[("1000.1P.dxf", d.dxf())],
        "1000.1P.dxf",
        millpath_core::Settings {
            probe_feed: Some(50.0),
            ..settings()
        },
    );
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    assert_eq!(run.outputs.len(), 3);
    assert!(run
        .outputs
        .iter()
        .all(|o| !o.path.to_string_lossy().ends_with("_Milling.gcode")));
    let z = run.output("_Z.txt");
    assert_eq!(
        z,
        "([10.000 10.000]/T=2.000) #51=\n([30.000 10.000]/L:left/T=3.000) #52=\n"
    );
    let probing = run.output("_Probing.gcode");
    assert!(probing.contains("G00 X10.000 Y10.000\nG00 Z4.000\nG38.3 Z0 F50.000\nG04 P4\nG00 Z5.000\nG00 X30.000 Y10.000\nG00 Z5.000\nG38.3"), "{probing}");
    let clean = run.output("_Clean.gcode");
    assert!(clean.contains("G01 Z0.800(=0.800+"), "{clean}");
    // adjust-z closes the loop
    let mut diags = millpath_core::Diags::default();
    let milling = millpath_core::probe::adjustz::adjust(
        clean,
        "c",
        &z.replace("#51=", "#51=2.1").replace("#52=", "#52=3.0"),
        "z",
        0.5,
        millpath_core::probe::adjustz::MaxOption::Long,
        &mut diags,
    )
    .unwrap();
    assert!(!diags.has_errors());
    assert!(milling.matches("(==").count() > 0);
    assert_eq!(
        milling.matches("(=").count(),
        milling.matches("(==").count(),
        "{milling}"
    );
}

#[test]
fn turn_markers_return_to_the_branch_point() {
    // start → (10,0); a dead-end branch up to (10,10) with a turn marker; then on to (30,0)
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 I2 B0")
        .end(L, (30.0, 0.0))
        .line(L, "DASHED", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "CONTINUOUS", (10.0, 0.0), (10.0, 10.0), "N1")
        .line(L, "DASHED", (10.0, 0.0), (30.0, 0.0), "N2");
    d.w.circle(L, Some("PHANTOM"), (10.0, 10.0), 0.75);
    let run = compile_one(&d);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let body = run.body().join("\n");
    // the branch is milled out and milled back in reverse
    assert!(
        body.contains("MillLine s=[10.000 0.000] e=[10.000 10.000]"),
        "{body}"
    );
    assert!(
        body.contains("MillLine s=[10.000 10.000] e=[10.000 0.000]"),
        "{body}"
    );
    assert!(body.contains("G00 X30.000 Y0.000"));
    // without the marker the same drawing is a dead end
    let mut d2 = Drawing::new();
    d2.start(L, (0.0, 0.0), "O2 T1 I2 B0")
        .end(L, (30.0, 0.0))
        .line(L, "DASHED", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "CONTINUOUS", (10.0, 0.0), (10.0, 10.0), "N1")
        .line(L, "DASHED", (10.0, 0.0), (30.0, 0.0), "N2");
    let run = compile_one(&d2);
    assert!(run.errors().contains(&Msg::NoMoreSegments));
    assert!(run.errors().contains(&Msg::EndNotAtLast));
    assert_eq!(
        run.messages()[0],
        "No more segments found after location [10.000 10.000]"
    );
}

#[test]
fn graph_errors() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 I2 B0")
        .end(L, (10.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "CONTINUOUS", (50.0, 50.0), (60.0, 50.0), "");
    let run = compile_one(&d);
    assert_eq!(run.errors(), [Msg::NotReached]);
    assert!(run.outputs.is_empty());

    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 I2 B0")
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "");
    // no "no error-free path" after an error that says why (pathdxf2gcode prints it: the
    // reference's rule, `reference_check`)
    assert_eq!(compile_one(&d).errors(), [Msg::EndMissing]);

    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 I2 B0")
        .start(L, (1.0, 0.0), "")
        .end(L, (10.0, 0.0))
        .line(L, "CENTER", (0.0, 0.0), (10.0, 0.0), "");
    let run = compile_one(&d);
    assert!(run.errors().contains(&Msg::TwoStartMarkers));
    let two = run
        .diags
        .iter()
        .find(|d| d.msg == Msg::TwoStartMarkers)
        .unwrap();
    assert_eq!(two.related.len(), 1, "points at the first marker too");
    assert_eq!(
        two.related[0].origin.context(),
        "CIRCLE @ [0.000 0.000] # 1000.1P[1000.1P.dxf]"
    );
    assert!(run.errors().contains(&Msg::LineTypeNotSupported));

    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 I2 B0")
        .end(L, (10.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "");
    d.w.text(L, (200.0, 200.0), 0.5, "B1");
    d.w.circle(L, Some("PHANTOM"), (40.0, 40.0), 2.0);
    let run = compile_one(&d);
    assert!(run.errors().contains(&Msg::NoOverlap));
    assert!(run.errors().contains(&Msg::NoSpecialMeaning));
}

#[test]
fn parameter_errors_and_warnings() {
    // duplicate key aborts the file: no path at all
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 I2 B0 B1")
        .end(L, (10.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "");
    let run = compile_one(&d);
    assert_eq!(run.errors(), [Msg::DuplicateParameter]);

    // range checks of the path
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O-3 T-2 I-1 B3 D2 S-3")
        .end(L, (10.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "");
    let errs = compile_one(&d).messages();
    for m in [
        "O=-3 must be > 0",
        "T=-2 must be > 0",
        "I=-1 must be > 0",
        "S=-3 must be above T=-2",
        "B=3 must not be larger than T=-2",
        "D=2 must be larger than B=3",
        "A=-12 must be > 0",
    ] {
        assert!(errs.iter().any(|e| e == m), "{m} in {errs:?}");
    }

    // missing T and O are reported in the chosen language (not hard-coded German)
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "I2 B0").end(L, (10.0, 0.0)).line(
        L,
        "CONTINUOUS",
        (0.0, 0.0),
        (10.0, 0.0),
        "",
    );
    let run = compile_one(&d);
    assert!(
        run.messages().contains(&"T value missing".to_string())
            && run.messages().contains(&"O value missing".to_string())
    );
    assert!(run
        .diags
        .iter()
        .any(|d| d.message(Lang::De) == "T-Wert fehlt"));

    // deliberate difference: a value that is no number is reported, unsupported keys too
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 I2 B0 F1O0")
        .end(L, (10.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "G1");
    let run = compile_one(&d);
    assert_eq!(run.warnings(), [Msg::NotANumber]);
    assert_eq!(run.errors(), [Msg::Unsupported]);
    assert_eq!(
        run.diags
            .iter()
            .find(|d| d.msg == Msg::NotANumber)
            .unwrap()
            .message(Lang::De),
        "F-Wert '1O0' ist keine Zahl und wird ignoriert"
    );

    // B missing at generation
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 I2").end(L, (10.0, 0.0)).line(
        L,
        "CONTINUOUS",
        (0.0, 0.0),
        (10.0, 0.0),
        "",
    );
    assert_eq!(compile_one(&d).messages(), ["B value missing"]);
}

#[test]
fn self_referencing_variable_is_an_error_not_a_hang() {
    let mut part = Drawing::new();
    let l = "2000_1P";
    part.start(l, (100.0, 100.0), "O2 T2 M20x2 I2 B=A :A?x")
        .end(l, (100.0, 120.0))
        .line(l, "CONTINUOUS", (100.0, 100.0), (100.0, 120.0), "");
    let run = compile(
        &[
            ("1000.1P.dxf", project(">2000.1P :A=A1", 20.0)),
            ("2000.dxf", part.dxf()),
        ],
        "1000.1P.dxf",
    );
    assert!(
        run.errors().contains(&Msg::SelfReference)
            || run.errors().contains(&Msg::ValueNotInDefinition),
        "{:?}",
        run.messages()
    );
}

#[test]
fn at_reference_uses_the_other_start_text() {
    let mut d = Drawing::new();
    d.start("1000_1P", (0.0, 0.0), "O2 T1 I2 B0")
        .end("1000_1P", (10.0, 0.0))
        .line("1000_1P", "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "");
    d.start("1000_2P", (0.0, 50.0), "@1000.1P")
        .end("1000_2P", (10.0, 50.0))
        .line("1000_2P", "CONTINUOUS", (0.0, 50.0), (10.0, 50.0), "");
    d.start("1000_3P", (0.0, 90.0), "@1000.9P")
        .end("1000_3P", (10.0, 90.0));
    let run = compile_with(
        &[("1000.dxf", d.dxf())],
        "1000.dxf",
        millpath_core::Settings {
            check: true,
            reference_check: true,
            ..settings()
        },
    );
    assert_eq!(
        run.errors(),
        [
            Msg::AtNotFound,
            Msg::ValueMissing,
            Msg::ValueMissing,
            Msg::Unsupported,
            Msg::NoSegments
        ]
    );
}

#[test]
fn more_than_one_path_without_check_mode() {
    let mut d = Drawing::new();
    for (l, y) in [("1000_1P", 0.0), ("1000_2P", 50.0)] {
        d.start(l, (0.0, y), "O2 T1 I2 B0").end(l, (10.0, y)).line(
            l,
            "CONTINUOUS",
            (0.0, y),
            (10.0, y),
            "",
        );
    }
    let run = compile(&[("1000.dxf", d.dxf())], "1000.dxf");
    assert_eq!(
        run.messages(),
        ["DXF file 1000.dxf contains more than one path layer: 1000.1P, 1000.2P"]
    );
}

#[test]
fn unreadable_input_is_an_error() {
    let run = compile(&[("other.dxf", "garbage".into())], "missing.dxf");
    assert_eq!(run.errors()[0], Msg::CannotRead);
    let run = compile(
        &[(
            "bad.dxf",
            "  0\nSECTION\n  2\nENTITIES\n  0\nLINE\n 10\nx\n  0\nENDSEC\n".into(),
        )],
        "bad.dxf",
    );
    assert_eq!(run.errors()[0], Msg::CannotLoadDxf);
    assert!(run.messages()[0].contains("line 8"), "{:?}", run.messages());
}

#[test]
fn mutated_drawings_never_panic() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1,2 B-0,1 P6 U30 D1")
        .end(L, (30.0, 0.0))
        .line(L, "DASHED", (0.0, 0.0), (10.0, 0.0), "N1")
        .circle(L, "BORDER", (10.0, 0.0), 5.0, "")
        .arc(L, "CONTINUOUS", (20.0, 0.0), 10.0, 0.0, 180.0, "")
        .line(L, "BORDER", (30.0, 0.0), (10.0, 0.0), "")
        .circle(L, "PHANTOM", (5.0, 5.0), 3.0, "");
    let base = d.dxf().into_bytes();
    let mut seed: u64 = 0x9E3779B97F4A7C15;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    for _ in 0..400 {
        let mut bytes = base.clone();
        for _ in 0..(1 + next() % 6) {
            let i = (next() as usize) % bytes.len();
            match next() % 4 {
                0 => bytes[i] = b"0123456789-.\n ~:=>"[(next() % 18) as usize],
                1 => {
                    bytes.remove(i);
                }
                2 => bytes.truncate(i),
                _ => bytes.insert(i, (next() % 256) as u8),
            }
        }
        let text = String::from_utf8_lossy(&bytes).into_owned();
        for check in [false, true] {
            let _ = compile_with(
                &[("1000.1P.dxf", text.clone())],
                "1000.1P.dxf",
                millpath_core::Settings {
                    check,
                    ..settings()
                },
            );
        }
    }
}

#[test]
fn duplicate_paths_in_other_files_are_reported_and_the_first_kept() {
    let mut other = Drawing::new();
    let l = "2000_1P";
    other
        .start(l, (0.0, 0.0), "O2 T2 M20x2 I2 B0 :B0~1")
        .end(l, (0.0, 20.0))
        .line(l, "CONTINUOUS", (0.0, 0.0), (0.0, 20.0), "");
    let files = [
        ("1000.1P.dxf", project(">2000.1P :B0,5", 20.0)),
        ("2000.dxf", part_file()),
        ("2000.1.dxf", other.dxf()),
    ];
    let run = compile(&files, "1000.1P.dxf");
    assert_eq!(run.errors(), [Msg::AlreadyDefined], "{:?}", run.messages());
    assert!(
        run.messages()[0].starts_with("Path 2000.1P has already been defined in 2000.1.dxf")
            || run.messages()[0].starts_with("Path 2000.1P has already been defined in 2000.dxf")
    );
}

#[test]
fn search_directories_and_restrictions_from_settings() {
    let files = [
        ("proj/1000.1P.dxf", project(">2000.1P :B0,5", 20.0)),
        ("lib/2000.dxf", part_file()),
    ];
    // not in the drawing's folder: not found until the library folder is searched
    let run = compile(&files, "proj/1000.1P.dxf");
    assert_eq!(run.errors(), [Msg::CouldNotFind]);
    let with_dir = millpath_core::Settings {
        search_dirs: vec!["lib".into()],
        ..settings()
    };
    let run = compile_with(&files, "proj/1000.1P.dxf", with_dir.clone());
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    assert_eq!(
        run.outputs[0].path,
        std::path::PathBuf::from("proj/1000.1P_Milling.gcode")
    );
    // /e 1000:Q$ forbids 2000.1P
    let restricted = millpath_core::Settings {
        restrictions: vec![("1000".into(), "Q$".into())],
        ..with_dir.clone()
    };
    assert_eq!(
        compile_with(&files, "proj/1000.1P.dxf", restricted).errors(),
        [Msg::Forbidden]
    );
    // a search directory that does not exist aborts the file with a clear message
    let missing = millpath_core::Settings {
        search_dirs: vec!["nowhere".into()],
        ..settings()
    };
    assert!(compile_with(&files, "proj/1000.1P.dxf", missing)
        .errors()
        .contains(&Msg::SearchDirMissing));
}

#[test]
fn thicker_subpath_than_its_project_is_reported() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T1 M20x2 I2 B0")
        .end(L, (30.0, 0.0))
        .line(L, "DASHED", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "DASHDOT", (10.0, 0.0), (30.0, 0.0), ">2000.1P :B0,5 T2");
    let run = compile(
        &[("1000.1P.dxf", d.dxf()), ("2000.dxf", part_file())],
        "1000.1P.dxf",
    );
    assert!(
        run.messages()
            .contains(&"T=1 at path is less than T=2 at subpath 2000.1P".to_string()),
        "{:?}",
        run.messages()
    );
}

#[test]
fn check_mode_uses_check_values_and_default_s() {
    // the library path alone: B=B only has a value with check values (B = 0 from 0~1)
    let run = compile_with(
        &[("2000.dxf", part_file())],
        "2000.dxf",
        millpath_core::Settings {
            check: true,
            ..settings()
        },
    );
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    // without check mode the same path has no B on its line: B=B stays literal
    let run = compile(&[("2000.dxf", part_file())], "2000.dxf");
    assert!(
        run.warnings().contains(&Msg::NotANumber),
        "{:?}",
        run.messages()
    );
}

#[test]
fn debug_output_lists_assignments() {
    let mut fs = millpath_core::MemFileSystem::default();
    fs.add("2000.dxf", part_file().into_bytes());
    let settings = millpath_core::Settings {
        debug_pattern: Some("B".into()),
        ..settings()
    };
    let mut session = millpath_core::Session::new(settings, &fs).unwrap();
    session.load_file(std::path::Path::new("2000.dxf"));
    let info = session.info.join("\n");
    assert!(
        info.contains("Object\n   LINE LAYER=2000_1P CODENAME=LINE"),
        "{info}"
    );
    assert!(
        info.contains("has assigned text ''B=B' @ [100.000 110.000]"),
        "{info}"
    );
}

#[test]
fn mutated_text_files_never_panic() {
    let base = "path 1000.1P {\n  start (0, 0)  O2 T2 I1,2 B-0,1 P6 U30 D1 :Bx,y\n  end (30, 0)\n  sweep (0, 0) -> (10, 0)  N1\n  bars helix (10, 0) d10\n  mill arc (20, 0) r10 from 0 to 180\n  bars (30, 0) -> (10, 0)  B=B\n  probe (5, 5)\n  turn (3, 3)\n  sub (10, 0) -> (30, 0)  >1000.1P\n}\n";
    let mut seed: u64 = 0xD1B54A32D192ED03;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    for _ in 0..300 {
        let mut chars: Vec<char> = base.chars().collect();
        for _ in 0..(1 + next() % 5) {
            if chars.is_empty() {
                break;
            }
            let i = (next() as usize) % chars.len();
            match next() % 3 {
                0 => {
                    chars.remove(i);
                }
                1 => chars.insert(
                    i,
                    "0123456789-.,() \n{}#\">=:~"
                        .chars()
                        .nth((next() % 25) as usize)
                        .unwrap(),
                ),
                _ => chars.truncate(i.max(1)),
            }
        }
        let text: String = chars.into_iter().collect();
        for check in [false, true] {
            let _ = compile_with(
                &[("1000.1P.mpath", text.clone())],
                "1000.1P.mpath",
                millpath_core::Settings {
                    check,
                    ..settings()
                },
            );
        }
    }
}

#[test]
fn text_files_compile_and_declared_circle_kinds_are_checked() {
    let text = "path 1000.1P {\n  start (0, 0)  O2 T2 I1,2 B-0,1\n  end (30, 0)\n  sweep (0, 0) -> (10, 0)\n  drill (10, 0) d4  # says drill, is a helix with O2\n  sweep (10, 0) -> (30, 0)\n}\n";
    let run = compile(&[("1000.1P.mpath", text.into())], "1000.1P.mpath");
    assert_eq!(run.errors(), []);
    assert_eq!(run.warnings(), [Msg::KindMismatch]);
    assert_eq!(
        run.diags[0].message(Lang::En),
        "Declared as drill, but with O=2 this circle is a helix"
    );
    assert_eq!(run.diags[0].origin.context(), "1000.1P.mpath:5:3");
    assert!(run
        .output("1000.1P_Milling.gcode")
        .contains("MillHelix l=[10.000 0.000] r=2.000"));
}

#[test]
fn toolpath_moves_follow_the_gcode() {
    let mut d = Drawing::new();
    d.start(L, (10.0, 20.0), "O2 T2 I1,2 B-0,3")
        .end(L, (67.687, 20.0))
        .line(L, "CONTINUOUS", (10.0, 20.0), (67.687, 20.0), "")
        .circle(L, "PHANTOM", (20.0, 30.0), 3.0, "");
    let mut fs = millpath_core::MemFileSystem::default();
    fs.add("1000.1P.dxf", d.dxf().into_bytes());
    let mut s = millpath_core::Session::new(
        millpath_core::Settings {
            sweep_height: 5.0,
            ..settings()
        },
        &fs,
    )
    .unwrap();
    s.load_file(std::path::Path::new("1000.1P.dxf"));
    let model = s.build_top("1000.1P").unwrap().unwrap();
    let tp =
        millpath_core::emit::toolpath(&model, &millpath_core::emit::Controller::reference(), 500.0)
            .unwrap();
    let kinds: Vec<&str> = tp.moves.iter().map(|m| m.kind).collect();
    // the plunges of a chain cut as its segment does: they are `mill`, not `drill`
    assert_eq!(
        kinds,
        ["rapid", "mill", "mill", "mill", "mill", "rapid", "rapid", "rapid"]
    );
    let first_mill = &tp.moves[2];
    assert_eq!((first_mill.from.x, first_mill.from.z), (0.0, 0.8));
    assert!((first_mill.to.x - 57.687).abs() < 1e-9 && first_mill.to.z == 0.8);
    match &first_mill.source {
        Some(Origin::Entity(e)) => assert_eq!(e.code_name, "LINE"),
        o => panic!("{o:?}"),
    }
    assert_eq!(tp.probes.len(), 1);
    assert_eq!(tp.probes[0].name, "#51");
    assert!((tp.probes[0].pos.x - 10.0).abs() < 1e-9);
    // every move names its line of the written (clean) program, and the times add up to
    // the statistics' (reference model: length / F · 1.4)
    let run = compile_with(
        &[("1000.1P.dxf", d.dxf())],
        "1000.1P.dxf",
        millpath_core::Settings {
            sweep_height: 5.0,
            ..settings()
        },
    );
    let clean = run.output("1000.1P_Clean.gcode");
    let lines: Vec<&str> = clean.lines().collect();
    assert!(lines[first_mill.line - 1].starts_with("G01 F150.000 X57.687 Y0.000 Z0.800"));
    let total: f64 = tp.moves.iter().map(|m| m.seconds).sum();
    let stats = &tp.stats;
    let minutes = stats.mill_min + stats.drill_min + stats.sweep_min;
    assert!((total / 60.0 - minutes).abs() < 1e-9, "{total} {minutes}");
}

#[test]
fn hand_written_arcs_compile_like_the_exact_form() {
    let sugar = "path 1000.1P {\n  start (10, 0)  O2 T1 I2 B0\n  end (0, 10)\n  mill (10, 0) -> (0, 10) ccw around (0, 0)\n}\n";
    let exact = "path 1000.1P {\n  start (10, 0)  O2 T1 I2 B0\n  end (0, 10)\n  mill arc (0, 0) r10 from 0 to 90\n}\n";
    let a = compile(&[("1000.1P.mpath", sugar.into())], "1000.1P.mpath");
    let b = compile(&[("1000.1P.mpath", exact.into())], "1000.1P.mpath");
    assert!(a.diags.is_empty(), "{:?}", a.messages());
    assert_eq!(a.output("_Milling.gcode"), b.output("_Milling.gcode"));
    assert!(a
        .output("_Milling.gcode")
        .contains("G03 F150.000 I-10.000 J0.000 X-10.000 Y10.000"));
}
