//! Every editor feature in-process, on a small workspace of text files.

mod support;

use millpath_ide::*;
use millpath_ide::{analyze, Pos, Workspace};
use support::{at, p, workspace};

const PART: &str = "path 2001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  sweep (0, 0) -> (5, 0)\n  mill (5, 0) -> (25, 0)\n  sweep (25, 0) -> (30, 0)\n}\n";
const PROJECT: &str = "path 2010.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (50, 0)\n  sweep (0, 0) -> (10, 10)\n  sub (10, 10) -> (40, 10)  >2001.1P\n  sweep (40, 10) -> (10, 30)\n  sub (10, 30) -> (40, 30)  >2001.1P\n  sweep (40, 30) -> (50, 0)\n}\n";
const NO_B: &str = "path 2030.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5\n  end (20, 0)\n  mill (0, 0) -> (20, 0)\n}\n";

fn setup() -> (tempfile::TempDir, Workspace) {
    workspace(&[
        ("2001.mpath", PART),
        ("2010.mpath", PROJECT),
        ("2030.mpath", NO_B),
    ])
}

#[test]
fn diagnostics_of_a_missing_b_value_with_range() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2030.mpath"));
    let d = a
        .diagnostics
        .iter()
        .find(|d| d.message(millpath_core::Lang::En) == "B value missing")
        .expect("B value missing");
    match &d.origin {
        millpath_core::Origin::Span {
            start, end, line, ..
        } => {
            assert_eq!(*line, 4);
            assert!(
                NO_B[*start as usize..*end as usize].starts_with("mill (0, 0) -> (20, 0)"),
                "{:?}",
                &NO_B[*start as usize..*end as usize]
            );
        }
        o => panic!("{o:?}"),
    }
    // unsaved buffers win over the disk
    let mut ws2 = ws.clone();
    ws2.overlays.insert(
        p(dir.path(), "2030.mpath"),
        NO_B.replace("I1,5", "I1,5 B-0,2"),
    );
    assert!(analyze(&ws2, &p(dir.path(), "2030.mpath"))
        .diagnostics
        .is_empty());
}

#[test]
fn hover_on_a_path_name_shows_its_statistics_and_exact_time() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2001.mpath"));
    let h = hover(&a, &ws, at(PART, "2001.1P") + 2).unwrap();
    let pv = millpath_ide::preview_of(&a, &ws, Some("2001.1P")).unwrap();
    assert!(
        h.markdown.starts_with("**path** `2001.1P`"),
        "{}",
        h.markdown
    );
    assert!(
        h.markdown
            .contains(&format!("Estimated time: **{}**", pv.time)),
        "{}",
        h.markdown
    );
    assert!(h.markdown.contains(&pv.stats[0]), "{}", h.markdown);
    assert_eq!(&PART[h.start..h.end], "2001.1P");
}

#[test]
fn hover_shows_inherited_values_and_their_origin() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2001.mpath"));
    let h = hover(&a, &ws, at(PART, "mill (5")).unwrap();
    assert!(
        h.markdown.contains("| B | -0,2 | path start (line 2) |"),
        "{}",
        h.markdown
    );
    assert!(
        h.markdown.contains("| F | 300 | millpath.toml"),
        "{}",
        h.markdown
    );
    assert!(
        h.markdown.contains("| I | 1,5 | path start (line 2) |"),
        "{}",
        h.markdown
    );
    assert!(
        // three passes of 20 mm at F300, the reference's ×1.4: 16.8 s
        h.markdown
            .contains("passes: 1.500, 0.000, -0.200 · length 20.000 mm · ca. 0:00:17"),
        "{}",
        h.markdown
    );
    // a parameter letter
    let h = hover(&a, &ws, at(PART, "I1,5")).unwrap();
    assert!(
        h.markdown.starts_with("**I** — infeed per pass"),
        "{}",
        h.markdown
    );
    // a subpath name
    let a = analyze(&ws, &p(dir.path(), "2010.mpath"));
    let h = hover(&a, &ws, at(PROJECT, ">2001.1P") + 2).unwrap();
    assert!(
        h.markdown.contains("T 3 · O 2 · M 10x3") && h.markdown.contains("size 30.000 mm"),
        "{}",
        h.markdown
    );
}

