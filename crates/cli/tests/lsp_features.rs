//! The structural LSP features over stdio with our own JSON-RPC client, in UTF-16 and in
//! UTF-8 positions on lines with umlauts and emoji: rename with prepareRename (and its
//! refusals), folding ranges, document links, document highlight, selection ranges, range
//! formatting, definition on the `path` header, symbol selection ranges.

mod common;

use common::lsp_client::{decode_uri, uri, Client};
use serde_json::{json, Value};
use std::path::Path;
use std::time::Duration;

const BIN: &str = env!("CARGO_BIN_EXE_millpath");
const T: Duration = Duration::from_secs(30);

const PART: &str = "# Teil für Schlitze 😀\npath 2001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  sweep (0, 0) -> (5, 0)\n  mill (5, 0) -> (25, 0)\n  sweep (25, 0) -> (30, 0)\n}\n";
/// The embedding lines carry a quoted word with umlauts and an emoji before `>NAME`, so
/// every column after it differs between UTF-16 and UTF-8.
const SUB1: &str = "  sub (10, 10) -> (40, 10)  \"Grüße😀\" >2001.1P";
const SUB2: &str = "  sub (10, 30) -> (40, 30)  \"ä😀ö\" >2001.1P  # zwei 😀";

fn project() -> String {
    format!("# Projekt 😀\n# zwei Schlitze\npath 2010.1P {{\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (50, 0)\n  sweep (0, 0) -> (10, 10)\n{SUB1}\n  sweep (40, 10) -> (10, 30)\n{SUB2}\n  sweep (40, 30) -> (50, 0)\n}}\n")
}

struct Session {
    c: Client,
    utf8: bool,
    _dir: tempfile::TempDir,
    dir: std::path::PathBuf,
    part: String,
    project: String,
}

impl Session {
    fn start(utf8: bool) -> Session {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path().to_path_buf();
        std::fs::write(
            d.join("millpath.toml"),
            "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n",
        )
        .unwrap();
        std::fs::write(d.join("2001.mpath"), PART).unwrap();
        std::fs::write(d.join("2010.mpath"), project()).unwrap();
        let mut c = Client::start(BIN);
        let enc = if utf8 {
            json!(["utf-8", "utf-16"])
        } else {
            json!(["utf-16"])
        };
        let init = c.initialize_with(json!({ "processId": null,
            "workspaceFolders": [{ "uri": uri(&d), "name": "ws" }],
            "capabilities": { "general": { "positionEncodings": enc } } }));
        let caps = &init["result"]["capabilities"];
        for cap in [
            "renameProvider",
            "foldingRangeProvider",
            "documentLinkProvider",
            "documentHighlightProvider",
            "selectionRangeProvider",
            "documentRangeFormattingProvider",
        ] {
            assert!(
                !caps[cap].is_null() && caps[cap] != json!(false),
                "{cap}: {caps}"
            );
        }
        assert_eq!(caps["renameProvider"]["prepareProvider"], true);
        let part = open(&mut c, &d.join("2001.mpath"), PART);
        let project = open(&mut c, &d.join("2010.mpath"), &project());
        c.wait_diagnostics(&project, T).expect("diagnostics");
        Session {
            c,
            utf8,
            _dir: dir,
            dir: d,
            part,
            project,
        }
    }

    /// The column of `prefix`'s end in the negotiated encoding.
    fn col(&self, prefix: &str) -> u64 {
        if self.utf8 {
            prefix.len() as u64
        } else {
            prefix.encode_utf16().count() as u64
        }
    }

    /// The position of the first `needle` in `text` (+ `skip` characters).
    fn pos(&self, text: &str, needle: &str, skip: usize) -> Value {
        let at = text.find(needle).unwrap_or_else(|| panic!("{needle}"));
        let at = at
            + needle
                .char_indices()
                .nth(skip)
                .map_or(needle.len(), |(i, _)| i);
        let line = text[..at].matches('\n').count();
        let start = text[..at].rfind('\n').map_or(0, |p| p + 1);
        json!({ "line": line, "character": self.col(&text[start..at]) })
    }

    fn range(&self, text: &str, needle: &str) -> Value {
        let chars = needle.chars().count();
        json!({ "start": self.pos(text, needle, 0), "end": self.pos(text, needle, chars) })
    }

    fn at(&self, doc: &str, p: Value) -> Value {
        json!({ "textDocument": { "uri": doc }, "position": p })
    }
}

fn open(c: &mut Client, path: &Path, text: &str) -> String {
    let doc = uri(path);
    c.notify("textDocument/didOpen", json!({ "textDocument": { "uri": doc, "languageId": "millpath", "version": 1, "text": text } }));
    doc
}

fn result(v: &Value) -> &Value {
    assert!(v.get("error").is_none(), "{v}");
    &v["result"]
}

