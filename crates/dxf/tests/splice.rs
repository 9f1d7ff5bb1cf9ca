//! `splice`: entities replaced on the layers a caller chooses, the rest of the file kept
//! byte for byte; handles, owners and table entries for the new ones; R12 and AutoCAD 2000
//! files; broken files refused with their line, never a panic.

use millpath_dxf::read_dxf;
use millpath_dxf::splice::{scan, NewEntity, NewShape, Record};
use millpath_dxf::writer::DxfWriter;

/// An AutoCAD 2000 drawing: a path layer `1_1P` and a dimension layer with a polyline.
fn r2000() -> String {
    let mut w = DxfWriter::new();
    w.layer("1_1P", "CONTINUOUS")
        .layer("BEMASSUNG", "CONTINUOUS")
        .circle("1_1P", Some("PHANTOM"), (0.0, 0.0), 0.5)
        .line("1_1P", Some("CONTINUOUS"), (0.0, 0.0), (10.0, 0.0))
        .line("BEMASSUNG", None, (0.0, -5.0), (10.0, -5.0))
        .text("BEMASSUNG", (5.0, -6.0), 2.5, "10")
        .mtext("1_1P", (0.0, 1.0), 0.35, &["T2 O2"]);
    w.finish()
}

fn new_entities() -> Vec<NewEntity> {
    vec![
        NewEntity {
            layer: "2_1P".into(),
            linetype: Some("DASHDOT".into()),
            shape: NewShape::Line {
                a: (0.0, 0.0),
                b: (20.0, 0.0),
            },
        },
        NewEntity {
            layer: "2_1P".into(),
            linetype: Some("PHANTOM".into()),
            shape: NewShape::Circle {
                c: (0.0, 0.0),
                r: 0.5,
            },
        },
        NewEntity {
            layer: "2_1P".into(),
            linetype: None,
            shape: NewShape::Text {
                at: (0.0, 1.0),
                height: 0.35,
                value: "T3 {O2}".into(),
            },
        },
    ]
}

fn on_path_layer(r: &Record) -> bool {
    r.layer.ends_with('P')
}

fn handles_on(text: &[u8], layer: &str) -> Vec<String> {
    let d = read_dxf(text).unwrap();
    d.entities
        .iter()
        .filter(|e| e.layer == layer)
        .map(|e| e.handle.clone())
        .collect()
}

fn header_value(text: &str, var: &str) -> Option<String> {
    let lines: Vec<&str> = text.lines().collect();
    let i = lines.iter().position(|l| l.trim() == var)?;
    lines.get(i + 2).map(|s| s.trim().to_string())
}

#[test]
fn r2000_keeps_other_layers_and_raises_the_handle_seed() {
    let before = r2000();
    let t = scan(before.as_bytes()).unwrap();
    assert_eq!(t.version(), "AC1015");
    let kept_before = handles_on(before.as_bytes(), "BEMASSUNG");
    let out = t.splice(&on_path_layer, &new_entities());
    let after = String::from_utf8(out).unwrap();
    let d = read_dxf(after.as_bytes()).unwrap();

    // the dimension layer: same entities, same handles, same bytes
    assert_eq!(handles_on(after.as_bytes(), "BEMASSUNG"), kept_before);
    let dim_record = &before[before.find("  0\nTEXT\n").unwrap()..];
    let dim_record = &dim_record[..dim_record[4..].find("  0\n").unwrap() + 4];
    assert!(after.contains(dim_record));
    // the old path layer's entities are gone, the new ones are there
    assert!(handles_on(after.as_bytes(), "1_1P").is_empty());
    let new: Vec<&millpath_dxf::Entity> = d.entities.iter().filter(|e| e.layer == "2_1P").collect();
    assert_eq!(new.len(), 3);
    match &new[2].kind {
        millpath_dxf::EntityKind::MText(m) => assert_eq!(m.value, "T3 \\{O2\\}"),
        k => panic!("{k:?}"),
    }

    // handles: fresh, unique, below the raised seed; owner = the model space record
    let seed_before =
        u64::from_str_radix(&header_value(&before, "$HANDSEED").unwrap(), 16).unwrap();
    let seed = u64::from_str_radix(&header_value(&after, "$HANDSEED").unwrap(), 16).unwrap();
    let mut all: Vec<u64> = Vec::new();
    // the pairs after the header (whose group 5 is the seed itself)
    let lines: Vec<&str> = after[after.find("ENDSEC").unwrap()..]
        .lines()
        .skip(1)
        .collect();
    for w in lines.chunks(2) {
        if matches!(w[0].trim(), "5" | "105") {
            all.push(u64::from_str_radix(w[1].trim(), 16).unwrap());
        }
    }
    let unique: std::collections::BTreeSet<u64> = all.iter().copied().collect();
    assert_eq!(unique.len(), all.len(), "duplicate handles");
    assert!(
        all.iter().all(|&h| h < seed),
        "seed {seed:X} not above every handle"
    );
    for e in &new {
        let h = u64::from_str_radix(&e.handle, 16).unwrap();
        assert!(h >= seed_before && h < seed);
        let at = after.find(&format!("  5\n{}\n", e.handle)).unwrap();
        assert!(after[at..].starts_with(&format!("  5\n{}\n330\n17\n", e.handle)));
    }

    // tables completed: the new layer and the new line type
    assert_eq!(d.layers.get("2_1P").map(String::as_str), Some("CONTINUOUS"));
    assert!(d.linetypes.iter().any(|l| l == "DASHDOT"));
    assert_eq!(d.linetypes.iter().filter(|l| *l == "PHANTOM").count(), 1);
    // everything before the ENTITIES section but the seed and the tables is as it was
    let cut = |s: &str| s[..s.find("$HANDSEED").unwrap()].to_string();
    assert_eq!(cut(&before), cut(&after));
    let tail = |s: &str| s[s.find("OBJECTS").unwrap()..].to_string();
    assert_eq!(tail(&before), tail(&after));
}

