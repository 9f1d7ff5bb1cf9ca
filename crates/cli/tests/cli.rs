//! The command line end to end: exit statuses, output files, settings, report formats.

mod common;

use common::{millpath, MACHINE};
use std::path::Path;

fn example() -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate/1234.1P.dxf"),
    )
    .unwrap()
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn compat_exit_statuses() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("1234.1P.dxf"), example()).unwrap();
    assert_eq!(
        millpath(dir.path(), &["pathdxf2gcode", "/?"]).status.code(),
        Some(2)
    );
    assert_eq!(
        millpath(dir.path(), &["pathdxf2gcode"]).status.code(),
        Some(2)
    );
    let o = millpath(dir.path(), &["pathdxf2gcode", "/v500", "/s5", "1234.1P"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("**** Options: /f missing or not > 0"));
    assert_eq!(
        millpath(dir.path(), &["pathdxf2gcode", "/f150", "/v500", "/s5"])
            .status
            .code(),
        Some(3)
    );
    // success, `.dxf` appended, German messages
    let o = millpath(
        dir.path(),
        &[
            "pathdxf2gcode",
            "-f",
            "150",
            "/v500",
            "/s5,5",
            "1234.1P",
            "/l",
            "de",
        ],
    );
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("---- Schreiben von 1234.1P_Milling.gcode"));
    let g = std::fs::read_to_string(dir.path().join("1234.1P_Milling.gcode")).unwrap();
    assert!(g.contains("G00 Z5.500") && g.contains("(Fräslänge:"));
    // a missing file: exit 1, nothing written
    let o = millpath(
        dir.path(),
        &["pathdxf2gcode", "/f150", "/v500", "/s5", "nope.dxf"],
    );
    assert_eq!(o.status.code(), Some(1));
}

#[test]
fn errors_leave_no_output_files() {
    let dir = tempfile::tempdir().unwrap();
    // a broken copy: the end marker is gone, so the path cannot be built
    let broken = example().replacen(
        "PHANTOM\n100\nAcDbCircle\n 10\n80.0",
        "PHANTOM\n100\nAcDbCircle\n 10\n85.0",
        1,
    );
    assert_ne!(broken, example());
    std::fs::write(dir.path().join("1234.1P.dxf"), broken).unwrap();
    let before = names(dir.path());
    let o = millpath(
        dir.path(),
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
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("error[") && err.contains("1234.1P.dxf:"),
        "{err}"
    );
    assert_eq!(names(dir.path()), before);
}

