//! Issue 11: the command line a machinist can trust. Each test failed before its fix.

use std::io::Read;
use std::path::Path;
use std::process::{Command, Output, Stdio};

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_millpath")
}

fn millpath(dir: &Path, args: &[&str]) -> Output {
    Command::new(bin())
        .args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .output()
        .unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn example() -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate/1234.1P.dxf"),
    )
    .unwrap()
}

/// The example with its first X coordinate in ENTITIES replaced by `value`; and that line.
fn with_coordinate(value: &str) -> (String, usize) {
    let s = example();
    let i = s.find("ENTITIES").unwrap();
    let j = s[i..].find("\n 10\n").unwrap() + i;
    let k = s[j + 5..].find('\n').unwrap() + j + 5;
    let line = s[..j + 5].matches('\n').count() + 1;
    (format!("{}{value}{}", &s[..j + 5], &s[k..]), line)
}

/// Item 1: a closed stdout ends the program quietly (status 141), never a panic.
#[test]
fn closed_stdout_ends_quietly() {
    let dir = tempfile::tempdir().unwrap();
    for i in 0..400 {
        std::fs::write(dir.path().join(format!("{i:03}.dxf")), "junk\n").unwrap();
    }
    let mut child = Command::new(bin())
        .args(["check", "--format", "sarif", "."])
        .current_dir(dir.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut out = child.stdout.take().unwrap();
    let mut first = [0u8; 1];
    out.read_exact(&mut first).unwrap();
    drop(out); // like `| head -c1`
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(141), "{err}");
    assert!(
        !err.contains("panicked") && !err.contains("Broken pipe"),
        "{err}"
    );
}