#[test]
fn preview_is_what_compile_writes() {
    let (dir, ws) = setup();
    let pv = preview(&ws, &p(dir.path(), "2010.mpath"), Some("2010.1P")).unwrap();
    assert!(pv.errors.is_empty(), "{:?}", pv.errors);
    let fs = millpath_core::OsFileSystem;
    let mut settings = millpath_core::Settings {
        feed: 300.0,
        sweep_speed: 1000.0,
        sweep_height: 10.0,
        ..Default::default()
    };
    settings.lang = millpath_core::Lang::En;
    let mut s = millpath_core::Session::new(settings, &fs).unwrap();
    let outcome = millpath_core::compile_file(
        &mut s,
        &p(dir.path(), "2010.mpath"),
        &millpath_core::banner(),
    );
    assert_eq!(outcome.outputs.len(), 1);
    assert_eq!(pv.gcode, outcome.outputs[0].content);
    assert_eq!(pv.stats.len(), 5);
}

#[test]
fn inlay_hints_show_inherited_depths() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2001.mpath"));
    let hints = inlay_hints(&a);
    assert_eq!(hints.len(), 1);
    assert_eq!(hints[0].label, "⇐ B-0,2");
    assert_eq!(
        hints[0].offset,
        at(PART, "mill (5, 0) -> (25, 0)") + "mill (5, 0) -> (25, 0)".len()
    );
}

#[test]
fn definition_and_references_of_subpath_names() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2010.mpath"));
    let defs = definition(&a, &ws, at(PROJECT, ">2001.1P") + 3);
    assert_eq!(defs.len(), 1);
    assert_eq!(defs[0].path, p(dir.path(), "2001.mpath"));
    // the `path NAME` header, not the start marker
    assert_eq!(defs[0].start, Pos { line: 0, col: 5 });
    assert_eq!(defs[0].end, Pos { line: 0, col: 12 });
    let part = analyze(&ws, &p(dir.path(), "2001.mpath"));
    let refs = references(&part, &ws, at(PART, "2001.1P"));
    assert_eq!(refs.len(), 2, "{refs:?}");
    assert!(refs.iter().all(|r| r.path == p(dir.path(), "2010.mpath")));
    assert_eq!(refs[0].start.line, 4);
    // DXF files count as well
    let mut w = millpath_dxf::writer::DxfWriter::new();
    w.circle("2040_1P", Some("PHANTOM"), (0.0, 0.0), 0.5)
        .line("2040_1P", Some("DASHDOT"), (0.0, 0.0), (30.0, 0.0))
        .mtext("2040_1P", (15.0, 0.0), 0.3, &[">2001.1P"]);
    std::fs::write(dir.path().join("2040.dxf"), w.finish()).unwrap();
    assert_eq!(references(&part, &ws, at(PART, "2001.1P")).len(), 3);
}

#[test]
fn symbols() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2010.mpath"));
    let syms = document_symbols(&a);
    assert_eq!(syms.len(), 1);
    assert_eq!(syms[0].name, "2010.1P");
    assert_eq!(syms[0].children.len(), 7);
    assert_eq!(syms[0].children[3].name, "sub (10, 10) -> (40, 10)");
    let all = workspace_symbols(&ws, "20");
    let names: Vec<&str> = all.iter().map(|s| s.0.as_str()).collect();
    assert!(
        names.contains(&"2001.1P") && names.contains(&"2010.1P") && names.contains(&"2030.1P"),
        "{names:?}"
    );
    assert_eq!(workspace_symbols(&ws, "2001").len(), 1);
}

