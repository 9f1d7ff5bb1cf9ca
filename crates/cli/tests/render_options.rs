//! `render` reads its settings as the other commands do (options over `millpath.toml` or
//! `--config`), gives a reason when a path cannot be drawn, and writes the HTML page only
//! when no other picture was asked for (as its help says); every argument of every command
//! has a description.

mod common;

use common::millpath;
use std::path::Path;

fn examples() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/text")
}

fn svg_of(dir: &Path, args: &[&str]) -> String {
    let mut all = vec!["render"];
    all.extend(args);
    all.extend(["--svg", "t.svg", "2010.mpath"]);
    let o = millpath(dir, &all);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read_to_string(dir.join("t.svg")).unwrap()
}

#[test]
fn render_takes_machine_options_and_config() {
    let dir = tempfile::tempdir().unwrap();
    for f in ["2001.mpath", "2010.mpath"] {
        std::fs::copy(examples().join(f), dir.path().join(f)).unwrap();
    }
    // no millpath.toml: the options are enough
    let machine = [
        "--feed",
        "200",
        "--sweep-speed",
        "900",
        "--sweep-height",
        "12",
    ];
    let a = svg_of(dir.path(), &machine);
    assert!(a.starts_with("<svg"));
    // --config names a settings file elsewhere
    let cfg = dir.path().join("elsewhere.toml");
    std::fs::write(&cfg, "feed = 200\nsweep_speed = 900\nsweep_height = 12\n").unwrap();
    let b = svg_of(dir.path(), &["--config", cfg.to_str().unwrap()]);
    assert_eq!(a, b, "same settings, same picture");
    // and without either it refuses, in the language asked for
    let o = millpath(dir.path(), &["render", "--lang", "de", "2010.mpath"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("Maschinenwerte fehlen"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn a_path_that_cannot_be_drawn_gets_a_reason() {
    let dir = tempfile::tempdir().unwrap();
    for f in ["2001.mpath", "2010.mpath", "millpath.toml"] {
        std::fs::copy(examples().join(f), dir.path().join(f)).unwrap();
    }
    let o = millpath(dir.path(), &["render", "--path", "9999.1P", "2010.mpath"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("no path 9999.1P") && err.contains("2010.1P"),
        "{err}"
    );
    assert!(!err.trim_end().ends_with(':'), "{err}");
    let o = millpath(dir.path(), &["render", "--path", "2010.1p", "2010.mpath"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("did you mean 2010.1P"));
}

#[test]
fn html_is_written_only_when_no_other_picture_is_asked_for() {
    let dir = tempfile::tempdir().unwrap();
    for f in ["2001.mpath", "2010.mpath", "millpath.toml"] {
        std::fs::copy(examples().join(f), dir.path().join(f)).unwrap();
    }
    let page = dir.path().join("2010_toolpath.html");
    let o = millpath(dir.path(), &["render", "--png", "t.png", "2010.mpath"]);
    assert!(o.status.success());
    assert!(dir.path().join("t.png").exists() && !page.exists());
    let help = String::from_utf8_lossy(&millpath(dir.path(), &["help", "render"]).stdout)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    assert!(
        help.contains("default when neither --svg nor --png is given"),
        "{help}"
    );
    let o = millpath(dir.path(), &["render", "2010.mpath"]);
    assert!(o.status.success());
    assert!(page.exists());
}

/// `millpath help CMD` describes every argument: no option or positional line without text.
#[test]
fn every_argument_of_every_command_has_a_description() {
    let dir = tempfile::tempdir().unwrap();
    let commands = [
        "compile", "check", "verify", "adjust-z", "dxf2text", "text2dxf", "fmt", "render", "lsp",
    ];
    for cmd in commands {
        let o = millpath(dir.path(), &["help", cmd]);
        let text = String::from_utf8_lossy(&o.stdout).into_owned();
        let mut section = "";
        for line in text.lines() {
            if !line.starts_with(' ') && line.ends_with(':') {
                section = line;
                continue;
            }
            if section != "Arguments:" && section != "Options:" {
                continue;
            }
            let t = line.trim();
            if !(t.starts_with('-') || t.starts_with('<')) {
                continue;
            }
            // an argument line: its description follows after two blanks (clap's own
            // `[default: …]`/`[possible values: …]` is none), or on the next lines (long help)
            let desc = t.split_once("  ").map_or("", |(_, d)| d.trim());
            if desc.is_empty() {
                let next = text.lines().skip_while(|l| *l != line).nth(1).unwrap_or("");
                let described = next.starts_with("          ")
                    && !next.trim().starts_with('-')
                    && !next.trim().starts_with('[');
                assert!(described, "{cmd}: `{t}` has no description\n{text}");
            } else {
                assert!(!desc.starts_with('['), "{cmd}: `{t}` has no description");
            }
        }
    }
}

#[test]
fn render_draws_the_cut_part_in_svg_and_png_when_asked() {
    let dir = tempfile::tempdir().unwrap();
    for f in ["2001.mpath", "2010.mpath", "millpath.toml"] {
        std::fs::copy(examples().join(f), dir.path().join(f)).unwrap();
    }
    let plain = svg_of(dir.path(), &[]);
    assert!(!plain.contains("#e8dcc4"), "no cut part unless asked");
    let cut = svg_of(dir.path(), &["--cut"]);
    // the uncut stock and depth levels of the cut cells under the moves
    assert!(cut.contains(r##"fill="#e8dcc4""##), "{}", &cut[..400]);
    assert!(cut.matches("fill=\"hsl(").count() >= 2);
    // a coarser grid: fewer, larger cells
    let coarse = svg_of(dir.path(), &["--cut", "--cut-cell", "1"]);
    assert!(coarse.len() < cut.len());
    let o = millpath(
        dir.path(),
        &["render", "--cut", "--png", "t.png", "2010.mpath"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read(dir.path().join("t.png"))
        .unwrap()
        .starts_with(b"\x89PNG"));
    let o = millpath(
        dir.path(),
        &["render", "--cut-cell", "-1", "--svg", "t.svg", "2010.mpath"],
    );
    assert!(!o.status.success());
}
