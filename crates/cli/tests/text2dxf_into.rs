//! `text2dxf` never destroys a drawing: it refuses to overwrite a DXF holding what it does
//! not write back (unless `--force`), and `--into` writes the paths into the drawing,
//! keeping the rest. On the examples, an R12 drawing, broken drawings and every shared
//! drawing (skipped without ../shared).

mod common;

use common::{millpath, MACHINE};
use std::path::{Path, PathBuf};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/text")
        .join(name)
}

/// A copy the test may change: the shared drawings are read-only, and `std::fs::copy` keeps
/// that (text2dxf refuses to replace a read-only drawing).
fn copy_writable(from: &Path, to: &Path) {
    std::fs::copy(from, to).unwrap();
    let mut p = std::fs::metadata(to).unwrap().permissions();
    #[allow(clippy::permissions_set_readonly_false)]
    p.set_readonly(false);
    std::fs::set_permissions(to, p).unwrap();
}

fn ok(o: &std::process::Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A LINE on a dimension layer, put into the ENTITIES section of a drawing we wrote.
const DIMENSION: &str =
    "  0\nLINE\n  5\nFFF0\n330\n17\n100\nAcDbEntity\n  8\nMASSE\n100\nAcDbLine\n 10\n0.0\n 20\n-9.0\n 30\n0.0\n 11\n50.0\n 21\n-9.0\n 31\n0.0\n";

fn add_dimension(dxf: &Path) {
    let s = std::fs::read_to_string(dxf).unwrap();
    let at = s.find("  0\nENDSEC\n  0\nSECTION\n  2\nOBJECTS").unwrap();
    std::fs::write(dxf, format!("{}{DIMENSION}{}", &s[..at], &s[at..])).unwrap();
}

#[test]
fn overwriting_is_refused_when_content_would_be_lost() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::copy(example("2001.mpath"), d.join("2001.mpath")).unwrap();
    // our own file: nothing to lose, overwritten without --force
    ok(&millpath(d, &["text2dxf", "2001.mpath"]));
    ok(&millpath(d, &["text2dxf", "2001.mpath"]));
    // a dimension drawn in CAD: refused, named, nothing written
    add_dimension(&d.join("2001.dxf"));
    let before = std::fs::read(d.join("2001.dxf")).unwrap();
    let o = millpath(d, &["text2dxf", "2001.mpath"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains(millpath_core::Msg::WouldLoseDrawing.code().as_str())
            && err.contains("layer MASSE (1 LINE)")
            && err.contains("--into 2001.dxf")
            && err.contains("--force"),
        "{err}"
    );
    assert_eq!(std::fs::read(d.join("2001.dxf")).unwrap(), before);
    let o = millpath(d, &["text2dxf", "2001.mpath", "--lang", "de"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("Layer MASSE (1 LINE)") && err.contains("überschreiben"),
        "{err}"
    );
    // --force overwrites
    ok(&millpath(d, &["text2dxf", "2001.mpath", "--force"]));
    assert!(!std::fs::read_to_string(d.join("2001.dxf"))
        .unwrap()
        .contains("MASSE"));
    // something that is no DXF at all is not overwritten either
    std::fs::write(d.join("notes.dxf"), "my notes\n").unwrap();
    let o = millpath(d, &["text2dxf", "2001.mpath", "-o", "notes.dxf"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains(millpath_core::Msg::NotOursToOverwrite.code().as_str()),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(d.join("notes.dxf")).unwrap(),
        "my notes\n"
    );
}

#[test]
fn into_keeps_the_rest_of_the_drawing_and_writes_the_edited_paths() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::copy(example("2001.mpath"), d.join("2001.mpath")).unwrap();
    ok(&millpath(d, &["text2dxf", "2001.mpath"]));
    add_dimension(&d.join("2001.dxf"));
    // the text edited: another depth
    let text = std::fs::read_to_string(d.join("2001.mpath")).unwrap();
    let edited = text.replacen("T3", "T4", 1);
    assert_ne!(text, edited);
    std::fs::write(d.join("2001.mpath"), &edited).unwrap();
    ok(&millpath(
        d,
        &["text2dxf", "2001.mpath", "--into", "2001.dxf"],
    ));
    let back = std::fs::read_to_string(d.join("2001.dxf")).unwrap();
    assert!(
        back.contains(DIMENSION),
        "the dimension is kept byte for byte"
    );
    // the drawing reads back as the edited text, and compiles as it
    let from_drawing = ok(&millpath(d, &["dxf2text", "2001.dxf"]));
    ok(&millpath(d, &["text2dxf", "2001.mpath", "-o", "fresh.dxf"]));
    assert_eq!(from_drawing, ok(&millpath(d, &["dxf2text", "fresh.dxf"])));
    assert!(from_drawing.contains("T4"));
    // -o writes elsewhere and leaves the drawing as it is
    let before = std::fs::read(d.join("2001.dxf")).unwrap();
    ok(&millpath(
        d,
        &[
            "text2dxf",
            "2001.mpath",
            "--into",
            "2001.dxf",
            "-o",
            "copy.dxf",
        ],
    ));
    assert_eq!(std::fs::read(d.join("2001.dxf")).unwrap(), before);
    assert_eq!(ok(&millpath(d, &["dxf2text", "copy.dxf"])), from_drawing);
}

/// An R12 drawing without handles, with CR LF line ends and a dimension layer.
const R12: &str = "  0\r\nSECTION\r\n  2\r\nHEADER\r\n  9\r\n$ACADVER\r\n  1\r\nAC1009\r\n  0\r\nENDSEC\r\n  0\r\nSECTION\r\n  2\r\nTABLES\r\n  0\r\nTABLE\r\n  2\r\nLAYER\r\n 70\r\n1\r\n  0\r\nLAYER\r\n  2\r\nMASSE\r\n 70\r\n0\r\n 62\r\n1\r\n  6\r\nCONTINUOUS\r\n  0\r\nENDTAB\r\n  0\r\nENDSEC\r\n  0\r\nSECTION\r\n  2\r\nENTITIES\r\n  0\r\nLINE\r\n  8\r\nMASSE\r\n 10\r\n0.0\r\n 20\r\n-9.0\r\n 30\r\n0.0\r\n 11\r\n50.0\r\n 21\r\n-9.0\r\n 31\r\n0.0\r\n  0\r\nENDSEC\r\n  0\r\nEOF\r\n";

#[test]
fn into_an_r12_drawing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::copy(example("2010.mpath"), d.join("2010.mpath")).unwrap();
    std::fs::write(d.join("r12.dxf"), R12).unwrap();
    // a plain text2dxf would lose the dimension
    assert_eq!(
        millpath(d, &["text2dxf", "2010.mpath", "-o", "r12.dxf"])
            .status
            .code(),
        Some(1)
    );
    ok(&millpath(
        d,
        &["text2dxf", "2010.mpath", "--into", "r12.dxf"],
    ));
    let back = std::fs::read_to_string(d.join("r12.dxf")).unwrap();
    assert!(back.starts_with(&R12[..R12.find("  0\r\nTABLE").unwrap()]));
    // the layer table got the path layer, and its count
    assert!(back.contains("  2\r\nLAYER\r\n 70\r\n2\r\n  0\r\nLAYER\r\n  2\r\nMASSE\r\n"));
    assert!(back.contains("  0\r\nLAYER\r\n  2\r\n2010_1P\r\n"));
    assert!(!back.replace("\r\n", "").contains('\n'), "CR LF kept");
    assert!(!back.contains("\r\n100\r\n") && !back.contains("\r\nMTEXT\r\n"));
    assert!(back.contains("  0\r\nLINE\r\n  8\r\nMASSE\r\n 10\r\n0.0\r\n 20\r\n-9.0\r\n"));
    ok(&millpath(d, &["text2dxf", "2010.mpath", "-o", "fresh.dxf"]));
    assert_eq!(
        ok(&millpath(d, &["dxf2text", "r12.dxf"])),
        ok(&millpath(d, &["dxf2text", "fresh.dxf"]))
    );
}

#[test]
fn a_broken_drawing_is_a_located_error_and_stays_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::copy(example("2001.mpath"), d.join("2001.mpath")).unwrap();
    let cut = &R12[..R12.find(" 21\r\n-9.0").unwrap() + 5];
    std::fs::write(d.join("cut.dxf"), cut).unwrap();
    let o = millpath(d, &["text2dxf", "2001.mpath", "--into", "cut.dxf"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("cut.dxf") && err.contains("line "), "{err}");
    assert_eq!(std::fs::read_to_string(d.join("cut.dxf")).unwrap(), cut);
    let names: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
    // a missing drawing
    let o = millpath(d, &["text2dxf", "2001.mpath", "--into", "none.dxf"]);
    assert_eq!(o.status.code(), Some(1));
}

/// Every shared drawing: dxf2text, then --into a copy of itself: the copy reads back as the
/// same text, keeps every non-path entity, and compiles to the same G-code.
#[test]
fn into_every_shared_drawing_changes_nothing_it_should_not() {
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/conformance/fixtures");
    let Ok(rd) = std::fs::read_dir(&shared) else {
        eprintln!("skipped: {} is absent", shared.display());
        return;
    };
    let mut files: Vec<PathBuf> = rd
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "dxf"))
        .collect();
    files.sort();
    let mut done = 0;
    for f in files {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a"), dir.path().join("b"));
        std::fs::create_dir(&a).unwrap();
        std::fs::create_dir(&b).unwrap();
        let name = f.file_name().unwrap().to_str().unwrap();
        copy_writable(&f, &a.join(name));
        copy_writable(&f, &b.join(name));
        let text = ok(&millpath(&b, &["dxf2text", name]));
        std::fs::write(b.join("t.mpath"), &text).unwrap();
        ok(&millpath(&b, &["text2dxf", "t.mpath", "--into", name]));
        assert_eq!(ok(&millpath(&b, &["dxf2text", name])), text, "{name}");
        // written back again, the same text changes no byte (issue 31)
        let once = std::fs::read(b.join(name)).unwrap();
        ok(&millpath(&b, &["text2dxf", "t.mpath", "--into", name]));
        assert!(
            std::fs::read(b.join(name)).unwrap() == once,
            "{name}: a second --into"
        );
        let orig = std::fs::read(&f).unwrap();
        let back = std::fs::read(b.join(name)).unwrap();
        let kept = |bytes: &[u8]| -> Vec<(String, String, String)> {
            let t = millpath_dxf::splice::scan(bytes).unwrap();
            t.entities()
                .iter()
                .filter(|r| {
                    // a parameter-text layer `PATH~A` belongs to its path
                    let base = r.layer.split('~').next().unwrap_or_default();
                    !text.contains(&format!("path {} ", base.replace('_', ".")))
                })
                .map(|r| (r.layer.clone(), r.kind.clone(), r.handle.clone()))
                .collect()
        };
        assert_eq!(kept(&orig), kept(&back), "{name}: non-path entities");
        let mut args = vec!["compile"];
        args.extend(MACHINE);
        args.push(name);
        let (ca, cb) = (millpath(&a, &args), millpath(&b, &args));
        assert_eq!(ca.status.code(), cb.status.code(), "{name}");
        for e in std::fs::read_dir(&a).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|e| e == "gcode" || e == "txt") {
                let other = b.join(p.file_name().unwrap());
                assert_eq!(
                    std::fs::read(&p).unwrap(),
                    std::fs::read(&other).unwrap(),
                    "{name}: {}",
                    p.display()
                );
            }
        }
        done += 1;
    }
    assert!(done > 0);
}