#[test]
fn completion_of_letters_names_and_kinds() {
    let (dir, mut ws) = setup();
    let path = p(dir.path(), "2030.mpath");
    let src = NO_B.replace("mill (0, 0) -> (20, 0)", "mill (0, 0) -> (20, 0)  ");
    ws.overlays.insert(path.clone(), src.clone());
    let a = analyze(&ws, &path);
    let off = at(&src, "(20, 0)  ") + "(20, 0)  ".len();
    let items = completion(&a, &ws, off);
    let labels: Vec<&str> = items.iter().map(|c| c.label.as_str()).collect();
    assert!(
        labels.contains(&"B") && labels.contains(&"F") && labels.contains(&"N"),
        "{labels:?}"
    );
    assert!(
        !labels.contains(&"T") && !labels.contains(&"O"),
        "T and O are not allowed on mill lines"
    );
    // subpath names after >
    let src2 = PROJECT.replace(">2001.1P", ">20");
    ws.overlays
        .insert(p(dir.path(), "2010.mpath"), src2.clone());
    let a = analyze(&ws, &p(dir.path(), "2010.mpath"));
    let items = completion(&a, &ws, at(&src2, ">20") + 3);
    assert!(items.iter().any(|c| c.label == "2001.1P"), "{items:?}");
    // element kinds at the start of a line inside a path
    let src3 = NO_B.replace("  end (20, 0)\n", "  end (20, 0)\n  \n");
    ws.overlays.insert(path.clone(), src3.clone());
    let a = analyze(&ws, &path);
    let items = completion(&a, &ws, at(&src3, "  \n  mill") + 2);
    assert!(items.iter().any(|c| c.label == "helix"), "{items:?}");
    // an opened quote (the trigger of post names in millpath.toml): nothing to offer
    let src4 = NO_B.replace("mill (0, 0) -> (20, 0)", "mill (0, 0) -> (20, 0)  \"");
    ws.overlays.insert(path.clone(), src4.clone());
    let a = analyze(&ws, &path);
    let items = completion(&a, &ws, at(&src4, "(20, 0)  \"") + "(20, 0)  \"".len());
    assert_eq!(items, Vec::new());
}

#[test]
fn formatting() {
    let (dir, mut ws) = setup();
    let path = p(dir.path(), "2030.mpath");
    ws.overlays.insert(
        path.clone(),
        "path 2030.1P {\n   mill (0,0)->(1,1)   B1\n}\n".into(),
    );
    let a = analyze(&ws, &path);
    assert_eq!(
        format(&a).unwrap(),
        "path 2030.1P {\n  mill (0, 0) -> (1, 1)  B1\n}\n"
    );
    ws.overlays
        .insert(path.clone(), "path X {\n  mill (0,\n}\n".into());
    assert_eq!(format(&analyze(&ws, &path)), None);
}

