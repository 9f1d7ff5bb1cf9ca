//! The language server as an editor session sees it, over stdio with our own JSON-RPC
//! client: cross-file republication, cancellation, parity with `millpath check`, position
//! encodings and incremental changes, clients that send only `rootUri`.

mod common;

use common::lsp_client::{uri, Client};
use serde_json::{json, Value};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_millpath");
const T: Duration = Duration::from_secs(30);

fn example(name: &str) -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/text")
            .join(name),
    )
    .unwrap()
}

fn open(c: &mut Client, path: &Path, text: &str) -> String {
    let doc = uri(path);
    // as editors open them: a drawing is not the text language
    let is_dxf = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("dxf"));
    let language = if is_dxf { "dxf" } else { "millpath" };
    c.notify("textDocument/didOpen", json!({ "textDocument": { "uri": doc, "languageId": language, "version": 1, "text": text } }));
    doc
}

/// Waits for diagnostics of `doc` that satisfy `ok` (earlier publications are skipped).
fn wait_until(c: &mut Client, doc: &str, ok: impl Fn(&Value) -> bool) -> Value {
    let deadline = Instant::now() + T;
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let d = c
            .wait_diagnostics(doc, left)
            .expect("the expected diagnostics in time");
        if ok(&d) {
            return d;
        }
    }
}

fn codes(d: &Value) -> Vec<String> {
    d["params"]["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x["code"].as_str().unwrap_or("").to_string())
        .collect()
}

/// A project (2010) embedding a part (2001): a change of the part, as an unsaved buffer, by
/// closing it (the disk wins again) and on disk with `workspace/didChangeWatchedFiles`,
/// republishes the project's diagnostics.
#[test]
fn a_subpath_change_republishes_the_files_embedding_it() {
    let dir = tempfile::tempdir().unwrap();
    let part = example("2001.mpath");
    let project = example("2010.mpath");
    let part_path = dir.path().join("2001.mpath");
    let project_path = dir.path().join("2010.mpath");
    std::fs::write(&part_path, &part).unwrap();
    std::fs::write(&project_path, &project).unwrap();
    let mut c = Client::start(BIN);
    let root = uri(dir.path());
    let init = c.initialize_with(json!({ "processId": null, "rootUri": root,
        "capabilities": { "workspace": { "didChangeWatchedFiles": { "dynamicRegistration": true } } } }));
    assert_eq!(
        init["result"]["capabilities"]["textDocumentSync"]["change"],
        2
    );
    let pdoc = open(&mut c, &project_path, &project);
    let d = c.wait_diagnostics(&pdoc, T).expect("project diagnostics");
    assert_eq!(d["params"]["diagnostics"], json!([]), "{d}");
    // the watcher was registered dynamically
    let _ = c.request("workspace/symbol", json!({ "query": "" }));
    assert!(
        c.server_requests
            .iter()
            .any(|r| r["method"] == "client/registerCapability"
                && r["params"]["registrations"][0]["method"] == "workspace/didChangeWatchedFiles"),
        "{:?}",
        c.server_requests
    );

    // 1. the part as an unsaved buffer: its path renamed, the project loses its subpath
    let sdoc = open(&mut c, &part_path, &part);
    c.wait_diagnostics(&sdoc, T).expect("part diagnostics");
    let renamed = part.replace("path 2001.1P", "path 2001.2P");
    c.notify("textDocument/didChange", json!({ "textDocument": { "uri": sdoc, "version": 2 }, "contentChanges": [{ "text": renamed }] }));
    wait_until(&mut c, &pdoc, |d| !codes(d).is_empty());
    // 2. closing the buffer: the file on disk (unchanged, fine) counts again
    c.notify(
        "textDocument/didClose",
        json!({ "textDocument": { "uri": sdoc } }),
    );
    wait_until(&mut c, &pdoc, |d| codes(d).is_empty());
    // 3. on disk, announced by the watcher
    std::fs::write(&part_path, &renamed).unwrap();
    c.notify(
        "workspace/didChangeWatchedFiles",
        json!({ "changes": [{ "uri": uri(&part_path), "type": 2 }] }),
    );
    wait_until(&mut c, &pdoc, |d| !codes(d).is_empty());
    // and back, saved
    std::fs::write(&part_path, &part).unwrap();
    c.notify(
        "workspace/didChangeWatchedFiles",
        json!({ "changes": [{ "uri": uri(&part_path), "type": 2 }] }),
    );
    wait_until(&mut c, &pdoc, |d| codes(d).is_empty());
    assert!(c.shutdown().success());
}

/// A generated path of `n` mill elements in short chains.
fn big(n: usize) -> String {
    let mut s = String::from("path 4001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n");
    let mut x = 0;
    s.push_str(&format!("  end ({}, 0)\n", n * 10 + 10));
    for i in 0..n {
        s.push_str(&format!("  sweep ({x}, 0) -> ({}, 0)\n", x + 5));
        x += 5;
        let b = if i % 7 == 0 { "  B-0,1" } else { "" };
        s.push_str(&format!("  mill ({x}, 0) -> ({}, 0){b}\n", x + 5));
        x += 5;
    }
    s.push_str(&format!("  sweep ({x}, 0) -> ({}, 0)\n}}\n", n * 10 + 10));
    s
}

/// `$/cancelRequest` for a slow request answers RequestCancelled (or drops it), and a cheap
/// request right after it answers at once.
#[test]
fn a_cancelled_request_gives_way_to_the_next() {
    let dir = tempfile::tempdir().unwrap();
    let mut c = Client::start(BIN);
    c.initialize(dir.path(), json!({ "lang": "en" }));
    let small = dir.path().join("2001.mpath");
    let sdoc = open(&mut c, &small, &example("2001.mpath"));
    c.wait_diagnostics(&sdoc, T).expect("diagnostics");
    let slow_path = dir.path().join("4001.mpath");
    let doc = open(&mut c, &slow_path, &big(4000));
    // a slow request: the G-code preview of a big path (analysis and compilation)
    let id = c.send_request(
        "millpath/gcodePreview",
        json!({ "textDocument": { "uri": doc }, "path": "4001.1P" }),
    );
    std::thread::sleep(Duration::from_millis(20));
    c.notify("$/cancelRequest", json!({ "id": id }));
    let t0 = Instant::now();
    let sym = c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": sdoc } }),
    );
    let cheap = t0.elapsed();
    assert_eq!(sym["result"][0]["name"], "2001.1P");
    assert!(
        cheap < Duration::from_secs(2),
        "cheap request took {cheap:?}"
    );
    if let Some(r) = c.wait_response(id, Duration::from_secs(60)) {
        assert_eq!(r["error"]["code"], -32800, "{r}");
    }
    assert!(c.shutdown().success());
}

