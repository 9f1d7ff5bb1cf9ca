//! Rename, folding, document links, highlights, selection and range formatting, and the
//! smaller answers (symbol names, hover table, completion, diagnostic ranges), in-process.

mod support;

use millpath_ide::*;
use std::path::Path;
use support::{at, p, workspace};

const PART: &str = "path 2001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  sweep (0, 0) -> (5, 0)\n  mill (5, 0) -> (25, 0)\n  sweep (25, 0) -> (30, 0)\n}\n";
const PROJECT: &str = "# a project\n# with two slots\npath 2010.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (50, 0)\n  sweep (0, 0) -> (10, 10)\n  sub (10, 10) -> (40, 10)  >2001.1P\n  sweep (40, 10) -> (10, 30)\n  # the second slot\n  # below the first\n  sub (10, 30) -> (40, 30)  >2001.1P\n  sweep (40, 30) -> (50, 0)\n}\n";
/// One chain of three mill segments and a single one.
const CHAINS: &str = "path 2030.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (40, 0)\n  mill (0, 0) -> (10, 0)  N1\n  mill (10, 0) -> (10, 10)  N2\n  mill (10, 10) -> (20, 10)  N3\n  sweep (20, 10) -> (30, 0)  N4\n  mill (30, 0) -> (40, 0)  N5\n}\n";

fn setup() -> (tempfile::TempDir, Workspace) {
    workspace(&[
        ("2001.mpath", PART),
        ("2010.mpath", PROJECT),
        ("2030.mpath", CHAINS),
    ])
}

/// Applies the rename edits of one file (positions are line/UTF-16 column).
fn apply(text: &str, edits: &[&FileEdit]) -> String {
    let idx = LineIndex::new(text);
    let mut e: Vec<(usize, usize, String)> = edits
        .iter()
        .map(|x| {
            (
                idx.offset(x.location.start),
                idx.offset(x.location.end),
                x.text.clone(),
            )
        })
        .collect();
    e.sort_by_key(|x| std::cmp::Reverse(x.0));
    let mut s = text.to_string();
    for (a, b, t) in e {
        s.replace_range(a..b, &t);
    }
    s
}

#[test]
fn rename_edits_every_header_and_embedding_in_text_files() {
    let (dir, mut ws) = setup();
    // the project is open with unsaved changes: the buffer is edited, not the disk
    let project = PROJECT.replace("# with two slots", "# with two slots (unsaved)");
    ws.overlays
        .insert(p(dir.path(), "2010.mpath"), project.clone());
    let a = analyze(&ws, &p(dir.path(), "2010.mpath"));
    let off = at(&project, ">2001.1P") + 3;
    let (s, e, name) = prepare_rename(&a, off).unwrap();
    assert_eq!((&project[s..e], name.as_str()), ("2001.1P", "2001.1P"));
    let edits = rename(&a, &ws, off, "2001.7Q").unwrap();
    assert_eq!(edits.len(), 3, "{edits:?}");
    let of = |f: &str| -> Vec<&FileEdit> {
        edits
            .iter()
            .filter(|e| e.location.path == p(dir.path(), f))
            .collect()
    };
    assert_eq!(
        apply(PART, &of("2001.mpath")),
        PART.replace("2001.1P", "2001.7Q")
    );
    let renamed = apply(&project, &of("2010.mpath"));
    assert_eq!(renamed, project.replace(">2001.1P", ">2001.7Q"));
    // after the edits the project compiles against the renamed part as before
    ws.overlays.insert(p(dir.path(), "2010.mpath"), renamed);
    ws.overlays
        .insert(p(dir.path(), "2001.mpath"), apply(PART, &of("2001.mpath")));
    assert_eq!(
        analyze(&ws, &p(dir.path(), "2010.mpath")).diagnostics,
        vec![]
    );
    // from the header: the same edits
    let part = analyze(&ws, &p(dir.path(), "2001.mpath"));
    assert_eq!(
        rename(&part, &ws, 7, "2001.8Q").unwrap().len(),
        3,
        "from the header"
    );
}