/// An R12 file as old CAD programs write it: no handles, no subclasses, CR LF line ends.
fn r12() -> String {
    let pairs: &[(i32, &str)] = &[
        (0, "SECTION"),
        (2, "HEADER"),
        (9, "$ACADVER"),
        (1, "AC1009"),
        (0, "ENDSEC"),
        (0, "SECTION"),
        (2, "TABLES"),
        (0, "TABLE"),
        (2, "LTYPE"),
        (70, "1"),
        (0, "LTYPE"),
        (2, "CONTINUOUS"),
        (70, "0"),
        (3, "Solid line"),
        (72, "65"),
        (73, "0"),
        (40, "0.0"),
        (0, "ENDTAB"),
        (0, "TABLE"),
        (2, "LAYER"),
        (70, "2"),
        (0, "LAYER"),
        (2, "0"),
        (70, "0"),
        (62, "7"),
        (6, "CONTINUOUS"),
        (0, "LAYER"),
        (2, "MASSE"),
        (70, "0"),
        (62, "1"),
        (6, "CONTINUOUS"),
        (0, "ENDTAB"),
        (0, "ENDSEC"),
        (0, "SECTION"),
        (2, "ENTITIES"),
        (0, "LINE"),
        (8, "1_1P"),
        (10, "0.0"),
        (20, "0.0"),
        (30, "0.0"),
        (11, "5.0"),
        (21, "0.0"),
        (31, "0.0"),
        (0, "POLYLINE"),
        (8, "1_1P"),
        (66, "1"),
        (0, "VERTEX"),
        (8, "1_1P"),
        (10, "0.0"),
        (20, "0.0"),
        (0, "SEQEND"),
        (8, "1_1P"),
        (0, "LINE"),
        (8, "MASSE"),
        (10, "0.0"),
        (20, "-3.0"),
        (30, "0.0"),
        (11, "5.0"),
        (21, "-3.0"),
        (31, "0.0"),
        (0, "ENDSEC"),
        (0, "EOF"),
    ];
    pairs
        .iter()
        .map(|(c, v)| format!("{c:>3}\r\n{v}\r\n"))
        .collect()
}

