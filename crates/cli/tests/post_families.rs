//! Every post's output is checked as its family (issue 32, item 4), end to end: custom posts
//! of the `rs274` family (line numbers, `;` comments), the `grbl` family (line numbers, `;`
//! comments) and the `marlin` family (one command a line, `;` comments, no `%`, arcs or
//! arcs as lines, `G4 S`, the end at `M5`) compile, and their programs are read clean by
//! `millpath verify --dialect FAMILY`; a custom post's program is held to its family's rules
//! like a built-in's (a `( )` comment in a Marlin program, a `%` line in a grbl program stop
//! the write); a family the checker cannot read (`xcam`) is refused, located, in English and
//! German, and nothing is written.

use std::path::Path;

mod common;

use common::{copy_text_examples as example, millpath};

fn shown(dir: &Path, name: &str) -> String {
    String::from_utf8(millpath(dir, &["post", "show", name]).stdout).unwrap()
}

fn gcode_files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".gcode"))
        .collect();
    v.sort();
    v
}

/// `post show BASE` with line numbers, `;` comments and the stock comment after a `;`.
fn numbered(dir: &Path, base: &str, name: &str) -> String {
    shown(dir, base)
        .replace(&format!("name = \"{base}\""), &format!("name = \"{name}\""))
        .replace(
            "[comments]\nstyle = \"parens\"",
            "[line_numbers]\nstart = 10\nstep = 10\n\n[comments]\nstyle = \"semicolon\"",
        )
        .replace(
            "comment = \"{indent}({text})\"",
            "comment = \"{indent}; {text}\"",
        )
        .replace("statistics = \"  ({text})\"", "statistics = \"; {text}\"")
        .replace(
            "stock = \"(MILLPATH-STOCK T={stock_top} O={tool_diameter} BOTTOM={stock_bottom})\"",
            "stock = \"; MILLPATH-STOCK T={stock_top} O={tool_diameter} BOTTOM={stock_bottom}\"",
        )
}

/// A Marlin router's post: `arcs` "ij" or "lines".
fn marlin(arcs: &str) -> String {
    format!(
        r#"[post]
name = "router"
description = "a Marlin router"
family = "marlin"
extension = "gcode"

[format]
decimals = 3
line_end = "lf"
percent = false
arcs = "{arcs}"

[comments]
style = "semicolon"

[capabilities]
probing = "none"
probe_log = false
spindle = true
dwell = true

[templates]
stock = "; MILLPATH-STOCK T={{stock_top}} O={{tool_diameter}} BOTTOM={{stock_bottom}}"
program_start = """
G21
G90
G1 F{{program_feed}}"""
spindle_on = "M3 S{{rpm}}"
dwell = "G4 S{{seconds}}"
comment = "{{indent}}; {{text}}"
statistics = "; {{text}}"
rapid_xy = "G0 X{{x}} Y{{y}}"
rapid_z = "G0 Z{{z}}"
retract = "G0 Z{{z}}"
plunge = "G1 F{{feed}} Z{{z}}"
linear = "G1 F{{feed}} X{{x}} Y{{y}} Z{{z}}"
arc_cw = "G2 F{{feed}} I{{i}} J{{j}} X{{x}} Y{{y}} Z{{z}}"
arc_ccw = "G3 F{{feed}} I{{i}} J{{j}} X{{x}} Y{{y}} Z{{z}}"
disabled = "; {{line}}"
spindle_off = "M5"
program_end = "M5"
"#
    )
}