#[test]
fn rename_refuses_invalid_names_names_in_use_and_names_in_drawings() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2001.mpath"));
    for bad in ["2001", "slot", "2001.1PP", "2001.1P x", ""] {
        let e = rename(&a, &ws, 7, bad).unwrap_err();
        assert!(e.contains("not a valid path name"), "{bad}: {e}");
    }
    // the file 2001.mpath is found for 2001.* only
    let e = rename(&a, &ws, 7, "2002.1P").unwrap_err();
    assert!(e.contains("2001.mpath") && e.contains("file name"), "{e}");
    // an existing name
    let e = rename(&a, &ws, 7, "2010.1P").unwrap_err();
    assert!(e.contains("already exists"), "{e}");
    // German
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\nlang = \"de\"\n",
    )
    .unwrap();
    let de = analyze(&ws, &p(dir.path(), "2001.mpath"));
    {
        let e = rename(&de, &ws, 7, "slot").unwrap_err();
        assert!(e.contains("kein gültiger Pfadname"), "{e}");
    }
    // a DXF drawing embedding the name: refused, naming the drawing
    let mut w = millpath_dxf::writer::DxfWriter::new();
    w.circle("2040_1P", Some("PHANTOM"), (0.0, 0.0), 0.5)
        .line("2040_1P", Some("DASHDOT"), (0.0, 0.0), (30.0, 0.0))
        .mtext("2040_1P", (15.0, 0.0), 0.3, &[">2001.1P"]);
    std::fs::write(dir.path().join("2040.dxf"), w.finish()).unwrap();
    let e = rename(&a, &ws, 7, "2001.7Q").unwrap_err();
    assert!(e.contains("2040.dxf") && e.contains("DXF"), "{e}");
    // a DXF defining the name
    std::fs::remove_file(dir.path().join("2040.dxf")).unwrap();
    let mut w = millpath_dxf::writer::DxfWriter::new();
    w.circle("2030_1P", Some("PHANTOM"), (0.0, 0.0), 0.5);
    std::fs::write(dir.path().join("2030.dxf"), w.finish()).unwrap();
    let c = analyze(&ws, &p(dir.path(), "2030.mpath"));
    let e = rename(&c, &ws, 7, "2030.2P").unwrap_err();
    assert!(e.contains("2030.dxf"), "{e}");
    // a name a drawing defines is in use
    let e = rename(&a, &ws, 7, "2001.9P").unwrap();
    assert_eq!(e.len(), 3);
    let mut w = millpath_dxf::writer::DxfWriter::new();
    w.circle("2001_9P", Some("PHANTOM"), (0.0, 0.0), 0.5);
    std::fs::write(dir.path().join("2001.9.dxf"), w.finish()).unwrap();
    let e = rename(&a, &ws, 7, "2001.9P").unwrap_err();
    assert!(
        e.contains("already exists in") && e.contains("2001.9.dxf"),
        "{e}"
    );
}

#[test]
fn folding_ranges_of_paths_and_comment_blocks() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2010.mpath"));
    let idx = LineIndex::new(PROJECT);
    let folds: Vec<(u32, u32, FoldKind)> = folding_ranges(&a)
        .iter()
        .map(|f| (idx.pos(f.start).line, idx.pos(f.end).line, f.kind))
        .collect();
    assert_eq!(
        folds,
        vec![
            (0, 1, FoldKind::Comment),
            (2, 11, FoldKind::Path),
            (8, 9, FoldKind::Comment)
        ]
    );
}

#[test]
fn document_links_open_the_defining_file() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2010.mpath"));
    let links = document_links(&a, &ws);
    assert_eq!(links.len(), 2);
    for l in &links {
        assert_eq!(&PROJECT[l.start..l.end], "2001.1P");
        assert_eq!(l.target, p(dir.path(), "2001.mpath"));
        assert_eq!(l.line, 0);
    }
    // a missing subpath is no link
    let mut ws = ws;
    let broken = PROJECT.replacen(">2001.1P", ">2002.1P", 1);
    ws.overlays
        .insert(p(dir.path(), "2010.mpath"), broken.clone());
    let a = analyze(&ws, &p(dir.path(), "2010.mpath"));
    assert_eq!(document_links(&a, &ws).len(), 1);
}