/// Entity types on a layer of a DXF's ENTITIES section (its own group 8; polyline
/// vertices and attributes not counted).
fn kinds_on(dxf: &str, layer: &str) -> Vec<String> {
    let lines: Vec<&str> = dxf.lines().map(str::trim).collect();
    let pairs: Vec<(&str, &str)> = lines.chunks_exact(2).map(|p| (p[0], p[1])).collect();
    let start = pairs.iter().position(|p| *p == ("2", "ENTITIES"));
    let mut kinds = Vec::new();
    let mut current: Option<&str> = None;
    for (code, value) in pairs.iter().skip(start.map_or(pairs.len(), |s| s + 1)) {
        match *code {
            "0" if *value == "ENDSEC" => break,
            "0" => current = Some(*value).filter(|v| !["VERTEX", "SEQEND", "ATTRIB"].contains(v)),
            "8" => {
                if let Some(kind) = current.take() {
                    if *value == layer {
                        kinds.push(kind.to_string());
                    }
                }
            }
            _ => {}
        }
    }
    kinds.sort();
    kinds
}

/// `--extended`: a CAD drawing with polylines and block references on its path layer, turned
/// into text by `dxf2text --extended`, goes back with `text2dxf --extended --into`. Unedited,
/// the drawing stays byte for byte. Edited, the polylines and blocks are replaced by the
/// text's lines and arcs (the edited text's G-code), the ELLIPSE on a layer of notes stays.
/// Without `--extended` they are kept, and a warning says that the paths may now be drawn
/// twice.
#[test]
fn extended_into_replaces_polylines_and_blocks_and_plain_into_warns() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cad =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/extended/drawings/cad/7001.dxf");
    copy_writable(&cad, &d.join("7001.dxf"));
    let mut compile = vec!["compile", "--extended"];
    compile.extend(MACHINE);
    compile.push("7001.dxf");
    ok(&millpath(
        d,
        &["dxf2text", "--extended", "7001.dxf", "-o", "7001.mpath"],
    ));
    let original = std::fs::read_to_string(&cad).unwrap();
    for k in ["INSERT", "LWPOLYLINE", "POLYLINE"] {
        assert!(kinds_on(&original, "7001_1P").contains(&k.to_string()));
    }

    // unedited: the path is as the drawing has it, nothing is written
    ok(&millpath(
        d,
        &["text2dxf", "--extended", "7001.mpath", "--into", "7001.dxf"],
    ));
    assert!(std::fs::read_to_string(d.join("7001.dxf")).unwrap() == original);

    // edited: replaced, no warning, the edited text's G-code without --extended
    let text = std::fs::read_to_string(d.join("7001.mpath")).unwrap();
    assert!(text.contains(" I1,5 "), "{text}");
    std::fs::write(d.join("7001.mpath"), text.replacen(" I1,5 ", " I1 ", 1)).unwrap();
    let t = d.join("text");
    std::fs::create_dir(&t).unwrap();
    std::fs::copy(d.join("7001.mpath"), t.join("7001.mpath")).unwrap();
    let mut of_text = vec!["compile"];
    of_text.extend(MACHINE);
    of_text.push("7001.mpath");
    ok(&millpath(&t, &of_text));
    let expected = std::fs::read_to_string(t.join("7001_Milling.gcode"))
        .unwrap()
        .replace("7001.mpath", "7001");
    let o = millpath(
        d,
        &["text2dxf", "--extended", "7001.mpath", "--into", "7001.dxf"],
    );
    ok(&o);
    let warning = millpath_core::Msg::IntoKeptExtended.code();
    assert!(!String::from_utf8_lossy(&o.stderr).contains(&warning));
    let back = std::fs::read_to_string(d.join("7001.dxf")).unwrap();
    let kinds = kinds_on(&back, "7001_1P");
    for k in ["INSERT", "LWPOLYLINE", "POLYLINE"] {
        assert!(!kinds.contains(&k.to_string()), "{kinds:?}");
    }
    assert_eq!(kinds_on(&back, "Notes"), kinds_on(&original, "Notes"));
    compile.retain(|a| *a != "--extended");
    ok(&millpath(d, &compile));
    let of_drawing = std::fs::read_to_string(d.join("7001_Milling.gcode")).unwrap();
    assert_eq!(of_drawing.replace("7001.dxf", "7001"), expected);

    // without --extended: kept, with a warning that names them and the way out
    copy_writable(&cad, &d.join("7001.dxf"));
    let o = millpath(d, &["text2dxf", "7001.mpath", "--into", "7001.dxf"]);
    ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains(&format!("warning[{warning}]"))
            && err.contains("layer 7001_1P (2 INSERT, 2 LWPOLYLINE, 1 POLYLINE)")
            && err.contains("text2dxf --extended --into 7001.dxf"),
        "{err}"
    );
    let back = std::fs::read_to_string(d.join("7001.dxf")).unwrap();
    assert!(kinds_on(&back, "7001_1P").contains(&"LWPOLYLINE".to_string()));
}