/// Parity: for every example and every shared drawing, the set of (code, message, line) the
/// server publishes equals what `millpath check --format json` reports for the file.
#[test]
fn editor_diagnostics_equal_check_for_every_drawing() {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<PathBuf> = Vec::new();
    let mut dirs = vec![
        manifest.join("../../examples/text"),
        manifest.join("../../examples/plate"),
    ];
    let shared = [
        manifest.join("../../../shared/conformance/fixtures"),
        manifest.join("../../../shared/samples"),
    ];
    for s in &shared {
        if s.is_dir() {
            dirs.push(s.clone());
        } else {
            eprintln!("skipping {}: not present", s.display());
        }
    }
    for d in &dirs {
        let mut v: Vec<PathBuf> = std::fs::read_dir(d)
            .unwrap()
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.extension()
                    .is_some_and(|x| x.eq_ignore_ascii_case("dxf") || x == "mpath")
            })
            .collect();
        v.sort();
        files.extend(v.into_iter().map(|p| p.canonicalize().unwrap()));
    }
    assert!(files.len() >= 3);
    let mut c = Client::start(BIN);
    c.initialize_with(json!({ "processId": null, "capabilities": {} }));
    let mut mismatches = Vec::new();
    for f in &files {
        let out = std::process::Command::new(BIN)
            .args(["check", "--format", "json"])
            .arg(f)
            .current_dir(f.parent().unwrap())
            .output()
            .unwrap();
        let v: Value =
            serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        let fname = f.display().to_string();
        let want: BTreeSet<(String, String, Option<u64>)> = v["diagnostics"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|d| d["location"]["file"].is_null() || d["location"]["file"] == fname.as_str())
            .map(|d| {
                (
                    d["code"].as_str().unwrap().to_string(),
                    d["message"].as_str().unwrap().to_string(),
                    d["location"]["line"].as_u64(),
                )
            })
            .collect();
        let bytes = std::fs::read(f).unwrap();
        let doc = open(&mut c, f, &String::from_utf8_lossy(&bytes));
        let d = c
            .wait_diagnostics(&doc, Duration::from_secs(120))
            .unwrap_or_else(|| panic!("no diagnostics for {}", f.display()));
        let with_line: BTreeSet<&(String, String, Option<u64>)> =
            want.iter().filter(|w| w.2.is_some()).collect();
        let got: BTreeSet<(String, String, Option<u64>)> = d["params"]["diagnostics"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| {
                let code = x["code"].as_str().unwrap_or("").to_string();
                let msg = x["message"].as_str().unwrap_or("").to_string();
                let line = x["range"]["start"]["line"].as_u64().unwrap() + 1;
                // a line only where check gives one (paths and files have none)
                let key = (code.clone(), msg.clone(), Some(line));
                if with_line.contains(&key) {
                    key
                } else {
                    (code, msg, None)
                }
            })
            .collect();
        if got != want {
            mismatches.push(format!(
                "{}:\n  check: {want:?}\n  editor: {got:?}",
                f.display()
            ));
        }
        c.notify(
            "textDocument/didClose",
            json!({ "textDocument": { "uri": doc } }),
        );
        let _ = c.wait_diagnostics(&doc, T);
    }
    assert!(mismatches.is_empty(), "{}", mismatches.join("\n"));
    assert!(c.shutdown().success());
}

