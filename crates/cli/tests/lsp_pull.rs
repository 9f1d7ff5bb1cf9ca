//! The newer LSP features over stdio with our own client: semantic tokens by range and as
//! deltas (result ids), pull diagnostics for a document and for the whole workspace (a DXF
//! nobody opened, files that cannot be read, unchanged reports), call hierarchy over
//! subpath embedding across text files and drawings, and cancellation that stops the work
//! of code lenses and the preview.

mod common;

use common::lsp_client::{decode_uri, uri, Client};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_millpath");
const T: Duration = Duration::from_secs(60);

const PART: &str = "# a slot\npath 2001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  sweep (0, 0) -> (5, 0)\n  mill (5, 0) -> (25, 0)\n  sweep (25, 0) -> (30, 0)\n}\n";
const PROJECT: &str = "path 2010.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (50, 0)\n  sweep (0, 0) -> (10, 10)\n  sub (10, 10) -> (40, 10)  >2001.1P\n  sweep (40, 10) -> (10, 30)\n  sub (10, 30) -> (40, 30)  >2001.1P\n  sweep (40, 30) -> (50, 0)\n}\n";

fn embedding(name: &str, sub: &str) -> String {
    format!("path {name} {{\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (50, 0)\n  sweep (0, 0) -> (10, 10)\n  sub (10, 10) -> (40, 10)  >{sub}\n  sweep (40, 10) -> (50, 0)\n}}\n")
}

/// A folder with millpath.toml, 2001 (the part), 2010 (embeds it twice), 3000.dxf (a
/// drawing embedding the part) and 3001.dxf (a drawing embedding a path that does not
/// exist); the drawings made by `millpath text2dxf`.
fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n",
    )
    .unwrap();
    std::fs::write(d.join("2001.mpath"), PART).unwrap();
    std::fs::write(d.join("2010.mpath"), PROJECT).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    for (name, sub) in [("3000", "2001.1P"), ("3001", "4242.1P")] {
        let src = tmp.path().join(format!("{name}.mpath"));
        std::fs::write(&src, embedding(&format!("{name}.1P"), sub)).unwrap();
        let out = common::millpath(
            tmp.path(),
            &[
                "text2dxf",
                src.to_str().unwrap(),
                "-o",
                d.join(format!("{name}.dxf")).to_str().unwrap(),
            ],
        );
        assert!(out.status.success(), "{out:?}");
    }
    dir
}

/// A client that pulls diagnostics (as VS Code and Neovim do).
fn start(d: &Path, pull: bool) -> Client {
    let mut c = Client::start(BIN);
    let caps = if pull {
        json!({ "textDocument": { "diagnostic": { "dynamicRegistration": false } },
                "workspace": { "diagnostics": { "refreshSupport": true } } })
    } else {
        json!({})
    };
    let init = c.initialize_with(json!({ "processId": null,
        "workspaceFolders": [{ "uri": uri(d), "name": "ws" }], "capabilities": caps }));
    let caps = &init["result"]["capabilities"];
    assert_eq!(
        caps["diagnosticProvider"]["workspaceDiagnostics"], true,
        "{caps}"
    );
    assert_eq!(caps["diagnosticProvider"]["interFileDependencies"], true);
    assert_eq!(caps["semanticTokensProvider"]["range"], true);
    assert_eq!(caps["semanticTokensProvider"]["full"]["delta"], true);
    assert_eq!(caps["callHierarchyProvider"], true);
    c
}

fn open(c: &mut Client, path: &Path, text: &str) -> String {
    let u = uri(path);
    c.notify(
        "textDocument/didOpen",
        json!({ "textDocument": { "uri": u, "languageId": "millpath", "version": 1, "text": text } }),
    );
    u
}

fn change(c: &mut Client, u: &str, version: i32, text: &str) {
    c.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": u, "version": version },
                "contentChanges": [{ "text": text }] }),
    );
}

fn ok(r: &Value) -> &Value {
    assert!(r.get("error").is_none(), "{r}");
    &r["result"]
}