/// A library drawing of two paths, made from our own text.
const LIBRARY: &str = "path 8998.1P {
  start (0, 0)  M3 O2 T3 I1,5 B2,5
  end (60, 0)
  mill (0, 0) -> (60, 0)
}

path 8998.2P {
  start (0, 20)  M3 O2 T3 I1,5 B2,5
  end (40, 20)
  mill (0, 20) -> (40, 20)
}
";

/// The text of one path written into a library of several: the paths missing from the text
/// are named and nothing is written; `--delete-missing-paths` deletes them on purpose.
#[test]
fn into_a_library_refuses_to_delete_the_paths_the_text_lacks() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("lib.mpath"), LIBRARY).unwrap();
    ok(&millpath(d, &["text2dxf", "lib.mpath", "-o", "lib.dxf"]));
    add_dimension(&d.join("lib.dxf"));
    let one = &LIBRARY[..LIBRARY.find("\npath 8998.2P").unwrap()];
    std::fs::write(d.join("one.mpath"), one.replace("T3", "T4")).unwrap();
    let before = std::fs::read(d.join("lib.dxf")).unwrap();
    for (lang, said) in [
        ("en", "lib.dxf holds paths that one.mpath does not define: 8998.2P. --into would delete them; nothing was written"),
        ("de", "lib.dxf enthält Pfade, die one.mpath nicht definiert: 8998.2P. --into würde sie löschen; es wurde nichts geschrieben"),
    ] {
        let o = millpath(d, &["text2dxf", "one.mpath", "--into", "lib.dxf", "--lang", lang]);
        assert_eq!(o.status.code(), Some(1));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(said) && err.contains("--delete-missing-paths"), "{err}");
        assert!(err.contains(millpath_core::Msg::IntoWouldDeletePaths.code().as_str()), "{err}");
        assert_eq!(std::fs::read(d.join("lib.dxf")).unwrap(), before);
    }
    // the option needs --into; its help in both languages
    let o = millpath(d, &["text2dxf", "one.mpath", "--delete-missing-paths"]);
    assert_eq!(o.status.code(), Some(2));
    let help = ok(&millpath(d, &["text2dxf", "--help"]));
    assert!(help.contains("--delete-missing-paths"), "{help}");
    let help = ok(&millpath(d, &["text2dxf", "--help", "--lang", "de"]));
    assert!(
        help.contains("die Pfade der Zeichnung löschen, die der Text nicht definiert"),
        "{help}"
    );
    // the whole text with one path edited: written, both paths there
    std::fs::write(d.join("lib.mpath"), LIBRARY.replacen("T3", "T4", 1)).unwrap();
    ok(&millpath(
        d,
        &["text2dxf", "lib.mpath", "--into", "lib.dxf"],
    ));
    let back = ok(&millpath(d, &["dxf2text", "lib.dxf"]));
    assert!(
        back.contains("path 8998.1P") && back.contains("path 8998.2P"),
        "{back}"
    );
    assert!(back.contains("T4"), "{back}");
    // a path deleted on purpose from the full text: with the option
    ok(&millpath(
        d,
        &[
            "text2dxf",
            "one.mpath",
            "--into",
            "lib.dxf",
            "--delete-missing-paths",
        ],
    ));
    let back = ok(&millpath(d, &["dxf2text", "lib.dxf"]));
    assert!(
        back.contains("path 8998.1P") && !back.contains("8998.2P"),
        "{back}"
    );
    assert!(std::fs::read_to_string(d.join("lib.dxf"))
        .unwrap()
        .contains(DIMENSION));
}

