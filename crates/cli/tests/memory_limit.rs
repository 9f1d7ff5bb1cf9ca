//! Under a 1 GB address-space limit (`ulimit -v`), no drawing kills the binary and no
//! keystroke kills the language server: hostile input ends in errors, not in an abort.

mod common;

use common::lsp_client::{uri, Client};
use common::MACHINE;
use serde_json::json;
use std::path::Path;
use std::process::Command;
use std::time::Duration;

const LIMIT_KB: u64 = 1024 * 1024;

fn limited(args: &[&str]) -> Command {
    let mut c = Command::new("sh");
    c.arg("-c")
        .arg(format!("ulimit -v {LIMIT_KB}; exec \"$@\""))
        .arg("sh")
        .arg(env!("CARGO_BIN_EXE_millpath"))
        .args(args);
    c
}

fn text_drawing(dir: &Path, name: &str, body: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, body).unwrap();
    p.to_string_lossy().into_owned()
}

fn path(start: &str, elements: &str) -> String {
    format!("path 1000.1P {{\n  start (0, 0)  {start}\n  end (30, 0)\n{elements}}}\n")
}

#[test]
fn hostile_drawings_end_in_errors_under_a_memory_limit() {
    let dir = tempfile::tempdir().unwrap();
    let line = "  mill (0, 0) -> (30, 0)\n";
    let helix = "  sweep (0, 0) -> (10, 0)\n  helix (10, 0) d8\n  sweep (10, 0) -> (30, 0)\n";
    let bars = "  bars (0, 0) -> (30, 0)\n";
    let cases = [
        path("O2 T2 I1 BNaN", line),
        path("O2 T2 I-1 B-0,1", helix),
        path("O2 T2 I0 B-0,1", helix),
        path("O2 T2 I0,000001 B-5", line),
        path("O2 T2 I0,000001 B-5", helix),
        path("O2 T2 I1 B-99999999999999999999", helix),
        path("O2 T2 I1 B0 D1 P0,000001 U0,000001", bars),
        "path 1000.1P {\n  start (0, 0)  O2 T2 I1 B0\n  end (1e9, 0)\n  mill (0, 0) -> (1e9, 0)\n}\n".to_string(),
        "path 1000.1P {\n  start (9.3e15, 0)  O2 T2 I1 B0\n  end (9.3e15, 1)\n  mill (9.3e15, 0) -> (9.3e15, 1)\n}\n".to_string(),
    ];
    for (i, body) in cases.iter().enumerate() {
        let f = text_drawing(dir.path(), &format!("c{i}.mpath"), body);
        for cmd in ["check", "compile"] {
            let mut args = vec![cmd];
            args.extend(MACHINE);
            args.push(&f);
            let out = limited(&args).output().unwrap();
            let code = out.status.code();
            assert_eq!(
                code,
                Some(1),
                "{cmd} case {i} ended with {:?}: {}",
                out.status,
                String::from_utf8_lossy(&out.stderr)
            );
        }
    }
}

#[test]
fn hostile_keystrokes_under_a_memory_limit_leave_the_server_answering() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n",
    )
    .unwrap();
    let mut c = Client::spawn(limited(&["lsp"]));
    c.initialize(dir.path(), json!({ "lang": "en" }));
    let doc = uri(&dir.path().join("1000.mpath"));
    let helix = "  sweep (0, 0) -> (10, 0)\n  helix (10, 0) d8\n  sweep (10, 0) -> (30, 0)\n";
    c.notify("textDocument/didOpen", json!({ "textDocument": { "uri": doc, "languageId": "millpath", "version": 1, "text": path("O2 T2 I1 B-0,1", helix) } }));
    c.wait_notification("textDocument/publishDiagnostics", Duration::from_secs(10))
        .expect("diagnostics");
    let starts = [
        "O2 T2 I-1 B-0,1",
        "O2 T2 I0 B-0,1",
        "O2 T2 I0,000001 B-5",
        "O2 T2 I1 B-99999999999999999999",
        "O2 T2 INaN B-0,1",
    ];
    for (v, s) in starts.iter().enumerate() {
        c.notify("textDocument/didChange", json!({ "textDocument": { "uri": doc, "version": v + 2 }, "contentChanges": [{ "text": path(s, helix) }] }));
        c.wait_notification("textDocument/publishDiagnostics", Duration::from_secs(20))
            .unwrap_or_else(|| panic!("no answer after {s}"));
        let h = c.request(
            "textDocument/hover",
            json!({ "textDocument": { "uri": doc }, "position": { "line": 5, "character": 4 } }),
        );
        assert!(
            h.get("result").is_some() || h.get("error").is_some(),
            "{s}: {h}"
        );
    }
    let status = c.shutdown();
    assert!(status.success(), "{status:?}");
}
