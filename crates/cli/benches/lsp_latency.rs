//! Bench script: median time from `didChange` to `publishDiagnostics` of the language server
//! on a generated 2,000-element file (target: under 20 ms). Run with
//! `cargo bench -p millpath-cli --bench lsp_latency`.

#[path = "../tests/common/lsp_client.rs"]
mod lsp_client;

use lsp_client::{uri, Client};
use serde_json::json;
use std::time::{Duration, Instant};

/// A path of `n` elements: a zig-zag of mill lines and sweeps.
pub fn big_file(n: usize, infeed: &str) -> String {
    let mut s = format!("path 3000.1P {{\n  start (0, 0)  M10x3 O2 T3 I{infeed} B-0,2\n");
    let segments = n - 2;
    let mut x = 0.0;
    let mut lines = Vec::new();
    for i in 0..segments {
        let kind = if i % 4 == 3 { "sweep" } else { "mill" };
        let y0 = if i % 2 == 0 { 0.0 } else { 5.0 };
        let y1 = 5.0 - y0;
        lines.push(format!("  {kind} ({x}, {y0}) -> ({}, {y1})\n", x + 1.0));
        x += 1.0;
    }
    let y_end = if segments.is_multiple_of(2) { 0.0 } else { 5.0 };
    s.push_str(&format!("  end ({x}, {y_end})\n"));
    for l in lines {
        s.push_str(&l);
    }
    s.push_str("}\n");
    s
}

fn main() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n",
    )
    .unwrap();
    let path = dir.path().join("3000.mpath");
    let text = big_file(2000, "1,5");
    assert_eq!(text.lines().count(), 2002);
    std::fs::write(&path, &text).unwrap();
    let mut c = Client::start(env!("CARGO_BIN_EXE_millpath"));
    c.initialize(dir.path(), json!({ "debounceMs": 0 }));
    let doc = uri(&path);
    c.notify("textDocument/didOpen", json!({ "textDocument": { "uri": doc, "languageId": "millpath", "version": 1, "text": text } }));
    let first = c
        .wait_notification("textDocument/publishDiagnostics", Duration::from_secs(60))
        .expect("diagnostics");
    assert_eq!(
        first["params"]["diagnostics"],
        json!([]),
        "the generated file is clean"
    );
    let mut times = Vec::new();
    for i in 0..31 {
        let infeed = if i % 2 == 0 { "1,2" } else { "1,5" };
        let changed = big_file(2000, infeed);
        let t0 = Instant::now();
        c.notify("textDocument/didChange", json!({ "textDocument": { "uri": doc, "version": i + 2 }, "contentChanges": [{ "text": changed }] }));
        c.wait_notification("textDocument/publishDiagnostics", Duration::from_secs(60))
            .expect("diagnostics");
        times.push(t0.elapsed());
    }
    times.sort();
    let median = times[times.len() / 2];
    println!("didChange → publishDiagnostics, 2,000 elements, {} runs: median {:.1} ms (min {:.1}, max {:.1})", times.len(), median.as_secs_f64() * 1e3, times[0].as_secs_f64() * 1e3, times[times.len() - 1].as_secs_f64() * 1e3);
    c.shutdown();
}