/// Compiles `drawing` with `post` (a file in `dir`), asserts it worked, and has the checker
/// read every program as `family`: clean.
fn compiles_clean(dir: &Path, post: &str, drawing: &str, family: &str, extra: &[&str]) {
    for f in gcode_files(dir) {
        std::fs::remove_file(dir.join(f)).unwrap();
    }
    let mut args = vec!["compile", "--post", post];
    args.extend(extra);
    args.push(drawing);
    let out = millpath(dir, &args);
    assert!(
        out.status.success(),
        "{post} {drawing}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let files = gcode_files(dir);
    assert!(!files.is_empty());
    for f in files {
        let verified = millpath(dir, &["verify", "--dialect", family, &f]);
        assert!(
            verified.status.success(),
            "{post}: {f} as {family}: {}",
            String::from_utf8_lossy(&verified.stdout)
        );
    }
}

#[test]
fn every_family_is_read_and_its_posts_programs_check_clean() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    example(d);
    std::fs::write(d.join("rs.toml"), numbered(d, "linuxcnc", "numbered")).unwrap();
    std::fs::write(d.join("gr.toml"), numbered(d, "grbl", "numbered_grbl")).unwrap();
    std::fs::write(d.join("router.toml"), marlin("ij")).unwrap();
    std::fs::write(d.join("router_lines.toml"), marlin("lines")).unwrap();
    for drawing in ["2020.mpath", "2010.mpath", "2001.mpath"] {
        compiles_clean(d, "rs.toml", drawing, "rs274", &["--spindle-rpm", "9000"]);
    }
    let milling = std::fs::read_to_string(d.join("2001_Milling.gcode")).unwrap();
    assert!(milling
        .lines()
        .skip(1)
        .all(|l| l.starts_with('N') || l == "%"));
    assert!(milling.contains("; MILLPATH-STOCK"), "{milling}");
    for drawing in ["2001.mpath", "2010.mpath"] {
        compiles_clean(d, "gr.toml", drawing, "grbl", &["--spindle-rpm", "9000"]);
        for router in ["router.toml", "router_lines.toml"] {
            compiles_clean(d, router, drawing, "marlin", &["--spindle-rpm", "255"]);
        }
    }
    let router = std::fs::read_to_string(d.join("2010_Milling.gcode")).unwrap();
    assert!(!router.contains('(') && !router.contains('%') && !router.contains("M30"));
    assert!(router.lines().any(|l| l.starts_with("G4 S")), "{router}");
    // arcs as lines: no G2/G3 in the program
    assert!(!router
        .lines()
        .any(|l| l.starts_with("G2 ") || l.starts_with("G3 ")));
}

#[test]
fn a_custom_posts_program_is_held_to_its_familys_rules() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    example(d);
    let refused = |post: &str, text: &str, want: &str| {
        std::fs::write(d.join(post), text).unwrap();
        let out = millpath(d, &["compile", "--post", post, "2001.mpath"]);
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(!out.status.success() && err.contains(want), "{post}: {err}");
        assert!(gcode_files(d).is_empty(), "{post}: nothing written");
    };
    // a Marlin post that writes ( ) comments: Marlin would not read them
    refused(
        "parens.toml",
        &marlin("ij").replace("comment = \"{indent}; {text}\"", "comment = \"({text})\""),
        "reads only ; comments",
    );
    // a grbl-family post with % lines: GRBL rejects them
    refused(
        "percent.toml",
        &numbered(d, "grbl", "pct").replace("percent = false", "percent = true"),
        "a % line: grbl",
    );
    // a Marlin post that ends with M30: Marlin deletes a file with it
    refused(
        "m30.toml",
        &marlin("ij").replace("program_end = \"M5\"", "program_end = \"M30\""),
        "M30 deletes a file",
    );
}

/// Every family is read now (xcam by verify's NCC reader): a post that claims the xcam
/// family but writes G-code is refused by the second opinion, located, in English and
/// German, and writes nothing.
#[test]
fn a_post_whose_text_is_not_its_family_is_refused_located() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    example(d);
    let xcam = shown(d, "linuxcnc")
        .replace("name = \"linuxcnc\"", "name = \"exchange\"")
        .replace("family = \"rs274\"", "family = \"xcam\"");
    std::fs::write(d.join("xcam.toml"), &xcam).unwrap();
    let out = millpath(d, &["compile", "--post", "xcam.toml", "2001.mpath"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{err}");
    assert!(
        err.contains("NCC: the header H must be the first line") && err.contains("2001.mpath:"),
        "{err}"
    );
    assert!(gcode_files(d).is_empty());
    let out = millpath(
        d,
        &[
            "compile",
            "--lang",
            "de",
            "--post",
            "xcam.toml",
            "2001.mpath",
        ],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("NCC: der Programmkopf H muss die erste Zeile sein"),
        "{err}"
    );
    assert!(gcode_files(d).is_empty());
}
