//! Posts end to end (issue 32): `post list`, `post show NAME` printed to a file and compiled
//! with unchanged gives the built-in's bytes (every built-in post, with the settings that
//! reach the output), `post =` in millpath.toml relative to it, a changed post's program
//! read by the checker and adjusted by adjust-z, and what a post cannot write refused.

use std::path::Path;

mod common;

use common::{copy_text_examples as example, millpath};

/// Every output file of a folder, by name.
fn outputs(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let n = p.file_name().unwrap().to_string_lossy();
            n.ends_with(".gcode") || n.ends_with("_Z.txt") || n.ends_with(".NCC")
        })
        .map(|p| {
            let bytes = std::fs::read(&p).unwrap();
            (p.file_name().unwrap().to_string_lossy().into_owned(), bytes)
        })
        .collect();
    v.sort();
    v
}

#[test]
fn post_list_names_every_built_in_post() {
    let dir = tempfile::tempdir().unwrap();
    let out = millpath(dir.path(), &["post", "list"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for name in [
        "reference",
        "linuxcnc",
        "grbl",
        "mach3",
        "uccnc",
        "centroid",
        "fluidnc",
        "grblhal",
        "marlin",
        "xcam",
    ] {
        assert!(text.lines().any(|l| l.starts_with(name)), "{text}");
    }
    let out = millpath(dir.path(), &["post", "show", "mach9"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no built-in post `mach9`"));
}

#[test]
fn a_shown_post_compiles_to_the_built_in_bytes() {
    let settings = [
        ("reference", ""),
        (
            "linuxcnc",
            "spindle_rpm = 12000\nspindle_dwell = 1.5\nplunge_feed = 90\n",
        ),
        ("grbl", "spindle_rpm = 9000.5\n"),
        ("linuxcnc", "probe_split = 3\n[heightmap]\nstep = 9\n"),
        ("grbl", "[heightmap]\nstep = 6\nmargin = 1\n"),
        // Mach and UCCNC write no G4 (its P unit is a setting there)
        ("mach3", "spindle_rpm = 12000\nspindle_dwell = 0\n"),
        ("uccnc", "spindle_rpm = 12000\nspindle_dwell = 0\n"),
        ("centroid", "spindle_rpm = 12000\nspindle_dwell = 1.5\n"),
        ("fluidnc", "spindle_rpm = 9000.5\n"),
        ("grblhal", "[heightmap]\nstep = 6\nmargin = 1\n"),
        // Marlin's M3 S is PWM 0-255 by default
        ("marlin", "spindle_rpm = 255\nspindle_dwell = 1.5\n"),
        ("xcam", "plunge_feed = 90\n"),
    ];
    for (name, extra) in settings {
        let built_in = tempfile::tempdir().unwrap();
        let file = tempfile::tempdir().unwrap();
        for d in [built_in.path(), file.path()] {
            example(d);
            let own = std::fs::read_to_string(d.join("millpath.toml")).unwrap();
            std::fs::write(d.join("millpath.toml"), format!("{own}{extra}")).unwrap();
        }
        let shown = millpath(file.path(), &["post", "show", name]);
        assert!(shown.status.success());
        std::fs::create_dir(file.path().join("posts")).unwrap();
        std::fs::write(file.path().join("posts/mine.toml"), &shown.stdout).unwrap();
        // the file named in millpath.toml, relative to it (top-level keys before tables)
        let toml = std::fs::read_to_string(file.path().join("millpath.toml")).unwrap();
        let toml = format!("post = \"posts/mine.toml\"\n{toml}");
        std::fs::write(file.path().join("millpath.toml"), toml).unwrap();
        let a = millpath(built_in.path(), &["compile", "--post", name, "."]);
        let b = millpath(file.path(), &["compile", "."]);
        assert_eq!(a.status.code(), b.status.code(), "{name} {extra}");
        let (a, b) = (outputs(built_in.path()), outputs(file.path()));
        // posts that cannot probe refuse the probed example (2020): two programs
        let least = if ["centroid", "marlin", "xcam"].contains(&name) {
            2
        } else {
            3
        };
        assert!(
            a.len() >= least,
            "{name} {extra}: {:?}",
            a.iter().map(|x| &x.0).collect::<Vec<_>>()
        );
        assert_eq!(
            a.iter().map(|x| &x.0).collect::<Vec<_>>(),
            b.iter().map(|x| &x.0).collect::<Vec<_>>()
        );
        for ((n, x), (_, y)) in a.iter().zip(&b) {
            assert!(x == y, "{name} {extra}: {n} differs");
        }
    }
}

#[test]
fn a_changed_post_writes_its_way_and_the_set_still_checks_and_adjusts() {
    let dir = tempfile::tempdir().unwrap();
    example(dir.path());
    let shown = millpath(dir.path(), &["post", "show", "linuxcnc"]).stdout;
    let post = String::from_utf8(shown)
        .unwrap()
        .replace("name = \"linuxcnc\"", "name = \"mymill\"")
        .replace("modal = []", "modal = [\"F\", \"motion\"]")
        .replace(
            "[comments]",
            "[line_numbers]\nstart = 10\nstep = 5\n\n[comments]",
        );
    std::fs::write(dir.path().join("mymill.toml"), post).unwrap();
    let out = millpath(dir.path(), &["compile", "--post", "mymill.toml", "."]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let milling = std::fs::read_to_string(dir.path().join("2001_Milling.gcode")).unwrap();
    let lines: Vec<&str> = milling.lines().collect();
    assert_eq!(lines[0], "%");
    assert!(lines[1].starts_with("N10 (millpath"), "{}", lines[1]);
    assert!(lines[2].starts_with("N15 "), "{}", lines[2]);
    // a repeated feed and motion word is left out, a changed one stays
    assert!(lines
        .iter()
        .any(|l| l.contains(" X") && !l.contains('G') && !l.contains('(')));
    // the probing set: the Z expressions stay on every corrected Z, so adjust-z reads it
    let clean = std::fs::read_to_string(dir.path().join("2020_Clean.gcode")).unwrap();
    assert!(clean.contains("(=") && clean.lines().all(|l| l == "%" || l.starts_with('N')));
    let z = std::fs::read_to_string(dir.path().join("2020_Z.txt")).unwrap();
    let filled: String = z.lines().map(|l| format!("{l}3.010\n")).collect();
    std::fs::write(dir.path().join("2020_Z.txt"), filled).unwrap();
    let adjusted = millpath(dir.path(), &["adjust-z", "--max", "1", "2020_Clean.gcode"]);
    assert!(
        adjusted.status.success(),
        "{}",
        String::from_utf8_lossy(&adjusted.stderr)
    );
}

#[test]
fn what_a_post_cannot_write_is_refused_and_a_bad_post_is_located() {
    let dir = tempfile::tempdir().unwrap();
    example(dir.path());
    let shown = millpath(dir.path(), &["post", "show", "linuxcnc"]).stdout;
    let post = String::from_utf8(shown)
        .unwrap()
        .replace("name = \"linuxcnc\"", "name = \"plain\"")
        .replace("probing = \"G38.3\"", "probing = \"none\"")
        .replace("spindle = true", "spindle = false");
    std::fs::write(dir.path().join("plain.toml"), post).unwrap();
    let refused = |args: &[&str], want: &str| {
        let out = millpath(dir.path(), args);
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(
            !out.status.success() && err.contains(want),
            "{args:?}: {err}"
        );
        assert!(outputs(dir.path()).is_empty(), "{args:?}: nothing written");
    };
    refused(
        &["compile", "--post", "plain.toml", "2020.mpath"],
        "The post plain cannot write Z probes",
    );
    refused(
        &[
            "compile",
            "--post",
            "plain.toml",
            "--spindle-rpm",
            "8000",
            "2001.mpath",
        ],
        "cannot write spindle_rpm",
    );
    refused(
        &[
            "compile",
            "--post",
            "plain.toml",
            "--heightmap-step",
            "5",
            "--lang",
            "de",
            "2001.mpath",
        ],
        "Der Post plain kann [heightmap] nicht schreiben",
    );
    std::fs::write(
        dir.path().join("bad.toml"),
        "[post]\nname = \"bad\"\nfamily = \"rs274\"\n[templates]\nlinear = \"G1 X{x} {feeed}\"\n",
    )
    .unwrap();
    refused(
        &["compile", "--post", "bad.toml", "2001.mpath"],
        "bad.toml:5:19: templates.linear: unknown variable {feeed}",
    );
    refused(
        &[
            "compile",
            "--post",
            "bad.toml",
            "--lang",
            "de",
            "2001.mpath",
        ],
        "unbekannte Variable {feeed}",
    );
    refused(
        &["compile", "--post", "mach9", "2001.mpath"],
        "no post `mach9`",
    );
}

#[test]
fn arcs_as_chords_or_radii_are_written_so_and_check_clean() {
    let dir = tempfile::tempdir().unwrap();
    example(dir.path());
    // an arc, helixes with bars, a drill: every kind of arc the emitter writes
    let drawing = "path 1000.1P {
  start (0, 0)  O2 T3 I1,2 B-0,3 D1 P6 U30 S8
  end (100, 0)
  sweep (0, 0) -> (10, 0)  N1
  bars helix (10, 0) d8
  bars (10, 0) -> (60, 0)
  mark (60, 0) -> (60, 10)
  mill arc (60, 20) r10 from 270 to 360
  sweep (70, 20) -> (90, 20)
  helix (90, 20) d6
  sweep (90, 20) -> (100, 0)
}
";
    std::fs::write(dir.path().join("1000.mpath"), drawing).unwrap();
    let linuxcnc =
        String::from_utf8(millpath(dir.path(), &["post", "show", "linuxcnc"]).stdout).unwrap();
    let chords = linuxcnc
        .replace("name = \"linuxcnc\"", "name = \"chords\"")
        .replace("arcs = \"ij\"", "arcs = \"lines\"\nchord_tolerance = 0.005");
    let radius = linuxcnc
        .replace("name = \"linuxcnc\"", "name = \"radius\"")
        .replace("arcs = \"ij\"", "arcs = \"r\"")
        .replace("I{i} J{j}", "R{r}");
    std::fs::write(dir.path().join("chords.toml"), chords).unwrap();
    std::fs::write(dir.path().join("radius.toml"), radius).unwrap();
    let arcs = |post: &str| {
        let out = millpath(dir.path(), &["compile", "--post", post, "1000.mpath"]);
        assert!(
            out.status.success(),
            "{post}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let program = std::fs::read_to_string(dir.path().join("1000_Milling.gcode")).unwrap();
        let verified = millpath(
            dir.path(),
            &["verify", "--dialect", "linuxcnc", "1000_Milling.gcode"],
        );
        assert!(
            verified.status.success(),
            "{post}: {}",
            String::from_utf8_lossy(&verified.stdout)
        );
        let arcs: Vec<String> = program
            .lines()
            .filter(|l| l.starts_with("G02") || l.starts_with("G03"))
            .map(str::to_string)
            .collect();
        (
            arcs,
            program.lines().filter(|l| l.starts_with("G01")).count(),
        )
    };
    let (ij, ij_lines) = arcs("linuxcnc");
    assert!(ij.len() > 4 && ij.iter().all(|l| l.contains(" I")));
    let (none, chord_lines) = arcs("chords.toml");
    assert!(
        none.is_empty() && chord_lines > ij_lines + 50,
        "{chord_lines}"
    );
    let (r, _) = arcs("radius.toml");
    assert!(r.len() >= ij.len() && r.iter().all(|l| l.contains(" R") && !l.contains(" I")));
}

/// The controller posts (docs/src/controllers.md): Mach and UCCNC write no G4 (its P unit is
/// a setting there) and probe with G31 (drawn probes: the set is checked and adjusted; height
/// maps refused); nothing probes on Centroid yet; refusals are at the setting or element that
/// asks; Centroid writes the dwell in seconds; FluidNC and grblHAL probe as GRBL does,
/// without `%` lines.
#[test]
fn controller_posts_refuse_what_they_cannot_write() {
    for name in ["mach3", "uccnc"] {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        example(d);
        let out = millpath(d, &["compile", "--post", name, "2020.mpath"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{name}: {err}");
        let probing = std::fs::read_to_string(d.join("2020_Probing.gcode")).unwrap();
        assert!(
            probing.contains("\nG31 Z0 F50.000\nM0\n"),
            "{name}: {probing}"
        );
        assert!(!probing.contains("G38") && !probing.contains('%'), "{name}");
        // the probes measured, the set adjusted; every program read clean as rs274
        let z = std::fs::read_to_string(d.join("2020_Z.txt")).unwrap();
        let filled: String = z.lines().map(|l| format!("{l}3.050\n")).collect();
        std::fs::write(d.join("2020_Z.txt"), filled).unwrap();
        let out = millpath(d, &["adjust-z", "--max", "0.5", "2020_Clean.gcode"]);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        for f in [
            "2020_Probing.gcode",
            "2020_Clean.gcode",
            "2020_Milling.gcode",
        ] {
            let v = millpath(d, &["verify", "--dialect", "rs274", f]);
            let report = format!(
                "{}{}",
                String::from_utf8_lossy(&v.stdout),
                String::from_utf8_lossy(&v.stderr)
            );
            assert!(
                v.status.success() && report.contains(" 0 error(s), 0 warning(s)"),
                "{name} {f}: {report}"
            );
        }
        // G31 is read as a probe move: with a feed of 0 it is an error; GRBL has no G31
        let stalled = probing.replacen("G31 Z0 F50.000", "G31 Z0 F0", 1);
        std::fs::write(d.join("stalled.gcode"), stalled).unwrap();
        let v = millpath(d, &["verify", "--dialect", "rs274", "stalled.gcode"]);
        let report = format!(
            "{}{}",
            String::from_utf8_lossy(&v.stdout),
            String::from_utf8_lossy(&v.stderr)
        );
        assert!(
            !v.status.success() && report.contains("F0"),
            "{name}: {report}"
        );
        let v = millpath(d, &["verify", "--dialect", "grbl", "2020_Probing.gcode"]);
        assert!(!v.status.success(), "{name}: grbl reads no G31");
        // a height map: refused, its points would all be typed in
        let out = millpath(
            d,
            &[
                "compile",
                "--post",
                name,
                "--heightmap-step",
                "5",
                "2001.mpath",
            ],
        );
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && err.contains("MP207") && err.contains("grid_probe"),
            "{name}: {err}"
        );
    }
    // Centroid: no probing yet
    let dir = tempfile::tempdir().unwrap();
    example(dir.path());
    let out = millpath(dir.path(), &["compile", "--post", "centroid", "2020.mpath"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_ne!(out.status.code(), Some(0));
    assert!(
        err.contains("MP207") && err.contains("2020.mpath:"),
        "{err}"
    );
    assert!(!dir.path().join("2020_Clean.gcode").exists());
    for (name, dwell) in [("mach3", false), ("uccnc", false), ("centroid", true)] {
        let dir = tempfile::tempdir().unwrap();
        example(dir.path());
        let toml = dir.path().join("millpath.toml");
        let own = std::fs::read_to_string(&toml).unwrap();
        std::fs::write(&toml, format!("{own}spindle_rpm = 12000\n")).unwrap();
        let out = millpath(dir.path(), &["compile", "--post", name, "2001.mpath"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.success(), dwell, "{name}: {err}");
        if dwell {
            let text = std::fs::read_to_string(dir.path().join("2001_Milling.gcode")).unwrap();
            assert!(text.contains("\nM3 S12000\nG4 P2\n"), "{name}");
            assert!(!text.starts_with('%'), "{name}");
        } else {
            assert!(err.contains("set spindle_dwell = 0"), "{name}: {err}");
            let de = millpath(
                dir.path(),
                &["compile", "--lang", "de", "--post", name, "2001.mpath"],
            );
            let de = String::from_utf8_lossy(&de.stderr);
            assert!(de.contains("spindle_dwell = 0 (oder"), "{name}: {de}");
            std::fs::write(
                &toml,
                format!("{own}spindle_rpm = 12000\nspindle_dwell = 0\n"),
            )
            .unwrap();
            let out = millpath(dir.path(), &["compile", "--post", name, "2001.mpath"]);
            assert!(out.status.success(), "{name}");
            let text = std::fs::read_to_string(dir.path().join("2001_Milling.gcode")).unwrap();
            assert!(
                text.contains("\nM3 S12000\n") && !text.contains("\nG4 "),
                "{name}"
            );
        }
    }
    for name in ["fluidnc", "grblhal"] {
        let dir = tempfile::tempdir().unwrap();
        example(dir.path());
        let out = millpath(dir.path(), &["compile", "--post", name, "2020.mpath"]);
        assert!(out.status.success(), "{name}");
        let probing = std::fs::read_to_string(dir.path().join("2020_Probing.gcode")).unwrap();
        assert!(probing.contains("\nG38.3 Z0 F50.000\n"), "{name}");
        assert!(
            !probing.contains('%') && !probing.contains("PROBEOPEN"),
            "{name}"
        );
    }
}

/// xcam (docs/src/controllers.md): probes, a height map and a spindle are refused at what
/// asks for them (MP207); a milling program is `NAME_Milling.NCC` with CR LF line ends, the
/// header first, and `millpath verify --dialect xcam` reads it clean.
#[test]
fn xcam_refuses_what_it_cannot_write_and_its_files_verify() {
    let dir = tempfile::tempdir().unwrap();
    example(dir.path());
    let out = millpath(dir.path(), &["compile", "--post", "xcam", "2020.mpath"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_ne!(out.status.code(), Some(0));
    assert!(
        err.contains("MP207") && err.contains("2020.mpath:"),
        "{err}"
    );
    let toml = dir.path().join("millpath.toml");
    let own = std::fs::read_to_string(&toml).unwrap();
    for extra in ["spindle_rpm = 12000\n", "[heightmap]\nstep = 5\n"] {
        std::fs::write(&toml, format!("{own}{extra}")).unwrap();
        let out = millpath(dir.path(), &["compile", "--post", "xcam", "2001.mpath"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_ne!(out.status.code(), Some(0), "{extra}");
        assert!(err.contains("MP207"), "{extra}: {err}");
        assert!(!dir.path().join("2001_Milling.NCC").exists());
    }
    std::fs::write(&toml, &own).unwrap();
    let out = millpath(
        dir.path(),
        &["compile", "--post", "xcam", "2001.mpath", "2010.mpath"],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for name in ["2001_Milling.NCC", "2010_Milling.NCC"] {
        let text = std::fs::read_to_string(dir.path().join(name)).unwrap();
        assert!(text.starts_with("H DX="), "{name}");
        assert!(text.ends_with("\r\n") && !text.replace("\r\n", "").contains('\n'));
        assert!(
            text.contains("\r\nGIN T=") && text.contains("\r\nG1 X="),
            "{name}"
        );
        let out = millpath(dir.path(), &["verify", "--dialect", "xcam", name]);
        let said = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(out.status.success(), "{name}: {said}");
        assert!(said.contains("0 error(s), 0 warning(s)"), "{name}: {said}");
        // a file cut after a contour is found truncated
        let cut = &text[..text.find("\r\nGIN ").unwrap()];
        std::fs::write(dir.path().join("cut.NCC"), cut).unwrap();
        let out = millpath(dir.path(), &["verify", "--dialect", "xcam", "cut.NCC"]);
        assert_eq!(out.status.code(), Some(1), "{name}");
    }
}