#[test]
fn code_actions_fix_missing_values_swapped_depths_and_dead_ends() {
    let (dir, mut ws) = setup();
    let path = p(dir.path(), "2030.mpath");
    let a = analyze(&ws, &path);
    let acts = code_actions(&a, 0, NO_B.len());
    let add = acts
        .iter()
        .find(|x| x.title.starts_with("Add B0"))
        .expect("add B");
    let fixed = apply(NO_B, &add.edits);
    assert!(
        fixed.contains("start (0, 0)  M10x3 O2 T3 I1,5 B0\n"),
        "{fixed}"
    );
    // D not above B
    let swapped = NO_B.replace("I1,5", "I1,5 B1 D-1");
    ws.overlays.insert(path.clone(), swapped.clone());
    let a = analyze(&ws, &path);
    let act = code_actions(&a, 0, swapped.len())
        .into_iter()
        .find(|x| x.title.contains("Swap"))
        .expect("swap");
    assert!(apply(&swapped, &act.edits).contains("B-1 D1"));
    // a dead-end branch: a turn marker brings the tool back
    let branch = "path 2030.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B0\n  end (20, 0)\n  mill (0, 0) -> (10, 0)\n  mill (10, 0) -> (10, 5)  N1\n  sweep (10, 0) -> (20, 0)  N2\n}\n";
    ws.overlays.insert(path.clone(), branch.into());
    let a = analyze(&ws, &path);
    let acts = code_actions(&a, 0, branch.len());
    let turn = acts
        .iter()
        .find(|x| x.title.contains("turn marker"))
        .expect("turn");
    let fixed = apply(branch, &turn.edits);
    assert!(fixed.contains("  turn (10, 5)\n"), "{fixed}");
    ws.overlays.insert(path.clone(), fixed);
    assert!(analyze(&ws, &path).diagnostics.is_empty());
    // a path that ends away from its end marker: a sweep closes it
    let open = "path 2030.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B0\n  end (20, 0)\n  mill (0, 0) -> (10, 5)\n}\n";
    ws.overlays.insert(path.clone(), open.into());
    let a = analyze(&ws, &path);
    let acts = code_actions(&a, 0, open.len());
    let sweep = acts
        .iter()
        .find(|x| x.title.contains("sweep"))
        .expect("sweep");
    let fixed = apply(open, &sweep.edits);
    assert!(fixed.contains("  sweep (10, 5) -> (20, 0)\n"), "{fixed}");
    ws.overlays.insert(path.clone(), fixed);
    assert!(analyze(&ws, &path).diagnostics.is_empty());
    // in German, with `lang = "de"` in millpath.toml: every title
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 150\nsweep_speed = 500\nsweep_height = 15\nlang = \"de\"\n",
    )
    .unwrap();
    let mut titles = Vec::new();
    for text in [NO_B, &swapped, branch, open] {
        ws.overlays.insert(path.clone(), text.into());
        let a = analyze(&ws, &path);
        titles.extend(code_actions(&a, 0, text.len()).into_iter().map(|x| x.title));
    }
    for de in [
        "B0 am Anfang von 2030.1P ergänzen",
        "Die Werte von B und D tauschen",
        "Wendemarke bei (10, 5)",
        "Leerfahrt von (10, 5) zur Ende-Markierung",
    ] {
        assert!(titles.iter().any(|t| t.contains(de)), "{de}: {titles:?}");
    }
    for en in ["Add", "Swap", "Close", "sweep", "Pin"] {
        assert!(!titles.iter().any(|t| t.contains(en)), "{en}: {titles:?}");
    }
}

fn apply(src: &str, edits: &[TextEdit]) -> String {
    let mut s = src.to_string();
    let mut e = edits.to_vec();
    e.sort_by_key(|x| std::cmp::Reverse(x.start));
    for x in e {
        s.replace_range(x.start..x.end, &x.text);
    }
    s
}

#[test]
fn semantic_tokens_and_code_lenses() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2001.mpath"));
    let toks = semantic_tokens(&a);
    assert!(toks.windows(2).all(|w| w[0].start <= w[1].start));
    let kinds: Vec<(&str, u32)> = toks
        .iter()
        .map(|t| (&PART[t.start..t.end], t.kind))
        .collect();
    assert!(
        kinds.contains(&("path", 0))
            && kinds.contains(&("2001.1P", 5))
            && kinds.contains(&("mill", 0))
    );
    assert!(kinds.contains(&("I", 2)) && kinds.contains(&("1,5", 3)) && kinds.contains(&("25", 1)));
    let lenses = code_lenses(&a, &ws);
    assert_eq!(lenses.len(), 1);
    assert_eq!(lenses[0].path, "2001.1P");
    assert!(
        lenses[0].title.contains("Milling length: 60 mm"),
        "{}",
        lenses[0].title
    );
    // the exact time, as the preview (and compile's summary) has it
    let pv = millpath_ide::preview_of(&a, &ws, None).unwrap();
    assert!(pv.time.starts_with("0:0"), "{}", pv.time);
    assert!(
        lenses[0].title.ends_with(&format!(" · ⏱ {}", pv.time)),
        "{}",
        lenses[0].title
    );
}

