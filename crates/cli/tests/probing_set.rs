//! The outputs of one drawing are one set (issue 20): all-or-none writing, stale outputs of
//! a failed compile, adjust-z refusing a mix, verify on adjusted programs.

mod common;

use std::path::Path;

const DRAWING: &str = "path 2020.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2
  end (60, 0)
  mill (0, 0) -> (60, 0)
  probe (10, 5)
  probe (50, 5)  L1
}
";

fn run(dir: &Path, args: &[&str]) -> (i32, String) {
    common::status_and_text(dir, args)
}

fn setup() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("2020.mpath"), DRAWING).unwrap();
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\nprobe_feed = 50\n",
    )
    .unwrap();
    dir
}

fn read(dir: &Path, name: &str) -> String {
    std::fs::read_to_string(dir.join(name)).unwrap_or_default()
}

fn fill(dir: &Path, a: &str, b: &str) {
    let z = read(dir, "2020_Z.txt")
        .replace("#51=", &format!("#51={a}"))
        .replace("#52=", &format!("#52={b}"));
    std::fs::write(dir.join("2020_Z.txt"), z).unwrap();
}

#[test]
fn a_set_that_cannot_be_written_whole_stays_old() {
    let dir = setup();
    let d = dir.path();
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    let old: Vec<String> = ["2020_Probing.gcode", "2020_Z.txt", "2020_Clean.gcode"]
        .iter()
        .map(|f| read(d, f))
        .collect();
    // a folder where the last file goes: no write can replace it, not even as root
    std::fs::rename(d.join("2020_Clean.gcode"), d.join("saved")).unwrap();
    std::fs::create_dir(d.join("2020_Clean.gcode")).unwrap();
    let moved = DRAWING.replace("probe (50, 5)", "probe (45, 5)");
    std::fs::write(d.join("2020.mpath"), moved.replace("B-0,2", "B-0,5")).unwrap();
    let (code, text) = run(d, &["compile", "2020.mpath"]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("Cannot write 2020_Clean.gcode"), "{text}");
    assert_eq!(read(d, "2020_Probing.gcode"), old[0]);
    assert_eq!(read(d, "2020_Z.txt"), old[1]);
    let names: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n.starts_with('.')), "{names:?}");
}

#[test]
fn adjust_z_refuses_a_mix_and_a_failed_compile_leaves_no_stale_output() {
    let dir = setup();
    let d = dir.path();
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    let old_clean = read(d, "2020_Clean.gcode");
    assert!(old_clean.lines().nth(1).unwrap().contains(" set="));
    std::fs::write(
        d.join("2020.mpath"),
        DRAWING.replace("probe (50, 5)", "probe (45, 5)"),
    )
    .unwrap();
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    std::fs::write(d.join("2020_Clean.gcode"), &old_clean).unwrap();
    fill(d, "3.1", "2.9");
    let (code, text) = run(d, &["adjust-z", "--max", "1", "2020"]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("2020_Clean.gcode and 2020_Z.txt are not from the same compile"),
        "{text}"
    );
    assert!(!d.join("2020_Milling.gcode").exists());
    // the consistent set is adjusted; a failed compile then removes what it cannot stand behind
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    fill(d, "3.1", "2.9");
    assert_eq!(run(d, &["adjust-z", "--max", "1", "2020"]).0, 0);
    std::fs::write(
        d.join("2020.mpath"),
        DRAWING.replace("-> (60, 0)", "-> (61, 0)"),
    )
    .unwrap();
    let (code, text) = run(d, &["compile", "2020.mpath"]);
    assert_eq!(code, 1);
    for f in [
        "2020_Milling.gcode",
        "2020_Probing.gcode",
        "2020_Clean.gcode",
    ] {
        assert!(!d.join(f).exists(), "{f}: {text}");
        assert!(text.contains(&format!("Removed {f}")), "{text}");
    }
    assert!(d.join("2020_Z.txt").exists(), "the measured heights stay");
    // pathdxf2gcode, the reference's drop-in, removes nothing
    std::fs::write(d.join("x_Milling.gcode"), "%\nM30\n%\n").unwrap();
    std::fs::write(d.join("x.mpath"), "broken").unwrap();
    let (code, _) = run(d, &["pathdxf2gcode", "/f150", "/v500", "/s15", "x.mpath"]);
    assert_ne!(code, 0);
    assert!(d.join("x_Milling.gcode").exists());
}

