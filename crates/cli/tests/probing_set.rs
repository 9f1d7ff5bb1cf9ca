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
    // the consistent set is adjusted (the values typed beside the mixed set's program cannot
    // be matched to its probe points: kept beside); a failed compile then removes what it
    // cannot stand behind
    let (code, text) = run(d, &["compile", "2020.mpath"]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("probing program is missing or of another compile"),
        "{text}"
    );
    assert!(read(d, "2020_Z.1.txt").contains("#52=2.9"));
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

/// examples/text/2020.mpath and its millpath.toml in a folder of their own.
fn example_2020() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/text");
    for f in ["2020.mpath", "millpath.toml"] {
        std::fs::copy(ex.join(f), dir.path().join(f)).unwrap();
    }
    dir
}

fn bytes(dir: &Path, name: &str) -> Vec<u8> {
    std::fs::read(dir.join(name)).unwrap_or_default()
}

fn names(dir: &Path) -> Vec<String> {
    let mut n: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    n.sort();
    n
}

/// The chain of issue 31: compile, fill in `_Z.txt` (as typed on the machine: a decimal
/// comma), adjust-z, then compile the unchanged drawing again, alone and as its folder: the
/// measured values and the adjusted program stay byte for byte, and adjust-z still works.
#[test]
fn recompiling_an_unchanged_drawing_keeps_the_measured_values_and_the_adjusted_program() {
    let dir = example_2020();
    let d = dir.path();
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    fill(d, "2,95", "3.1");
    let (code, text) = run(d, &["adjust-z", "--max", "0.5", "2020_Clean.gcode"]);
    assert_eq!(code, 0, "{text}");
    let (z, milling) = (bytes(d, "2020_Z.txt"), bytes(d, "2020_Milling.gcode"));
    assert!(String::from_utf8_lossy(&z).contains("#51=2,95"));
    for args in [&["compile", "2020.mpath"][..], &["compile", "."]] {
        let (code, text) = run(d, args);
        assert_eq!(code, 0, "{args:?}: {text}");
        assert_eq!(bytes(d, "2020_Z.txt"), z, "{args:?}: {text}");
        assert_eq!(bytes(d, "2020_Milling.gcode"), milling, "{args:?}: {text}");
        assert!(!text.contains("MP144"), "{args:?}: {text}");
        assert!(
            text.contains("Keeping (measured values of the same probes)"),
            "{args:?}: {text}"
        );
    }
    assert_eq!(
        names(d),
        [
            "2020.mpath",
            "2020_Clean.gcode",
            "2020_Milling.gcode",
            "2020_Probing.gcode",
            "2020_Z.txt",
            "millpath.toml"
        ]
    );
    let (code, text) = run(d, &["adjust-z", "--max", "0.5", "2020_Clean.gcode"]);
    assert_eq!(code, 0, "{text}");
    assert_eq!(bytes(d, "2020_Milling.gcode"), milling);
    // the probing program cleaned away after probing: _Clean.gcode still says this set
    std::fs::remove_file(d.join("2020_Probing.gcode")).unwrap();
    let (code, text) = run(d, &["compile", "2020.mpath"]);
    assert_eq!(code, 0, "{text}");
    assert_eq!(bytes(d, "2020_Z.txt"), z, "{text}");
    assert_eq!(bytes(d, "2020_Milling.gcode"), milling, "{text}");
    // in German the program's comments are German: another set, the same probes
    let (code, text) = run(d, &["compile", "--lang", "de", "2020.mpath"]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("---- Behalten (Messwerte derselben Messpunkte) 2020_Z.txt"),
        "{text}"
    );
    assert_eq!(bytes(d, "2020_Z.txt"), z);
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    assert_eq!(run(d, &["adjust-z", "--max", "0.5", "2020"]).0, 0);
    assert_eq!(bytes(d, "2020_Milling.gcode"), milling);
    // another depth, the same probes: the values stay, the program adjusted from the other
    // set goes, and adjust-z takes the kept values for the new set
    std::fs::write(
        d.join("2020.mpath"),
        read(d, "2020.mpath").replace("B-0,2", "B-0,3"),
    )
    .unwrap();
    let (code, text) = run(d, &["compile", "2020.mpath"]);
    assert_eq!(code, 0, "{text}");
    assert_eq!(bytes(d, "2020_Z.txt"), z);
    assert!(text.contains("Removed 2020_Milling.gcode"), "{text}");
    let (code, text) = run(d, &["adjust-z", "--max", "0.5", "2020_Clean.gcode"]);
    assert_eq!(code, 0, "{text}");
    assert!(
        read(d, "2020_Milling.gcode").contains("Z-0.323(==-0.300+"),
        "{}",
        read(d, "2020_Milling.gcode")
    );
    // a read-only _Z.txt of the same probes is not touched either
    let mut ro = std::fs::metadata(d.join("2020_Z.txt"))
        .unwrap()
        .permissions();
    ro.set_readonly(true);
    std::fs::set_permissions(d.join("2020_Z.txt"), ro).unwrap();
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    assert_eq!(bytes(d, "2020_Z.txt"), z);
    assert!(std::fs::metadata(d.join("2020_Z.txt"))
        .unwrap()
        .permissions()
        .readonly());
}

