//! Buffers that are not `*.mpath` files: an editor's untitled buffer (VS Code's "Open DXF as
//! Text") and a file opened with the language id `millpath` are text, never a drawing to load.
//! The server's own command is `millpath.server.preview`, so that it does not collide with the
//! editors' client-side `millpath.preview` (the code lenses' command).

mod common;

use common::lsp_client::{uri, Client};
use serde_json::json;
use std::time::Duration;

const PART: &str = "path 2001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  sweep (0, 0) -> (5, 0)\n  mill (5, 0) -> (25, 0)\n  sweep (25, 0) -> (30, 0)\n}\n";

fn diagnostics(c: &mut Client, doc: &str) -> Vec<serde_json::Value> {
    loop {
        let d = c
            .wait_notification("textDocument/publishDiagnostics", Duration::from_secs(10))
            .expect("diagnostics");
        if d["params"]["uri"] == doc {
            return d["params"]["diagnostics"].as_array().unwrap().clone();
        }
    }
}

#[test]
fn untitled_and_millpath_buffers_are_text_and_the_command_is_the_servers() {
    let dir = tempfile::tempdir().unwrap();
    let mut c = Client::start(env!("CARGO_BIN_EXE_millpath"));
    let init = c.initialize(
        dir.path(),
        json!({ "lang": "en", "feed": 300, "sweep_speed": 1000, "sweep_height": 10 }),
    );
    assert_eq!(
        init["result"]["capabilities"]["executeCommandProvider"]["commands"],
        json!(["millpath.server.preview"])
    );
    // an untitled buffer
    let doc = "untitled:Untitled-1";
    c.notify("textDocument/didOpen", json!({ "textDocument": { "uri": doc, "languageId": "millpath", "version": 1, "text": PART } }));
    let diags = diagnostics(&mut c, doc);
    assert!(
        diags
            .iter()
            .all(|d| !d["message"].as_str().unwrap().contains("DXF")),
        "{diags:?}"
    );
    let pv = c.request(
        "millpath/gcodePreview",
        json!({ "textDocument": { "uri": doc }, "path": "2001.1P" }),
    );
    assert!(
        pv["result"]["gcode"].as_str().unwrap().contains("G1"),
        "{pv}"
    );
    let lens = c.request(
        "textDocument/codeLens",
        json!({ "textDocument": { "uri": doc } }),
    );
    assert_eq!(lens["result"][0]["command"]["command"], "millpath.preview");
    let ex = c.request(
        "workspace/executeCommand",
        json!({ "command": "millpath.server.preview", "arguments": [doc, "2001.1P"] }),
    );
    assert!(
        ex["result"]["gcode"].as_str().unwrap().contains("G1"),
        "{ex}"
    );
    // a file without the .mpath extension opened as millpath
    let txt = dir.path().join("notes.txt");
    std::fs::write(&txt, PART).unwrap();
    let doc = uri(&txt);
    c.notify("textDocument/didOpen", json!({ "textDocument": { "uri": doc, "languageId": "millpath", "version": 1, "text": PART.replace(" B-0,2", "") } }));
    let diags = diagnostics(&mut c, &doc);
    assert!(
        diags.iter().any(|d| d["message"] == "B value missing"),
        "{diags:?}"
    );
    c.shutdown();
}