#[test]
fn verify_is_clean_on_adjusted_programs_in_every_dialect() {
    for dialect in ["reference", "linuxcnc", "grbl"] {
        let dir = setup();
        let d = dir.path();
        assert_eq!(
            run(d, &["compile", "--dialect", dialect, "2020.mpath"]).0,
            0
        );
        fill(d, "3.3", "2.8");
        assert_eq!(run(d, &["adjust-z", "--max", "1", "2020"]).0, 0);
        let verify = |file: &str| {
            run(
                d,
                &[
                    "verify",
                    "--dialect",
                    dialect,
                    "--top",
                    "3",
                    "--tool",
                    "2",
                    "--bottom",
                    "-0.2",
                    file,
                ],
            )
        };
        let (code, text) = verify("2020_Milling.gcode");
        assert_eq!(code, 0, "{dialect}: {text}");
        assert!(
            text.contains("0 error(s), 0 warning(s)"),
            "{dialect}: {text}"
        );
        // the last pass cut 0.5 deeper than the measured surface minus the depth
        let milling = read(d, "2020_Milling.gcode");
        let deeper: String = milling
            .lines()
            .map(|l| match l.split_once(" Z0.009(==-0.200+") {
                Some((head, tail)) if head.contains('X') => {
                    format!("{head} Z-0.491(==-0.700+{tail}\n")
                }
                _ => format!("{l}\n"),
            })
            .collect();
        assert_ne!(deeper, milling, "{dialect}");
        std::fs::write(d.join("deeper.gcode"), deeper).unwrap();
        let (code, text) = verify("deeper.gcode");
        assert_eq!(code, 1, "{dialect}: {text}");
        assert!(
            text.contains("below the deepest drawn depth -0.200"),
            "{text}"
        );
    }
}

/// The set opened and saved again in Notepad (a byte-order mark, CRLF): adjust-z reads past
/// the mark and writes the program it writes from the plain files, without a mark, which
/// LinuxCNC would reject ("Bad character"); verify names a mark in a program it is given.
#[test]
fn a_set_saved_with_a_byte_order_mark_adjusts_as_the_plain_set() {
    let dir = setup();
    let d = dir.path();
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    fill(d, "3.3", "2.8");
    assert_eq!(run(d, &["adjust-z", "--max", "1", "2020"]).0, 0);
    let plain = read(d, "2020_Milling.gcode");
    for name in ["2020_Clean.gcode", "2020_Z.txt"] {
        let notepad = format!("\u{feff}{}", read(d, name).replace('\n', "\r\n"));
        std::fs::write(d.join(name), notepad).unwrap();
    }
    let (code, text) = run(d, &["adjust-z", "--max", "1", "2020"]);
    assert_eq!(code, 0, "{text}");
    let adjusted = read(d, "2020_Milling.gcode");
    assert!(!adjusted.starts_with('\u{feff}'), "{adjusted}");
    assert_eq!(adjusted.replace("\r\n", "\n"), plain);
    // the program saved with a mark: verify says what it is, in both languages
    std::fs::write(d.join("bom.gcode"), format!("\u{feff}{plain}")).unwrap();
    let (code, text) = run(d, &["verify", "bom.gcode"]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("bom.gcode:1: error: a byte-order mark (U+FEFF"),
        "{text}"
    );
    let (_, text) = run(d, &["verify", "--lang", "de", "bom.gcode"]);
    assert!(text.contains("ohne BOM speichern"), "{text}");
}
