//! Every message has a location a person can find: `file:line:col` in a text file, the path
//! name where a message is about a path (also in a DXF, where JSON always had it), the file
//! itself for a file that cannot be read, written or removed; no spurious "End marker
//! missing" after a syntax error in the end line; advice on entity order that can be
//! followed on one piece of a polyline.

mod common;

use common::{millpath, MACHINE};
use millpath_core::Msg;
use std::path::Path;

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

fn stdout(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The `--> …` line after the message with `code`.
fn location_line<'a>(report: &'a str, code: &str) -> &'a str {
    let mut lines = report.lines();
    lines
        .by_ref()
        .find(|l| l.contains(&format!("[{code}]")))
        .unwrap_or_else(|| panic!("no {code} in:\n{report}"));
    lines
        .find(|l| l.trim_start().starts_with("-->") || l.contains("╭─["))
        .unwrap_or_else(|| panic!("no location after {code} in:\n{report}"))
}

const NO_END: &str =
    "path 3002.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  mill (0, 0) -> (20, 0)\n}\n";

#[test]
fn a_missing_marker_names_its_path_in_a_dxf_and_its_line_in_a_text() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "3002.mpath", NO_END);
    let out = millpath(dir.path(), &["text2dxf", "3002.mpath"]);
    assert!(out.status.success(), "{out:?}");
    let out = millpath(dir.path(), &["check", "3002.dxf", "3002.mpath"]);
    let report = stdout(&out);
    let code = Msg::EndMissing.code();
    let dxf = location_line(&report, &code);
    assert!(dxf.contains("3002.dxf (path 3002.1P)"), "{dxf}");
    let text = report.split("3002.dxf (path").nth(1).unwrap();
    assert!(
        location_line(text, &code).contains("3002.mpath:1:1 (path 3002.1P)"),
        "{report}"
    );
    let out = millpath(dir.path(), &["check", "--lang", "de", "3002.dxf"]);
    assert!(stdout(&out).contains("3002.dxf (Pfad 3002.1P)"), "{out:?}");
    let out = millpath(dir.path(), &["check", "--format", "github", "3002.mpath"]);
    assert!(
        stdout(&out).contains("file=3002.mpath,line=1,col=1,"),
        "{out:?}"
    );
}

#[test]
fn a_path_name_off_the_pattern_is_located_at_its_header_line() {
    let dir = tempfile::tempdir().unwrap();
    let text = "# a comment\npath foo {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  mill (0, 0) -> (10, 0)\n  end (10, 0)\n}\n";
    write(dir.path(), "name.mpath", text);
    let out = millpath(dir.path(), &["check", "name.mpath"]);
    let report = stdout(&out);
    let line = location_line(&report, &Msg::PathNameNoMatch.code());
    assert!(line.contains("name.mpath:2:1 (path foo)"), "{report}");
}

#[test]
fn a_syntax_error_in_the_end_line_gives_no_missing_end_marker() {
    let dir = tempfile::tempdir().unwrap();
    for end in ["end (20, 0", "end (20; 0)"] {
        let text = format!(
            "path 3001.1P {{\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  mill (0, 0) -> (20, 0)\n  {end}\n}}\n"
        );
        write(dir.path(), "3001.mpath", &text);
        let out = millpath(dir.path(), &["check", "--format", "json", "3001.mpath"]);
        let v: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
        let codes: Vec<&str> = v["diagnostics"]
            .as_array()
            .unwrap()
            .iter()
            .map(|d| d["code"].as_str().unwrap())
            .collect();
        // one syntax error, and nothing after it
        assert_eq!(codes.len(), 1, "{end}: {v}");
        let name = v["diagnostics"][0]["name"].as_str().unwrap_or_default();
        assert!(name.starts_with("Syntax"), "{end}: {v}");
        assert_eq!(v["diagnostics"][0]["location"]["line"], 4);
        assert_eq!(out.status.code(), Some(1));
    }
}

#[test]
fn a_subpath_not_found_never_ends_in_an_empty_file_list() {
    let dir = tempfile::tempdir().unwrap();
    let project = "path 3003.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  sub (0, 0) -> (20, 0)  >9999.1P\n  end (20, 0)\n}\n";
    write(dir.path(), "3003.mpath", project);
    let out = millpath(dir.path(), &["check", "3003.mpath"]);
    let report = stdout(&out);
    let line = report
        .lines()
        .find(|l| l.contains(&Msg::CouldNotFind.code()))
        .unwrap_or_else(|| panic!("{report}"));
    assert!(!line.trim_end().ends_with("file(s)"), "{line}");
    assert!(
        line.contains("no drawing in") && line.contains("file-name pattern"),
        "{line}"
    );
    // found, but broken: said so, with its file
    let part =
        "path 9999.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  mill (0, 0) -> (20, 0)\n}\n";
    write(dir.path(), "9999.mpath", part);
    let out = millpath(dir.path(), &["check", "--lang", "de", "3003.mpath"]);
    let report = stdout(&out);
    assert!(
        report.contains("Pfad 9999.1P (in ./9999.mpath) kann nicht eingebettet werden")
            || report.contains("Pfad 9999.1P (in 9999.mpath) kann nicht eingebettet werden"),
        "{report}"
    );
}