#[test]
fn rename_with_prepare_in_both_encodings() {
    for utf8 in [false, true] {
        let mut s = Session::start(utf8);
        let project = project();
        // prepareRename on the second embedding (after the emoji): the name without `>`
        let p = s.pos(&project, ">2001.1P  # zwei", 3);
        let r =
            s.c.request("textDocument/prepareRename", s.at(&s.project.clone(), p));
        let want = {
            let line = 8;
            let from = s.col(&SUB2[..SUB2.find(">2001").unwrap() + 1]);
            json!({ "start": { "line": line, "character": from }, "end": { "line": line, "character": from + 7 } })
        };
        assert_eq!(result(&r)["range"], want, "utf8 {utf8}");
        assert_eq!(result(&r)["placeholder"], "2001.1P");
        // rename: the header in the part, both embeddings in the project
        let p = s.pos(&project, ">2001.1P  # zwei", 3);
        let mut params = s.at(&s.project.clone(), p);
        params["newName"] = json!("2001.5S");
        let r = s.c.request("textDocument/rename", params);
        let changes = result(&r)["changes"].as_object().unwrap().clone();
        assert_eq!(changes.len(), 2, "{r}");
        for (doc, edits) in &changes {
            let edits = edits.as_array().unwrap();
            if decode_uri(doc).ends_with("2001.mpath") {
                assert_eq!(edits.len(), 1);
                assert_eq!(edits[0]["range"], s.range(PART, "2001.1P"));
                assert_eq!(edits[0]["newText"], "2001.5S");
            } else {
                assert!(decode_uri(doc).ends_with("2010.mpath"), "{doc}");
                let mut ranges: Vec<Value> = edits.iter().map(|e| e["range"].clone()).collect();
                ranges.sort_by_key(|r| r["start"]["line"].as_u64());
                let whole = |line: u64, text: &str| {
                    let from = s.col(&text[..text.find(">2001").unwrap()]);
                    json!({ "start": { "line": line, "character": from }, "end": { "line": line, "character": from + 8 } })
                };
                assert_eq!(ranges, vec![whole(6, SUB1), whole(8, SUB2)], "utf8 {utf8}");
                assert!(edits.iter().all(|e| e["newText"] == ">2001.5S"));
            }
        }
        // refused: an invalid name, with the pattern named
        let p = s.pos(PART, "2001.1P", 2);
        let mut params = s.at(&s.part.clone(), p.clone());
        params["newName"] = json!("Schlitz");
        let r = s.c.request("textDocument/rename", params);
        let msg = r["error"]["message"].as_str().unwrap_or_default();
        assert!(msg.contains("not a valid path name"), "{r}");
        assert_eq!(r["error"]["code"], -32803, "RequestFailed");
        // refused: a drawing embeds the name
        let mut w = millpath_dxf::writer::DxfWriter::new();
        w.circle("2040_1P", Some("PHANTOM"), (0.0, 0.0), 0.5)
            .line("2040_1P", Some("DASHDOT"), (0.0, 0.0), (30.0, 0.0))
            .mtext("2040_1P", (15.0, 0.0), 0.3, &[">2001.1P"]);
        std::fs::write(s.dir.join("2040.dxf"), w.finish()).unwrap();
        let mut params = s.at(&s.part.clone(), p);
        params["newName"] = json!("2001.5S");
        let r = s.c.request("textDocument/rename", params);
        let msg = r["error"]["message"].as_str().unwrap_or_default();
        assert!(msg.contains("2040.dxf"), "{r}");
        assert!(s.c.shutdown().success());
    }
}

