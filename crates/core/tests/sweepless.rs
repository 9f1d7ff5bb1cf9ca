//! Sweepless milling (W, reference-output.md §7.3) on drawings of our own: one and several
//! runs, start = end (closed) and start ≠ end (open, back-milling). The expected files are
//! written by hand from the spec, move by move and figure by figure (comments beside them).

mod support;

use support::*;

/// The fixed prologue (§4.1) for S = 15: Sx = 15·(1 + 2e-6) prints as 15.000.
const PROLOGUE: &str = "%
(millpath test)
(1000.1P.dxf)
F150
G17 G21 G40 G49 G54 G80 G90 G94
T1
(SweepSafelyTo [0.000 0.000 15.000])
G00 Z15.000
G00 X0.000 Y0.000
  (Model 1000.1P[1000.1P.dxf])
";

fn milling(d: &Drawing) -> String {
    let run = compile_one(d);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    run.output("_Milling.gcode").to_string()
}

#[test]
fn open_chain_several_runs_mills_back_and_retraces_a_shallower_segment() {
    // passes: first line 1.5, 1.0; second line (own B1,5) 1.5 only → retraced at 1.5 in run 1
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I0,5 B1 W1,5")
        .end(L, (20.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "CONTINUOUS", (10.0, 0.0), (20.0, 0.0), "B1,5");
    let expected = PROLOGUE.to_string()
        // run 0 at 1.5: from Sx rapid to T = 2 (13.00003 sweep), feed to 1.5 (0.5 drill)
        + "    (DrillOrPullZFromTo 15.000 1.500)
G00 Z2.000
G01 Z1.500
  (MillLine s=[0.000 0.000] e=[10.000 0.000] fr=1.500 to=1.500 bt=False)
G01 F150.000 X10.000 Y0.000 Z1.500
  (MillLine s=[10.000 0.000] e=[20.000 0.000] fr=1.500 to=1.500 bt=False)
G01 F150.000 X20.000 Y0.000 Z1.500
"
        // back-milling of run 0, reversed, same depth
        + "  (MillLine s=[20.000 0.000] e=[10.000 0.000] fr=1.500 to=1.500 bt=False)
G01 F150.000 X10.000 Y0.000 Z1.500
  (MillLine s=[10.000 0.000] e=[0.000 0.000] fr=1.500 to=1.500 bt=False)
G01 F150.000 X0.000 Y0.000 Z1.500
"
        // run 1: 1.0 (drill 2 − 1 = 1.0), then the second line's last pass 1.5 (sweep 0.5)
        + "    (DrillOrPullZFromTo 1.500 1.000)
G01 Z1.000
  (MillLine s=[0.000 0.000] e=[10.000 0.000] fr=1.000 to=1.000 bt=False)
G01 F150.000 X10.000 Y0.000 Z1.000
    (DrillOrPullZFromTo 1.000 1.500)
G00 Z1.500
  (MillLine s=[10.000 0.000] e=[20.000 0.000] fr=1.500 to=1.500 bt=False)
G01 F150.000 X20.000 Y0.000 Z1.500
G00 Z15.000
"
        // mill 6·10 = 60 (0.56 min); drill 0.5 + 1 = 1.5 → 2 (0.014 min);
        // sweeps 13.00003 + 0.5 + 13.50003 = 27.00006 (0.0756 min); sum 88.50006 → 89;
        // commands: 2 + 4 + 1 + 1 + 1 + 1 + final = 11
        + "  (Milling length:    60 mm   ca.  1 min)
  (Drill length:     2 mm   ca.  1 min)
  (Sweeps:         27 mm   ca.  1 min)
  (Sum:            89 mm   ca.  1 min)
  (Command count: 11)
M30
%
";
    assert_eq!(milling(&d), expected);
}

#[test]
fn closed_chain_several_runs_has_no_back_milling() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I0,5 B0,5 W1,5")
        .end(L, (0.0, 0.0))
        // N9997 pins the direction (both edges at the start are 10 long: warning MP118)
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "N9997")
        .line(L, "CONTINUOUS", (10.0, 0.0), (10.0, 10.0), "")
        .line(L, "CONTINUOUS", (10.0, 10.0), (0.0, 10.0), "")
        .line(L, "CONTINUOUS", (0.0, 10.0), (0.0, 0.0), "");
    let square = |z: &str| {
        format!(
            "  (MillLine s=[0.000 0.000] e=[10.000 0.000] fr={z} to={z} bt=False)
G01 F150.000 X10.000 Y0.000 Z{z}
  (MillLine s=[10.000 0.000] e=[10.000 10.000] fr={z} to={z} bt=False)
G01 F150.000 X10.000 Y10.000 Z{z}
  (MillLine s=[10.000 10.000] e=[0.000 10.000] fr={z} to={z} bt=False)
G01 F150.000 X0.000 Y10.000 Z{z}
  (MillLine s=[0.000 10.000] e=[0.000 0.000] fr={z} to={z} bt=False)
G01 F150.000 X0.000 Y0.000 Z{z}
"
        )
    };
    let expected = PROLOGUE.to_string()
        + "    (DrillOrPullZFromTo 15.000 1.500)
