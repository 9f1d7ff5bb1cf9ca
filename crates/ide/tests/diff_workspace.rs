//! The workspace as `millpath diff` compiles a version in it: `--heightmap-step` and
//! `--heightmap-margin` go over each file's `[heightmap]` as `compile` takes them (the step
//! keeps the table's other keys, a margin alone widens the table's grid, neither makes a
//! grid where the file has none unless the step is given), and every path of a document
//! compiles from its one analysis (the text is read and parsed once, whatever the number of
//! paths).

use millpath_ide::{analyze, analyze_parsed, toolpath_moves, toolpath_moves_of, Workspace};

fn heightmap(toml: &str, options: (Option<f64>, Option<f64>)) -> Option<(f64, f64, bool)> {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("millpath.toml"), toml).unwrap();
    let ws = Workspace {
        heightmap_options: options,
        ..Workspace::default()
    };
    let s = ws.settings_for(&dir.path().join("2001.mpath")).settings;
    s.heightmap.map(|h| (h.step, h.margin, h.area.is_some()))
}

#[test]
fn the_options_go_over_the_table() {
    let table = "[heightmap]\nstep = 10\nmargin = 3\narea = [0, 0, 50, 50]\n";
    assert_eq!(heightmap(table, (None, None)), Some((10.0, 3.0, true)));
    // a margin alone: the table's grid, wider
    assert_eq!(heightmap(table, (None, Some(7.0))), Some((10.0, 7.0, true)));
    // a step alone keeps the table's margin and area
    assert_eq!(
        heightmap(table, (Some(20.0), None)),
        Some((20.0, 3.0, true))
    );
    assert_eq!(
        heightmap(table, (Some(20.0), Some(1.0))),
        Some((20.0, 1.0, true))
    );
    // without a table: the step makes a grid, a margin alone none
    assert_eq!(heightmap("", (None, Some(7.0))), None);
    assert_eq!(
        heightmap("", (Some(5.0), Some(2.0))),
        Some((5.0, 2.0, false))
    );
}

/// Many paths in one text: each compiles from the analysis to the moves a fresh read gives,
/// and without the text at hand any more (it is not read again per path).
#[test]
fn every_path_compiles_from_the_one_analysis() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n",
    )
    .unwrap();
    let mut text = String::new();
    for i in 1..=20 {
        text.push_str(&format!(
            "path 3000.{i}P {{\n  start (0, 0)  M3x40 O2 T3 I1,5 B-0,{i}\n  end (30, 0)\n  mill (0, 0) -> (10, {i})\n  mill (10, {i}) -> (30, 0)\n}}\n\n"
        ));
    }
    let at = dir.path().join("3000.mpath");
    let mut ws = Workspace::default();
    ws.overlays.insert(at.clone(), text.clone());
    let a = analyze(&ws, &at);
    assert!(!a.has_errors(), "{:?}", a.diagnostics);
    let (tree, errors) = millpath_syntax::parse(&text);
    assert!(errors.is_empty());
    let parsed = analyze_parsed(&ws, &at, tree);
    assert_eq!(parsed.diagnostics, a.diagnostics);
    let fresh: Vec<_> = (1..=20)
        .map(|i| toolpath_moves(&ws, &at, Some(&format!("3000.{i}P"))).unwrap())
        .collect();
    // the text gone: a path read again would not be found
    let gone = Workspace::default();
    for (i, want) in (1..=20).zip(&fresh) {
        let name = format!("3000.{i}P");
        for a in [&a, &parsed] {
            let got = toolpath_moves_of(&gone, a, &name).unwrap();
            assert_eq!(got.moves, want.moves, "{name}");
        }
    }
    assert!(toolpath_moves(&gone, &at, Some("3000.1P")).is_err());
}
