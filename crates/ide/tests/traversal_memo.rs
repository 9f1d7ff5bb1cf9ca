//! The editor's memo of walks (`core/build/traverse_memo.rs`) gives exactly what a fresh
//! analysis gives, over a sequence of edits: parameter edits take the previous walk, edits
//! of geometry, N, markers, kinds and contested texts walk again.

mod support;

use millpath_core::build::walk::walk;
use millpath_core::Diags;
use millpath_ide::*;
use support::{p, workspace};

/// A star with turn markers (N1, N2), and a square loop started at a corner (its first step
/// is a choice the line order makes: a warning, two contested segments).
const BASE: &str = "path 2110.1P {
  start (0, 0)  M3 O2 T3 I1,5 B1
  end (20, 0)
  sweep (0, 0) -> (10, 0)
  mill (10, 0) -> (10, 10)  N1
  turn (10, 10)
  mill (10, 0) -> (10, -10)  N2
  turn (10, -10)
  sweep (10, 0) -> (20, 0)
}
path 2110.2P {
  start (0, 0)  M3 O2 T3 I1,5 B1
  end (0, 0)
  mill (0, 0) -> (10, 0)
  mill (10, 0) -> (10, 10)
  mill (10, 10) -> (0, 10)
  mill (0, 10) -> (0, 0)
}
";

/// Each edit (what is replaced, by what) and how many of the two walks it leaves as they were.
const EDITS: &[(&str, &str, usize)] = &[
    // a parameter, same length: both walks kept
    ("I1,5 B1\n  end (20", "I1,2 B1\n  end (20", 2),
    // a parameter, longer: every location after it moves, the walks are kept
    ("I1,2 B1\n  end (20", "I1,25 B1\n  end (20", 2),
    // a point moved (the segment and its turn marker)
    (
        "(10, 10)  N1\n  turn (10, 10)",
        "(10, 12)  N1\n  turn (10, 12)",
        1,
    ),
    // the branches' order swapped
    ("N1\n", "N3\n", 1),
    // a turn marker removed: a dead end, an error (such a walk is not kept)
    ("  turn (10, -10)\n", "", 1),
    // and put back
    (
        "  mill (10, 0) -> (10, -10)  N2\n",
        "  mill (10, 0) -> (10, -10)  N2\n  turn (10, -10)\n",
        1,
    ),
    // a text on a contested segment of the loop (the walk compares such texts)
    (
        "mill (0, 10) -> (0, 0)\n",
        "mill (0, 10) -> (0, 0)  F100\n",
        1,
    ),
    // the other contested segment milled there and back once more (a duplicate drawn the
    // other way and one drawn the same way: no choice between them)
    (
        "  mill (0, 0) -> (10, 0)\n",
        "  mill (0, 0) -> (10, 0)\n  mill (10, 0) -> (0, 0)\n  mill (0, 0) -> (10, 0)\n",
        1,
    ),
    // the duplicate's text differs: a rival again
    (
        "  mill (10, 0) -> (0, 0)\n",
        "  mill (10, 0) -> (0, 0)  F200\n",
        1,
    ),
    // lines above both paths: every location moves, nothing else
    ("path 2110.1P {", "# a comment\n\npath 2110.1P {", 2),
    // a kind changed
    ("sweep (10, 0) -> (20, 0)", "mill (10, 0) -> (20, 0)", 1),
    // a segment pinned with N (an order key)
    (
        "mill (0, 0) -> (10, 0)\n",
        "mill (0, 0) -> (10, 0)  N9997\n",
        1,
    ),
    // nothing the walks read
    (
        "M3 O2 T3 I1,5 B1\n  end (0, 0)",
        "M3 O2 T3 I1 B1\n  end (0, 0)",
        2,
    ),
];

#[test]
fn remembered_walks_give_what_fresh_analyses_give() {
    let (dir, mut ws) = workspace(&[]);
    let path = p(dir.path(), "2110.mpath");
    let mut text = BASE.to_string();
    ws.overlays.insert(path.clone(), text.clone());
    let mut prev = analyze(&ws, &path);
    assert_eq!(prev.traversals.reused(), 0);
    let mut warned = false;
    for (i, (from, to, kept)) in EDITS.iter().enumerate() {
        assert!(text.contains(from), "edit {i}: {from:?}");
        text = text.replacen(from, to, 1);
        ws.overlays.insert(path.clone(), text.clone());
        let a = analyze_from(&ws, &path, Some(&prev), &|| false).unwrap();
        let fresh = analyze(&ws, &path);
        assert_eq!(a.diagnostics, fresh.diagnostics, "edit {i}:\n{text}");
        assert_eq!(a.traversals.reused(), *kept, "edit {i}:\n{text}");
        assert_eq!(fresh.traversals.reused(), 0);
        // each remembered walk is the walk of the path as it is now
        for raw in &a.paths {
            let (Some(s), Some(e)) = (&raw.start, &raw.end) else {
                panic!("edit {i}: markers")
            };
            let now = walk(raw, s.pos, e.pos, &mut Diags::default());
            match a.traversals.remembered(&raw.name) {
                Some(kept) => assert_eq!(kept, now, "edit {i}, {}", raw.name),
                // only a walk that reported an error is not kept
                None => assert!(!a.diagnostics.is_empty(), "edit {i}, {}", raw.name),
            }
        }
        warned |= a
            .diagnostics
            .iter()
            .any(|d| d.msg == millpath_core::Msg::OrderDecidesText);
        prev = a;
    }
    assert!(warned, "the loop's choice was warned about");
}