/// Item 2: SARIF URIs are RFC 3986 URIs relative to %SRCROOT%, or file:/// URIs.
#[test]
fn sarif_uris_are_uris() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("d a")).unwrap();
    let (bad, _) = with_coordinate("NaN");
    std::fs::write(dir.path().join("d a/x #1 ü.dxf"), &bad).unwrap();
    let o = millpath(
        dir.path(),
        &["check", "--format", "sarif", "./d a/x #1 ü.dxf"],
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let run = &v["runs"][0];
    let loc = &run["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"];
    assert_eq!(loc["uri"], "d%20a/x%20%231%20%C3%BC.dxf");
    assert_eq!(loc["uriBaseId"], "%SRCROOT%");
    let root = run["originalUriBaseIds"]["%SRCROOT%"]["uri"]
        .as_str()
        .unwrap();
    assert!(
        root.starts_with("file:///") && root.ends_with('/'),
        "{root}"
    );
    for r in run["tool"]["driver"]["rules"].as_array().unwrap() {
        let t = r["shortDescription"]["text"].as_str().unwrap();
        assert!(!t.contains("{0}") && !t.contains("{1}"), "{t}");
    }
    // an absolute input inside the checked folder (the root, no repository here): relative
    // to %SRCROOT% like the others
    let abs = dir.path().join("d a/x #1 ü.dxf");
    let o = millpath(
        dir.path(),
        &["check", "--format", "sarif", abs.to_str().unwrap()],
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let uri = v["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]
        ["uri"]
        .as_str()
        .unwrap()
        .to_string();
    assert_eq!(uri, "d%20a/x%20%231%20%C3%BC.dxf");
    // a file outside the root: a file:/// URI
    let inner = dir.path().join("inner");
    std::fs::create_dir_all(&inner).unwrap();
    let o = millpath(
        &inner,
        &["check", "--format", "sarif", abs.to_str().unwrap()],
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let uri = v["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]
        ["uri"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(
        uri.starts_with("file:///") && uri.ends_with("/d%20a/x%20%231%20%C3%BC.dxf"),
        "{uri}"
    );
}

fn git(dir: &Path, args: &[&str]) -> Output {
    let o = Command::new("git")
        .args(args)
        .current_dir(dir)
        .env("GIT_CONFIG_NOSYSTEM", "1")
        .env("HOME", dir)
        .output()
        .unwrap();
    o
}

/// Item 3: `dxf2text --textconv` keeps `git diff` alive on an unreadable drawing.
#[test]
fn textconv_survives_truncated_dxf() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // without --textconv: exit 1, nothing on stdout (a plain conversion must fail)
    std::fs::write(d.join("a.dxf"), "0\nSECTION\n2\n").unwrap();
    let o = millpath(d, &["dxf2text", "a.dxf"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(o.stdout.is_empty());
    let o = millpath(d, &["dxf2text", "--textconv", "a.dxf"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    assert!(text(&o.stdout).contains("a.dxf"), "{}", text(&o.stdout));

    assert!(git(d, &["init", "-q"]).status.success());
    git(d, &["config", "user.email", "t@example.com"]);
    git(d, &["config", "user.name", "t"]);
    git(
        d,
        &[
            "config",
            "diff.dxf.textconv",
            &format!("{} dxf2text --textconv", bin()),
        ],
    );
    std::fs::write(d.join(".gitattributes"), "*.dxf diff=dxf\n").unwrap();
    let full = example();
    std::fs::write(d.join("a.dxf"), &full[..full.len() / 2]).unwrap();
    git(d, &["add", "."]);
    assert!(git(d, &["commit", "-qm", "truncated"]).status.success());
    std::fs::write(d.join("a.dxf"), &full[..full.len() / 3]).unwrap();
    let o = git(d, &["diff"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let diff = text(&o.stdout);
    assert!(diff.contains("a.dxf") && diff.contains("# "), "{diff}");
    // a readable drawing against the truncated one: the new text shows
    std::fs::write(d.join("a.dxf"), &full).unwrap();
    let o = git(d, &["diff"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(text(&o.stdout).contains("+"), "{}", text(&o.stdout));
}

/// Item 4: render says why there is nothing to draw.
#[test]
fn render_says_why() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // render, like compile, needs the machine settings
    std::fs::write(
        d.join("millpath.toml"),
        "feed = 150\nsweep_speed = 500\nsweep_height = 15\n",
    )
    .unwrap();
    std::fs::write(d.join("empty.dxf"), "").unwrap();
    std::fs::write(d.join("bad.mpath"), "garbage ((\n").unwrap();
    let o = millpath(d, &["render", "nothere.mpath"]);
    let e = text(&o.stderr);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        e.contains("Cannot read file") && !e.contains("no path"),
        "{e}"
    );
    let o = millpath(d, &["render", "empty.dxf"]);
    let e = text(&o.stderr);
    assert!(
        e.contains("Cannot load DXF file") && !e.contains("no path"),
        "{e}"
    );
    let o = millpath(d, &["render", "bad.mpath"]);
    let e = text(&o.stderr);
    assert!(e.contains("bad.mpath:1:1") && !e.contains("no path"), "{e}");
}

/// Item 6: a folder compiles every drawing in it; never `folder.dxf`.
#[test]
fn compile_a_folder() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("plate")).unwrap();
    std::fs::write(d.join("plate/1234.1P.dxf"), example()).unwrap();
    let o = millpath(
        d,
        &["compile", "-f", "150", "-v", "500", "-s", "5", "plate"],
    );
    let e = text(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{e}");
    assert!(d.join("plate/1234.1P_Milling.gcode").is_file(), "{e}");
    assert!(!e.contains("plate.dxf"), "{e}");
    std::fs::create_dir(d.join("none")).unwrap();
    let o = millpath(
        d.join("none").as_path(),
        &["compile", "-f", "1", "-v", "1", "-s", "1", "."],
    );
    let e = text(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "{e}");
    assert!(!e.contains("..dxf") && e.contains("no drawings"), "{e}");
}

/// Item 7: a binary file shows a short escaped excerpt.
#[test]
fn binary_input_is_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let mut bytes = b"\x7fELF\x02\x01\x01\0\0\0\0\0\0\0\0\0\x03\0>\0".to_vec();
    bytes.extend(vec![b'A'; 5000]);
    bytes.extend(b"\0\0\n");
    std::fs::write(dir.path().join("b.dxf"), &bytes).unwrap();
    let o = millpath(dir.path(), &["check", "b.dxf"]);
    let all = [o.stdout.clone(), o.stderr.clone()].concat();
    assert!(!all.contains(&0) && !all.contains(&0x7f), "{}", text(&all));
    let out = text(&o.stdout);
    assert!(out.contains("\\0") && out.len() < 600, "{out}");
}

/// Item 8: non-finite coordinates are errors at their DXF line.
#[test]
fn non_finite_coordinates_in_check() {
    let dir = tempfile::tempdir().unwrap();
    for v in ["1e999", "NaN"] {
        let (s, _) = with_coordinate(v);
        std::fs::write(dir.path().join("n.dxf"), s).unwrap();
        let o = millpath(dir.path(), &["check", "n.dxf"]);
        assert_eq!(o.status.code(), Some(1));
        let out = text(&o.stdout);
        assert!(
            out.contains("not finite") && out.contains("n.dxf:599 (CIRCLE on layer"),
            "{out}"
        );
    }
}

/// Item 9: no drawings: exit 3 with a message.
#[test]
fn check_without_drawings_is_exit_3() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("notes.txt"), "x").unwrap();
    let o = millpath(dir.path(), &["check", "."]);
    assert_eq!(o.status.code(), Some(3));
    assert!(
        text(&o.stderr).contains("no drawings"),
        "{}",
        text(&o.stderr)
    );
}

/// Item 10: a missing file is one message, located at the file, in every format.
#[test]
fn missing_file_is_one_located_message() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = millpath(
        d,
        &["compile", "-f", "1", "-v", "1", "-s", "1", "nothere.mpath"],
    );
    let e = text(&o.stderr);
    assert_eq!(e.matches("error[").count(), 1, "{e}");
    assert!(
        e.contains("--> nothere.mpath") && !e.contains("Input") && !e.contains("DXF file"),
        "{e}"
    );
    let o = millpath(d, &["check", "--format", "json", "nothere.mpath"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["diagnostics"].as_array().unwrap().len(), 1);
    assert_eq!(v["diagnostics"][0]["location"]["file"], "nothere.mpath");
    let o = millpath(d, &["check", "--format", "sarif", "nothere.mpath"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        v["runs"][0]["results"][0]["locations"]
            .as_array()
            .unwrap()
            .len(),
        1
    );
    // a .mpath file with errors: not "DXF file"
    std::fs::write(d.join("bad.mpath"), "garbage ((\n").unwrap();
    let o = millpath(
        d,
        &["compile", "-f", "1", "-v", "1", "-s", "1", "bad.mpath"],
    );
    assert!(!text(&o.stderr).contains("DXF file"), "{}", text(&o.stderr));
    // a failed write: no "Writing" and no statistics before the error
    std::fs::write(d.join("1234.1P.dxf"), example()).unwrap();
    std::fs::create_dir(d.join("1234.1P_Milling.gcode")).unwrap();
    let o = millpath(
        d,
        &[
            "compile",
            "-f",
            "150",
            "-v",
            "500",
            "-s",
            "5",
            "1234.1P.dxf",
        ],
    );
    let e = text(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(!e.contains("Writing") && !e.contains("length"), "{e}");
}

/// Item 11: German location lines.
#[test]
fn german_locations() {
    let dir = tempfile::tempdir().unwrap();
    let (s, _) = with_coordinate("NaN");
    std::fs::write(dir.path().join("n.dxf"), s).unwrap();
    let o = millpath(dir.path(), &["check", "--lang", "de", "n.dxf"]);
    let out = text(&o.stdout);
    assert!(
        out.contains("auf Layer") && out.contains("Handle") && out.contains("bei ["),
        "{out}"
    );
    assert!(
        out.contains("= Pfad ") && !out.contains("on layer") && !out.contains("error"),
        "{out}"
    );
}

/// Item 12: help everywhere, and only the options a command uses.
#[test]
fn help_texts() {
    let dir = tempfile::tempdir().unwrap();
    let o = millpath(dir.path(), &["pathdxf2gcode", "--help"]);
    let e = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2));
    assert!(!e.contains("not supported") && e.contains("/h"), "{e}");
    for cmd in ["check", "compile"] {
        let o = millpath(dir.path(), &[cmd, "--help"]);
        assert!(text(&o.stdout).contains(".mpath"), "{}", text(&o.stdout));
    }
    for cmd in ["dxf2text", "text2dxf"] {
        let o = millpath(dir.path(), &[cmd, "--help"]);
        let h = text(&o.stdout);
        assert!(
            !h.contains("--feed") && !h.contains("--sweep") && h.contains("--lang"),
            "{h}"
        );
    }
}

/// Item 13: the human check report goes to stdout, progress lines to stderr.
#[test]
fn check_report_on_stdout() {
    let dir = tempfile::tempdir().unwrap();
    let (s, _) = with_coordinate("NaN");
    std::fs::write(dir.path().join("n.dxf"), s).unwrap();
    let o = millpath(dir.path(), &["check", "."]);
    let out = text(&o.stdout);
    let err = text(&o.stderr);
    assert!(
        out.contains("error[MP") && out.contains("checked 1 file(s)"),
        "{out}"
    );
    assert!(
        !err.contains("error[MP") && err.contains("---- Reading"),
        "{err}"
    );
}

/// Item 14: `-o -` is standard output.
#[test]
fn dash_is_stdout() {
    let dir = tempfile::tempdir().unwrap();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/text/2001.mpath");
    std::fs::copy(&src, dir.path().join("2001.mpath")).unwrap();
    let o = millpath(dir.path(), &["text2dxf", "2001.mpath", "-o", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    assert!(text(&o.stdout).contains("ENTITIES"));
    assert!(!dir.path().join("-").exists());
    std::fs::write(dir.path().join("a.dxf"), example()).unwrap();
    let o = millpath(dir.path(), &["dxf2text", "a.dxf", "-o", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    assert!(!o.stdout.is_empty());
    assert!(!dir.path().join("-").exists());
}

/// Item 5: every complete example (fenced `mpath`) in docs/language.md checks and compiles,
/// with examples/text/ as the folder of its subpaths; fragments are fenced `mpath fragment`.
#[test]
fn language_doc_examples_compile() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let doc = std::fs::read_to_string(root.join("docs/language.md")).unwrap();
    let mut examples = Vec::new();
    let mut lines = doc.lines();
    while let Some(l) = lines.next() {
        if let Some(info) = l.strip_prefix("```") {
            let body: Vec<&str> = lines
                .by_ref()
                .take_while(|l| !l.starts_with("```"))
                .collect();
            let info = info.trim();
            if info == "mpath" {
                examples.push(body.join("\n") + "\n");
            } else {
                // an unmarked block that looks like a complete path must be marked
                assert!(
                    info.starts_with("mpath") || !body.iter().any(|l| l.starts_with("path ")),
                    "unmarked example in docs/language.md:\n{}",
                    body.join("\n")
                );
            }
        }
    }
    assert!(!examples.is_empty());
    for ex in examples {
        let dir = tempfile::tempdir().unwrap();
        for e in std::fs::read_dir(root.join("examples/text")).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|e| e == "mpath") {
                std::fs::copy(&p, dir.path().join(p.file_name().unwrap())).unwrap();
            }
        }
        let name = ex
            .lines()
            .find_map(|l| l.strip_prefix("path "))
            .and_then(|l| l.split(['.', ' ']).next())
            .unwrap()
            .to_string();
        let file = format!("{name}.mpath");
        std::fs::write(dir.path().join(&file), &ex).unwrap();
        let o = millpath(dir.path(), &["check", &file]);
        assert_eq!(o.status.code(), Some(0), "{ex}\n{}", text(&o.stdout));
        let o = millpath(
            dir.path(),
            &["compile", "-f", "150", "-v", "500", "-s", "5", &file],
        );
        assert_eq!(o.status.code(), Some(0), "{ex}\n{}", text(&o.stderr));
    }
}

/// Item 15: an error in a .mpath file shows its source line with the span underlined,
/// plain when piped or with NO_COLOR, in English and German.
#[test]
fn mpath_errors_show_the_source() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("e.mpath"),
        "path 1234.1P {\n  start (0, 0)  T3 O2\n  mill (0, 0) -> (1 ü, 1)\n}\n",
    )
    .unwrap();
    let o = millpath(dir.path(), &["check", "e.mpath"]);
    let out = text(&o.stdout);
    assert!(!out.contains('\u{1b}'), "{out}");
    assert!(out.contains("e.mpath:3:21"), "{out}");
    assert!(out.contains("  mill (0, 0) -> (1 ü, 1)"), "{out}");
    let line = out
        .lines()
        .find(|l| l.contains("error here"))
        .unwrap_or_default();
    assert!(!line.is_empty(), "{out}");
    let caret = out.lines().find(|l| l.contains('┬')).unwrap();
    let src = out.lines().find(|l| l.contains("mill (0, 0)")).unwrap();
    assert_eq!(
        caret.chars().position(|c| c == '┬'),
        src.chars().position(|c| c == 'ü'),
        "{out}"
    );
    let o = millpath(dir.path(), &["check", "--lang", "de", "e.mpath"]);
    let out = text(&o.stdout);
    assert!(
        out.contains("Fehler hier") && out.contains("Fehler"),
        "{out}"
    );
}