/// Relative tokens → (line, column, length, type) per token.
fn absolute(data: &[u64]) -> Vec<[u64; 4]> {
    let (mut line, mut col) = (0, 0);
    data.chunks(5)
        .map(|t| {
            if t[0] > 0 {
                line += t[0];
                col = t[1];
            } else {
                col += t[1];
            }
            [line, col, t[2], t[3]]
        })
        .collect()
}

fn ints(v: &Value) -> Vec<u64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap())
        .collect()
}

#[test]
fn semantic_tokens_by_range_and_as_deltas() {
    let dir = workspace();
    let mut c = start(dir.path(), true);
    let u = open(&mut c, &dir.path().join("2010.mpath"), PROJECT);
    let full = c.request(
        "textDocument/semanticTokens/full",
        json!({ "textDocument": { "uri": u } }),
    );
    let full = ok(&full).clone();
    let id1 = full["resultId"].as_str().expect("a result id").to_string();
    let data1 = ints(&full["data"]);
    let all = absolute(&data1);
    assert!(all.len() > 20, "{all:?}");

    // a range: exactly the tokens on its lines, the first relative to the document start
    let r = c.request(
        "textDocument/semanticTokens/range",
        json!({ "textDocument": { "uri": u },
                "range": { "start": { "line": 3, "character": 0 }, "end": { "line": 5, "character": 0 } } }),
    );
    let part = absolute(&ints(&ok(&r)["data"]));
    let want: Vec<[u64; 4]> = all
        .iter()
        .filter(|t| (3..=5).contains(&t[0]))
        .copied()
        .collect();
    assert!(!want.is_empty());
    assert_eq!(part, want);

    // an edit in one line: the delta applied to the old data gives the new full tokens
    let edited = PROJECT.replace("(40, 10) -> (10, 30)", "(40, 10) -> (10, 30)  # back");
    change(&mut c, &u, 2, &edited);
    let d = c.request(
        "textDocument/semanticTokens/full/delta",
        json!({ "textDocument": { "uri": u }, "previousResultId": id1 }),
    );
    let d = ok(&d).clone();
    let edits = d["edits"].as_array().expect("a delta, not whole tokens");
    assert_eq!(edits.len(), 1, "{d}");
    let id2 = d["resultId"].as_str().unwrap().to_string();
    assert_ne!(id1, id2);
    let mut data2 = data1.clone();
    for e in edits {
        let start = e["start"].as_u64().unwrap() as usize;
        let del = e["deleteCount"].as_u64().unwrap() as usize;
        let ins = e.get("data").map(ints).unwrap_or_default();
        assert!(ins.len() < data1.len() / 2, "the delta is small: {e}");
        data2.splice(start..start + del, ins);
    }
    let fresh = c.request(
        "textDocument/semanticTokens/full",
        json!({ "textDocument": { "uri": u } }),
    );
    let fresh = ints(&ok(&fresh)["data"]);
    assert_eq!(data2, fresh);
    assert!(
        absolute(&fresh).iter().any(|t| t[3] == 4),
        "the new comment"
    );

    // a previous id that is not the last one sent: the whole tokens
    let d = c.request(
        "textDocument/semanticTokens/full/delta",
        json!({ "textDocument": { "uri": u }, "previousResultId": "no-such-id" }),
    );
    let d = ok(&d);
    assert!(d.get("edits").is_none(), "{d}");
    assert_eq!(ints(&d["data"]), fresh);
    assert!(c.shutdown().success());
}

fn codes(items: &Value) -> Vec<String> {
    items
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["code"].as_str().unwrap_or("").to_string())
        .collect()
}