#[test]
fn folding_links_highlights_and_selection_in_both_encodings() {
    for utf8 in [false, true] {
        let mut s = Session::start(utf8);
        let project = project();
        let doc = s.project.clone();
        // folding: the leading comment block and the path (up to the line before `}`)
        let r = s.c.request(
            "textDocument/foldingRange",
            json!({ "textDocument": { "uri": doc } }),
        );
        let folds: Vec<(u64, u64, String)> = result(&r)
            .as_array()
            .unwrap()
            .iter()
            .map(|f| {
                (
                    f["startLine"].as_u64().unwrap(),
                    f["endLine"].as_u64().unwrap(),
                    f["kind"].as_str().unwrap_or("").to_string(),
                )
            })
            .collect();
        assert_eq!(
            folds,
            vec![(0, 1, "comment".to_string()), (2, 9, "region".to_string())]
        );
        // links: both embeddings open the part
        let r = s.c.request(
            "textDocument/documentLink",
            json!({ "textDocument": { "uri": doc } }),
        );
        let links = result(&r).as_array().unwrap().clone();
        assert_eq!(links.len(), 2, "{r}");
        for (l, (line, text)) in links.iter().zip([(6, SUB1), (8, SUB2)]) {
            assert!(decode_uri(l["target"].as_str().unwrap()).ends_with("/2001.mpath"));
            let from = s.col(&text[..text.find(">2001").unwrap() + 1]);
            assert_eq!(
                l["range"],
                json!({ "start": { "line": line, "character": from }, "end": { "line": line, "character": from + 7 } })
            );
        }
        // highlight: every use of the name
        let p = s.pos(&project, ">2001.1P", 2);
        let r = s.c.request("textDocument/documentHighlight", s.at(&doc, p));
        let hs = result(&r).as_array().unwrap().clone();
        assert_eq!(hs.len(), 2, "{r}");
        assert_eq!(
            hs[1]["range"]["start"]["character"],
            s.col(&SUB2[..SUB2.find(">2001").unwrap()])
        );
        // selection: parameter → element → path → file
        let p = s.pos(&project, ">2001.1P  # zwei", 3);
        let r = s.c.request(
            "textDocument/selectionRange",
            json!({ "textDocument": { "uri": doc }, "positions": [p] }),
        );
        let mut sel = &result(&r)[0];
        let mut chain = Vec::new();
        while sel.is_object() {
            chain.push(sel["range"].clone());
            sel = &sel["parent"];
        }
        assert_eq!(chain.len(), 4, "{r}");
        let from = s.col(&SUB2[..SUB2.find(">2001").unwrap()]);
        assert_eq!(
            chain[0],
            json!({ "start": { "line": 8, "character": from }, "end": { "line": 8, "character": from + 8 } })
        );
        assert_eq!(
            chain[1],
            json!({ "start": { "line": 8, "character": 2 }, "end": { "line": 8, "character": s.col(SUB2) } })
        );
        assert_eq!(chain[2]["start"], json!({ "line": 2, "character": 0 }));
        assert_eq!(chain[2]["end"], json!({ "line": 10, "character": 1 }));
        assert_eq!(chain[3]["start"], json!({ "line": 0, "character": 0 }));
        assert!(s.c.shutdown().success());
    }
}

#[test]
fn range_formatting_definition_and_symbols() {
    for utf8 in [false, true] {
        let mut s = Session::start(utf8);
        // definition from an embedding: the `path` header, not the start marker
        let project = project();
        let p = s.pos(&project, ">2001.1P", 3);
        let r =
            s.c.request("textDocument/definition", s.at(&s.project.clone(), p));
        assert_eq!(result(&r)[0]["range"], s.range(PART, "2001.1P"), "{r}");
        // symbols: the selection range is the name
        let r = s.c.request(
            "textDocument/documentSymbol",
            json!({ "textDocument": { "uri": s.project } }),
        );
        let sym = &result(&r)[0];
        assert_eq!(sym["selectionRange"], s.range(&project, "2010.1P"));
        assert_eq!(sym["range"]["start"], json!({ "line": 2, "character": 0 }));
        let sub = &sym["children"][3];
        let from = s.col("  ");
        assert_eq!(sub["selectionRange"]["start"]["character"], from);
        assert_eq!(
            sub["selectionRange"]["end"]["character"],
            s.col("  sub (10, 10) -> (40, 10)")
        );
        // range formatting: only the path in range; a no-op on formatted text
        let messy = format!("{PART}\npath 2001.2P {{  # ä😀\n   mill (0,0)->(1,1)   B1\n}}\n");
        let path = s.dir.join("2001.mpath");
        s.c.notify("textDocument/didChange", json!({ "textDocument": { "uri": uri(&path), "version": 2 }, "contentChanges": [{ "text": messy }] }));
        let r = s.c.request("textDocument/rangeFormatting", json!({ "textDocument": { "uri": s.part },
            "range": { "start": { "line": 10, "character": 0 }, "end": { "line": 10, "character": 3 } },
            "options": { "tabSize": 2, "insertSpaces": true } }));
        let edits = result(&r).as_array().unwrap().clone();
        assert_eq!(edits.len(), 1, "{r}");
        assert_eq!(
            edits[0]["newText"],
            "path 2001.2P {  # ä😀\n  mill (0, 0) -> (1, 1)  B1\n}"
        );
        assert_eq!(
            edits[0]["range"]["start"],
            json!({ "line": 9, "character": 0 })
        );
        assert_eq!(
            edits[0]["range"]["end"],
            json!({ "line": 11, "character": 1 })
        );
        let r = s.c.request("textDocument/rangeFormatting", json!({ "textDocument": { "uri": s.part },
            "range": { "start": { "line": 0, "character": 0 }, "end": { "line": 7, "character": 1 } },
            "options": { "tabSize": 2, "insertSpaces": true } }));
        assert_eq!(result(&r), &json!([]), "formatted already");
        assert!(s.c.shutdown().success());
    }
}
