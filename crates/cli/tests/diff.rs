//! `millpath diff` end to end: files and git revisions, exit statuses, the three formats,
//! German, and hostile input (binary, truncated, unrelated files, renames, a CAD re-save
//! that only reorders the entities).

mod common;
use common::{copy_text_examples, status_and_text};
use std::path::Path;
use std::process::Command;

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

fn git(dir: &Path, args: &[&str]) {
    let ok = Command::new("git")
        .args(["-c", "user.email=t@t", "-c", "user.name=t"])
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
        .status
        .success();
    assert!(ok, "git {args:?}");
}

/// 2001.mpath with its start's depth changed (the slot inherits it).
fn deeper_2001(dir: &Path) -> String {
    std::fs::read_to_string(dir.join("2001.mpath"))
        .unwrap()
        .replace("B-0,2", "B-0,5")
}

#[test]
fn files_exit_statuses_and_the_effect() {
    let d = tempfile::tempdir().unwrap();
    copy_text_examples(d.path());
    let (code, text) = status_and_text(d.path(), &["diff", "2001.mpath", "2001.mpath"]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("No change."), "{text}");
    std::fs::create_dir(d.path().join("new")).unwrap();
    std::fs::copy(
        d.path().join("millpath.toml"),
        d.path().join("new/millpath.toml"),
    )
    .unwrap();
    write(d.path(), "new/2001.mpath", &deeper_2001(d.path()));
    let (code, text) = status_and_text(d.path(), &["diff", "2001.mpath", "new/2001.mpath"]);
    assert_eq!(code, 1, "{text}");
    // the written change, the element it reaches, the group, the compiled figures
    assert!(text.contains("parameters (line 4)"), "{text}");
    assert!(
        text.contains("effect (line 7): mill (5, 0) -> (25, 0)"),
        "{text}"
    );
    assert!(
        text.contains("B -0,2 → -0,5 on 1 element, from path start (line 4)"),
        "{text}"
    );
    assert!(text.contains("lowest Z -0.2 → -0.5"), "{text}");
    assert!(text.contains("G-code changed"), "{text}");
    // German
    let (code, text) = status_and_text(
        d.path(),
        &["diff", "--lang", "de", "2001.mpath", "new/2001.mpath"],
    );
    assert_eq!(code, 1);
    assert!(text.contains("tiefstes Z -0,2 → -0,5"), "{text}");
    assert!(text.contains("G-Code geändert"), "{text}");
    // JSON
    let (code, text) = status_and_text(
        d.path(),
        &["diff", "--format", "json", "2001.mpath", "new/2001.mpath"],
    );
    assert_eq!(code, 1);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let p = &v["files"][0]["paths"][0];
    assert_eq!(p["status"], "changed");
    assert_eq!(p["effects"][0]["count"], 1);
    assert_eq!(p["before"]["lowest_z"], -0.2);
    assert_eq!(p["after"]["lowest_z"], -0.5);
    assert_eq!(p["gcode_changed"], true);
    // markdown: a table of the figures, the change in bold
    let (_, text) = status_and_text(
        d.path(),
        &[
            "diff",
            "--format",
            "markdown",
            "2001.mpath",
            "new/2001.mpath",
        ],
    );
    assert!(text.contains("| lowest Z | -0.2 | **-0.5** |"), "{text}");
    // the embedding drawing: the change reaches it through the subpath
    std::fs::copy(d.path().join("2010.mpath"), d.path().join("new/2010.mpath")).unwrap();
    let (code, text) = status_and_text(d.path(), &["diff", "2010.mpath", "new/2010.mpath"]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("moves of the embedded element 2001.mpath:7 changed"),
        "{text}"
    );
}