#[test]
fn toolpath_for_the_view() {
    let (dir, ws) = setup();
    let tp = toolpath(&ws, &p(dir.path(), "2010.mpath"), None).unwrap();
    assert_eq!(tp["path"], "2010.1P");
    let moves = tp["moves"].as_array().unwrap();
    // the horizontal cuts: two embedded slots, three passes each (plunges are `mill` too)
    let mills: Vec<&serde_json::Value> = moves
        .iter()
        .filter(|m| m["kind"] == "mill" && m["from"][0] != m["to"][0])
        .collect();
    assert_eq!(mills.len(), 6);
    // the slots' moves come from the part's mill line, in the part's file
    let src = &tp["sources"][mills[0]["source"].as_u64().unwrap() as usize];
    assert!(
        src["file"].as_str().unwrap().ends_with("2001.mpath"),
        "{src}"
    );
    assert_eq!(src["line"], 4);
    assert_eq!(src["text"], "mill (5, 0) -> (25, 0)");
    assert!(moves.iter().any(|m| m["kind"] == "rapid"));
    assert_eq!(tp["bounds"]["minZ"], -0.2);
    // every move names its line of the written program, rounded numbers, a time
    let preview = millpath_ide::preview(&ws, &p(dir.path(), "2010.mpath"), None).unwrap();
    let lines: Vec<&str> = preview.gcode.lines().collect();
    for m in moves {
        let line = m["line"].as_u64().unwrap() as usize;
        assert_eq!(lines[line - 1], m["gcode"], "{m}");
        assert!(m["t"].as_f64().unwrap() >= 0.0);
        for v in m["to"].as_array().unwrap() {
            let s = v.to_string();
            assert!(s.split('.').nth(1).is_none_or(|d| d.len() <= 3), "{s}");
        }
    }
    assert_eq!(tp["stats"][0], preview.stats[0]);
    // the exact time beside the seconds, as the preview has it
    assert_eq!(tp["time"], preview.time.as_str());
    let s = tp["seconds"].as_f64().unwrap();
    assert_eq!(
        tp["time"].as_str().unwrap(),
        millpath_core::emit::stats::hms(s)
    );
    assert!(toolpath(&ws, &p(dir.path(), "2010.mpath"), Some("9.9Q")).is_err());
}

#[test]
fn preview_follows_the_dialect_of_the_settings() {
    let (dir, ws) = setup();
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\ndialect = \"grbl\"\nspindle_rpm = 9000\n",
    )
    .unwrap();
    let pv = preview(&ws, &p(dir.path(), "2010.mpath"), Some("2010.1P")).unwrap();
    assert!(pv.gcode.starts_with("(millpath V."), "{}", pv.gcode);
    assert!(pv.gcode.contains("\nF300.000\nT1\nM3 S9000\nG4 P2\n"));
    assert!(pv.gcode.contains("\nG01 F150.000 Z1.500\n"));
    assert!(pv.gcode.ends_with("M5\nM30\n"));
}

/// Without machine settings the preview says so (compile would refuse); the placeholders
/// F150/S15 are never used silently.
#[test]
fn preview_without_machine_settings_says_so() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("2001.mpath"), PART).unwrap();
    let ws = Workspace::default();
    let pv = preview(&ws, &p(dir.path(), "2001.mpath"), None).unwrap();
    assert!(
        pv.errors
            .iter()
            .any(|e| e.starts_with("missing machine settings: feed, sweep_speed, sweep_height")),
        "{:?}",
        pv.errors
    );
    // the editor's settings fill them
    let mut ws = Workspace::default();
    ws.client.feed = Some(300.0);
    ws.client.sweep_speed = Some(1000.0);
    ws.client.sweep_height = Some(10.0);
    let pv = preview(&ws, &p(dir.path(), "2001.mpath"), None).unwrap();
    assert!(pv.errors.is_empty(), "{:?}", pv.errors);
}

/// A square milled from a corner: the order of two equally long lines decides the direction.
const SQUARE: &str = "path 2040.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (0, 0)\n  mill (0, 0) -> (20, 0)\n  mill (20, 0) -> (20, 20)\n  mill (20, 20) -> (0, 20)\n  mill (0, 20) -> (0, 0)\n}\n";

