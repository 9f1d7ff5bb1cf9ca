//! Posts in the editor (issue 32, item 5) over stdio with our own JSON-RPC client: completion
//! and hover of `post = "…"` in millpath.toml, a post file's located errors as diagnostics
//! (English and German; a huge post answered, the server alive), the preview written through
//! a custom post file exactly as `millpath compile` writes it, and a saved change of the post
//! file re-checking the open drawing.

mod common;

use common::lsp_client::{uri, Client};
use serde_json::{json, Value};
use std::path::Path;
use std::time::Duration;

const BIN: &str = env!("CARGO_BIN_EXE_millpath");
const T: Duration = Duration::from_secs(30);
const PART: &str = "path 2001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  sweep (0, 0) -> (5, 0)\n  mill (5, 0) -> (25, 0)\n  sweep (25, 0) -> (30, 0)\n}\n";
const GRBL: &str = include_str!("../../post/posts/grbl.toml");
const SETTINGS: &str =
    "feed = 300\nsweep_speed = 1000\nsweep_height = 10\npost = \"posts/mine.toml\"\n";

/// The built-in grbl post as a custom one: its own name, four decimals.
fn mine() -> String {
    GRBL.replace("name = \"grbl\"", "name = \"mine\"")
        .replace("description = \"GRBL 1.1:", "description = \"My router:")
        .replace("decimals = 3", "decimals = 4")
}

fn project(lang: &str) -> (tempfile::TempDir, Client) {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("posts")).unwrap();
    std::fs::write(d.join("posts/mine.toml"), mine()).unwrap();
    std::fs::write(d.join("millpath.toml"), SETTINGS).unwrap();
    std::fs::write(d.join("2001.mpath"), PART).unwrap();
    let mut c = Client::start(BIN);
    c.initialize_with(json!({ "processId": null,
        "workspaceFolders": [{ "uri": uri(d), "name": "ws" }],
        "initializationOptions": { "lang": lang },
        "capabilities": { "workspace": { "didChangeWatchedFiles": { "dynamicRegistration": true } } } }));
    (dir, c)
}

fn open(c: &mut Client, path: &Path, lang: &str, text: &str) -> String {
    let u = uri(path);
    c.notify(
        "textDocument/didOpen",
        json!({ "textDocument": { "uri": u, "languageId": lang, "version": 1, "text": text } }),
    );
    u
}

fn diagnostics(c: &mut Client, u: &str) -> Vec<Value> {
    c.wait_diagnostics(u, T).expect("diagnostics")["params"]["diagnostics"]
        .as_array()
        .unwrap()
        .clone()
}

#[test]
fn post_names_complete_and_hover_in_millpath_toml() {
    let (dir, mut c) = project("en");
    let settings = open(&mut c, &dir.path().join("millpath.toml"), "toml", SETTINGS);
    // a valid millpath.toml: no diagnostics
    assert_eq!(diagnostics(&mut c, &settings), Vec::<Value>::new());
    // inside the quotes of `post = "`
    let r = c.request(
        "textDocument/completion",
        json!({ "textDocument": { "uri": settings }, "position": { "line": 3, "character": 8 } }),
    );
    let items = r["result"].as_array().unwrap_or_else(|| panic!("{r}"));
    let item = |label: &str| {
        items
            .iter()
            .find(|i| i["label"] == label)
            .unwrap_or_else(|| panic!("no {label}: {r}"))
            .clone()
    };
    for name in [
        "reference",
        "linuxcnc",
        "grbl",
        "mach3",
        "uccnc",
        "centroid",
    ] {
        let i = item(name);
        assert_eq!(i["insertText"], name);
        assert!(!i["detail"].as_str().unwrap().is_empty(), "{i}");
    }
    assert!(item("grbl")["detail"]
        .as_str()
        .unwrap()
        .starts_with("GRBL 1.1"));
    let own = item("posts/mine.toml");
    assert!(
        own["detail"].as_str().unwrap().starts_with("My router"),
        "{own}"
    );
    // nothing offered on another line
    let r = c.request(
        "textDocument/completion",
        json!({ "textDocument": { "uri": settings }, "position": { "line": 0, "character": 7 } }),
    );
    assert_eq!(r["result"], json!([]), "{r}");
    // hover on the post file's name: its family, capabilities and where it comes from
    let h = c.request(
        "textDocument/hover",
        json!({ "textDocument": { "uri": settings }, "position": { "line": 3, "character": 12 } }),
    );
    let md = h["result"]["contents"]["value"]
        .as_str()
        .unwrap_or_else(|| panic!("{h}"));
    for part in [
        "**post mine** — My router",
        "- Family: grbl",
        "- Probing: G38.3",
        "- Spindle: yes",
        "- Dwell: yes",
        "- Arcs: G2/G3 I J",
        "posts/mine.toml`",
    ] {
        assert!(md.contains(part), "{part}: {md}");
    }
    assert_eq!(
        h["result"]["range"]["start"],
        json!({ "line": 3, "character": 8 })
    );
    // a built-in's name, typed into the buffer
    let text = SETTINGS.replace("posts/mine.toml", "linuxcnc");
    c.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": settings, "version": 2 }, "contentChanges": [{ "text": text }] }),
    );
    let h = c.request(
        "textDocument/hover",
        json!({ "textDocument": { "uri": settings }, "position": { "line": 3, "character": 10 } }),
    );
    let md = h["result"]["contents"]["value"]
        .as_str()
        .unwrap_or_else(|| panic!("{h}"));
    assert!(
        md.contains("- Family: rs274") && md.contains("- Probing: G38.3"),
        "{md}"
    );
    assert!(md.contains("millpath post show linuxcnc"), "{md}");
    // a name that is no post: located at the value
    let text = SETTINGS.replace("posts/mine.toml", "mach9");
    c.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": settings, "version": 3 }, "contentChanges": [{ "text": text }] }),
    );
    let d = loop {
        let d = diagnostics(&mut c, &settings);
        if !d.is_empty() {
            break d;
        }
    };
    assert!(
        d[0]["message"]
            .as_str()
            .unwrap()
            .contains("no post `mach9`"),
        "{d:?}"
    );
    assert_eq!(d[0]["range"]["start"], json!({ "line": 3, "character": 8 }));
    assert!(c.shutdown().success());
}