/// A probe moved, the other not: the old file is kept beside (never over an earlier one),
/// the value of the unchanged probe is carried over, the warning says so in both languages.
#[test]
fn a_changed_drawing_keeps_the_old_values_beside_and_carries_over_the_unchanged_probe() {
    let dir = example_2020();
    let d = dir.path();
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    fill(d, "2,95", "3.1");
    assert_eq!(run(d, &["adjust-z", "--max", "0.5", "2020"]).0, 0);
    let filled = bytes(d, "2020_Z.txt");
    let drawing = read(d, "2020.mpath");
    std::fs::write(
        d.join("2020.mpath"),
        drawing.replace("probe (50, 5)", "probe (45, 5)"),
    )
    .unwrap();
    let (code, text) = run(d, &["compile", "2020.mpath"]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains(
            "2020_Z.txt held 2 measured value(s) of another probing set: kept as 2020_Z.1.txt. 1 carried over to the new 2020_Z.txt"
        ) && text.contains("1 probe(s) of the new set have no value yet"),
        "{text}"
    );
    assert!(text.contains("Removed 2020_Milling.gcode"), "{text}");
    assert_eq!(bytes(d, "2020_Z.1.txt"), filled);
    assert_eq!(
        read(d, "2020_Z.txt"),
        "([10.000 5.000]/T=3.000) #51=2,95\n([45.000 5.000]/L:1/T=3.000) #52=\n"
    );
    // the second probe measured: adjust-z takes the new set
    fill(d, "", "3.05");
    let (code, text) = run(d, &["adjust-z", "--max", "0.5", "2020"]);
    assert_eq!(code, 0, "{text}");
    // moved again, in German: a second side file, the first one untouched
    let second = bytes(d, "2020_Z.txt");
    std::fs::write(
        d.join("2020.mpath"),
        drawing.replace("probe (50, 5)", "probe (40, 5)"),
    )
    .unwrap();
    let (code, text) = run(d, &["compile", "--lang", "de", "2020.mpath"]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("2020_Z.txt enthielt 2 Messwert(e) eines anderen Antastsatzes: als 2020_Z.2.txt aufbewahrt. 1 in die neue 2020_Z.txt übernommen"),
        "{text}"
    );
    assert_eq!(bytes(d, "2020_Z.1.txt"), filled);
    assert_eq!(bytes(d, "2020_Z.2.txt"), second);
    assert!(read(d, "2020_Z.txt").starts_with("([10.000 5.000]/T=3.000) #51=2,95\n"));
    // the start point moved: every probe is elsewhere on the machine, nothing is carried
    let third = bytes(d, "2020_Z.txt");
    std::fs::write(
        d.join("2020.mpath"),
        drawing
            .replace("probe (50, 5)", "probe (40, 5)")
            .replace("start (0, 0)", "start (0, 1)")
            .replace("mill (0, 0)", "mill (0, 1)"),
    )
    .unwrap();
    let (code, text) = run(d, &["compile", "2020.mpath"]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("kept as 2020_Z.3.txt. 0 carried over"),
        "{text}"
    );
    assert_eq!(bytes(d, "2020_Z.3.txt"), third);
    assert!(!read(d, "2020_Z.txt").contains("2,95"));
}

/// Removes the drawing's outputs and side files.
fn clear(d: &Path) {
    for n in names(d) {
        if n.contains("_Z.") || n.ends_with(".gcode") {
            std::fs::remove_file(d.join(n)).unwrap();
        }
    }
}

