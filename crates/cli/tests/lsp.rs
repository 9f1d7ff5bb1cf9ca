//! The language server end to end over stdio, as an editor drives it.

mod common;

use common::lsp_client::{uri, Client};
use serde_json::json;
use std::time::Duration;

const PART: &str = "path 2001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  sweep (0, 0) -> (5, 0)\n  mill (5, 0) -> (25, 0)\n  sweep (25, 0) -> (30, 0)\n}\n";

fn setup() -> (tempfile::TempDir, Client) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("2001.mpath"), PART).unwrap();
    let mut c = Client::start(env!("CARGO_BIN_EXE_millpath"));
    let init = c.initialize(dir.path(), json!({ "lang": "en" }));
    assert_eq!(init["result"]["serverInfo"]["name"], "millpath");
    (dir, c)
}

#[test]
fn diagnostics_hover_preview_and_more_over_stdio() {
    let (dir, mut c) = setup();
    let path = dir.path().join("2001.mpath");
    let doc = uri(&path);
    let broken = PART.replace(" B-0,2", "");
    c.notify("textDocument/didOpen", json!({ "textDocument": { "uri": doc, "languageId": "millpath", "version": 1, "text": broken } }));
    let d = c
        .wait_notification("textDocument/publishDiagnostics", Duration::from_secs(10))
        .expect("diagnostics");
    let diags = d["params"]["diagnostics"].as_array().unwrap();
    let b = diags
        .iter()
        .find(|x| x["message"] == "B value missing")
        .unwrap_or_else(|| panic!("{diags:?}"));
    assert_eq!(b["range"]["start"], json!({ "line": 4, "character": 2 }));
    assert_eq!(b["severity"], 1);
    // the fix arrives as a change
    c.notify("textDocument/didChange", json!({ "textDocument": { "uri": doc, "version": 2 }, "contentChanges": [{ "text": PART }] }));
    let d = c
        .wait_notification("textDocument/publishDiagnostics", Duration::from_secs(10))
        .expect("diagnostics");
    assert_eq!(d["params"]["diagnostics"], json!([]));
    // hover on the mill line
    let h = c.request(
        "textDocument/hover",
        json!({ "textDocument": { "uri": doc }, "position": { "line": 4, "character": 4 } }),
    );
    let md = h["result"]["contents"]["value"].as_str().unwrap();
    assert!(md.contains("| B | -0,2 | path start (line 2) |"), "{md}");
    // preview = compile output
    let pv = c.request(
        "millpath/gcodePreview",
        json!({ "textDocument": { "uri": doc }, "path": "2001.1P" }),
    );
    let gcode = pv["result"]["gcode"].as_str().unwrap().to_string();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(["compile", "2001.mpath"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(out.status.success());
    assert_eq!(
        gcode,
        std::fs::read_to_string(dir.path().join("2001_Milling.gcode")).unwrap()
    );
    // the other requests answer
    let sym = c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": doc } }),
    );
    assert_eq!(sym["result"][0]["name"], "2001.1P");
    let toks = c.request(
        "textDocument/semanticTokens/full",
        json!({ "textDocument": { "uri": doc } }),
    );
    assert!(toks["result"]["data"].as_array().unwrap().len() > 20);
    let hints = c.request("textDocument/inlayHint", json!({ "textDocument": { "uri": doc }, "range": { "start": { "line": 0, "character": 0 }, "end": { "line": 9, "character": 0 } } }));
    assert_eq!(hints["result"][0]["label"], "⇐ B-0,2");
    let lens = c.request(
        "textDocument/codeLens",
        json!({ "textDocument": { "uri": doc } }),
    );
    assert_eq!(lens["result"][0]["command"]["command"], "millpath.preview");
    let fmt = c.request("textDocument/formatting", json!({ "textDocument": { "uri": doc }, "options": { "tabSize": 2, "insertSpaces": true } }));
    assert_eq!(fmt["result"], json!(null));
    let typing = PART.replace("(25, 0)\n", "(25, 0)  \n");
    c.notify("textDocument/didChange", json!({ "textDocument": { "uri": doc, "version": 3 }, "contentChanges": [{ "text": typing }] }));
    let comp = c.request(
        "textDocument/completion",
        json!({ "textDocument": { "uri": doc }, "position": { "line": 4, "character": 26 } }),
    );
    assert!(comp["result"]
        .as_array()
        .unwrap()
        .iter()
        .any(|i| i["label"] == "B"));
    let ws = c.request("workspace/symbol", json!({ "query": "2001" }));
    assert_eq!(ws["result"][0]["name"], "2001.1P");
    assert!(c.shutdown().success());
}

/// The README's contract: a path `compile` would refuse gives a result with its reasons in
/// `errors` and no G-code, not a JSON-RPC error.
#[test]
fn preview_of_a_path_with_errors_is_a_result_with_errors() {
    let (dir, mut c) = setup();
    let doc = uri(&dir.path().join("2001.mpath"));
    let broken = PART.replace(" B-0,2", "");
    c.notify("textDocument/didOpen", json!({ "textDocument": { "uri": doc, "languageId": "millpath", "version": 1, "text": broken } }));
    c.wait_notification("textDocument/publishDiagnostics", Duration::from_secs(10))
        .expect("diagnostics");
    let pv = c.request(
        "millpath/gcodePreview",
        json!({ "textDocument": { "uri": doc }, "path": "2001.1P" }),
    );
    assert!(pv.get("error").is_none(), "{pv}");
    let r = &pv["result"];
    assert_eq!(r["gcode"], "", "{pv}");
    assert_eq!(r["path"], "2001.1P");
    let errors = r["errors"].as_array().unwrap();
    assert!(
        errors
            .iter()
            .any(|e| e.as_str().unwrap().contains("B value missing")),
        "{pv}"
    );
    // a path the file does not have: the reason names the paths it has
    let pv = c.request(
        "millpath/gcodePreview",
        json!({ "textDocument": { "uri": doc }, "path": "2001.1p" }),
    );
    let e = pv["result"]["errors"][0].as_str().unwrap_or_default();
    assert!(
        e.contains("no path 2001.1p") && e.contains("2001.1P"),
        "{pv}"
    );
    assert!(c.shutdown().success());
}

#[test]
fn the_server_survives_bad_requests() {
    let (dir, mut c) = setup();
    let doc = uri(&dir.path().join("nope.mpath"));
    // requests for documents that do not exist, garbage positions, unknown paths
    let h = c.request(
        "textDocument/hover",
        json!({ "textDocument": { "uri": doc }, "position": { "line": 999, "character": 999 } }),
    );
    assert!(h.get("result").is_some() || h.get("error").is_some());
    let pv = c.request(
        "millpath/gcodePreview",
        json!({ "textDocument": { "uri": doc }, "path": "9.9Q" }),
    );
    // a file that does not exist: a result whose errors say so
    assert!(
        pv.get("error").is_some() || !pv["result"]["errors"].as_array().unwrap().is_empty(),
        "{pv}"
    );
    let bad = c.request("textDocument/hover", json!({ "nonsense": true }));
    assert!(bad.get("error").is_some());
    c.notify("textDocument/didOpen", json!({ "textDocument": { "uri": doc, "languageId": "millpath", "version": 1, "text": "path {{{ ( ->\n\u{0}" } }));
    assert!(c
        .wait_notification("textDocument/publishDiagnostics", Duration::from_secs(10))
        .is_some());
    // and still answers
    let sym = c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": doc } }),
    );
    assert!(sym.get("result").is_some());
    assert!(c.shutdown().success());
}