G00 Z2.000
G01 Z1.500
"
        + &square("1.500")
        + "    (DrillOrPullZFromTo 1.500 1.000)
G01 Z1.000
"
        + &square("1.000")
        + "    (DrillOrPullZFromTo 1.000 0.500)
G01 Z0.500
"
        + &square("0.500")
        + "G00 Z15.000
"
        // mill 3·40 = 120 (1.12 min → 2); drill 0.5 + 1 + 1.5 = 3 (0.028 min);
        // sweeps 13.00003 + 14.50003 = 27.50006 → 28; sum 150.50006 → 151 (1.225 min → 2);
        // commands: 2 + 4 + 1 + 4 + 1 + 4 + final = 17
        + "  (Milling length:   120 mm   ca.  2 min)
  (Drill length:     3 mm   ca.  1 min)
  (Sweeps:         28 mm   ca.  1 min)
  (Sum:           151 mm   ca.  2 min)
  (Command count: 17)
M30
%
";
    assert_eq!(milling(&d), expected);
}

#[test]
fn open_chain_one_run() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I0,5 B1 W1")
        .end(L, (10.0, 5.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "CONTINUOUS", (10.0, 0.0), (10.0, 5.0), "");
    let expected = PROLOGUE.to_string()
        + "    (DrillOrPullZFromTo 15.000 1.000)
G00 Z2.000
G01 Z1.000
  (MillLine s=[0.000 0.000] e=[10.000 0.000] fr=1.000 to=1.000 bt=False)
G01 F150.000 X10.000 Y0.000 Z1.000
  (MillLine s=[10.000 0.000] e=[10.000 5.000] fr=1.000 to=1.000 bt=False)
G01 F150.000 X10.000 Y5.000 Z1.000
G00 Z15.000
"
        // mill 15 (0.14 min); drill 1; sweeps 13.00003 + 14.00003 = 27.00006; sum 43.00006
        + "  (Milling length:    15 mm   ca.  1 min)
  (Drill length:     1 mm   ca.  1 min)
  (Sweeps:         27 mm   ca.  1 min)
  (Sum:            43 mm   ca.  1 min)
  (Command count: 5)
M30
%
";
    assert_eq!(milling(&d), expected);
}

#[test]
fn closed_chain_one_run_with_an_arc() {
    // a line out and a half circle back: ccw from (20,0) around (10,0) to (0,0)
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I0,5 B1 W1")
        .end(L, (0.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (20.0, 0.0), "")
        .arc(L, "CONTINUOUS", (10.0, 0.0), 10.0, 0.0, 180.0, "");
    let expected = PROLOGUE.to_string()
        + "    (DrillOrPullZFromTo 15.000 1.000)
G00 Z2.000
G01 Z1.000
  (MillLine s=[0.000 0.000] e=[20.000 0.000] fr=1.000 to=1.000 bt=False)
G01 F150.000 X20.000 Y0.000 Z1.000
  (MillArc l=[10.000 0.000] r=10.000 a0=0.000 a1=180.000 fr=1.000 to=1.000 p0=[20.000 0.000] p1=[0.000 0.000] bt=False)
G03 F150.000 I-10.000 J0.000 X0.000 Y0.000 Z1.000
G00 Z15.000
"
        // mill 20 + 10π = 51.416 (0.48 min); drill 1; sweeps 27.00006; sum 79.416 → 79
        + "  (Milling length:    51 mm   ca.  1 min)
  (Drill length:     1 mm   ca.  1 min)
  (Sweeps:         27 mm   ca.  1 min)
  (Sum:            79 mm   ca.  1 min)
  (Command count: 5)
M30
%
";
    assert_eq!(milling(&d), expected);
}