/// A path named `slot` does not match the path-name pattern: MP089 in the editor too.
#[test]
fn a_path_name_off_the_pattern_is_reported_in_the_editor() {
    let dir = tempfile::tempdir().unwrap();
    let mut c = Client::start(BIN);
    c.initialize(dir.path(), json!({}));
    let text = example("2001.mpath").replace("2001.1P", "slot");
    let doc = open(&mut c, &dir.path().join("2001.mpath"), &text);
    let d = c.wait_diagnostics(&doc, T).expect("diagnostics");
    assert!(codes(&d).contains(&"MP089".to_string()), "{d}");
}

const UTF_LINE: &str = "  mill (5, 0) -> (25, 0)  \"Grüße😀\" B-0,2 # ä😀";

fn utf_doc() -> String {
    format!("# Größe 😀 über alles\npath 2001.1P {{\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  sweep (0, 0) -> (5, 0)\n{UTF_LINE}\n  sweep (25, 0) -> (30, 0)\n}}\n")
}

/// Columns in UTF-16 code units (default) and in bytes (`positionEncoding: utf-8`): the
/// diagnostic's range and an incremental edit after umlauts and an emoji.
#[test]
fn positions_in_utf16_and_utf8_with_umlauts_and_emoji() {
    for utf8 in [false, true] {
        let dir = tempfile::tempdir().unwrap();
        let mut c = Client::start(BIN);
        let caps = if utf8 {
            json!({ "general": { "positionEncodings": ["utf-8", "utf-16"] } })
        } else {
            json!({ "general": { "positionEncodings": ["utf-16"] } })
        };
        let init = c.initialize_with(json!({ "processId": null, "capabilities": caps }));
        assert_eq!(
            init["result"]["capabilities"]["positionEncoding"],
            if utf8 { "utf-8" } else { "utf-16" }
        );
        let col = |s: &str| -> u64 {
            if utf8 {
                s.len() as u64
            } else {
                s.encode_utf16().count() as u64
            }
        };
        let doc = open(&mut c, &dir.path().join("2001.mpath"), &utf_doc());
        let d = c.wait_diagnostics(&doc, T).expect("diagnostics");
        let diags = d["params"]["diagnostics"].as_array().unwrap();
        assert_eq!(diags.len(), 1, "{d}");
        // the element's line without its trailing comment
        let end = &UTF_LINE[..UTF_LINE.find(" # ").unwrap()];
        assert_eq!(
            diags[0]["range"],
            json!({ "start": { "line": 5, "character": 2 }, "end": { "line": 5, "character": col(end) } }),
            "utf8: {utf8}"
        );
        // remove the quoted word: an incremental edit located after the umlauts and emoji
        let from = UTF_LINE.find('"').unwrap();
        let to = UTF_LINE.find(" B-").unwrap() + 1;
        let (a, b) = (col(&UTF_LINE[..from]), col(&UTF_LINE[..to]));
        c.notify("textDocument/didChange", json!({ "textDocument": { "uri": doc, "version": 2 }, "contentChanges": [
            { "range": { "start": { "line": 5, "character": a }, "end": { "line": 5, "character": b } }, "text": "" },
            // and an edit in the first line, after the emoji
            { "range": { "start": { "line": 0, "character": col("# Größe 😀") }, "end": { "line": 0, "character": col("# Größe 😀 über") } }, "text": " unter" }
        ] }));
        let d = c.wait_diagnostics(&doc, T).expect("diagnostics");
        assert_eq!(d["params"]["diagnostics"], json!([]), "utf8 {utf8}: {d}");
        let f = c.request("textDocument/formatting", json!({ "textDocument": { "uri": doc }, "options": { "tabSize": 2, "insertSpaces": true } }));
        if let Some(edits) = f["result"].as_array() {
            let text = edits[0]["newText"].as_str().unwrap();
            assert!(text.starts_with("# Größe 😀 unter alles\n"), "{text}");
            assert!(text.contains("(25, 0)  B-0,2"), "{text}");
        }
        // hover on the B after the comment-free line: the parameter's documentation
        let line = "  mill (5, 0) -> (25, 0)  B-0,2 # ä😀";
        let h = c.request("textDocument/hover", json!({ "textDocument": { "uri": doc }, "position": { "line": 5, "character": col(&line[..line.find('B').unwrap()]) } }));
        assert!(h["result"]["contents"]["value"].is_string(), "{h}");
        assert!(c.shutdown().success());
    }
}

