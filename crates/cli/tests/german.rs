//! German output of every command, with no English message text left: each command runs
//! with `--lang de` (and once with `lang = "de"` only in millpath.toml) on inputs that make
//! it print messages — errors, warnings, progress, option errors of clap, hover in the
//! editor — and no English word of a list may appear outside file names, message codes,
//! options, quoted user text, source lines and G-code.

mod common;

use common::lsp_client::{uri, Client};
use common::millpath;
use serde_json::json;
use std::path::Path;
use std::time::Duration;

/// Words that only English message text has (whole words, any case; not `Argument`,
/// `Layer`, `Handle`, which German shares).
const ENGLISH: &[&str] = &[
    "error",
    "errors",
    "warning",
    "warnings",
    "expected",
    "found",
    "line",
    "lines",
    "missing",
    "not",
    "cannot",
    "writing",
    "reading",
    "checking",
    "file",
    "files",
    "must",
    "value",
    "values",
    "the",
    "is",
    "and",
    "of",
    "for",
    "with",
    "at",
    "on",
    "from",
    "usage",
    "options",
    "help",
    "print",
    "invalid",
    "unexpected",
    "required",
    "removed",
    "volume",
    "default",
    "own",
    "when",
    "embedded",
    "checked",
    "path",
    "here",
    "more",
    "information",
    "try",
    "tip",
    "formatted",
    "unreadable",
    "passes",
    "length",
    "top",
    "level",
    "no",
];

/// The English words of `text` outside file names, codes, options, quoted text, source
/// lines (`  3 │ …`) and G-code (`    | …`).
fn english_words(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    for line in text.lines() {
        // G-code quoted by verify, source lines shown under a message
        if line.starts_with("    | ") || line.contains('│') {
            continue;
        }
        // a GitHub annotation: its message after the protocol's `::…::`
        let line = match line.strip_prefix("::") {
            Some(rest) => rest.rsplit("::").next().unwrap_or(""),
            None => line,
        };
        let mut kept = String::new();
        let mut quote: Option<char> = None;
        for c in line.chars() {
            match quote {
                Some(q) if c == q => quote = None,
                Some(_) => {}
                None if c == '\'' || c == '`' || c == '"' => quote = Some(c),
                None => kept.push(c),
            }
        }
        for word in kept.split_whitespace() {
            // file names, paths, options, codes: not message text
            // (and `<FILE>`: placeholders of the command-line syntax, as option names)
            if word.contains(['.', '/', '\\', '_', '=', '[', ']', '<', '>'])
                || word.starts_with('-')
                || word.starts_with("MP")
            {
                continue;
            }
            for w in word.split(|c: char| !c.is_alphabetic()) {
                if ENGLISH.contains(&w.to_lowercase().as_str()) {
                    found.push(format!("{w} in: {line}"));
                }
            }
        }
    }
    found
}

fn assert_german(what: &str, text: &str) {
    let english = english_words(text);
    assert!(
        english.is_empty(),
        "{what}: English text:\n{}\n--- whole output:\n{text}",
        english.join("\n")
    );
}

fn run(dir: &Path, args: &[&str]) -> String {
    let out = millpath(dir, args);
    format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

const GOOD: &str = "path 3001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (20, 0)\n  mill (0, 0) -> (20, 0)\n}\n";
/// Errors in the build (B above T, a subpath nowhere), no syntax error (the parser's
/// messages are another part of the work).
const BAD: &str = "path 3002.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B4\n  end (20, 0)\n  sub (0, 0) -> (20, 0)  >9999.1P\n}\n";
/// A loop started at a corner: the order warning.
const WARN: &str = "path 3003.1P {\n  start (0, 0)  M10x3 O2 T2 I1 B0,5\n  end (0, 0)\n  mill (0, 0) -> (10, 0)\n  mill (10, 0) -> (10, 10)\n  mill (10, 10) -> (0, 10)\n  mill (0, 10) -> (0, 0)\n}\n";

fn folder(toml: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("millpath.toml"), toml).unwrap();
    std::fs::write(d.join("3001.mpath"), GOOD).unwrap();
    std::fs::write(d.join("3002.mpath"), BAD).unwrap();
    std::fs::write(d.join("3003.mpath"), WARN).unwrap();
    std::fs::write(d.join("ugly.mpath"), GOOD.replace("  ", "    ")).unwrap();
    dir
}