#[test]
fn document_pull_with_result_ids_and_no_push() {
    let dir = workspace();
    let mut c = start(dir.path(), true);
    let bad = PROJECT.replace(">2001.1P", ">2002.1P");
    let u = open(&mut c, &dir.path().join("2010.mpath"), &bad);
    let r = c.request(
        "textDocument/diagnostic",
        json!({ "textDocument": { "uri": u } }),
    );
    let r = ok(&r).clone();
    assert_eq!(r["kind"], "full", "{r}");
    let id = r["resultId"].as_str().unwrap().to_string();
    let codes1 = codes(&r["items"]);
    assert!(!codes1.is_empty(), "{r}");
    // the same as `millpath check` says for the file
    std::fs::write(dir.path().join("2010.mpath"), &bad).unwrap();
    let check = common::millpath(dir.path(), &["check", "--format", "json", "2010.mpath"]);
    let check: Value = serde_json::from_slice(&check.stdout).unwrap();
    assert_eq!(codes(&check["diagnostics"]), codes1);

    // asked again with its result id: unchanged
    let again = c.request(
        "textDocument/diagnostic",
        json!({ "textDocument": { "uri": u }, "previousResultId": id }),
    );
    assert_eq!(ok(&again)["kind"], "unchanged", "{again}");
    assert_eq!(ok(&again)["resultId"], id.as_str());

    // fixed: a full report, empty, under a new id
    change(&mut c, &u, 2, PROJECT);
    let fixed = c.request(
        "textDocument/diagnostic",
        json!({ "textDocument": { "uri": u }, "previousResultId": id }),
    );
    let fixed = ok(&fixed).clone();
    assert_eq!(fixed["kind"], "full");
    assert_eq!(fixed["items"], json!([]));
    assert_ne!(fixed["resultId"], id.as_str());

    // a change of the part it embeds: the client is asked to pull again
    let part = open(&mut c, &dir.path().join("2001.mpath"), PART);
    change(&mut c, &part, 2, &PART.replace("end (30, 0)", ""));
    let t = Instant::now();
    while !c
        .server_requests
        .iter()
        .any(|r| r["method"] == "workspace/diagnostic/refresh")
    {
        assert!(t.elapsed() < T, "no refresh");
        // answers the server's requests on the way
        let _ = c.wait_notification("none", Duration::from_millis(100));
    }
    let after = c.request(
        "textDocument/diagnostic",
        json!({ "textDocument": { "uri": u }, "previousResultId": fixed["resultId"] }),
    );
    assert_eq!(ok(&after)["kind"], "full");
    assert!(ok(&after)["items"][0]["message"]
        .as_str()
        .unwrap()
        .contains("2001.1P"));

    // nothing pushed to a client that pulls
    let pushed = c.wait_notification("textDocument/publishDiagnostics", Duration::from_secs(1));
    assert!(pushed.is_none(), "{pushed:?}");
    assert!(c.shutdown().success());
}

#[test]
fn a_client_without_pull_still_gets_pushed_diagnostics() {
    let dir = workspace();
    let mut c = start(dir.path(), false);
    let bad = PROJECT.replace(">2001.1P", ">2002.1P");
    let u = open(&mut c, &dir.path().join("2010.mpath"), &bad);
    let n = c.wait_diagnostics(&u, T).expect("pushed");
    assert!(!codes(&n["params"]["diagnostics"]).is_empty(), "{n}");
    assert!(c.shutdown().success());
}

/// `uri → report` of a workspace pull.
fn by_file(r: &Value) -> std::collections::BTreeMap<String, Value> {
    r["items"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| {
            let name = decode_uri(i["uri"].as_str().unwrap());
            let name = name.rsplit('/').next().unwrap().to_string();
            (name, i.clone())
        })
        .collect()
}