/// Typing, keystroke by keystroke, values that once killed the server (a minus in front of a
/// helix's I looped the emitter until the memory ran out): it answers every one.
#[test]
fn hostile_keystrokes_leave_the_server_answering() {
    let (dir, mut c) = setup();
    let path = dir.path().join("3001.mpath");
    let doc = uri(&path);
    let text = |i: &str| {
        format!("path 3001.1P {{\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (40, 0)\n  sweep (0, 0) -> (10, 0)\n  helix (10, 0) d8  {i}\n  sweep (10, 0) -> (40, 0)\n}}\n")
    };
    c.notify("textDocument/didOpen", json!({ "textDocument": { "uri": doc, "languageId": "millpath", "version": 1, "text": text("I1") } }));
    c.wait_notification("textDocument/publishDiagnostics", Duration::from_secs(10))
        .expect("diagnostics");
    let keystrokes = [
        "I-1",
        "I0",
        "I-",
        "INaN",
        "Iinf",
        "I1e999",
        "I0,0000001",
        "I-99999999999999999999",
    ];
    for (v, i) in keystrokes.iter().enumerate() {
        c.notify("textDocument/didChange", json!({ "textDocument": { "uri": doc, "version": v + 2 }, "contentChanges": [{ "text": text(i) }] }));
        let d = c
            .wait_notification("textDocument/publishDiagnostics", Duration::from_secs(20))
            .unwrap_or_else(|| panic!("no diagnostics after typing {i}"));
        assert!(
            !d["params"]["diagnostics"].as_array().unwrap().is_empty(),
            "{i}: an error expected"
        );
        let pv = c.request(
            "millpath/gcodePreview",
            json!({ "textDocument": { "uri": doc }, "path": "3001.1P" }),
        );
        assert!(
            pv.get("result").is_some() || pv.get("error").is_some(),
            "{i}: {pv}"
        );
    }
    // still alive and right after all that
    c.notify("textDocument/didChange", json!({ "textDocument": { "uri": doc, "version": 99 }, "contentChanges": [{ "text": text("I1") }] }));
    let d = c
        .wait_notification("textDocument/publishDiagnostics", Duration::from_secs(20))
        .expect("diagnostics");
    assert_eq!(d["params"]["diagnostics"], json!([]));
}