#[test]
fn compile_reads_millpath_toml_and_flags_override() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("1234.1P.dxf"), example()).unwrap();
    // no settings at all: a clear usage error
    let o = millpath(dir.path(), &["compile", "1234.1P.dxf"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("millpath.toml"));
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 222\nsweep_speed = 1000\nsweep_height = 12\n",
    )
    .unwrap();
    let o = millpath(dir.path(), &["compile", "1234.1P.dxf"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let g = std::fs::read_to_string(dir.path().join("1234.1P_Milling.gcode")).unwrap();
    assert!(g.contains("F222.000") && g.contains("G00 Z12.000"));
    let o = millpath(
        dir.path(),
        &["compile", "--feed", "111", "--lang", "de", "1234.1P.dxf"],
    );
    assert_eq!(o.status.code(), Some(0));
    let g = std::fs::read_to_string(dir.path().join("1234.1P_Milling.gcode")).unwrap();
    assert!(g.contains("F111.000") && g.contains("(Fräslänge:"));
    std::fs::write(dir.path().join("millpath.toml"), "feed = 'x'\n").unwrap();
    let o = millpath(dir.path(), &["compile", "1234.1P.dxf"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("millpath.toml"));
}

#[test]
fn check_formats_and_exit_status() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    std::fs::write(dir.path().join("sub/1234.1P.dxf"), example()).unwrap();
    let o = millpath(dir.path(), &["check", "."]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        names(&dir.path().join("sub")) == ["1234.1P.dxf"],
        "check writes nothing"
    );
    std::fs::write(
        dir.path().join("sub/1234.2P.dxf"),
        example()
            .replace("1234_1P", "1234_2P")
            .replace("O2\\P", "O9\\P"),
    )
    .unwrap();
    let o = millpath(dir.path(), &["check", "--format", "json", "sub"]);
    assert_eq!(o.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["files"], 2);
    let d = &v["diagnostics"][0];
    assert_eq!(d["severity"], "error");
    assert!(d["location"]["line"].as_u64().unwrap() > 0);
    let o = millpath(dir.path(), &["check", "--format", "github", "sub"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.lines()
            .all(|l| l.starts_with("::error ") || l.starts_with("::warning ")),
        "{out}"
    );
    assert!(out.contains("file=sub/1234.2P.dxf,line="));
    let o = millpath(dir.path(), &["check", "--format", "sarif", "sub"]);
    assert_eq!(o.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["version"], "2.1.0");
    let results = v["runs"][0]["results"].as_array().unwrap();
    assert!(!results.is_empty());
    assert_eq!(
        results[0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"],
        "sub/1234.2P.dxf"
    );
}

#[test]
fn adjust_z_end_to_end() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("p_Z.txt"),
        "([1.000 1.000]/T=2.000) #51=2,1\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("p_Clean.gcode"),
        "%\nG01 Z0.800(=0.800+1.000*[#51-2.000])\nM30\n%\n",
    )
    .unwrap();
    let o = millpath(dir.path(), &["pathgcodeadjustz", "/m", "0,5", "p.dxf"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let m = std::fs::read_to_string(dir.path().join("p_Milling.gcode")).unwrap();
    assert_eq!(m, "%\nG01 Z0.900(==0.800+1.000*[#51-2.000])\nM30\n%\n");
    // too far off: error, no new file
    std::fs::remove_file(dir.path().join("p_Milling.gcode")).unwrap();
    std::fs::write(
        dir.path().join("p_Z.txt"),
        "([1.000 1.000]/T=2.000) #51=3\n",
    )
    .unwrap();
    let o = millpath(dir.path(), &["adjust-z", "--max", "0.5", "p_Clean.gcode"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr)
        .contains("Value 3 for #51 differs from 2.000 by more than --max=0.5"));
    assert!(!dir.path().join("p_Milling.gcode").exists());
    // a malformed expression is an error with its column, not a crash
    std::fs::write(
        dir.path().join("p_Z.txt"),
        "([1.000 1.000]/T=2.000) #51=2\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("p_Clean.gcode"),
        "%\nG01 Z0.800(=0.800+1.000*[#51-2.000)\nM30\n%\n",
    )
    .unwrap();
    let o = millpath(dir.path(), &["pathgcodeadjustz", "/m0.5", "p"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("']' expected at column"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(
        millpath(dir.path(), &["pathgcodeadjustz", "p"])
            .status
            .code(),
        Some(2)
    );
    // missing files are errors
    assert_eq!(
        millpath(dir.path(), &["pathgcodeadjustz", "/m1", "q"])
            .status
            .code(),
        Some(1)
    );
}

fn examples() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

#[test]
fn text_examples_are_formatted_and_compile_like_their_dxf_form() {
    let o = millpath(&examples(), &["fmt", "--check", "."]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    let dir = tempfile::tempdir().unwrap();
    let (text, back) = (dir.path().join("text"), dir.path().join("back"));
    std::fs::create_dir(&text).unwrap();
    std::fs::create_dir(&back).unwrap();
    for name in ["2001", "2010", "2020"] {
        std::fs::copy(
            examples().join(format!("text/{name}.mpath")),
            text.join(format!("{name}.mpath")),
        )
        .unwrap();
        let o = millpath(
            &text,
            &[
                "text2dxf",
                &format!("{name}.mpath"),
                "-o",
                back.join(format!("{name}.dxf")).to_str().unwrap(),
            ],
        );
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    for name in ["2010", "2020"] {
        let args = ["compile", "-f", "300", "-v", "1000", "-s", "10", "-z", "50"];
        let a = millpath(&text, &[&args[..], &[&format!("{name}.mpath")]].concat());
        let b = millpath(&back, &[&args[..], &[&format!("{name}.dxf")]].concat());
        assert_eq!(
            a.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&a.stderr)
        );
        assert_eq!(
            b.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&b.stderr)
        );
    }
    // the probing set's digest covers the file-name comment, which differs: masked
    let read = |d: &Path, f: &str| {
        let t = std::fs::read_to_string(d.join(f)).unwrap();
        let t = match t.find(" set=") {
            Some(at) => format!("{}{}", &t[..at + 5], &t[(at + 21).min(t.len())..]),
            None => t,
        };
        t.replace(".mpath", ".dxf")
    };
    assert_eq!(
        read(&text, "2010_Milling.gcode"),
        read(&back, "2010_Milling.gcode")
    );
    assert!(read(&text, "2010_Milling.gcode").contains("START Subpath 2001.1P[2001.dxf]"));
    for f in ["2020_Probing.gcode", "2020_Z.txt", "2020_Clean.gcode"] {
        assert_eq!(read(&text, f), read(&back, f), "{f}");
    }
    // dxf2text of the written DXF gives the text back (comments aside)
    let o = millpath(&back, &["dxf2text", "2020.dxf"]);
    assert_eq!(
        String::from_utf8_lossy(&o.stdout),
        "path 2020.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (60, 0)\n  probe (10, 5)\n  probe (50, 5)  L1\n  mill (0, 0) -> (60, 0)\n}\n"
    );
}

#[test]
fn fmt_rewrites_and_refuses_broken_files() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("a.mpath"),
        "path   X {\n   mill (0,0)->(1,1)   B1\n}\n",
    )
    .unwrap();
    assert_eq!(
        millpath(dir.path(), &["fmt", "--check", "a.mpath"])
            .status
            .code(),
        Some(1)
    );
    assert_eq!(
        millpath(dir.path(), &["fmt", "a.mpath"]).status.code(),
        Some(0)
    );
    assert_eq!(
        std::fs::read_to_string(dir.path().join("a.mpath")).unwrap(),
        "path X {\n  mill (0, 0) -> (1, 1)  B1\n}\n"
    );
    std::fs::write(dir.path().join("b.mpath"), "path X {\n  mill (0,0)->\n}\n").unwrap();
    let o = millpath(dir.path(), &["fmt", "b.mpath"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("b.mpath:2:"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(
        std::fs::read_to_string(dir.path().join("b.mpath")).unwrap(),
        "path X {\n  mill (0,0)->\n}\n"
    );
    // text2dxf refuses a file with syntax errors and writes nothing
    assert_eq!(
        millpath(dir.path(), &["text2dxf", "b.mpath"]).status.code(),
        Some(1)
    );
    assert!(!dir.path().join("b.dxf").exists());
}

#[test]
fn render_writes_a_toolpath_page_and_an_svg() {
    let dir = tempfile::tempdir().unwrap();
    for f in ["2001.mpath", "2010.mpath", "millpath.toml"] {
        std::fs::copy(examples().join("text").join(f), dir.path().join(f)).unwrap();
    }
    let o = millpath(dir.path(), &["render", "2010.mpath", "--svg", "t.svg"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let svg = std::fs::read_to_string(dir.path().join("t.svg")).unwrap();
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    assert!(svg.matches("<line").count() >= 10 && svg.contains("stroke-dasharray"));
    let o = millpath(dir.path(), &["render", "2010.mpath"]);
    assert_eq!(o.status.code(), Some(0));
    let html = std::fs::read_to_string(dir.path().join("2010_toolpath.html")).unwrap();
    assert!(html.contains(r#"<script id="toolpath-data" type="application/json">{"#));
    assert!(html.contains(r#""kind":"mill""#));
    // the page is the bundled viewer, with three.js inside and nothing to fetch
    assert!(html.contains("three.js") && !html.contains("<script src"));
    // a PNG of the top view, drawn without a browser: cuts in colour on white
    let o = millpath(dir.path(), &["render", "2010.mpath", "--png", "t.png"]);
    assert_eq!(o.status.code(), Some(0));
    let png = std::fs::read(dir.path().join("t.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let width = u32::from_be_bytes(png[16..20].try_into().unwrap());
    let height = u32::from_be_bytes(png[20..24].try_into().unwrap());
    assert_eq!(width.max(height), 1200, "{width}x{height}");
    // a path that does not exist
    let o = millpath(
        dir.path(),
        &["render", "2010.mpath", "--path", "9.9Q", "--svg", "x.svg"],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(!dir.path().join("x.svg").exists());
}

/// `render` without machine settings refuses like `compile` (no placeholder F150/S15).
#[test]
fn render_without_machine_settings_refuses() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        examples().join("text").join("2001.mpath"),
        dir.path().join("2001.mpath"),
    )
    .unwrap();
    let o = millpath(dir.path(), &["render", "2001.mpath", "--svg", "t.svg"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("missing machine settings"));
    assert!(!dir.path().join("t.svg").exists());
}

/// `compile` reports the volume the written program removes (the second opinion's stock
/// model); the reference command line's output stays the reference's.
#[test]
fn compile_reports_the_removed_volume() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("1234.1P.dxf"), example()).unwrap();
    let mut args = vec!["compile"];
    args.extend(MACHINE);
    args.push("1234.1P.dxf");
    let out = millpath(dir.path(), &args);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    let line = err
        .lines()
        .find(|l| l.contains("Removed volume:"))
        .unwrap_or_else(|| panic!("{err}"));
    let mm3: f64 = line
        .split_whitespace()
        .rev()
        .nth(1)
        .and_then(|v| v.parse().ok())
        .unwrap();
    assert!(mm3 > 0.0, "{line}");
    let compat = millpath(
        dir.path(),
        &["pathdxf2gcode", "/f150", "/v500", "/s15", "1234.1P.dxf"],
    );
    assert!(!String::from_utf8_lossy(&compat.stderr).contains("Removed volume"));
}

/// Where the drawing's entity order decides the milling direction (a square started at a
/// corner): `check` and `compile` warn at the LINE that was taken; `pathdxf2gcode` prints
/// what the reference prints, and writes the same program as `compile`.
#[test]
fn order_warning_in_check_and_compile_not_in_pathdxf2gcode() {
    let dir = tempfile::tempdir().unwrap();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../core/tests/fixtures/order/3001.mpath");
    std::fs::copy(&src, dir.path().join("3001.mpath")).unwrap();
    let o = millpath(dir.path(), &["text2dxf", "3001.mpath", "-o", "3001.dxf"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = millpath(dir.path(), &["check", "--format", "json", "3001.dxf"]);
    assert_eq!(o.status.code(), Some(0), "a warning is no failure");
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let list = v["diagnostics"].as_array().unwrap();
    assert_eq!(list.len(), 1, "{v}");
    let d = &list[0];
    let code = millpath_core::Msg::OrderDecides.code();
    assert_eq!(d["code"], code.as_str());
    assert_eq!(d["severity"], "warning");
    assert!(d["message"].as_str().unwrap().contains("N9997"), "{d}");
    // the location is the LINE from the start corner (0, 0) to (20, 0)
    let line = d["location"]["line"].as_u64().unwrap() as usize;
    let dxf = std::fs::read_to_string(dir.path().join("3001.dxf")).unwrap();
    let entity: Vec<&str> = dxf.lines().skip(line - 1).take(40).collect();
    assert_eq!(entity[..2], ["  0", "LINE"], "{entity:?}");
    let at = |code: &str| {
        entity
            .iter()
            .position(|l| l.trim() == code)
            .map(|i| entity[i + 1].trim())
    };
    assert_eq!(
        (at("10"), at("20"), at("11"), at("21")),
        (Some("0.0"), Some("0.0"), Some("20.0"), Some("0.0")),
        "{entity:?}"
    );
    let flags = ["-f", "150", "-v", "500", "-s", "5"];
    let o = millpath(
        dir.path(),
        &[&["compile"][..], &flags, &["3001.dxf"]].concat(),
    );
    assert_eq!(o.status.code(), Some(0));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(&format!("warning[{code}]")), "{err}");
    let compiled = std::fs::read(dir.path().join("3001_Milling.gcode")).unwrap();
    std::fs::remove_file(dir.path().join("3001_Milling.gcode")).unwrap();
    let o = millpath(
        dir.path(),
        &["pathdxf2gcode", "/f150", "/v500", "/s5", "3001.dxf"],
    );
    assert_eq!(o.status.code(), Some(0));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("++++") && !err.contains("order"), "{err}");
    let reference = std::fs::read(dir.path().join("3001_Milling.gcode")).unwrap();
    assert_eq!(
        String::from_utf8_lossy(&reference)
            .lines()
            .skip(2)
            .collect::<Vec<_>>(),
        String::from_utf8_lossy(&compiled)
            .lines()
            .skip(2)
            .collect::<Vec<_>>()
    );
}

/// Two texts that want one element: `check` warns (the file order decides), the reference's
/// command line stays silent about it.
#[test]
fn text_order_warning_in_check_not_in_pathdxf2gcode() {
    let dir = tempfile::tempdir().unwrap();
    let mut w = millpath_dxf::writer::DxfWriter::new();
    let l = "1000_1P";
    w.circle(l, Some("PHANTOM"), (0.0, 0.0), 0.5)
        .mtext(l, (0.0, 0.0), 0.5, &["O2", "T2", "M20x2", "I2", "B-1"])
        .circle(l, Some("PHANTOM"), (40.0, 0.0), 1.0)
        .line(l, Some("DASHED"), (0.0, 0.0), (40.0, 0.0))
        .circle(l, Some("CONTINUOUS"), (10.0, 0.0), 3.0)
        .circle(l, Some("CONTINUOUS"), (16.0, 0.0), 3.0)
        .text(l, (12.0, 0.0), 0.5, "F100")
        .text(l, (12.5, 0.0), 0.5, "F200");
    std::fs::write(dir.path().join("1000.dxf"), w.finish()).unwrap();
    let code = millpath_core::Msg::TextTakenFirst.code();
    let o = millpath(dir.path(), &["check", "--format", "json", "1000.dxf"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let codes: Vec<&str> = v["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["code"].as_str().unwrap())
        .collect();
    assert!(codes.contains(&code.as_str()), "{v}");
    let o = millpath(
        dir.path(),
        &["pathdxf2gcode", "/f150", "/v500", "/s5", "1000.dxf"],
    );
    let all = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(!all.contains("F200") && !all.contains("order"), "{all}");
}

/// A text element's diagnostic spans the element, not its trailing comment (the same range
/// the editor shows).
#[test]
fn check_range_stops_before_the_trailing_comment() {
    let dir = tempfile::tempdir().unwrap();
    let src = "path 8000.1P {\n  start (0, 0)  T2 O2 B-0.3 I1\n  mill (0, 0) -> (10, 0)  B9  # too deep\n  end (10, 0)\n}\n";
    std::fs::write(dir.path().join("8000.mpath"), src).unwrap();
    let o = millpath(dir.path(), &["check", "--format", "json", "8000.mpath"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let loc = &v["diagnostics"][0]["location"];
    let (start, end) = (
        loc["start"].as_u64().unwrap() as usize,
        loc["end"].as_u64().unwrap() as usize,
    );
    assert_eq!(&src[start..end], "mill (0, 0) -> (10, 0)  B9");
}

/// Numbers on the command line take a decimal comma, as the drawings do (`--feed 300,5`,
/// `--max 0,5`); a number that is none is refused at its option.
#[test]
fn options_take_a_decimal_comma() {
    let dir = tempfile::tempdir().unwrap();
    let text = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/text");
    for f in ["2020.mpath", "millpath.toml"] {
        std::fs::copy(text.join(f), dir.path().join(f)).unwrap();
    }
    let o = millpath(dir.path(), &["compile", "--feed", "300,5", "2020.mpath"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let clean = std::fs::read_to_string(dir.path().join("2020_Clean.gcode")).unwrap();
    assert!(clean.contains("F300.500"), "{clean}");
    let z = dir.path().join("2020_Z.txt");
    let filled = std::fs::read_to_string(&z)
        .unwrap()
        .replace("#51=\n", "#51=3,1\n")
        .replace("#52=\n", "#52=2,9\n");
    std::fs::write(&z, filled).unwrap();
    // 0,05 is a limit of 0.05 mm: the probes 0.1 mm off are refused, 0,5 takes them
    let o = millpath(dir.path(), &["adjust-z", "--max", "0,05", "2020"]);
    assert_eq!(o.status.code(), Some(1));
    let o = millpath(dir.path(), &["adjust-z", "--max", "0,5", "2020"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = millpath(
        dir.path(),
        &[
            "verify",
            "--top",
            "3",
            "--tool",
            "2,0",
            "--bottom",
            "-0,5",
            "2020_Milling.gcode",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = millpath(dir.path(), &["compile", "--feed", "1,000.5", "2020.mpath"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--feed"));
}