#[test]
fn workspace_pull_checks_every_drawing_open_or_not() {
    let dir = workspace();
    let d = dir.path();
    // cannot be read: NUL bytes without a byte-order mark, and a link to nothing
    std::fs::write(d.join("5000.mpath"), b"path 5000.1P {\0}\n").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(d.join("nowhere"), d.join("5001.mpath")).unwrap();
    // below a hidden folder: not a workspace drawing
    std::fs::create_dir(d.join(".git")).unwrap();
    std::fs::write(d.join(".git/6000.mpath"), "garbage").unwrap();

    let mut c = start(d, true);
    // one open buffer with an unsaved error
    let u = open(
        &mut c,
        &d.join("2001.mpath"),
        &PART.replace("end (30, 0)", ""),
    );
    let r = c.request("workspace/diagnostic", json!({ "previousResultIds": [] }));
    let files = by_file(ok(&r));
    let mut names: Vec<&str> = files.keys().map(String::as_str).collect();
    names.sort();
    let mut want = vec![
        "2001.mpath",
        "2010.mpath",
        "3000.dxf",
        "3001.dxf",
        "5000.mpath",
    ];
    if cfg!(unix) {
        want.push("5001.mpath");
    }
    assert_eq!(names, want);
    for (name, rep) in &files {
        assert_eq!(rep["kind"], "full", "{name}: {rep}");
        assert!(rep["resultId"].is_string(), "{name}");
    }
    // the DXF nobody opened: its error, as `millpath check` reports it
    let dxf = d.join("3001.dxf");
    let check = common::millpath(d, &["check", "--format", "json", dxf.to_str().unwrap()]);
    let check: Value = serde_json::from_slice(&check.stdout).unwrap();
    let want_codes = codes(&check["diagnostics"]);
    assert!(!want_codes.is_empty());
    assert_eq!(codes(&files["3001.dxf"]["items"]), want_codes);
    assert_eq!(
        files["3001.dxf"]["items"][0]["message"],
        check["diagnostics"][0]["message"]
    );
    let line = check["diagnostics"][0]["location"]["line"]
        .as_u64()
        .unwrap();
    assert_eq!(
        files["3001.dxf"]["items"][0]["range"]["start"]["line"],
        line - 1
    );
    // the open buffer as typed (the end marker is missing), not the file on disk: the
    // drawing and the text embedding it say so
    assert!(!codes(&files["2001.mpath"]["items"]).is_empty());
    for embedding in ["3000.dxf", "2010.mpath"] {
        let m = files[embedding]["items"][0]["message"].as_str().unwrap();
        assert!(m.contains("2001.1P"), "{embedding}: {m}");
    }
    assert_eq!(files["2001.mpath"]["version"], 1);
    // what cannot be read is a diagnostic, not a failure
    let nul = common::millpath(d, &["check", "--format", "json", "5000.mpath"]);
    let nul: Value = serde_json::from_slice(&nul.stdout).unwrap();
    assert_eq!(
        codes(&files["5000.mpath"]["items"]),
        codes(&nul["diagnostics"])
    );
    if cfg!(unix) {
        assert_eq!(files["5001.mpath"]["items"].as_array().unwrap().len(), 1);
    }

    // again with the result ids: all unchanged
    let previous: Vec<Value> = files
        .values()
        .map(|r| json!({ "uri": r["uri"], "value": r["resultId"] }))
        .collect();
    let again = c.request(
        "workspace/diagnostic",
        json!({ "previousResultIds": previous }),
    );
    for (name, rep) in by_file(ok(&again)) {
        assert_eq!(rep["kind"], "unchanged", "{name}: {rep}");
        assert_eq!(rep["resultId"], files[&name]["resultId"], "{name}");
    }

    // the buffer fixed, the part on disk renamed: the buffer wins, the embeddings are
    // fine now; the drawing that embeds something else is unchanged
    std::fs::write(d.join("2001.mpath"), PART.replace("2001.1P", "2009.1P")).unwrap();
    change(&mut c, &u, 2, PART);
    let third = c.request(
        "workspace/diagnostic",
        json!({ "previousResultIds": previous }),
    );
    let third = by_file(ok(&third));
    for f in ["2001.mpath", "2010.mpath", "3000.dxf"] {
        assert_eq!(third[f]["kind"], "full", "{f}");
        assert_eq!(third[f]["items"], json!([]), "{f}");
    }
    assert_eq!(third["3001.dxf"]["kind"], "unchanged");
    assert_eq!(third["5000.mpath"]["kind"], "unchanged");
    // closed: the renamed part on disk counts
    c.notify(
        "textDocument/didClose",
        json!({ "textDocument": { "uri": u } }),
    );
    let fourth = c.request(
        "workspace/diagnostic",
        json!({ "previousResultIds": previous }),
    );
    let fourth = by_file(ok(&fourth));
    assert_eq!(
        fourth["3000.dxf"]["kind"], "full",
        "{:?}",
        fourth["3000.dxf"]
    );
    assert!(!codes(&fourth["3000.dxf"]["items"]).is_empty());
    assert_eq!(fourth["2010.mpath"]["kind"], "full");
    assert_eq!(fourth["3001.dxf"]["kind"], "unchanged");
    assert!(c.shutdown().success());
}