/// `--into` with a text the drawing already holds leaves the file byte for byte as it is
/// (no new handles, `$HANDSEED` as it was), so version control sees no change; on our own
/// library and on every shared sample drawing (skipped without ../shared).
#[test]
fn into_with_the_same_text_twice_leaves_the_drawing_byte_identical() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("lib.mpath"), LIBRARY).unwrap();
    ok(&millpath(d, &["text2dxf", "lib.mpath", "-o", "lib.dxf"]));
    add_dimension(&d.join("lib.dxf"));
    // the first --into writes the paths (from dxf2text's order); every later one changes nothing
    let text = ok(&millpath(d, &["dxf2text", "lib.dxf"]));
    std::fs::write(d.join("lib.mpath"), &text).unwrap();
    ok(&millpath(
        d,
        &["text2dxf", "lib.mpath", "--into", "lib.dxf"],
    ));
    let once = std::fs::read(d.join("lib.dxf")).unwrap();
    for _ in 0..2 {
        ok(&millpath(
            d,
            &["text2dxf", "lib.mpath", "--into", "lib.dxf"],
        ));
        assert_eq!(std::fs::read(d.join("lib.dxf")).unwrap(), once);
    }
    // into another file (-o): the same bytes
    ok(&millpath(
        d,
        &[
            "text2dxf",
            "lib.mpath",
            "--into",
            "lib.dxf",
            "-o",
            "copy.dxf",
        ],
    ));
    assert_eq!(std::fs::read(d.join("copy.dxf")).unwrap(), once);
    // an edit is written, and written back it is the same again
    std::fs::write(d.join("lib.mpath"), text.replacen("T3", "T4", 1)).unwrap();
    ok(&millpath(
        d,
        &["text2dxf", "lib.mpath", "--into", "lib.dxf"],
    ));
    let edited = std::fs::read(d.join("lib.dxf")).unwrap();
    assert_ne!(edited, once);
    ok(&millpath(
        d,
        &["text2dxf", "lib.mpath", "--into", "lib.dxf"],
    ));
    assert_eq!(std::fs::read(d.join("lib.dxf")).unwrap(), edited);
    // an element moved by 0.001 is a change
    std::fs::write(
        d.join("lib.mpath"),
        text.replacen("(60, 0)", "(60.001, 0)", 2),
    )
    .unwrap();
    ok(&millpath(
        d,
        &["text2dxf", "lib.mpath", "--into", "lib.dxf"],
    ));
    assert_ne!(std::fs::read(d.join("lib.dxf")).unwrap(), edited);

    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/samples");
    let Ok(rd) = std::fs::read_dir(&shared) else {
        eprintln!("skipped: {} is absent", shared.display());
        return;
    };
    let mut done = 0;
    for f in rd.map(|e| e.unwrap().path()) {
        if !f.extension().is_some_and(|e| e.eq_ignore_ascii_case("dxf")) {
            continue;
        }
        copy_writable(&f, &d.join("s.dxf"));
        let text = ok(&millpath(d, &["dxf2text", "s.dxf"]));
        std::fs::write(d.join("s.mpath"), &text).unwrap();
        ok(&millpath(d, &["text2dxf", "s.mpath", "--into", "s.dxf"]));
        let once = std::fs::read(d.join("s.dxf")).unwrap();
        ok(&millpath(d, &["text2dxf", "s.mpath", "--into", "s.dxf"]));
        assert!(
            std::fs::read(d.join("s.dxf")).unwrap() == once,
            "{}",
            f.display()
        );
        done += 1;
    }
    assert!(done > 0);
}