#[test]
fn order_warning_at_the_chosen_line_with_a_pinning_fix() {
    let (dir, mut ws) = setup();
    let path = p(dir.path(), "2040.mpath");
    ws.overlays.insert(path.clone(), SQUARE.into());
    let a = analyze(&ws, &path);
    let d = a
        .diagnostics
        .iter()
        .find(|d| d.msg == millpath_core::Msg::OrderDecidesText)
        .expect("order warning");
    assert_eq!(d.severity, millpath_core::Severity::Warning);
    let en = d.message(millpath_core::Lang::En);
    assert!(en.contains("the formatter keeps this order"), "{en}");
    assert!(en.contains("N9997"), "{en}");
    assert!(d
        .message(millpath_core::Lang::De)
        .contains("Reihenfolge der Zeilen"));
    let millpath_core::Origin::Span { start, end, .. } = d.origin else {
        panic!("{:?}", d.origin)
    };
    assert_eq!(
        SQUARE[start as usize..end as usize].trim_end(),
        "mill (0, 0) -> (20, 0)"
    );
    // the formatter keeps the order of the lines that carries the choice
    let swapped = SQUARE.replace(
        "  mill (0, 0) -> (20, 0)\n  mill (20, 0) -> (20, 20)\n  mill (20, 20) -> (0, 20)\n  mill (0, 20) -> (0, 0)\n",
        "  mill (0, 20) -> (0, 0)\n  mill (20, 20) -> (0, 20)\n  mill (20, 0) -> (20, 20)\n  mill (0, 0) -> (20, 0)\n",
    );
    ws.overlays.insert(path.clone(), swapped.clone());
    let b = analyze(&ws, &path);
    assert_eq!(format(&b).as_deref(), Some(swapped.as_str()), "order kept");
    let other = b
        .diagnostics
        .iter()
        .find(|d| d.msg == millpath_core::Msg::OrderDecidesText)
        .expect("order warning");
    let millpath_core::Origin::Span { start, end, .. } = other.origin else {
        panic!()
    };
    assert_eq!(
        swapped[start as usize..end as usize].trim_end(),
        "mill (0, 20) -> (0, 0)"
    );
    // the quick fix pins the direction; the warning is gone, the G-code is the warned one
    ws.overlays.insert(path.clone(), SQUARE.into());
    let before = preview(&ws, &path, None).unwrap().gcode;
    let fix = code_actions(&a, 0, SQUARE.len())
        .into_iter()
        .find(|x| x.title.starts_with("Pin the choice with N9997"))
        .expect("pin");
    let fixed = apply(SQUARE, &fix.edits);
    assert!(
        fixed.contains("  mill (0, 0) -> (20, 0)  N9997\n"),
        "{fixed}"
    );
    ws.overlays.insert(path.clone(), fixed);
    let c = analyze(&ws, &path);
    assert!(c.diagnostics.is_empty(), "{:?}", c.diagnostics);
    assert_eq!(preview(&ws, &path, None).unwrap().gcode, before);
    // a pinned line keeps its place after the swap too: no warning
    let pinned_swapped = swapped.replace("mill (0, 0) -> (20, 0)", "mill (0, 0) -> (20, 0)  N9997");
    ws.overlays.insert(path.clone(), pinned_swapped);
    assert!(analyze(&ws, &path).diagnostics.is_empty());
}

/// Every move of a chain reports its own segment, and the line of the written program.
#[test]
fn toolpath_moves_report_their_own_segment() {
    let (dir, ws) = setup();
    let src = "path 2040.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (0, 0)\n  mill (0, 0) -> (20, 0)\n  mill (20, 0) -> (20, 10)\n  mark (20, 10) -> (0, 0)  D2\n}\n";
    std::fs::write(dir.path().join("2040.mpath"), src).unwrap();
    let tp = toolpath(&ws, &p(dir.path(), "2040.mpath"), None).unwrap();
    let sources = tp["sources"].as_array().unwrap();
    let moves = tp["moves"].as_array().unwrap();
    let line_of =
        |m: &serde_json::Value| m["source"].as_u64().map(|i| &sources[i as usize]["line"]);
    // the vertical branch (20,0)->(20,10) is line 5 (0-based 4), not the chain's first
    let branch: Vec<&serde_json::Value> = moves
        .iter()
        .filter(|m| {
            m["kind"] == "mill" && m["from"][0] == 20.0 && m["to"][0] == 20.0 && m["to"][1] == 10.0
        })
        .collect();
    assert!(!branch.is_empty());
    for m in &branch {
        assert_eq!(line_of(m), Some(&serde_json::json!(4)), "{m}");
    }
    let marks: Vec<&serde_json::Value> = moves.iter().filter(|m| m["kind"] == "mark").collect();
    assert!(!marks.is_empty());
    for m in marks {
        assert_eq!(line_of(m), Some(&serde_json::json!(5)), "{m}");
    }
    let preview = millpath_ide::preview(&ws, &p(dir.path(), "2040.mpath"), None).unwrap();
    let lines: Vec<&str> = preview.gcode.lines().collect();
    let l = branch[0]["line"].as_u64().unwrap() as usize;
    assert!(
        lines[l - 1].starts_with("G01 F300.000 X20.000 Y10.000"),
        "{}",
        lines[l - 1]
    );
}