const MACHINE_TOML: &str = "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n";

/// The command lines that print messages, with `extra` (`--lang de` or nothing).
fn commands(dir: &Path, lang: &[&str]) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut go = |args: &[&str]| {
        let mut a: Vec<&str> = args[..1].to_vec();
        a.extend(lang);
        a.extend(&args[1..]);
        let mut text = run(dir, &a);
        if a.windows(2)
            .any(|w| w[0] == "--format" && (w[1] == "json" || w[1] == "sarif"))
        {
            // the keys and the severity are the format's; the messages are for people
            let start = text.find('{').unwrap_or(0);
            let v: serde_json::Value = serde_json::Deserializer::from_str(&text[start..])
                .into_iter()
                .next()
                .and_then(Result::ok)
                .unwrap_or_else(|| panic!("{text}"));
            let mut texts = vec![text[..start].to_string()];
            json_texts(&v, &mut texts);
            text = texts.join("\n");
        }
        out.push((a.join(" "), text));
    };
    go(&["compile", "3001.mpath", "3002.mpath", "3003.mpath"]);
    go(&["compile", "3001.mpath", "missing.dxf"]);
    for format in ["human", "json", "github", "sarif"] {
        go(&[
            "check",
            "--format",
            format,
            "3001.mpath",
            "3002.mpath",
            "3003.mpath",
        ]);
    }
    go(&["check", "empty-folder"]);
    go(&["text2dxf", "3001.mpath"]);
    go(&["text2dxf", "3001.mpath", "-o", "empty-folder"]);
    go(&["dxf2text", "3001.dxf", "-o", "back.mpath"]);
    go(&["dxf2text", "missing.dxf"]);
    go(&["dxf2text", "--textconv", "missing.dxf"]);
    // why a DXF cannot be read (the DXF reader's own words)
    go(&["compile", "broken.dxf"]);
    go(&["dxf2text", "broken.dxf"]);
    go(&["text2dxf", "3001.mpath", "--into", "broken.dxf"]);
    go(&["compile", "3001.mpath"]);
    go(&["verify", "3001_Milling.gcode", "bad.gcode", "missing.gcode"]);
    go(&["verify", "--tool", "0", "3001_Milling.gcode"]);
    go(&["adjust-z", "--max", "1", "3001", "missing"]);
    go(&["fmt", "--check", "ugly.mpath", "missing.mpath"]);
    go(&["fmt", "ugly.mpath"]);
    // clap's own errors
    go(&["check", "--bogus", "3001.mpath"]);
    go(&["check", "--formt", "json", "3001.mpath"]);
    go(&["check"]);
    go(&["verify", "--dialect", "foo", "x.gcode"]);
    go(&["adjust-z", "--max", "abc", "x"]);
    out
}

/// The texts for people in a JSON or SARIF report: every `message` and `text`.
fn json_texts(v: &serde_json::Value, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, v) in m {
                match (k.as_str(), v) {
                    ("message" | "text", serde_json::Value::String(s)) => out.push(s.clone()),
                    _ => json_texts(v, out),
                }
            }
        }
        serde_json::Value::Array(a) => a.iter().for_each(|v| json_texts(v, out)),
        _ => {}
    }
}

fn prepare(dir: &Path) {
    std::fs::create_dir(dir.join("empty-folder")).unwrap();
    // a DXF whose second group code is a word
    std::fs::write(dir.join("broken.dxf"), "  0\nSECTION\nlayer\nENTITIES\n").unwrap();
    std::fs::write(
        dir.join("bad.gcode"),
        "%\nG0 Z5\nG1 X10 Y0 Z-3\nG2 X0 Y0 I1 J0\n%\n",
    )
    .unwrap();
}