#[test]
fn files_that_cannot_be_read_or_written_are_named_as_the_location() {
    let dir = tempfile::tempdir().unwrap();
    // unreadable: the missing drawing is the location, not "Input"
    let out = millpath(dir.path(), &["dxf2text", "missing.dxf"]);
    let err = stderr(&out);
    assert!(
        location_line(&err, &Msg::CannotRead.code()).contains("--> missing.dxf"),
        "{err}"
    );
    // unwritable: the output file is the location, not "Options"
    write(dir.path(), "3002.mpath", NO_END);
    let out = millpath(
        dir.path(),
        &["text2dxf", "3002.mpath", "-o", "no-dir/out.dxf"],
    );
    let err = stderr(&out);
    assert!(
        location_line(&err, &Msg::CannotWrite.code()).contains("--> no-dir/out.dxf"),
        "{err}"
    );
    // a stale _Milling.gcode removed by adjust-z: the removed file is the location
    write(dir.path(), "p_Milling.gcode", "%\nM30\n%\n");
    std::thread::sleep(std::time::Duration::from_millis(20));
    write(dir.path(), "p_Clean.gcode", "not a program\n");
    write(dir.path(), "p_Z.txt", "");
    let out = millpath(dir.path(), &["adjust-z", "--max", "1", "p"]);
    let err = stderr(&out);
    assert!(
        location_line(&err, &Msg::StaleMillingRemoved.code()).contains("--> p_Milling.gcode"),
        "{err}"
    );
}

/// `text` (a DXF written by text2dxf) with its LINE entities replaced by one closed
/// LWPOLYLINE through `points` on `layer`.
fn lines_to_polyline(text: &str, layer: &str, points: &[(f64, f64)]) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    let mut inserted = false;
    while i + 1 < lines.len() {
        if lines[i].trim() == "0" && lines[i + 1] == "LINE" {
            if !inserted {
                inserted = true;
                let mut poly = format!(
                    "  0\nLWPOLYLINE\n  5\nFFF0\n100\nAcDbEntity\n  8\n{layer}\n100\nAcDbPolyline\n 90\n{}\n 70\n1\n",
                    points.len()
                );
                for (x, y) in points {
                    poly.push_str(&format!(" 10\n{x}\n 20\n{y}\n"));
                }
                out.push(poly.trim_end().to_string());
            }
            i += 2;
            while i + 1 < lines.len() && lines[i].trim() != "0" {
                i += 2;
            }
            continue;
        }
        out.push(format!("{}\n{}", lines[i], lines[i + 1]));
        i += 2;
    }
    out.join("\n") + "\n"
}

#[test]
fn order_advice_on_a_polyline_piece_says_to_explode_it_first() {
    let dir = tempfile::tempdir().unwrap();
    let square = "path 3005.1P {\n  start (0, 0)  O2 T2 I1 B0,5\n  end (0, 0)\n  mill (0, 0) -> (10, 0)\n  mill (10, 0) -> (10, 10)\n  mill (10, 10) -> (0, 10)\n  mill (0, 10) -> (0, 0)\n}\n";
    write(dir.path(), "3005.mpath", square);
    let out = millpath(dir.path(), &["text2dxf", "3005.mpath", "-o", "lines.dxf"]);
    assert!(out.status.success(), "{out:?}");
    let lines = std::fs::read_to_string(dir.path().join("lines.dxf")).unwrap();
    // drawn as four LINEs: N at the line taken pins it
    let out = millpath(dir.path(), &["check", "--format", "json", "lines.dxf"]);
    let v: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(v["diagnostics"][0]["code"], Msg::OrderDecides.code(), "{v}");
    // the same square as one closed polyline: N on it would hold for all four pieces
    let poly = lines_to_polyline(
        &lines,
        "3005_1P",
        &[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)],
    );
    assert!(poly.contains("LWPOLYLINE") && !poly.contains("\nLINE\n"));
    write(dir.path(), "3005.dxf", &poly);
    let out = millpath(
        dir.path(),
        &["check", "--extended", "--format", "json", "3005.dxf"],
    );
    let v: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    let d = &v["diagnostics"][0];
    assert_eq!(d["code"], Msg::OrderDecidesPiece.code(), "{v}");
    let msg = d["message"].as_str().unwrap();
    assert!(
        msg.contains("explode it into lines and arcs") && msg.contains("N9997"),
        "{msg}"
    );
    // following the advice: the pieces as lines, N9997 at the piece taken, no warning
    let pinned = square.replace("mill (0, 0) -> (10, 0)", "mill (0, 0) -> (10, 0)  N9997");
    write(dir.path(), "3005.mpath", &pinned);
    let out = millpath(dir.path(), &["text2dxf", "3005.mpath", "-o", "pinned.dxf"]);
    assert!(out.status.success());
    let mut args = vec!["compile"];
    args.extend(MACHINE);
    args.push("pinned.dxf");
    let out = millpath(dir.path(), &args);
    assert!(out.status.success(), "{out:?}");
    assert!(!stderr(&out).contains(&Msg::OrderDecides.code()), "{out:?}");
}