fn item_names(v: &Value, key: &str) -> Vec<(String, String, usize)> {
    let mut out: Vec<(String, String, usize)> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            let f = decode_uri(c[key]["uri"].as_str().unwrap());
            (
                c[key]["name"].as_str().unwrap().to_string(),
                f.rsplit('/').next().unwrap().to_string(),
                c["fromRanges"].as_array().unwrap().len(),
            )
        })
        .collect();
    out.sort();
    out
}

#[test]
fn call_hierarchy_over_subpaths_across_text_and_dxf() {
    let dir = workspace();
    let d = dir.path();
    let mut c = start(d, false);
    let pu = open(&mut c, &d.join("2010.mpath"), PROJECT);
    // on a `>2001.1P` embedding (line 4)
    let col = PROJECT.lines().nth(4).unwrap().rfind('>').unwrap() + 2;
    let prep = c.request(
        "textDocument/prepareCallHierarchy",
        json!({ "textDocument": { "uri": pu }, "position": { "line": 4, "character": col } }),
    );
    let items = ok(&prep)
        .as_array()
        .unwrap_or_else(|| panic!("{prep} {col}"))
        .clone();
    assert_eq!(items.len(), 1, "{prep}");
    let part = &items[0];
    assert_eq!(part["name"], "2001.1P");
    assert!(decode_uri(part["uri"].as_str().unwrap()).ends_with("/2001.mpath"));
    assert_eq!(part["selectionRange"]["start"]["line"], 1, "the header");

    let inc = c.request("callHierarchy/incomingCalls", json!({ "item": part }));
    assert_eq!(
        item_names(ok(&inc), "from"),
        vec![
            ("2010.1P".into(), "2010.mpath".into(), 2),
            ("3000.1P".into(), "3000.dxf".into(), 1),
        ]
    );
    // the ranges of the embeddings in the text: the `>2001.1P` texts of lines 4 and 6
    let from_2010 = ok(&inc)
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["from"]["name"] == "2010.1P")
        .unwrap();
    let lines: Vec<u64> = from_2010["fromRanges"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["start"]["line"].as_u64().unwrap())
        .collect();
    assert_eq!(lines, vec![4, 6]);
    assert_eq!(from_2010["from"]["selectionRange"]["start"]["line"], 0);

    // on the header of the project: what it embeds
    let prep = c.request(
        "textDocument/prepareCallHierarchy",
        json!({ "textDocument": { "uri": pu }, "position": { "line": 0, "character": 7 } }),
    );
    let project = ok(&prep)[0].clone();
    assert_eq!(project["name"], "2010.1P");
    let out = c.request("callHierarchy/outgoingCalls", json!({ "item": project }));
    assert_eq!(
        item_names(ok(&out), "to"),
        vec![("2001.1P".into(), "2001.mpath".into(), 2)]
    );
    // from a drawing: the DXF's path embeds the part (the range is its text's line)
    let dxf_item = ok(&inc)
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["from"]["name"] == "3000.1P")
        .unwrap()["from"]
        .clone();
    let out = c.request("callHierarchy/outgoingCalls", json!({ "item": dxf_item }));
    assert_eq!(
        item_names(ok(&out), "to"),
        vec![("2001.1P".into(), "2001.mpath".into(), 1)]
    );
    // the part embeds nothing; the project is embedded by nobody
    let out = c.request("callHierarchy/outgoingCalls", json!({ "item": part }));
    assert_eq!(ok(&out), &json!([]));
    let inc = c.request("callHierarchy/incomingCalls", json!({ "item": project }));
    assert_eq!(ok(&inc), &json!([]));
    // not on a name: nothing to prepare
    let none = c.request(
        "textDocument/prepareCallHierarchy",
        json!({ "textDocument": { "uri": pu }, "position": { "line": 3, "character": 3 } }),
    );
    assert!(ok(&none).is_null() || ok(&none) == &json!([]), "{none}");
    assert!(c.shutdown().success());
}