#[test]
fn every_command_with_lang_de_prints_no_english() {
    let dir = folder(MACHINE_TOML);
    prepare(dir.path());
    for (cmd, out) in commands(dir.path(), &["--lang", "de"]) {
        assert_german(&cmd, &out);
    }
    // help: clap's headings and every description in German, for every command
    for cmd in [
        "compile", "check", "verify", "adjust-z", "dxf2text", "text2dxf", "fmt", "render",
    ] {
        let help = run(dir.path(), &[cmd, "--lang", "de", "--help"]);
        assert_german(&format!("{cmd} --help"), &help);
    }
    let help = run(dir.path(), &["compile", "--lang", "de", "--help"]);
    assert!(help.contains("Vorschub der Fräsbewegungen"), "{help}");
    for de in [
        "Aufruf: millpath compile [OPTIONEN]",
        "Argumente:",
        "Optionen:",
        "Hilfe anzeigen",
    ] {
        assert!(help.contains(de), "{de}: {help}");
    }
    for en in [
        "Usage:",
        "Options:",
        "Arguments:",
        "Print help",
        "[OPTIONS]",
    ] {
        assert!(!help.contains(en), "{en}: {help}");
    }
    // render has the language of millpath.toml
    std::fs::write(
        dir.path().join("millpath.toml"),
        format!("{MACHINE_TOML}lang = \"de\"\n"),
    )
    .unwrap();
    for args in [
        &["render", "3001.mpath", "--svg", "a.svg"][..],
        &["render", "3002.mpath"],
        &["render", "3001.mpath", "--png", "empty-folder"],
    ] {
        assert_german(&args.join(" "), &run(dir.path(), args));
    }
}

#[test]
fn lang_de_in_millpath_toml_alone_is_honoured_by_every_command() {
    let dir = folder(&format!("{MACHINE_TOML}lang = \"de\"\n"));
    prepare(dir.path());
    for (cmd, out) in commands(dir.path(), &[]) {
        assert_german(&cmd, &out);
    }
    // the first message of compile comes before the settings are complete
    let bare = tempfile::tempdir().unwrap();
    std::fs::write(bare.path().join("millpath.toml"), "lang = \"de\"\n").unwrap();
    std::fs::write(bare.path().join("3001.mpath"), GOOD).unwrap();
    let out = run(bare.path(), &["compile", "3001.mpath"]);
    assert!(out.starts_with("Fehler: Maschinenwerte fehlen"), "{out}");
    assert_german("compile without machine settings", &out);
}

#[test]
fn the_check_is_strong_enough_to_see_english() {
    // what the commands printed before: each must be caught
    for english in [
        "error: unexpected argument '--bogus' found",
        "For more information, try '--help'.",
        "ugly.mpath: not formatted",
        "---- Writing a.svg",
        "error[MP039]: End marker missing",
        "| S | 10 | default (top level; T+O = 5 when embedded or checked) |",
        "Pfadanfang (line 4)",
    ] {
        assert!(!english_words(english).is_empty(), "{english}");
    }
    assert!(
        english_words("Fehler[MP039]: Ende-Markierung fehlt\n  --> a.dxf (Pfad 3001.1P)")
            .is_empty()
    );
}

#[test]
fn hover_in_the_editor_is_german() {
    let dir = folder(&format!("{MACHINE_TOML}lang = \"de\"\n"));
    let path = dir.path().join("3001.mpath");
    let mut c = Client::start(env!("CARGO_BIN_EXE_millpath"));
    c.initialize(dir.path(), json!({}));
    let doc = uri(&path);
    c.notify("textDocument/didOpen", json!({ "textDocument": { "uri": doc, "languageId": "millpath", "version": 1, "text": GOOD } }));
    c.wait_diagnostics(&doc, Duration::from_secs(10))
        .expect("diagnostics");
    // the mill line (an element with its table), a parameter letter, the start line
    for (line, character) in [(3, 4), (1, 17), (1, 4), (2, 4)] {
        let h = c.request(
            "textDocument/hover",
            json!({ "textDocument": { "uri": doc }, "position": { "line": line, "character": character } }),
        );
        let md = h["result"]["contents"]["value"]
            .as_str()
            .unwrap_or_else(|| panic!("{h}"));
        // the markdown: table bars and bold marks are no words
        let md = md.replace(['|', '*'], " ");
        assert_german(&format!("hover at {line}:{character}"), &md);
    }
    let h = c.request(
        "textDocument/hover",
        json!({ "textDocument": { "uri": doc }, "position": { "line": 3, "character": 4 } }),
    );
    let md = h["result"]["contents"]["value"].as_str().unwrap();
    assert!(md.contains("Pfadanfang (Zeile 2)"), "{md}");
    assert!(md.contains("Hauptpfad"), "{md}");
    c.shutdown();
}