/// A client that sends only `rootUri` (no `workspaceFolders`) gets workspace symbols and
/// references across the files of its root.
#[test]
fn a_client_with_only_root_uri_gets_cross_file_features() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("2001.mpath"), example("2001.mpath")).unwrap();
    std::fs::write(dir.path().join("2010.mpath"), example("2010.mpath")).unwrap();
    let mut c = Client::start(BIN);
    c.initialize_with(json!({ "processId": null, "rootUri": uri(dir.path()), "capabilities": {} }));
    let ws = c.request("workspace/symbol", json!({ "query": "2010" }));
    assert_eq!(ws["result"][0]["name"], "2010.1P", "{ws}");
    // references of 2001.1P from its definition: the two embeddings in 2010
    let text = example("2001.mpath");
    let doc = open(&mut c, &dir.path().join("2001.mpath"), &text);
    let line = text
        .lines()
        .position(|l| l.starts_with("path 2001.1P"))
        .unwrap();
    let r = c.request("textDocument/references", json!({ "textDocument": { "uri": doc }, "position": { "line": line, "character": 7 }, "context": { "includeDeclaration": true } }));
    let in_project = r["result"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|l| l["uri"].as_str().unwrap().ends_with("2010.mpath"))
        .count();
    assert_eq!(in_project, 2, "{r}");
    let in_part = |r: &Value| {
        r["result"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|l| l["uri"].as_str().unwrap().ends_with("2001.mpath"))
            .count()
    };
    assert_eq!(in_part(&r), 1, "the declaration is included: {r}");
    // without the declaration
    let r = c.request("textDocument/references", json!({ "textDocument": { "uri": doc }, "position": { "line": line, "character": 7 }, "context": { "includeDeclaration": false } }));
    assert_eq!(in_part(&r), 0, "{r}");
    assert_eq!(r["result"].as_array().unwrap().len(), 2, "{r}");
    assert!(c.shutdown().success());
}

/// `exit` without `shutdown` ends the server with status 1 (LSP), after it: 0.
#[test]
fn exit_without_shutdown_is_status_1() {
    let dir = tempfile::tempdir().unwrap();
    let mut c = Client::start(BIN);
    c.initialize(dir.path(), json!({}));
    assert_eq!(c.exit_without_shutdown().code(), Some(1));
    let mut c = Client::start(BIN);
    c.initialize(dir.path(), json!({}));
    assert_eq!(c.shutdown().code(), Some(0));
}