/// Many paths with many passes: compiling them all takes seconds.
fn heavy(base: u32, paths: usize, segments: usize) -> String {
    let mut s = String::new();
    for p in 0..paths {
        s.push_str(&format!(
            "path {base}.{}P {{\n  start (0, 0)  M50x40 O2 T40 I0,5 B-0,2\n  end ({}, 0)\n",
            p + 1,
            segments * 10 + 10
        ));
        let mut x = 0;
        for _ in 0..segments {
            s.push_str(&format!("  sweep ({x}, 0) -> ({}, 0)\n", x + 5));
            x += 5;
            s.push_str(&format!("  mill ({x}, 0) -> ({}, 0)\n", x + 5));
            x += 5;
        }
        s.push_str(&format!(
            "  sweep ({x}, 0) -> ({}, 0)\n}}\n",
            segments * 10 + 10
        ));
    }
    s
}

/// CPU time (user + system) of a process, from /proc.
fn cpu_time(pid: u32) -> Option<Duration> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks: u64 = f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?;
    // USER_HZ is 100 on Linux
    Some(Duration::from_millis(ticks * 10))
}

/// A cancelled code lens, preview (`millpath/gcodePreview` or the command
/// `millpath.server.preview`) or toolpath request answers -32800 at once, and its compile
/// stops (the server's CPU goes idle instead of finishing the work); the server stays healthy.
#[test]
fn cancellation_stops_the_work_of_lenses_preview_and_toolpath() {
    if cpu_time(std::process::id()).is_none() {
        eprintln!("skipping: no /proc");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().to_path_buf();
    std::fs::write(
        d.join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 50\n",
    )
    .unwrap();
    let text = heavy(7000, 40, 300);
    let path: PathBuf = d.join("7000.mpath");
    let mut c = start(&d, false);
    let u = open(&mut c, &path, &text);
    c.wait_diagnostics(&u, Duration::from_secs(300))
        .expect("diagnostics");
    // one long path: its preview compiles for seconds
    let long = open(&mut c, &d.join("7100.mpath"), &heavy(7100, 1, 4000));
    c.wait_diagnostics(&long, Duration::from_secs(300))
        .expect("diagnostics");
    // the whole work, uncancelled, for scale
    let t0 = Instant::now();
    let cpu0 = cpu_time(c.pid()).unwrap();
    let r = c.request(
        "millpath/gcodePreview",
        json!({ "textDocument": { "uri": u }, "path": "7000.2P" }),
    );
    assert!(ok(&r)["gcode"].as_str().unwrap().len() > 1000, "{r}");
    let one = t0.elapsed();
    let one_cpu = cpu_time(c.pid()).unwrap() - cpu0;
    eprintln!("one path's preview: {one:?} ({one_cpu:?} CPU); the lenses compile 40");

    for (method, params) in [
        (
            "textDocument/codeLens",
            json!({ "textDocument": { "uri": u } }),
        ),
        (
            "millpath/gcodePreview",
            json!({ "textDocument": { "uri": long }, "path": "7100.1P" }),
        ),
        (
            "millpath/toolpath",
            json!({ "textDocument": { "uri": u }, "path": "7000.31P" }),
        ),
        // the server's own preview command runs the same preview
        (
            "workspace/executeCommand",
            json!({ "command": "millpath.server.preview", "arguments": [long, "7100.1P"] }),
        ),
    ] {
        let id = c.send_request(method, params);
        std::thread::sleep(Duration::from_millis(100));
        c.notify("$/cancelRequest", json!({ "id": id }));
        let t = Instant::now();
        let r = c
            .wait_response(id, Duration::from_secs(5))
            .expect("an answer");
        assert_eq!(r["error"]["code"], -32800, "{method}: {r}");
        assert!(
            t.elapsed() < Duration::from_secs(2),
            "{method}: {:?}",
            t.elapsed()
        );
        // the work stops: over the next 1.5 s the server hardly runs
        std::thread::sleep(Duration::from_millis(100));
        let a = cpu_time(c.pid()).unwrap();
        std::thread::sleep(Duration::from_millis(1500));
        let busy = cpu_time(c.pid()).unwrap() - a;
        eprintln!("{method}: CPU over the 1.5 s after cancelling: {busy:?}");
        assert!(
            busy < Duration::from_millis(400),
            "{method}: the cancelled work went on ({busy:?} CPU in 1.5 s)"
        );
    }
    // healthy: a lens request answers every path (it compiles 40 paths: on a busy machine,
    // with a debug build, that takes longer than the client's usual 30 s)
    let id = c.send_request(
        "textDocument/codeLens",
        json!({ "textDocument": { "uri": u } }),
    );
    let lenses = c
        .wait_response(id, Duration::from_secs(300))
        .expect("the lenses");
    let lenses = ok(&lenses).as_array().unwrap().clone();
    assert_eq!(lenses.len(), 40);
    assert!(lenses[0]["command"]["title"]
        .as_str()
        .unwrap()
        .contains("G-code"));
    assert!(c.shutdown().success());
}

/// Parity: one workspace pull over each folder of the examples and the shared drawings
/// gives, per drawing, the (code, message, line) set `millpath check --format json` reports.
#[test]
fn workspace_pull_equals_check_for_every_drawing() {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut dirs = vec![
        manifest.join("../../examples/text"),
        manifest.join("../../examples/plate"),
    ];
    for s in ["conformance/fixtures", "samples"] {
        let p = manifest.join("../../../shared").join(s);
        if p.is_dir() {
            dirs.push(p);
        } else {
            eprintln!("skipping {}: not present", p.display());
        }
    }
    let mut mismatches = Vec::new();
    let mut checked = 0;
    for dir in dirs {
        let dir = dir.canonicalize().unwrap();
        let mut c = start(&dir, true);
        let r = c.request("workspace/diagnostic", json!({ "previousResultIds": [] }));
        let reports = ok(&r)["items"].as_array().unwrap().clone();
        assert!(c.shutdown().success());
        for rep in reports {
            let f = PathBuf::from(decode_uri(rep["uri"].as_str().unwrap()).replace("file://", ""));
            if f.parent() != Some(dir.as_path()) {
                continue;
            }
            let out = std::process::Command::new(BIN)
                .args(["check", "--format", "json"])
                .arg(&f)
                .current_dir(&dir)
                .output()
                .unwrap();
            let v: Value = serde_json::from_slice(&out.stdout).unwrap();
            let fname = f.display().to_string();
            let want: std::collections::BTreeSet<(String, String, Option<u64>)> = v["diagnostics"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|d| {
                    d["location"]["file"].is_null() || d["location"]["file"] == fname.as_str()
                })
                .map(|d| {
                    (
                        d["code"].as_str().unwrap().to_string(),
                        d["message"].as_str().unwrap().to_string(),
                        d["location"]["line"].as_u64(),
                    )
                })
                .collect();
            let got: std::collections::BTreeSet<(String, String, Option<u64>)> = rep["items"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| {
                    let key = (
                        x["code"].as_str().unwrap_or("").to_string(),
                        x["message"].as_str().unwrap_or("").to_string(),
                        Some(x["range"]["start"]["line"].as_u64().unwrap() + 1),
                    );
                    // a line only where check gives one (paths and files have none)
                    if want.contains(&key) {
                        key
                    } else {
                        (key.0, key.1, None)
                    }
                })
                .collect();
            if got != want {
                mismatches.push(format!("{fname}:\n  check: {want:?}\n  pull: {got:?}"));
            }
            checked += 1;
        }
    }
    assert!(checked >= 4, "{checked}");
    assert!(mismatches.is_empty(), "{}", mismatches.join("\n"));
}