/// An editor's copies of two revisions, elsewhere: `--at` compiles them as the drawing in the
/// work tree (its millpath.toml and subpaths), as the diff in its own folder does.
#[test]
fn copies_read_at_the_drawing() {
    let d = tempfile::tempdir().unwrap();
    copy_text_examples(d.path());
    let copies = tempfile::tempdir().unwrap();
    let c = copies.path();
    std::fs::create_dir_all(c.join("HEAD")).unwrap();
    std::fs::create_dir_all(c.join("working tree")).unwrap();
    std::fs::copy(d.path().join("2001.mpath"), c.join("HEAD/2001.mpath")).unwrap();
    write(c, "working tree/2001.mpath", &deeper_2001(d.path()));
    let seconds = |args: &[&str]| {
        let (code, text) = status_and_text(c, args);
        assert_eq!(code, 1, "{text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        let p = &v["files"][0]["paths"][0];
        assert_eq!(p["effects"][0]["count"], 1, "{text}");
        assert_eq!(v["files"][0]["old"], "HEAD/2001.mpath");
        p["before"]["seconds"].as_f64().unwrap()
    };
    let pair = [
        "diff",
        "--format",
        "json",
        "HEAD/2001.mpath",
        "working tree/2001.mpath",
    ];
    let at = d.path().join("2001.mpath");
    let with_at = seconds(&[&pair[..], &["--at", at.to_str().unwrap()]].concat());
    let without = seconds(&pair);
    // the examples' millpath.toml sets the feeds: the same figure as the diff in place
    let (_, text) = status_and_text(
        d.path(),
        &["diff", "--format", "json", "2001.mpath", "2001.mpath"],
    );
    assert!(text.contains("\"changed\": false"), "{text}");
    write(d.path(), "new.mpath", &deeper_2001(d.path()));
    let (_, text) = status_and_text(
        d.path(),
        &["diff", "--format", "json", "2001.mpath", "new.mpath"],
    );
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let in_place = v["files"][0]["paths"][0]["before"]["seconds"]
        .as_f64()
        .unwrap();
    assert_eq!(with_at, in_place);
    assert_ne!(
        with_at, without,
        "millpath.toml beside the drawing was not read"
    );
    // the subpath (2010 embeds 2001) is found beside the drawing: both versions compile
    // (in folders without 2001.mpath)
    std::fs::create_dir_all(c.join("old")).unwrap();
    std::fs::create_dir_all(c.join("new")).unwrap();
    let t = std::fs::read_to_string(d.path().join("2010.mpath")).unwrap();
    write(c, "old/2010.mpath", &t);
    write(c, "new/2010.mpath", &t.replace("B-0,2 D2,5", "B-0,5 D2,5"));
    let pair = [
        "diff",
        "--format",
        "json",
        "old/2010.mpath",
        "new/2010.mpath",
    ];
    let error = |args: &[&str]| {
        let (code, text) = status_and_text(c, args);
        assert_eq!(code, 1, "{text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        v["files"][0]["paths"][0]["before"]["error"].clone()
    };
    let at = d.path().join("2010.mpath");
    assert!(error(&[&pair[..], &["--at", at.to_str().unwrap()]].concat()).is_null());
    assert!(!error(&pair).is_null(), "2001.mpath found without --at");
    // only with two files
    let (code, text) = status_and_text(d.path(), &["diff", "HEAD", "--at", "2001.mpath"]);
    assert_eq!(code, 2, "{text}");
    assert!(text.contains("--at goes with OLD NEW"), "{text}");
}

#[test]
fn a_change_without_effect_says_so() {
    let d = tempfile::tempdir().unwrap();
    copy_text_examples(d.path());
    // 2010's start depth: no element of 2010.1P mills down to it (the G-code stays the same)
    let t = std::fs::read_to_string(d.path().join("2010.mpath")).unwrap();
    std::fs::create_dir(d.path().join("new")).unwrap();
    for f in ["2001.mpath", "millpath.toml"] {
        std::fs::copy(d.path().join(f), d.path().join("new").join(f)).unwrap();
    }
    write(
        d.path(),
        "new/2010.mpath",
        &t.replace("B-0,2 D2,5", "B-0,5 D2,5"),
    );
    let (code, text) = status_and_text(d.path(), &["diff", "2010.mpath", "new/2010.mpath"]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("G-code unchanged"), "{text}");
    assert!(!text.contains("effect"), "{text}");
}

#[test]
fn reordered_and_converted_drawings_are_no_change() {
    let d = tempfile::tempdir().unwrap();
    let plate = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate");
    for f in ["1234.1P.dxf", "millpath.toml"] {
        std::fs::copy(plate.join(f), d.path().join(f)).unwrap();
    }
    let (code, text) = status_and_text(d.path(), &["dxf2text", "1234.1P.dxf", "-o", "text.mpath"]);
    assert_eq!(code, 0, "{text}");
    // a DXF against its own text
    let (code, text) = status_and_text(d.path(), &["diff", "1234.1P.dxf", "text.mpath"]);
    assert_eq!(code, 0, "{text}");
    // the entities in reverse order (a CAD re-save) with the paths written as a DXF again
    let t = std::fs::read_to_string(d.path().join("text.mpath")).unwrap();
    let mut lines: Vec<&str> = t.lines().collect();
    let (first, last) = (1, lines.len() - 1);
    lines[first..last].reverse();
    write(d.path(), "reordered.mpath", &(lines.join("\n") + "\n"));
    let (code, text) = status_and_text(
        d.path(),
        &["text2dxf", "reordered.mpath", "-o", "reordered.dxf"],
    );
    assert_eq!(code, 0, "{text}");
    let (code, text) = status_and_text(d.path(), &["diff", "1234.1P.dxf", "reordered.dxf"]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("No change."), "{text}");
}

#[test]
fn git_revisions() {
    let d = tempfile::tempdir().unwrap();
    copy_text_examples(d.path());
    git(d.path(), &["init", "-q"]);
    git(d.path(), &["add", "."]);
    git(d.path(), &["commit", "-qm", "one"]);
    let (code, text) = status_and_text(d.path(), &["diff"]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("No drawing changed."), "{text}");
    write(d.path(), "2001.mpath", &deeper_2001(d.path()));
    let (code, text) = status_and_text(d.path(), &["diff", "HEAD", "--", "2001.mpath"]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("HEAD:2001.mpath → 2001.mpath"), "{text}");
    assert!(text.contains("lowest Z -0.2 → -0.5"), "{text}");
    // without files: what git lists as changed
    let (code, text) = status_and_text(d.path(), &["diff"]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("2001.1P: changed"), "{text}");
    git(d.path(), &["commit", "-qam", "two"]);
    let (code, text) = status_and_text(d.path(), &["diff", "HEAD~1..HEAD", "--format", "markdown"]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("#### `2001.1P`: changed"), "{text}");
    let (code, _) = status_and_text(d.path(), &["diff", "HEAD..HEAD"]);
    assert_eq!(code, 0);
    // a renamed file with the same paths: no change
    git(d.path(), &["mv", "2020.mpath", "2021.mpath"]);
    let (code, text) = status_and_text(d.path(), &["diff"]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("HEAD:2020.mpath → 2021.mpath"), "{text}");
    // a file new since the revision: every path added
    write(
        d.path(),
        "2030.mpath",
        "path 2030.1P {\n  start (0, 0)  T1 O2 B-1\n  end (5, 0)\n  mill (0, 0) -> (5, 0)\n}\n",
    );
    let (code, text) = status_and_text(d.path(), &["diff", "HEAD", "--", "2030.mpath"]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("2030.1P: added"), "{text}");
    // a revision git does not know
    let (code, text) = status_and_text(d.path(), &["diff", "nosuchrev", "--", "2001.mpath"]);
    assert_eq!(code, 2, "{text}");
}

#[test]
fn hostile_inputs() {
    let d = tempfile::tempdir().unwrap();
    copy_text_examples(d.path());
    let plate = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate/1234.1P.dxf");
    let dxf = std::fs::read(plate).unwrap();
    std::fs::write(d.path().join("whole.dxf"), &dxf).unwrap();
    std::fs::write(d.path().join("truncated.dxf"), &dxf[..dxf.len() / 2]).unwrap();
    let binary: Vec<u8> = (0..4096u32).map(|i| (i * 7919 % 251) as u8).collect();
    std::fs::write(d.path().join("binary.dxf"), &binary).unwrap();
    std::fs::write(d.path().join("binary.mpath"), &binary).unwrap();
    for (a, b) in [
        ("whole.dxf", "truncated.dxf"),
        ("binary.dxf", "whole.dxf"),
        ("2001.mpath", "binary.mpath"),
        ("2001.mpath", "missing.mpath"),
    ] {
        let (code, text) = status_and_text(d.path(), &["diff", a, b]);
        assert_eq!(code, 2, "{a} {b}: {text}");
        assert!(text.contains("error"), "{a} {b}: {text}");
        assert!(!text.contains("panicked"), "{text}");
    }
    // unrelated drawings: one path removed, another added
    let (code, text) = status_and_text(d.path(), &["diff", "2001.mpath", "2020.mpath"]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("2001.1P: removed") && text.contains("2020.1P: added"),
        "{text}"
    );
    // a path renamed inside a file: paired by its elements
    let t = std::fs::read_to_string(d.path().join("2001.mpath")).unwrap();
    write(
        d.path(),
        "renamed.mpath",
        &t.replace("path 2001.1P", "path 2001.2P"),
    );
    let (code, text) = status_and_text(
        d.path(),
        &["diff", "--no-compile", "2001.mpath", "renamed.mpath"],
    );
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("2001.2P: renamed from 2001.1P"), "{text}");
}

/// The machine options count in the compiles, over each version's millpath.toml, as they
/// count in `compile`: a slower feed makes both versions' estimate longer, and `--dialect`
/// with `--spindle-rpm` changes the written program without changing the drawing.
#[test]
fn machine_options_count() {
    let d = tempfile::tempdir().unwrap();
    copy_text_examples(d.path());
    write(d.path(), "new.mpath", &deeper_2001(d.path()));
    let figures = |extra: &[&str]| {
        let args = [
            &["diff", "--format", "json", "2001.mpath", "new.mpath"][..],
            extra,
        ]
        .concat();
        let (code, text) = status_and_text(d.path(), &args);
        assert_eq!(code, 1, "{text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        let p = v["files"][0]["paths"][0].clone();
        (
            p["before"]["seconds"].as_f64().unwrap(),
            p["after"]["seconds"].as_f64().unwrap(),
        )
    };
    let (plain_before, plain_after) = figures(&[]);
    let (slow_before, slow_after) = figures(&["--feed", "10"]);
    assert!(
        slow_before > plain_before * 2.0,
        "{slow_before} vs {plain_before}"
    );
    assert!(
        slow_after > plain_after * 2.0,
        "{slow_after} vs {plain_after}"
    );
    // compile with the same option prints the same estimate (h:mm:ss)
    let (code, text) = status_and_text(d.path(), &["compile", "--feed", "10", "2001.mpath"]);
    assert_eq!(code, 0, "{text}");
    let secs = slow_before.round() as u64;
    let shown = format!("{}:{:02}:{:02}", secs / 3600, secs / 60 % 60, secs % 60);
    assert!(
        text.contains(&format!("Estimated time: {shown}")),
        "{shown}: {text}"
    );
    // a bad value is refused before anything compiles (exit 2), as in compile
    let (code, text) = status_and_text(
        d.path(),
        &["diff", "--feed", "-5", "2001.mpath", "new.mpath"],
    );
    assert_eq!(code, 2, "{text}");
    // a settings file given by --config counts as well
    write(d.path(), "slow.toml", "feed = 10\n");
    let (cfg_before, _) = figures(&["--config", "slow.toml"]);
    assert!(
        (cfg_before - slow_before).abs() < 1e-9,
        "{cfg_before} vs {slow_before}"
    );
}

/// `--svg NEW` for `--svg new.svg` would replace a drawing by its picture: refused (exit 2),
/// the drawing byte-identical, in git mode too (the work-tree file).
#[test]
fn pictures_never_replace_a_drawing() {
    let d = tempfile::tempdir().unwrap();
    copy_text_examples(d.path());
    write(d.path(), "new.mpath", &deeper_2001(d.path()));
    let before = std::fs::read(d.path().join("new.mpath")).unwrap();
    for flag in ["--svg", "--png", "--html"] {
        let (code, text) = status_and_text(
            d.path(),
            &["diff", "2001.mpath", "new.mpath", flag, "new.mpath"],
        );
        assert_eq!(code, 2, "{flag}: {text}");
        assert!(text.contains("is the drawing this command reads"), "{text}");
        assert_eq!(std::fs::read(d.path().join("new.mpath")).unwrap(), before);
    }
    git(d.path(), &["init", "-q"]);
    git(d.path(), &["add", "."]);
    git(d.path(), &["commit", "-qm", "one"]);
    write(d.path(), "2001.mpath", &deeper_2001(d.path()));
    let edited = std::fs::read(d.path().join("2001.mpath")).unwrap();
    let (code, text) = status_and_text(
        d.path(),
        &["diff", "HEAD", "--svg", "2001.mpath", "--", "2001.mpath"],
    );
    assert_eq!(code, 2, "{text}");
    assert_eq!(std::fs::read(d.path().join("2001.mpath")).unwrap(), edited);
    // another name is written
    let (code, text) = status_and_text(
        d.path(),
        &["diff", "2001.mpath", "new.mpath", "--svg", "change.svg"],
    );
    assert!(code <= 1, "{text}");
    assert!(d.path().join("change.svg").exists());
}

/// In git mode a drawing of a revision is read with that revision's `millpath.toml`: its
/// path-name pattern (`/n`) finds the paths of a DXF, whatever the work tree's settings are.
#[test]
fn a_revision_is_read_with_its_own_settings() {
    let d = tempfile::tempdir().unwrap();
    let toml = "feed = 300\nsweep_speed = 1000\nsweep_height = 10\npath_pattern = \"([A-Z]{2})[.]([0-9]+)([A-Z])\"\n";
    write(d.path(), "millpath.toml", toml);
    let drawing = |depth: &str| {
        let text = format!("path AB.1P {{\n  start (0, 0)  M3x40 O2 T3 I1,5 B{depth} D2,5\n  end (80, 0)\n  mill (0, 0) -> (40, 0)\n  mill (40, 0) -> (80, 0)\n}}\n");
        write(d.path(), "AB.mpath", &text);
        let (code, text) = status_and_text(d.path(), &["text2dxf", "AB.mpath", "-o", "AB.dxf"]);
        assert_eq!(code, 0, "{text}");
        std::fs::remove_file(d.path().join("AB.mpath")).unwrap();
    };
    drawing("-0,2");
    git(d.path(), &["init", "-q"]);
    git(d.path(), &["add", "."]);
    git(d.path(), &["commit", "-qm", "one"]);
    drawing("-0,5");
    git(d.path(), &["commit", "-qam", "two"]);
    // the work tree's settings name paths otherwise: the DXF has none by them
    write(
        d.path(),
        "millpath.toml",
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n",
    );
    let (code, text) = status_and_text(d.path(), &["diff", "HEAD~1..HEAD"]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("AB.1P: changed"), "{text}");
    assert!(text.contains("B -0,2 → -0,5 on 2 elements"), "{text}");
    // the work tree itself is read with its own settings: no path of that name
    let (code, text) = status_and_text(d.path(), &["diff", "HEAD", "--", "AB.dxf"]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("AB.1P: removed"), "{text}");
}

/// A folder with the machine settings in millpath.toml.
fn machine_folder() -> tempfile::TempDir {
    let d = tempfile::tempdir().unwrap();
    write(
        d.path(),
        "millpath.toml",
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n",
    );
    d
}

/// One slot, milled at `depth`.
fn slot(depth: &str) -> String {
    format!("path 3000.1P {{\n  start (0, 0)  M3x40 O2 T3 I1,5 B{depth}\n  end (80, 0)\n  mill (0, 0) -> (80, 0)\n}}\n")
}

#[test]
fn an_option_in_error_stops_a_diff_of_revisions() {
    let d = machine_folder();
    write(d.path(), "3000.mpath", &slot("-0,2"));
    git(d.path(), &["init", "-q"]);
    git(d.path(), &["add", "."]);
    git(d.path(), &["commit", "-qm", "one"]);
    write(d.path(), "3000.mpath", &slot("-0,5"));
    git(d.path(), &["commit", "-qam", "two"]);
    // a post that does not exist is the options' error (exit 2), not a diff without it
    let (code, out) = status_and_text(d.path(), &["diff", "HEAD~1..HEAD", "--post", "nosuch"]);
    assert_eq!(code, 2, "{out}");
    assert!(out.contains("nosuch"), "{out}");
    let (code, out) = status_and_text(d.path(), &["diff", "HEAD~1..HEAD", "--post", "grbl"]);
    assert_eq!(code, 1, "{out}");
}

#[test]
fn an_option_value_in_error_stops_the_diff_with_its_reason() {
    let d = machine_folder();
    write(d.path(), "old.mpath", &slot("-0,2"));
    write(d.path(), "new.mpath", &slot("-0,5"));
    // before: both versions "did not compile", exit 1, and no word of the option
    for (option, said) in [
        ("--feed=-5", "feed=-5 must be > 0"),
        ("--sweep-height=0", "sweep_height=0 must be > 0"),
        ("--feed=nan", "feed=NaN"),
        ("--feed=1e300", "feed=1e300"),
        ("--plunge-feed=0", "plunge_feed=0 must be > 0"),
        ("--feed-override=5000", "feed_override=5000"),
    ] {
        let (code, out) = status_and_text(d.path(), &["diff", option, "old.mpath", "new.mpath"]);
        assert_eq!(code, 2, "{option}: {out}");
        assert!(
            out.contains(said) && out.contains("Options"),
            "{option}: {out}"
        );
    }
    let (code, out) = status_and_text(
        d.path(),
        &[
            "diff",
            "--lang",
            "de",
            "--feed=-5",
            "old.mpath",
            "new.mpath",
        ],
    );
    assert_eq!(code, 2, "{out}");
    assert!(out.contains("feed=-5 muss > 0 sein"), "{out}");
    // the language of millpath.toml beside the drawings, as the rest of the report
    let de = machine_folder();
    write(
        de.path(),
        "millpath.toml",
        "lang = \"de\"\nfeed = 300\nsweep_speed = 1000\nsweep_height = 10\n",
    );
    write(de.path(), "old.mpath", &slot("-0,2"));
    write(de.path(), "new.mpath", &slot("-0,5"));
    let (code, out) = status_and_text(de.path(), &["diff", "--feed=-5", "old.mpath", "new.mpath"]);
    assert_eq!(code, 2, "{out}");
    assert!(out.contains("feed=-5 muss > 0 sein"), "{out}");
    // git difftool's page likewise: no page for options in error
    let (code, out) = status_and_text(
        d.path(),
        &[
            "difftool",
            "--feed=-5",
            "old.mpath",
            "new.mpath",
            "--html",
            "page.html",
        ],
    );
    assert_eq!(code, 2, "{out}");
    assert!(out.contains("feed=-5 must be > 0"), "{out}");
    assert!(!d.path().join("page.html").exists());
    // a sane value is a diff as before
    let (code, out) = status_and_text(d.path(), &["diff", "--feed=250", "old.mpath", "new.mpath"]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("G-code changed"), "{out}");
}