#[test]
fn r12_without_handles_stays_without_handles_and_keeps_its_line_ends() {
    let before = r12();
    let t = scan(before.as_bytes()).unwrap();
    let kinds: Vec<&str> = t.entities().iter().map(|r| r.kind.as_str()).collect();
    // VERTEX and SEQEND belong to their POLYLINE
    assert_eq!(kinds, ["LINE", "POLYLINE", "LINE"]);
    let after = String::from_utf8(t.splice(&on_path_layer, &new_entities())).unwrap();
    assert!(
        !after.replace("\r\n", "").contains('\n'),
        "a lone LF line end"
    );
    assert!(!after.contains("  5\r\n") && !after.contains("100\r\n"));
    assert!(!after.contains("VERTEX") && !after.contains("POLYLINE"));
    assert!(!after.contains("MTEXT"), "R12 has no MTEXT");
    let d = read_dxf(after.as_bytes()).unwrap();
    let layers: Vec<&str> = d.entities.iter().map(|e| e.layer.as_str()).collect();
    assert_eq!(layers, ["MASSE", "2_1P", "2_1P", "2_1P"]);
    match &d.entities[3].kind {
        millpath_dxf::EntityKind::Text(t) => assert_eq!(t.value, "T3 {O2}"),
        k => panic!("{k:?}"),
    }
    // the tables got the new layer and line types, and their counts
    assert!(d.layers.contains_key("2_1P"));
    assert!(d.linetypes.iter().any(|l| l == "PHANTOM"));
    assert!(after.contains("LAYER\r\n 70\r\n3\r\n"));
    assert!(after.contains("LTYPE\r\n 70\r\n3\r\n"));
}

#[test]
fn r12_with_handles_gets_handles() {
    // a handle on an entity and a seed: new entities continue from the seed
    let before = r12()
        .replace(
            "  0\r\nLINE\r\n  8\r\nMASSE",
            "  0\r\nLINE\r\n  5\r\n2A\r\n  8\r\nMASSE",
        )
        .replace(
            "  9\r\n$ACADVER\r\n  1\r\nAC1009\r\n",
            "  9\r\n$ACADVER\r\n  1\r\nAC1009\r\n  9\r\n$HANDSEED\r\n  5\r\n30\r\n",
        );
    let t = scan(before.as_bytes()).unwrap();
    let after = String::from_utf8(t.splice(&on_path_layer, &new_entities())).unwrap();
    let d = read_dxf(after.as_bytes()).unwrap();
    let handles: Vec<&str> = d.entities.iter().map(|e| e.handle.as_str()).collect();
    assert_eq!(handles[0], "2A");
    assert!(handles[1..]
        .iter()
        .all(|h| u64::from_str_radix(h, 16).unwrap() >= 0x30));
    assert!(!after.contains("330\r\n"), "R12 has no owners");
}

#[test]
fn a_file_without_entities_section_gets_one() {
    let before = r12();
    let start = before.find("  0\r\nSECTION\r\n  2\r\nENTITIES").unwrap();
    let end = before.find("  0\r\nEOF").unwrap();
    let before = format!("{}{}", &before[..start], &before[end..]);
    let t = scan(before.as_bytes()).unwrap();
    let after = t.splice(&on_path_layer, &new_entities());
    assert_eq!(read_dxf(&after).unwrap().entities.len(), 3);
}

#[test]
fn broken_files_are_refused_with_their_line_and_never_panic() {
    let good = r2000();
    let err = scan(&good.as_bytes()[..good.len() / 2]).err().unwrap();
    assert!(err.line > 0, "{err}");
    let bad = good.replacen(" 40\n0.5\n", " 40\nzero\n", 1);
    let err = scan(bad.as_bytes()).err().unwrap();
    assert!(err.to_string().contains("zero") && err.line > 0, "{err}");
    // every cut of a file: a result or an error, no panic
    let small = r12();
    for cut in 0..small.len() {
        if let Ok(t) = scan(&small.as_bytes()[..cut]) {
            let _ = t.splice(&on_path_layer, &new_entities());
        }
    }
}

#[test]
fn code_page_is_kept_for_new_texts() {
    // windows-1252: `°` is one byte; a character it lacks becomes \U+XXXX
    let before = r2000();
    let t = scan(before.as_bytes()).unwrap();
    let new = vec![NewEntity {
        layer: "2_1P".into(),
        linetype: None,
        shape: NewShape::Text {
            at: (0.0, 0.0),
            height: 1.0,
            value: "Ω 45°".into(),
        },
    }];
    let out = t.splice(&on_path_layer, &new);
    assert!(out.windows(11).any(|w| w == b"\\U+03A9 45\xB0"));
    let d = read_dxf(&out).unwrap();
    match &d.entities.last().unwrap().kind {
        millpath_dxf::EntityKind::MText(m) => assert_eq!(m.value, "Ω 45°"),
        k => panic!("{k:?}"),
    }
}
