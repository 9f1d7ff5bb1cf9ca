//! Edits of one path, then of another, then both reverted: after each, the editor's
//! incremental analysis (from the previous version: reparsed line, reused objects and walks)
//! reports exactly what a fresh analysis of the same text reports, and the reverted text
//! what the original did. The paths take every way the quick check emits (fast chains of
//! lines, arcs and marks, a sweepless chain, a drill, subpath-free sweeps), and the edits
//! make the emitter itself refuse (a move beyond the sane range, a missing depth).

mod support;

use millpath_core::Msg;
use millpath_ide::*;
use support::{p, workspace};

const BASE: &str = "path 2120.1P {
  start (0, 0)  M3 O2 T3 I1,5 B-0,2 D1
  end (40, 0)
  mill (0, 0) -> (10, 0)
  mill (10, 0) -> (20, 0) ccw around (15, 0)
  mark (20, 0) -> (20, 10)
  sweep (20, 10) -> (30, 10)
  drill (30, 10) d2
  mill (30, 10) -> (40, 0)
}
path 2120.2P {
  start (0, 0)  M3 O2 T3 I0,5 W1 B-0,5
  end (0, 0)
  mill (0, 0) -> (10, 0)
  mill (10, 0) -> (10, 10)
  mill (10, 10) -> (0, 0)
}
path 2120.3P {
  start (0, 0)  M3 O2 T3 I1 B0
  end (30, 0)
  mill (0, 0) -> (10, 5)
  mill (10, 5) -> (20, 0)
  sweep (20, 0) -> (30, 0)
}
";

/// (what is replaced, by what); the last ones undo the first ones.
const EDITS: &[(&str, &str)] = &[
    // path 1: a corner moved (two segments, the chains' passes and sweeps change)
    (
        "mark (20, 0) -> (20, 10)\n  sweep (20, 10)",
        "mark (20, 0) -> (20, 12)\n  sweep (20, 12)",
    ),
    // path 3: sums beyond the sane range (T + O): the emitter refuses a move
    ("M3 O2 T3 I1 B0", "M3 O9e5 T9e5 I1e5 B0"),
    // path 2: the sweepless chain's infeed
    ("I0,5 W1", "I0,25 W1"),
    // path 1: its depth gone (a value the emitter finds missing)
    ("I1,5 B-0,2 D1", "I1,5 D1"),
    // every edit undone, in another order
    ("M3 O9e5 T9e5 I1e5 B0", "M3 O2 T3 I1 B0"),
    ("I1,5 D1", "I1,5 B-0,2 D1"),
    (
        "mark (20, 0) -> (20, 12)\n  sweep (20, 12)",
        "mark (20, 0) -> (20, 10)\n  sweep (20, 10)",
    ),
    ("I0,25 W1", "I0,5 W1"),
];

#[test]
fn each_incremental_analysis_is_a_fresh_one() {
    let (dir, mut ws) = workspace(&[]);
    let path = p(dir.path(), "2120.mpath");
    let mut text = BASE.to_string();
    ws.overlays.insert(path.clone(), text.clone());
    let first = analyze(&ws, &path);
    assert_eq!(first.diagnostics, [], "a clean start");
    let mut prev = analyze(&ws, &path);
    let mut seen = Vec::new();
    for (i, (from, to)) in EDITS.iter().enumerate() {
        assert!(text.contains(from), "edit {i}: {from:?}");
        text = text.replacen(from, to, 1);
        ws.overlays.insert(path.clone(), text.clone());
        let a = analyze_from(&ws, &path, Some(&prev), &|| false).unwrap();
        let fresh = analyze(&ws, &path);
        assert_eq!(a.diagnostics, fresh.diagnostics, "edit {i}:\n{text}");
        seen.extend(a.diagnostics.iter().map(|d| d.msg));
        prev = a;
    }
    assert_eq!(text, BASE);
    assert_eq!(prev.diagnostics, first.diagnostics, "reverted");
    // the edits did reach the emitter's own refusals
    for msg in [Msg::MoveOutOfRange, Msg::ValueMissing] {
        assert!(seen.contains(&msg), "{msg:?} in {seen:?}");
    }
}