#[test]
fn a_post_file_gets_the_loaders_located_errors() {
    let (dir, mut c) = project("en");
    let path = dir.path().join("posts/mine.toml");
    let broken = mine().replace("tool = \"T{tool_number}\"", "tool = \"T{tool_numbr}\"");
    let line = broken
        .lines()
        .position(|l| l.starts_with("tool = "))
        .unwrap();
    let post = open(&mut c, &path, "toml", &broken);
    let d = diagnostics(&mut c, &post);
    assert_eq!(d.len(), 1, "{d:?}");
    let m = d[0]["message"].as_str().unwrap();
    assert!(
        m.contains("templates.tool") && m.contains("unknown variable {tool_numbr}"),
        "{m}"
    );
    assert_eq!(d[0]["range"]["start"]["line"], line as u64, "{d:?}");
    assert_eq!(d[0]["severity"], 1);
    // fixed in the buffer: no diagnostics
    c.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": post, "version": 2 }, "contentChanges": [{ "text": mine() }] }),
    );
    assert_eq!(diagnostics(&mut c, &post), Vec::<Value>::new());
    // a TOML file with a [post] table and a family, outside posts/, is a post too
    let other = dir.path().join("router.toml");
    let text = "[post]\nname = \"r\"\nfamily = \"grbl2\"\n[templates]\n";
    let u = open(&mut c, &other, "toml", text);
    let d = diagnostics(&mut c, &u);
    assert!(
        d[0]["message"].as_str().unwrap().contains("post.family"),
        "{d:?}"
    );
    assert_eq!(d[0]["range"]["start"]["line"], 2, "{d:?}");
    // any other TOML file: nothing
    let u = open(
        &mut c,
        &dir.path().join("Cargo.toml"),
        "toml",
        "[package]\nname = 1\n",
    );
    assert_eq!(diagnostics(&mut c, &u), Vec::<Value>::new());
    // hostile: a post of 2 MB, and one of deeply nested braces; the server answers each
    let huge = format!("{}\n# {}\n", mine(), "x".repeat(2_000_000));
    let u = open(&mut c, &dir.path().join("posts/huge.toml"), "toml", &huge);
    let d = diagnostics(&mut c, &u);
    assert!(
        d[0]["message"].as_str().unwrap().contains("at most 262144"),
        "{d:?}"
    );
    let nested = mine().replace(
        "tool = \"T{tool_number}\"",
        &format!("tool = \"{}{}\"", "{".repeat(50_000), "}".repeat(50_000)),
    );
    let u = open(
        &mut c,
        &dir.path().join("posts/nested.toml"),
        "toml",
        &nested,
    );
    let d = diagnostics(&mut c, &u);
    assert_eq!(d.len(), 1, "{d:?}");
    assert!(
        d[0]["message"].as_str().unwrap().contains("templates.tool"),
        "{d:?}"
    );
    let h = c.request(
        "textDocument/hover",
        json!({ "textDocument": { "uri": post }, "position": { "line": 0, "character": 0 } }),
    );
    assert!(h.get("error").is_none(), "{h}");
    assert!(c.shutdown().success());
}