#[test]
fn highlights_of_names_and_chains() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2010.mpath"));
    let hs = document_highlights(&a, at(PROJECT, ">2001.1P") + 2);
    let texts: Vec<&str> = hs.iter().map(|h| &PROJECT[h.start..h.end]).collect();
    assert_eq!(texts, vec![">2001.1P", ">2001.1P"]);
    let hs = document_highlights(&a, at(PROJECT, "2010.1P"));
    assert!(hs.len() == 1 && hs[0].write);
    // an element: every element of its chain
    let c = analyze(&ws, &p(dir.path(), "2030.mpath"));
    let hs = document_highlights(&c, at(CHAINS, "mill (10, 0)"));
    let texts: Vec<&str> = hs.iter().map(|h| &CHAINS[h.start..h.end]).collect();
    assert_eq!(
        texts,
        vec![
            "mill (0, 0) -> (10, 0)",
            "mill (10, 0) -> (10, 10)",
            "mill (10, 10) -> (20, 10)"
        ]
    );
    let hs = document_highlights(&c, at(CHAINS, "mill (30, 0)"));
    let texts: Vec<&str> = hs.iter().map(|h| &CHAINS[h.start..h.end]).collect();
    assert_eq!(texts, vec!["mill (30, 0) -> (40, 0)"]);
}

#[test]
fn selection_ranges_grow_from_parameter_to_file() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2001.mpath"));
    let r = selection_ranges(&a, at(PART, "I1,5") + 1);
    let texts: Vec<&str> = r.iter().map(|(s, e)| &PART[*s..*e]).collect();
    assert_eq!(texts[0], "I1,5");
    assert_eq!(texts[1], "start (0, 0)  M10x3 O2 T3 I1,5 B-0,2");
    assert!(texts[2].starts_with("path 2001.1P {") && texts[2].ends_with('}'));
    assert_eq!(texts[3], PART);
    assert!(r.windows(2).all(|w| w[1].0 <= w[0].0 && w[0].1 <= w[1].1));
}

#[test]
fn range_formatting_touches_only_the_paths_in_range() {
    let (dir, mut ws) = setup();
    let path = p(dir.path(), "2030.mpath");
    let messy = "path 2030.1P {\n   mill (0,0)->(1,1)   B1\n}\n\npath 2030.2P {\n   mill (0,0)->(1,1)   B1\n}\n";
    ws.overlays.insert(path.clone(), messy.into());
    let a = analyze(&ws, &path);
    let second = at(messy, "path 2030.2P");
    let edits = format_range(&a, second + 20, second + 25).unwrap();
    assert_eq!(edits.len(), 1);
    let mut out = messy.to_string();
    out.replace_range(edits[0].start..edits[0].end, &edits[0].text);
    assert_eq!(
        out,
        "path 2030.1P {\n   mill (0,0)->(1,1)   B1\n}\n\npath 2030.2P {\n  mill (0, 0) -> (1, 1)  B1\n}\n"
    );
    // a no-op on formatted text (every example, every range)
    for f in ["2001.mpath", "2010.mpath", "2020.mpath"] {
        let text = std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../examples/text")
                .join(f),
        )
        .unwrap();
        ws.overlays.insert(path.clone(), text.clone());
        let a = analyze(&ws, &path);
        assert_eq!(format(&a).as_deref(), Some(text.as_str()), "{f}");
        assert_eq!(format_range(&a, 0, text.len()), Some(vec![]), "{f}");
    }
}

#[test]
fn symbol_selection_is_the_name() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2001.mpath"));
    let s = &document_symbols(&a)[0];
    assert_eq!(&PART[s.name_start..s.name_end], "2001.1P");
    assert!(s.end - s.start > 100);
    let c = &s.children[3];
    assert_eq!(&PART[c.name_start..c.name_end], "mill (5, 0) -> (25, 0)");
}

