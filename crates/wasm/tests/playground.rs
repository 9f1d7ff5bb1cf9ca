//! The playground's answers on the examples, natively (the page runs the same code in wasm):
//! compile's files equal core's compile of the files on disk, a missing B is reported at its
//! line, hover has the value table, dxf2text/text2dxf round trip.

use millpath_core::{compile_file, OsFileSystem, Session};
use millpath_wasm::playground::Playground;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/text")
}

/// The examples folder loaded as the page loads it (under `/examples/text`).
fn loaded() -> Playground {
    let mut p = Playground::new("en");
    for e in std::fs::read_dir(examples()).unwrap() {
        let path = e.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let text = std::fs::read_to_string(&path).unwrap();
        p.set_file(&format!("/examples/text/{name}"), &text);
    }
    p
}

fn json(s: String) -> Value {
    serde_json::from_str(&s).unwrap()
}

#[test]
fn compile_writes_what_core_writes_from_disk() {
    let p = loaded();
    for stem in ["2001", "2010", "2020"] {
        let got = json(p.compile(&format!("/examples/text/{stem}.mpath"), None));
        let input = examples().join(format!("{stem}.mpath"));
        let cfg = millpath_core::load::config::parse(
            &std::fs::read_to_string(examples().join("millpath.toml")).unwrap(),
            &examples(),
        )
        .unwrap();
        let mut settings = millpath_core::Settings::default();
        cfg.apply(&mut settings, &mut Default::default());
        let mut session = Session::new(settings, &OsFileSystem).unwrap();
        let want = compile_file(&mut session, &input, &millpath_core::banner());
        assert!(!want.outputs.is_empty(), "{stem}: {:?}", session.diags.list);
        let files = got["files"].as_array().unwrap();
        assert_eq!(files.len(), want.outputs.len(), "{stem}: {got}");
        for (g, w) in files.iter().zip(&want.outputs) {
            assert_eq!(g["name"], w.path.file_name().unwrap().to_str().unwrap());
            assert_eq!(g["content"].as_str().unwrap(), w.content, "{stem}");
        }
        assert_eq!(got["messages"], Value::Array(vec![]), "{stem}");
    }
}

#[test]
fn a_removed_b_is_reported_at_its_line_and_hover_has_the_table() {
    let mut p = loaded();
    let f = "/examples/text/2001.mpath";
    assert_eq!(json(p.diagnostics(f)), Value::Array(vec![]));
    let text = std::fs::read_to_string(examples().join("2001.mpath")).unwrap();
    p.set_file(f, &text.replace(" B-0,2", ""));
    let d = json(p.diagnostics(f));
    let b = millpath_core::Msg::ValueMissing.code();
    let hit = d
        .as_array()
        .unwrap()
        .iter()
        .find(|x| x["code"] == b.as_str());
    let hit = hit.unwrap_or_else(|| panic!("{d}"));
    // at the element that needs it: the slot's `mill` line
    assert_eq!(hit["line"], 7);
    assert_eq!(hit["severity"], "error");
    // hover on the `mill` keyword of line 7: the element's value table
    let at = text.find("mill (5").unwrap() + 1;
    let h = json(p.hover(f, at));
    assert!(h["markdown"].as_str().unwrap().contains('|'), "{h}");
    assert_eq!(json(p.path_at(f, at)), "2001.1P");
}

#[test]
fn text2dxf_then_dxf2text_gives_the_text_back() {
    let p = loaded();
    let f = "/examples/text/2010.mpath";
    let dxf = json(p.text2dxf(f));
    let dxf = dxf["dxf"].as_str().unwrap();
    let back = json(p.dxf2text("/examples/text/2010.dxf", dxf.as_bytes()));
    let text = back["text"].as_str().unwrap();
    assert!(text.contains("path 2010.1P {"), "{text}");
    assert!(text.contains(">2001.1P"), "{text}");
    // completion after `>` offers the part
    let c = json(
        p.completion(
            f,
            std::fs::read_to_string(examples().join("2010.mpath"))
                .unwrap()
                .find(">2001")
                .unwrap()
                + 1,
        ),
    );
    assert!(
        c["items"]
            .as_array()
            .unwrap()
            .iter()
            .any(|i| i["label"] == "2001.1P"),
        "{c}"
    );
}

/// The post selector: each built-in post's files are what compile writes with `--post NAME`
/// (core's compile over the disk with that post), and switching the post changes the G-code.
#[test]
fn the_post_selector_compiles_with_the_chosen_post() {
    let mut p = loaded();
    let names: Vec<String> = json(Playground::posts())
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x["name"].as_str().unwrap().to_string())
        .collect();
    assert!(
        names.len() >= 8 && names.iter().any(|n| n == "mach3"),
        "{names:?}"
    );
    let f = "/examples/text/2001.mpath";
    let mut seen: Vec<(String, String)> = Vec::new();
    for name in &names {
        p.set_post(name);
        let got = json(p.compile(f, None));
        let cfg = millpath_core::load::config::parse(
            &std::fs::read_to_string(examples().join("millpath.toml")).unwrap(),
            &examples(),
        )
        .unwrap();
        let mut settings = millpath_core::Settings::default();
        cfg.apply(&mut settings, &mut Default::default());
        let read = |p: &Path| std::fs::read_to_string(p).map_err(|e| e.to_string());
        let (dialect, post) = millpath_core::emit::dialect::select_post(
            name,
            Path::new(""),
            &read,
            millpath_core::Lang::En,
        )
        .unwrap();
        settings.dialect = dialect;
        settings.post = post;
        let mut session = Session::new(settings, &OsFileSystem).unwrap();
        let want = compile_file(
            &mut session,
            &examples().join("2001.mpath"),
            &millpath_core::banner(),
        );
        let files = got["files"].as_array().unwrap();
        assert_eq!(files.len(), want.outputs.len(), "{name}: {got}");
        assert!(!files.is_empty(), "{name}: {got}");
        for (g, w) in files.iter().zip(&want.outputs) {
            assert_eq!(
                g["name"],
                w.path.file_name().unwrap().to_str().unwrap(),
                "{name}"
            );
            assert_eq!(g["content"].as_str().unwrap(), w.content, "{name}");
        }
        let gcode = files[0]["content"].as_str().unwrap().to_string();
        seen.push((name.clone(), gcode));
    }
    let of = |n: &str| &seen.iter().find(|(m, _)| m == n).unwrap().1;
    // GRBL has no `%` lines, LinuxCNC has them; Mach3 is another program again
    assert!(of("linuxcnc").starts_with("%\n") && !of("grbl").starts_with('%'));
    assert_ne!(of("grbl"), of("linuxcnc"));
    assert_ne!(of("mach3"), of("linuxcnc"));
    // empty: back to millpath.toml's (no post: the reference)
    p.set_post("");
    let back = json(p.compile(f, None));
    assert_eq!(
        back["files"][0]["content"].as_str().unwrap(),
        of("reference")
    );
}