/// `[machine]` with `max_velocity` alone is an error of millpath.toml, located there (it
/// said "Options", where no such option exists).
#[test]
fn a_machine_table_without_acceleration_is_located_at_millpath_toml() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "3002.mpath",
        &NO_END.replace("  mill", "  end (20, 0)\n  mill"),
    );
    write(
        dir.path(),
        "millpath.toml",
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n[machine]\nmax_velocity = 3000\n",
    );
    let out = millpath(dir.path(), &["check", "3002.mpath"]);
    let report = format!("{}{}", stdout(&out), stderr(&out));
    let at = location_line(&report, &Msg::MachineNeedsAcceleration.code());
    assert!(at.contains("millpath.toml"), "{report}");
    let out = millpath(dir.path(), &["check", "--format", "github", "3002.mpath"]);
    assert!(
        stdout(&out).contains("::error file=millpath.toml,title=millpath MP098"),
        "{}",
        stdout(&out)
    );
}

/// The report formats give a message once located: no second place in its text (the
/// reference's `; FILE:LINE:COL`, kept in the `****` lines), and `github` keeps the hint.
#[test]
fn reports_keep_hints_and_locate_a_message_once() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "1004.mpath",
        "path 1004.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (20, 0)\n  mill (0, 0) -> (20, 0)  b1\n}\n",
    );
    let out = millpath(dir.path(), &["check", "--format", "github", "1004.mpath"]);
    let github = stdout(&out);
    assert!(
        github.contains("::Unsupported b value%0A= did you mean B? (keys are capital letters)"),
        "{github}"
    );
    let out = millpath(dir.path(), &["check", "1004.mpath"]);
    let human = stdout(&out);
    assert!(
        human.contains("error[MP019]: Unsupported b value\n"),
        "{human}"
    );
    let out = millpath(dir.path(), &["check", "--format", "json", "1004.mpath"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["diagnostics"][0]["message"], "Unsupported b value");
    let out = millpath(dir.path(), &["check", "--format", "sarif", "1004.mpath"]);
    assert!(
        !stdout(&out).contains("value; 1004.mpath"),
        "{}",
        stdout(&out)
    );
    // the reference's line keeps its text
    let out = millpath(
        dir.path(),
        &["pathdxf2gcode", "/c", "/f1", "/v1", "/s1", "1004.mpath"],
    );
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("Unsupported b value; 1004.mpath:4:"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A CAD program's name of a known line type (`Continuous`) says how it would be read.
#[test]
fn an_unknown_line_type_points_to_the_extended_mode() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "3002.mpath",
        &NO_END.replace("  mill", "  end (20, 0)\n  mill"),
    );
    let out = millpath(dir.path(), &["text2dxf", "3002.mpath"]);
    assert!(out.status.success(), "{out:?}");
    let dxf = std::fs::read_to_string(dir.path().join("3002.dxf")).unwrap();
    let dxf = dxf.replace("\nCONTINUOUS\n", "\nContinuous\n");
    write(dir.path(), "3002.dxf", &dxf);
    let out = millpath(dir.path(), &["check", "3002.dxf"]);
    let report = stdout(&out);
    assert!(
        report.contains("Line type Continuous not supported"),
        "{report}"
    );
    assert!(
        report.contains("= the extended mode reads it as CONTINUOUS: --extended, or input = \"extended\" in millpath.toml"),
        "{report}"
    );
    let out = millpath(dir.path(), &["check", "--lang", "de", "3002.dxf"]);
    assert!(stdout(&out).contains("der erweiterte Modus liest sie als CONTINUOUS"));
    let out = millpath(dir.path(), &["check", "--extended", "3002.dxf"]);
    assert!(out.status.success(), "{}", stdout(&out));
}
