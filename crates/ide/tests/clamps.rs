//! Clamps in the editor: the analysis behind the language server's diagnostics reports a
//! move into a `[[clamp]]` as you type (located at the element), and the toolpath view gets
//! the boxes and the moves that touch them.

mod support;

use millpath_core::Msg;
use millpath_ide::{analyze, toolpath};
use support::{p, workspace};

const SLOT: &str = "path 3001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2 S10\n  end (60, 0)\n  sweep (0, 0) -> (10, 0)\n  mill (10, 0) -> (50, 0)\n  sweep (50, 0) -> (60, 0)\n}\n";

fn with_clamp(dir: &std::path::Path, max_z: f64) {
    std::fs::write(
        dir.join("millpath.toml"),
        format!("feed = 300\nsweep_speed = 1000\nsweep_height = 10\n[[clamp]]\nname = \"vice\"\nmin = [54, -3, 0]\nmax = [56, 3, {max_z}]\n"),
    )
    .unwrap();
}

#[test]
fn a_move_into_a_clamp_is_reported_as_you_type_at_its_element() {
    let (dir, ws) = workspace(&[("3001.mpath", SLOT)]);
    let file = p(dir.path(), "3001.mpath");
    assert!(analyze(&ws, &file).diagnostics.is_empty());
    with_clamp(dir.path(), 10.0);
    let a = analyze(&ws, &file);
    let hit = a
        .diagnostics
        .iter()
        .find(|d| d.msg == Msg::ClampHit)
        .unwrap_or_else(|| panic!("{:?}", a.diagnostics));
    assert!(hit
        .message(millpath_core::Lang::En)
        .contains("clamp 'vice'"));
    match &hit.origin {
        millpath_core::Origin::Span { line, .. } => assert_eq!(*line, 6),
        o => panic!("{o:?}"),
    }
    // the clamp lowered below the sweep: nothing to say
    with_clamp(dir.path(), 9.9);
    assert!(analyze(&ws, &file).diagnostics.is_empty());
}

#[test]
fn the_toolpath_view_gets_the_clamps_and_the_moves_that_touch_them() {
    let (dir, ws) = workspace(&[("3001.mpath", SLOT)]);
    let file = p(dir.path(), "3001.mpath");
    with_clamp(dir.path(), 10.0);
    let tp = toolpath(&ws, &file, None).unwrap();
    assert_eq!(tp["clamps"][0]["name"], "vice");
    assert_eq!(tp["clamps"][0]["max"][2], 10.0);
    let hit: Vec<&serde_json::Value> = tp["moves"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|m| m.get("hits").is_some())
        .collect();
    // the last sweep, at S10 over the box
    assert_eq!(hit.len(), 1, "{hit:?}");
    assert_eq!(hit[0]["kind"], "rapid");
    assert_eq!(hit[0]["hits"][0], 0);
    assert_eq!(hit[0]["to"][0], 60.0);
    with_clamp(dir.path(), 9.9);
    let tp = toolpath(&ws, &file, None).unwrap();
    assert!(tp["moves"]
        .as_array()
        .unwrap()
        .iter()
        .all(|m| m.get("hits").is_none()));
}