/// A file on disk as Windows tools write it (a UTF-8 BOM, UTF-16 LE with CRLF) reads as the
/// plain file: no diagnostics, the same paths, a typo located from the first real character.
#[test]
fn files_with_a_bom_or_in_utf16_read_as_plain_text() {
    let (dir, ws) = setup();
    let mut bom = b"\xEF\xBB\xBF".to_vec();
    bom.extend_from_slice(PART.as_bytes());
    let mut utf16 = vec![0xFF, 0xFE];
    utf16.extend(
        PART.replace('\n', "\r\n")
            .encode_utf16()
            .flat_map(u16::to_le_bytes),
    );
    for (name, bytes) in [("2001.mpath", bom), ("2001.mpath", utf16)] {
        std::fs::write(dir.path().join(name), &bytes).unwrap();
        let a = analyze(&ws, &p(dir.path(), name));
        assert!(a.diagnostics.is_empty(), "{:?}", a.diagnostics);
        assert_eq!(a.paths.len(), 1);
        assert!(a.src.starts_with("path 2001.1P {"));
    }
    let mut typo = b"\xEF\xBB\xBF".to_vec();
    typo.extend_from_slice(PART.replace("mill (5", "mil (5").as_bytes());
    std::fs::write(dir.path().join("2001.mpath"), &typo).unwrap();
    let a = analyze(&ws, &p(dir.path(), "2001.mpath"));
    let d = &a.diagnostics[0];
    assert_eq!(d.msg, millpath_core::Msg::SyntaxKindDidYouMean);
    let millpath_core::Origin::Span {
        start,
        end,
        line,
        col,
        ..
    } = &d.origin
    else {
        panic!("{d:?}")
    };
    assert_eq!(
        (&a.src[*start as usize..*end as usize], *line, *col),
        ("mil", 5, 3)
    );
}

/// A height map said in the drawing (`K`): hover explains it, completion offers it at the
/// path start, and the preview (linuxcnc) is the grid set compile writes.
#[test]
fn a_height_map_in_the_start_text() {
    let (dir, mut ws) = setup();
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\ndialect = \"linuxcnc\"\n",
    )
    .unwrap();
    let path = p(dir.path(), "2001.mpath");
    let src = PART.replace("B-0,2\n", "B-0,2 K10+2\n");
    ws.overlays.insert(path.clone(), src.clone());
    let a = analyze(&ws, &path);
    let h = hover(&a, &ws, at(&src, "K10+2")).unwrap();
    assert!(
        h.markdown.starts_with("**K** — height map"),
        "{}",
        h.markdown
    );
    let pv = preview(&ws, &path, None).unwrap();
    assert!(pv.errors.is_empty(), "{:?}", pv.errors);
    let probing = pv.probing.expect("a probing set");
    assert!(probing.contains("STEP=10.000)"), "{probing}");
    assert!(pv.z_txt.is_some_and(|z| z.contains("#1000=")));
    // completion at the start text offers K
    let src2 = PART.replace("B-0,2\n", "B-0,2 \n");
    ws.overlays.insert(path.clone(), src2.clone());
    let a = analyze(&ws, &path);
    let items = completion(&a, &ws, at(&src2, "B-0,2 ") + "B-0,2 ".len());
    assert!(items.iter().any(|c| c.label == "K"), "{items:?}");
}
