//! The extended input mode end to end, on our own drawings: a hand-written DXF with an
//! LWPOLYLINE, a closed POLYLINE with bulges, a MINSERT array and a scaled, rotated block,
//! line-type names of other CAD programs, and an ELLIPSE on a layer that is not a path.
//! Its twin drawn as LINE/ARC (text2dxf of tests/extended/drawings/7001.mpath) must compile
//! to the same G-code; the reference mode warns once per ignored entity.

mod common;

use common::{millpath, MACHINE};
use std::path::{Path, PathBuf};

fn drawings() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/extended/drawings")
}

/// A temporary folder with the hand-made drawing (`cad.dxf` → `7001.dxf`) or the twin.
fn folder(hand: bool) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    if hand {
        std::fs::copy(drawings().join("cad/7001.dxf"), dir.path().join("7001.dxf")).unwrap();
    } else {
        let src = drawings().join("7001.mpath");
        let out = millpath(
            dir.path(),
            &["text2dxf", src.to_str().unwrap(), "-o", "7001.dxf"],
        );
        assert!(out.status.success(), "{out:?}");
    }
    dir
}

fn compile(dir: &Path, extra: &[&str]) -> (i32, Vec<u8>, String) {
    let mut args = vec!["compile"];
    args.extend(MACHINE);
    args.extend(extra);
    args.push("7001.dxf");
    let out = millpath(dir, &args);
    let gcode = std::fs::read(dir.join("7001_Milling.gcode")).unwrap_or_default();
    let _ = std::fs::remove_file(dir.join("7001_Milling.gcode"));
    (
        out.status.code().unwrap_or(-1),
        gcode,
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn hand_made_cad_drawing_compiles_like_its_line_arc_twin() {
    let twin = folder(false);
    let (code, expected, _) = compile(twin.path(), &[]);
    assert_eq!(code, 0);
    assert!(expected.len() > 500);
    let hand = folder(true);
    let (code, gcode, err) = compile(hand.path(), &["--extended"]);
    assert_eq!(code, 0, "{err}");
    assert!(gcode == expected, "G-code differs:\n{err}");
    // the same through millpath.toml
    std::fs::write(hand.path().join("millpath.toml"), "input = \"extended\"\n").unwrap();
    let (code, gcode, _) = compile(hand.path(), &[]);
    assert_eq!((code, gcode == expected), (0, true));
    // and dxf2text writes plain elements, the same as for the twin
    let text = |dir: &Path| {
        let o = millpath(dir, &["dxf2text", "--extended", "7001.dxf"]);
        String::from_utf8(o.stdout).unwrap()
    };
    let plain = text(twin.path());
    assert!(plain.contains("mill arc"), "{plain}");
    assert_eq!(text(hand.path()), plain);
}

#[test]
fn reference_mode_warns_once_per_ignored_entity_with_its_line() {
    let hand = folder(true);
    let out = millpath(hand.path(), &["check", "--format", "json", "7001.dxf"]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let ignored: Vec<(String, u64)> = report["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|d| d["name"] == "IgnoredEntity")
        .map(|d| {
            (
                d["location"]["entity"].as_str().unwrap().to_string(),
                d["location"]["line"].as_u64().unwrap(),
            )
        })
        .collect();
    // the ELLIPSE is on layer Notes, not a path: no warning
    let expected = [
        ("LWPOLYLINE", 133),
        ("POLYLINE", 153),
        ("LWPOLYLINE", 225),
        ("INSERT", 255),
        ("INSERT", 275),
    ];
    let expected: Vec<(String, u64)> = expected.iter().map(|(k, l)| (k.to_string(), *l)).collect();
    assert_eq!(ignored, expected);
    let text = std::fs::read_to_string(hand.path().join("7001.dxf")).unwrap();
    for (_, line) in &ignored {
        let kind = text.lines().nth(*line as usize).unwrap();
        assert!(
            ["LWPOLYLINE", "POLYLINE", "INSERT"].contains(&kind),
            "{kind}"
        );
    }
    // human output, in German too, names the way to include them
    let de = millpath(hand.path(), &["check", "--lang", "de", "7001.dxf"]);
    let de =
        String::from_utf8_lossy(&de.stdout).into_owned() + &String::from_utf8_lossy(&de.stderr);
    assert!(de.contains("POLYLINE (Zeile 153) ignoriert"), "{de}");
    assert!(de.contains("--extended"), "{de}");
    // the reference command line stays as silent as the reference
    let out = millpath(hand.path(), &["pathdxf2gcode", "/c", "7001.dxf"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("ignored"), "{err}");
    assert!(
        err.contains("****"),
        "the drawing's real error is still there: {err}"
    );
}

#[test]
fn ellipses_and_splines_on_path_layers_are_refused_not_approximated() {
    let hand = folder(true);
    let path = hand.path().join("7001.dxf");
    let text = std::fs::read_to_string(&path).unwrap();
    // the ELLIPSE moves onto the path layer; a SPLINE joins it
    let moved = text.replace(
        "ELLIPSE\n  5\nA7\n  8\nNotes",
        "ELLIPSE\n  5\nA7\n  8\n7001_1P",
    );
    let moved = moved.replace(
        "  0\nMTEXT\n  5\nA8",
        "  0\nSPLINE\n  5\nA9\n  8\n7001_1P\n 10\n1.0\n 20\n2.0\n 30\n0.0\n  0\nMTEXT\n  5\nA8",
    );
    assert_ne!(moved, text);
    std::fs::write(&path, moved).unwrap();
    let (code, _, err) = compile(hand.path(), &["--extended"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("ELLIPSE is not supported"), "{err}");
    assert!(err.contains("SPLINE is not supported"), "{err}");
    assert!(err.contains("not approximated"), "{err}");
}

#[test]
fn blocks_that_nest_without_end_are_stopped() {
    let dir = tempfile::tempdir().unwrap();
    // block A inserts itself: resolving stops at the depth bound with a located error
    let dxf = "  0\nSECTION\n  2\nHEADER\n  9\n$ACADVER\n  1\nAC1015\n  0\nENDSEC\n  0\nSECTION\n  2\nBLOCKS\n  0\nBLOCK\n  2\nA\n 10\n0\n 20\n0\n  0\nLINE\n  8\n0\n 10\n0\n 20\n0\n 11\n1\n 21\n0\n  0\nINSERT\n  8\n0\n  2\nA\n 10\n1\n 20\n0\n 70\n2\n  0\nENDBLK\n  0\nENDSEC\n  0\nSECTION\n  2\nENTITIES\n  0\nINSERT\n  5\nB1\n  8\n7002_1P\n  2\nA\n 10\n0\n 20\n0\n  0\nENDSEC\n  0\nEOF\n";
    std::fs::write(dir.path().join("7002.dxf"), dxf).unwrap();
    let out = millpath(dir.path(), &["check", "--extended", "7002.dxf"]);
    let all =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    assert!(all.contains("nested deeper than 16"), "{all}");
    assert!(all.contains("7002.dxf:"), "{all}");
}