/// The diagnostics of an open post file and millpath.toml come back under the URI the
/// client opened them with, spelled as the client spelled it (a percent-encoded letter here;
/// under Windows `Z%3A` against `z:`), not the server's own spelling of the path.
#[test]
fn diagnostics_go_back_under_the_clients_uri() {
    let (dir, mut c) = project("en");
    let broken = mine().replace("tool = \"T{tool_number}\"", "tool = \"T{tool_numbr}\"");
    for (file, text) in [
        ("posts/mine.toml", broken.as_str()),
        ("millpath.toml", "feed = 300\npost = \"nosuch\"\n"),
    ] {
        let plain = uri(&dir.path().join(file));
        let at = plain.rfind("/m").unwrap();
        let spelled = format!("{}/%6D{}", &plain[..at], &plain[at + 2..]);
        assert_ne!(spelled, plain);
        c.notify(
            "textDocument/didOpen",
            json!({ "textDocument": { "uri": spelled, "languageId": "toml", "version": 1, "text": text } }),
        );
        let n = c.wait_diagnostics(&spelled, T).expect("diagnostics");
        assert_eq!(n["params"]["uri"], spelled.as_str(), "{file}: {n}");
        assert!(
            !n["params"]["diagnostics"].as_array().unwrap().is_empty(),
            "{file}: {n}"
        );
        c.notify(
            "textDocument/didClose",
            json!({ "textDocument": { "uri": spelled } }),
        );
        let n = c.wait_diagnostics(&spelled, T).expect("cleared on close");
        assert_eq!(n["params"]["uri"], spelled.as_str(), "{file}: {n}");
    }
    assert!(c.shutdown().success());
}

#[test]
fn post_errors_are_german_with_lang_de() {
    let (dir, mut c) = project("de");
    let broken = mine().replace("decimals = 4", "decimals = 1e300");
    let post = open(&mut c, &dir.path().join("posts/mine.toml"), "toml", &broken);
    let d = diagnostics(&mut c, &post);
    let m = d[0]["message"].as_str().unwrap();
    assert!(m.contains("erwartet eine ganze Zahl von 0 bis"), "{m}");
    assert!(c.shutdown().success());
}

#[test]
fn the_preview_writes_through_the_custom_post_and_follows_its_saves() {
    let (dir, mut c) = project("en");
    let d = dir.path();
    let doc = open(&mut c, &d.join("2001.mpath"), "millpath", PART);
    assert_eq!(diagnostics(&mut c, &doc), Vec::<Value>::new());
    let preview = |c: &mut Client| {
        let pv = c.request(
            "millpath/gcodePreview",
            json!({ "textDocument": { "uri": doc }, "path": "2001.1P" }),
        );
        pv["result"]["gcode"]
            .as_str()
            .unwrap_or_else(|| panic!("{pv}"))
            .to_string()
    };
    let compiled = || {
        let out = std::process::Command::new(BIN)
            .args(["compile", "2001.mpath"])
            .current_dir(d)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        std::fs::read_to_string(d.join("2001_Milling.gcode")).unwrap()
    };
    let gcode = preview(&mut c);
    assert_eq!(gcode, compiled());
    // the custom post's four decimals, no `%` (grbl family)
    assert!(gcode.contains("X25.0000"), "{gcode}");
    assert!(!gcode.starts_with('%'), "{gcode}");
    // the toolpath view's cut part reads the program (by the post's family)
    let tp = c.request(
        "millpath/toolpath",
        json!({ "textDocument": { "uri": doc }, "path": "2001.1P" }),
    );
    assert!(tp["result"]["cut"].is_object(), "{tp}");
    // the post file saved with two decimals: the open drawing is checked again
    std::fs::write(
        d.join("posts/mine.toml"),
        mine().replace("decimals = 4", "decimals = 2"),
    )
    .unwrap();
    c.notify(
        "workspace/didChangeWatchedFiles",
        json!({ "changes": [{ "uri": uri(&d.join("posts/mine.toml")), "type": 2 }] }),
    );
    assert_eq!(diagnostics(&mut c, &doc), Vec::<Value>::new());
    let gcode = preview(&mut c);
    assert!(
        gcode.contains("X25.00\n") || gcode.contains("X25.00 "),
        "{gcode}"
    );
    assert_eq!(gcode, compiled());
    // saved broken: the drawing's diagnostics say so, as compile refuses
    std::fs::write(
        d.join("posts/mine.toml"),
        mine().replace("M30", "M30 {nothing}"),
    )
    .unwrap();
    c.notify(
        "workspace/didChangeWatchedFiles",
        json!({ "changes": [{ "uri": uri(&d.join("posts/mine.toml")), "type": 2 }] }),
    );
    let diags = diagnostics(&mut c, &doc);
    assert!(
        diags.iter().any(|x| {
            let m = x["message"].as_str().unwrap();
            m.contains("millpath.toml: post:") && m.contains("unknown variable {nothing}")
        }),
        "{diags:?}"
    );
    assert!(c.shutdown().success());
}