/// The hover's value table is a GFM table: header, separator, rows of the same width, and
/// nothing glued to its last row.
#[test]
fn hover_table_is_a_well_formed_markdown_table() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2001.mpath"));
    let md = hover(&a, &ws, at(PART, "mill (5")).unwrap().markdown;
    let lines: Vec<&str> = md.lines().collect();
    let first = lines.iter().position(|l| l.starts_with('|')).unwrap();
    let table: Vec<&str> = lines[first..]
        .iter()
        .take_while(|l| l.starts_with('|'))
        .copied()
        .collect();
    let cells = |l: &str| -> Vec<String> {
        l.trim_matches('|')
            .split('|')
            .map(|c| c.trim().to_string())
            .collect()
    };
    assert_eq!(cells(table[0]), vec!["parameter", "value", "from"], "{md}");
    // the separator row, columns left-aligned like their values
    assert!(cells(table[1]).iter().all(|c| c == ":--"), "{md}");
    assert!(table.len() > 3);
    for row in &table {
        assert_eq!(cells(row).len(), 3, "{row}");
        assert!(cells(row).iter().all(|c| !c.is_empty()), "{row}");
    }
    assert!(lines[first - 1].is_empty(), "a blank line before: {md}");
    let after = lines.get(first + table.len()).copied().unwrap_or("");
    assert!(after.is_empty(), "a blank line after: {md}");
    assert!(md.contains("\npasses: "), "{md}");
}

#[test]
fn completion_does_not_offer_the_unused_c() {
    let (dir, mut ws) = setup();
    let path = p(dir.path(), "2001.mpath");
    for (el, needle) in [
        ("start (0, 0)  ", "start (0, 0)  "),
        ("drill (3, 3) d2  ", "drill (3, 3) d2  "),
    ] {
        let src = PART.replace("  end (30, 0)\n", &format!("  end (30, 0)\n  {el}\n"));
        ws.overlays.insert(path.clone(), src.clone());
        let a = analyze(&ws, &path);
        let off = src.rfind(needle).unwrap() + needle.len();
        let labels: Vec<String> = completion(&a, &ws, off)
            .into_iter()
            .map(|c| c.label)
            .collect();
        assert!(!labels.is_empty(), "{el}");
        assert!(!labels.contains(&"C".to_string()), "{el}: {labels:?}");
    }
}

#[test]
fn a_diagnostic_range_stops_before_the_trailing_comment() {
    let (dir, mut ws) = setup();
    let path = p(dir.path(), "2001.mpath");
    let src = PART.replace(
        "  mill (5, 0) -> (25, 0)\n",
        "  mill (5, 0) -> (25, 0)  B-0,2 T7 # ä😀 note\n",
    );
    ws.overlays.insert(path.clone(), src.clone());
    let a = analyze(&ws, &path);
    let d = a
        .diagnostics
        .iter()
        .find(|d| diagnostic_range(&a, &d.origin).is_some_and(|(s, _)| s > 0))
        .expect("a located diagnostic");
    let (s, e) = diagnostic_range(&a, &d.origin).unwrap();
    assert_eq!(&src[s..e], "mill (5, 0) -> (25, 0)  B-0,2 T7");
}

/// The lenses' statistics say when they come from placeholder machine settings.
#[test]
fn code_lenses_say_when_machine_settings_are_missing() {
    let (dir, ws) = setup();
    let a = analyze(&ws, &p(dir.path(), "2001.mpath"));
    let title = &code_lenses(&a, &ws)[0].title;
    assert!(!title.contains("missing"), "{title}");
    std::fs::remove_file(dir.path().join("millpath.toml")).unwrap();
    let a = analyze(&ws, &p(dir.path(), "2001.mpath"));
    let title = &code_lenses(&a, &ws)[0].title;
    assert!(
        title.contains("machine settings missing (placeholders)"),
        "{title}"
    );
}

/// The toolpath view says when it shows placeholder machine settings.
#[test]
fn toolpath_says_when_machine_settings_are_missing() {
    let (dir, ws) = setup();
    let data = toolpath(&ws, &p(dir.path(), "2001.mpath"), None).unwrap();
    assert_eq!(data["warnings"], serde_json::json!([]));
    std::fs::remove_file(dir.path().join("millpath.toml")).unwrap();
    let data = toolpath(&ws, &p(dir.path(), "2001.mpath"), None).unwrap();
    let w = data["warnings"][0].as_str().unwrap_or_default();
    assert!(w.starts_with("missing machine settings: feed"), "{data}");
    // the page gets the warning with its data (the title shows it: the browser test)
    assert!(toolpath_html(&data).contains("missing machine settings: feed"));
}