/// A `_Z.txt` that is garbage, cut off, read-only, or whose probing program is gone is
/// never replaced without its bytes kept beside; when no copy can be kept, nothing of the
/// drawing is written.
#[test]
fn hostile_z_files_are_kept_beside() {
    let dir = example_2020();
    let d = dir.path();
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    fill(d, "2,95", "3.1");
    let filled = read(d, "2020_Z.txt");
    let moved = read(d, "2020.mpath").replace("probe (50, 5)", "probe (45, 5)");
    let original = read(d, "2020.mpath");
    let cases: [(&str, Vec<u8>, &str); 4] = [
        (
            "garbage",
            b"\x00\x17\xffnot a _Z.txt".to_vec(),
            "could not be read as a _Z.txt (it is no UTF-8 or UTF-16 text): kept as 2020_Z.1.txt",
        ),
        (
            "a line",
            b"#51=2.95\n".to_vec(),
            "could not be read as a _Z.txt (line 1 is not of the form",
        ),
        // cut in its second line: that line is no probe line any more
        (
            "cut off",
            filled.as_bytes()[..filled.len() - 12].to_vec(),
            "(line 2 is not of the form",
        ),
        // cut in its last value: `3.1` could have been `3.15`, so it is not carried over
        (
            "cut value",
            filled.trim_end().as_bytes()[..filled.trim_end().len() - 1].to_vec(),
            "held 2 measured value(s) of another probing set: kept as 2020_Z.1.txt. 1 carried over",
        ),
    ];
    for (what, old, said) in cases {
        clear(d);
        std::fs::write(d.join("2020.mpath"), &original).unwrap();
        assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
        std::fs::write(d.join("2020_Z.txt"), &old).unwrap();
        std::fs::write(d.join("2020.mpath"), &moved).unwrap();
        let (code, text) = run(d, &["compile", "2020.mpath"]);
        assert_eq!(code, 0, "{what}: {text}");
        assert!(text.contains(said), "{what}: {text}");
        assert_eq!(bytes(d, "2020_Z.1.txt"), old, "{what}");
    }
    // a file of 65 MiB (a device, a log saved under the name): kept beside unread
    clear(d);
    std::fs::write(d.join("2020.mpath"), &original).unwrap();
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    std::fs::File::create(d.join("2020_Z.txt"))
        .unwrap()
        .set_len(65 << 20)
        .unwrap();
    std::fs::write(d.join("2020.mpath"), &moved).unwrap();
    let (code, text) = run(d, &["compile", "--lang", "de", "2020.mpath"]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("2020_Z.txt ließ sich nicht als _Z.txt lesen (sie ist größer als 64 MiB): als 2020_Z.1.txt aufbewahrt"),
        "{text}"
    );
    assert_eq!(
        std::fs::metadata(d.join("2020_Z.1.txt")).unwrap().len(),
        65 << 20
    );
    // read-only, its probing program gone (a failed compile removed it): a read-only output is
    // never replaced (issue 31 item 6), so the compile refuses, the file stays as it is and no
    // copy is left beside it
    clear(d);
    std::fs::write(d.join("2020.mpath"), &original).unwrap();
    assert_eq!(run(d, &["compile", "2020.mpath"]).0, 0);
    let z = d.join("2020_Z.txt");
    std::fs::write(&z, &filled).unwrap();
    let mut ro = std::fs::metadata(&z).unwrap().permissions();
    ro.set_readonly(true);
    std::fs::set_permissions(&z, ro).unwrap();
    std::fs::remove_file(d.join("2020_Probing.gcode")).unwrap();
    std::fs::write(d.join("2020.mpath"), &moved).unwrap();
    let (code, text) = run(d, &["compile", "2020.mpath"]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("Cannot write 2020_Z.txt: read-only: not replaced"),
        "{text}"
    );
    assert_eq!(read(d, "2020_Z.txt"), filled);
    assert!(std::fs::metadata(&z).unwrap().permissions().readonly());
    assert!(!d.join("2020_Z.1.txt").exists(), "{text}");
    // made writable, the same compile keeps the measured file beside, nothing compared
    let mut rw = std::fs::metadata(&z).unwrap().permissions();
    #[allow(clippy::permissions_set_readonly_false)]
    rw.set_readonly(false);
    std::fs::set_permissions(&z, rw).unwrap();
    let (code, text) = run(d, &["compile", "2020.mpath"]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("2020_Z.txt held 2 measured value(s) of another probing set, but its probing program is missing or of another compile"), "{text}");
    assert_eq!(read(d, "2020_Z.1.txt"), filled);
    // no free name for a copy: nothing of the drawing is written, nothing left behind
    for n in 2..=999 {
        std::fs::write(d.join(format!("2020_Z.{n}.txt")), "").unwrap();
    }
    fill(d, "2.9", "3.0");
    let before: Vec<Vec<u8>> = ["2020_Z.txt", "2020_Probing.gcode", "2020_Clean.gcode"]
        .iter()
        .map(|f| bytes(d, f))
        .collect();
    std::fs::write(d.join("2020.mpath"), &original).unwrap();
    let (code, text) = run(d, &["compile", "2020.mpath"]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("2020_Z.txt may hold measured values and could not be kept as"),
        "{text}"
    );
    let after: Vec<Vec<u8>> = ["2020_Z.txt", "2020_Probing.gcode", "2020_Clean.gcode"]
        .iter()
        .map(|f| bytes(d, f))
        .collect();
    assert_eq!(before, after);
    assert!(
        !names(d).iter().any(|n| n.starts_with('.')),
        "{:?}",
        names(d)
    );
}
