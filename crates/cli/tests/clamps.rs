//! `[[clamp]]` keep-out boxes end to end: `compile` refuses a program whose tool touches one
//! (every dialect, located at the element), `check` says the same, `verify` finds the same
//! moves on its own (`--clamp`, `--config`, the nearest millpath.toml), bad boxes are located
//! at millpath.toml; over every shared drawing with boxes placed on its own toolpath.

mod common;

use common::{millpath, status_and_text};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// A slot from (10, 0) to (50, 0) with O2 (radius 1), sweeps at S10 before and after it.
const SLOT: &str = "path 3001.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2 S10
  end (60, 0)
  sweep (0, 0) -> (10, 0)
  mill (10, 0) -> (50, 0)
  sweep (50, 0) -> (60, 0)
}
";

fn project(dir: &Path, dialect: &str, clamps: &[(&str, [f64; 3], [f64; 3])]) {
    std::fs::write(dir.join("3001.mpath"), SLOT).unwrap();
    let mut toml =
        format!("feed = 100\nsweep_speed = 500\nsweep_height = 10\ndialect = \"{dialect}\"\n");
    for (name, min, max) in clamps {
        toml.push_str(&format!(
            "[[clamp]]\nname = \"{name}\"\nmin = {min:?}\nmax = {max:?}\n"
        ));
    }
    std::fs::write(dir.join("millpath.toml"), toml).unwrap();
}

fn compile(dir: &Path) -> (i32, String) {
    let _ = std::fs::remove_file(dir.join("3001_Milling.gcode"));
    status_and_text(dir, &["compile", "3001.mpath"])
}

const DIALECTS: [&str; 3] = ["reference", "linuxcnc", "grbl"];

#[test]
fn a_sweep_over_a_clamp_at_sweep_height_refuses_and_a_lower_clamp_passes() {
    let dir = tempfile::tempdir().unwrap();
    for dialect in DIALECTS {
        // under the last sweep (50 → 60 at S10), its top at the sweep height
        project(
            dir.path(),
            dialect,
            &[("vice", [54.0, -3.0, 0.0], [56.0, 3.0, 10.0])],
        );
        let (status, text) = compile(dir.path());
        assert_eq!(status, 1, "{dialect}: {text}");
        assert!(text.contains("runs into clamp 'vice'"), "{dialect}: {text}");
        // located at the sweep element of the drawing
        assert!(text.contains("3001.mpath:6:3"), "{dialect}: {text}");
        assert!(!dir.path().join("3001_Milling.gcode").exists());
        // check says what compile says
        let (status, check) = status_and_text(dir.path(), &["check", "3001.mpath"]);
        assert_eq!(status, 1, "{check}");
        assert!(check.contains("runs into clamp 'vice'"), "{check}");
        // 0.01 mm lower: the sweep clears it
        project(
            dir.path(),
            dialect,
            &[("vice", [54.0, -3.0, 0.0], [56.0, 3.0, 9.99])],
        );
        let (status, text) = compile(dir.path());
        assert_eq!(status, 0, "{dialect}: {text}");
        assert!(dir.path().join("3001_Milling.gcode").exists());
    }
}

/// The message lines (`error[…]: …`) of a command's output.
fn message_lines(text: &str) -> Vec<String> {
    text.lines()
        .filter(|l| l.starts_with("error[") || l.starts_with("warning["))
        .map(str::to_string)
        .collect()
}

/// `check` keeps no program text (the checker reads each line as it is written, the lines
/// its findings point at come from a second emission): its messages name the same G-code
/// line, number and text, as compile's, which checks the written text.
#[test]
fn check_names_the_same_gcode_line_as_compile() {
    let dir = tempfile::tempdir().unwrap();
    for dialect in DIALECTS {
        // two boxes: the first sweep's and the cut's
        project(
            dir.path(),
            dialect,
            &[
                ("vice", [4.0, -3.0, 0.0], [6.0, 3.0, 10.0]),
                ("stop", [29.0, -2.0, -5.0], [31.0, 2.0, 5.0]),
            ],
        );
        let (status, compiled) = compile(dir.path());
        assert_eq!(status, 1, "{dialect}: {compiled}");
        let (status, checked) = status_and_text(dir.path(), &["check", "3001.mpath"]);
        assert_eq!(status, 1, "{dialect}: {checked}");
        let (compiled, checked) = (message_lines(&compiled), message_lines(&checked));
        assert!(compiled.len() >= 2, "{dialect}: {compiled:?}");
        // a G-code line's text in the message: `line N 'G0…'`
        assert!(
            compiled
                .iter()
                .all(|l| l.contains("line") && l.contains("'G0")),
            "{dialect}: {compiled:?}"
        );
        assert_eq!(checked, compiled, "{dialect}");
    }
}

#[test]
fn a_cut_grazing_a_clamp_closer_than_the_tool_radius_refuses() {
    let dir = tempfile::tempdir().unwrap();
    for dialect in DIALECTS {
        // beside the slot (y = 0, radius 1): 0.99 mm away refuses, 1.01 mm passes
        project(
            dir.path(),
            dialect,
            &[("left", [20.0, 0.99, -5.0], [30.0, 9.0, 1.0])],
        );
        let (status, text) = compile(dir.path());
        assert_eq!(status, 1, "{dialect}: {text}");
        assert!(text.contains("runs into clamp 'left'"), "{text}");
        assert!(text.contains("3001.mpath:5:3"), "{dialect}: {text}");
        project(
            dir.path(),
            dialect,
            &[("left", [20.0, 1.01, -5.0], [30.0, 9.0, 1.0])],
        );
        let (status, text) = compile(dir.path());
        assert_eq!(status, 0, "{dialect}: {text}");
    }
    // German
    project(
        dir.path(),
        "grbl",
        &[("links", [20.0, 0.5, -5.0], [30.0, 9.0, 1.0])],
    );
    let (status, text) = status_and_text(dir.path(), &["compile", "--lang", "de", "3001.mpath"]);
    assert_eq!(status, 1, "{text}");
    assert!(text.contains("fährt in die Spannpratze 'links'"), "{text}");
}

#[test]
fn verify_finds_the_clamp_by_option_by_config_and_by_the_nearest_millpath_toml() {
    let dir = tempfile::tempdir().unwrap();
    project(dir.path(), "linuxcnc", &[]);
    let (status, text) = compile(dir.path());
    assert_eq!(status, 0, "{text}");
    let g = "3001_Milling.gcode";
    let args = ["verify", "--dialect", "linuxcnc", g];
    let (status, clean) = status_and_text(dir.path(), &args);
    assert_eq!(status, 0, "{clean}");
    let (status, text) = status_and_text(
        dir.path(),
        &[
            "verify",
            "--dialect",
            "linuxcnc",
            "--clamp",
            "vice,54,-3,0,56,3,10",
            g,
        ],
    );
    assert_eq!(status, 1, "{text}");
    assert!(text.contains("runs into clamp \"vice\""), "{text}");
    // the same box in the program's millpath.toml
    project(
        dir.path(),
        "linuxcnc",
        &[("vice", [54.0, -3.0, 0.0], [56.0, 3.0, 10.0])],
    );
    let (status, near) = status_and_text(dir.path(), &args);
    assert_eq!(status, 1, "{near}");
    assert!(near.contains("runs into clamp \"vice\""), "{near}");
    // --config names the file; a wrong --clamp is refused
    let (status, _) = status_and_text(
        dir.path(),
        &[
            "verify",
            "--dialect",
            "linuxcnc",
            "--config",
            "millpath.toml",
            g,
        ],
    );
    assert_eq!(status, 1);
    let (status, text) = status_and_text(dir.path(), &["verify", "--clamp", "vice,1,2,3", g]);
    assert_eq!(status, 2, "{text}");
    assert!(
        text.contains("NAME,XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX"),
        "{text}"
    );
    let (status, text) = status_and_text(dir.path(), &["verify", "--clamp", "v,0,0,0,0,1,1", g]);
    assert_eq!(status, 2, "{text}");
    assert!(text.contains("min must be below max on x"), "{text}");
}

#[test]
fn bad_clamps_are_located_at_millpath_toml() {
    let dir = tempfile::tempdir().unwrap();
    project(
        dir.path(),
        "linuxcnc",
        &[("flat", [0.0, 0.0, 5.0], [1.0, 1.0, 5.0])],
    );
    let (status, text) = compile(dir.path());
    assert_eq!(status, 2, "{text}");
    assert!(text.contains("millpath.toml"), "{text}");
    assert!(
        text.contains("Clamp 'flat': min must be below max on z"),
        "{text}"
    );
    // not finite (TOML has nan and inf)
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 100\nsweep_speed = 500\nsweep_height = 10\n[[clamp]]\nmin = [0, nan, 0]\nmax = [1, 1, 1]\n",
    )
    .unwrap();
    let (status, text) = compile(dir.path());
    assert_eq!(status, 2, "{text}");
    assert!(text.contains("clamp[1].min.y (clamp 1)=NaN"), "{text}");
    // too many
    let mut toml = String::from("feed = 100\nsweep_speed = 500\nsweep_height = 10\n");
    for i in 0..=millpath_verify::MAX_CLAMPS {
        toml.push_str(&format!(
            "[[clamp]]\nmin = [{i}, 100, 0]\nmax = [{}, 101, 1]\n",
            i + 1
        ));
    }
    std::fs::write(dir.path().join("millpath.toml"), toml).unwrap();
    let (status, text) = compile(dir.path());
    assert_eq!(status, 2, "{text}");
    assert!(
        text.contains(&format!(
            "declares {} clamps, more than {}",
            millpath_verify::MAX_CLAMPS + 1,
            millpath_verify::MAX_CLAMPS
        )),
        "{text}"
    );
    // the language server's view: the editor's check reports it too (ide tests)
}

fn shared() -> Option<PathBuf> {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared");
    if p.join("conformance/fixtures").is_dir() {
        Some(p)
    } else {
        eprintln!("skipped: ../shared/conformance is not there");
        None
    }
}

/// Where every cutting line (G01/G02/G03) of a program ends, X, Y and Z carried over from
/// the lines before (each line of this compiler's programs starts with its motion word).
fn cut_ends(program: &str) -> Vec<[f64; 3]> {
    let mut pos = [f64::NAN; 3];
    let mut ends = Vec::new();
    for l in program.lines() {
        let words: Vec<&str> = l
            .split('(')
            .next()
            .unwrap_or("")
            .split_whitespace()
            .collect();
        for w in &words {
            for (k, c) in ['X', 'Y', 'Z'].into_iter().enumerate() {
                if let Some(v) = w.strip_prefix(c).and_then(|v| v.parse::<f64>().ok()) {
                    pos[k] = v;
                }
            }
        }
        let cut = matches!(
            words.first(),
            Some(&("G01" | "G1" | "G02" | "G2" | "G03" | "G3"))
        );
        if cut && pos.iter().all(|v| v.is_finite()) {
            ends.push(pos);
        }
    }
    ends
}

/// The tool's path through a program, sampled: (1-based line, x, y, z) every `step` mm or
/// less along each G00/G01/G02/G03 (arcs by I/J from the start, Z linear) — a plain second
/// reading of the G-code, independent of the checker's exact geometry.
fn samples(program: &str, step: f64) -> Vec<(usize, [f64; 3])> {
    let mut pos = [f64::NAN; 3];
    let mut motion = 0;
    let mut out = Vec::new();
    for (n, l) in program.lines().enumerate() {
        // comments: `(…)` and everything after `;`
        let code = l.split([';', '(']).next().unwrap_or("");
        let word = |c: char| {
            code.split_whitespace()
                .find_map(|w| w.strip_prefix(c)?.parse::<f64>().ok())
        };
        for w in code.split_whitespace() {
            match w {
                "G00" | "G0" => motion = 0,
                "G01" | "G1" => motion = 1,
                "G02" | "G2" => motion = 2,
                "G03" | "G3" => motion = 3,
                _ => {}
            }
        }
        let mut to = pos;
        for (k, c) in ['X', 'Y', 'Z'].into_iter().enumerate() {
            if let Some(v) = word(c) {
                to[k] = v;
            }
        }
        // a line without axis words does not move (a repeated position does: the tool is there)
        let moves = ['X', 'Y', 'Z'].into_iter().any(|c| word(c).is_some());
        if !moves || to.iter().any(|v| v.is_nan()) {
            pos = to;
            continue;
        }
        let from = if pos.iter().any(|v| v.is_nan()) {
            to
        } else {
            pos
        };
        let lerp = |t: f64| [0, 1, 2].map(|k| from[k] + t * (to[k] - from[k]));
        if motion >= 2 {
            let (cx, cy) = (
                from[0] + word('I').unwrap_or(0.0),
                from[1] + word('J').unwrap_or(0.0),
            );
            let r = (from[0] - cx).hypot(from[1] - cy);
            let a0 = (from[1] - cy).atan2(from[0] - cx);
            let a1 = (to[1] - cy).atan2(to[0] - cx);
            let tau = std::f64::consts::TAU;
            let mut sweep = if motion == 3 { a1 - a0 } else { a0 - a1 }.rem_euclid(tau);
            if sweep < 1e-9 {
                sweep = tau;
            }
            let pieces = ((r * sweep / step).ceil() as usize).max(1);
            for k in 0..=pieces {
                let t = k as f64 / pieces as f64;
                let a = if motion == 3 {
                    a0 + t * sweep
                } else {
                    a0 - t * sweep
                };
                out.push((
                    n + 1,
                    [
                        cx + r * a.cos(),
                        cy + r * a.sin(),
                        from[2] + t * (to[2] - from[2]),
                    ],
                ));
            }
        } else {
            let len = (0..3)
                .map(|k| (to[k] - from[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            let pieces = ((len / step).ceil() as usize).max(1);
            for k in 0..=pieces {
                out.push((n + 1, lerp(k as f64 / pieces as f64)));
            }
        }
        pos = to;
    }
    out
}

/// (line, clamp) where a sample of the tool (radius `r`) is within `r + grow` of the box in
/// XY with its tip at most `grow` above the box's top.
fn sampled_hits(
    samples: &[(usize, [f64; 3])],
    clamps: &[(String, [f64; 3], [f64; 3])],
    r: f64,
    grow: f64,
) -> BTreeSet<(usize, String)> {
    let mut hits = BTreeSet::new();
    for (line, p) in samples {
        for (name, min, max) in clamps {
            let dx = (min[0] - p[0]).max(p[0] - max[0]).max(0.0);
            let dy = (min[1] - p[1]).max(p[1] - max[1]).max(0.0);
            if dx.hypot(dy) <= r + grow && p[2] <= max[2] + grow {
                hits.insert((*line, name.clone()));
            }
        }
    }
    hits
}

/// (G-code line, clamp name) of compile's clamp errors (`check --format json`).
fn compile_hits(json: &str) -> BTreeSet<(usize, String)> {
    let v: serde_json::Value = serde_json::from_str(json).unwrap();
    v["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|d| d["name"] == "ClampHit")
        .map(|d| {
            let m = d["message"].as_str().unwrap();
            let name = m
                .split("clamp '")
                .nth(1)
                .unwrap()
                .split('\'')
                .next()
                .unwrap();
            let line = m
                .split("G-code line ")
                .nth(1)
                .unwrap()
                .split(' ')
                .next()
                .unwrap();
            (line.parse().unwrap(), name.to_string())
        })
        .collect()
}

/// (G-code line, clamp name) of verify's clamp findings (`--format json`).
fn verify_hits(json: &str) -> BTreeSet<(usize, String)> {
    let v: serde_json::Value = serde_json::from_str(json).unwrap();
    v["files"][0]["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["code"] == "clamp-hit")
        .map(|f| {
            let m = f["message"].as_str().unwrap();
            let name = m
                .split("clamp \"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap();
            (f["line"].as_u64().unwrap() as usize, name.to_string())
        })
        .collect()
}

#[test]
fn verify_finds_the_same_hits_as_compile_on_every_shared_drawing() {
    let Some(shared) = shared() else { return };
    let mut drawings: Vec<PathBuf> = ["conformance/fixtures", "samples"]
        .iter()
        .flat_map(|d| std::fs::read_dir(shared.join(d)).into_iter().flatten())
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("dxf")))
        .collect();
    drawings.sort();
    let (mut programs, mut boxes, mut hits, mut hit_boxes, mut sampled) = (0, 0, 0, 0, 0);
    // the dialects whose programs carry O in their (MILLPATH-STOCK …) comment
    for (drawing, dialect) in drawings.iter().flat_map(|d| [(d, "linuxcnc"), (d, "grbl")]) {
        let dir = tempfile::tempdir().unwrap();
        let name = drawing.file_name().unwrap().to_string_lossy().into_owned();
        std::fs::copy(drawing, dir.path().join(&name)).unwrap();
        let settings =
            format!("feed = 150\nsweep_speed = 500\nsweep_height = 15\ndialect = \"{dialect}\"\n");
        std::fs::write(dir.path().join("millpath.toml"), &settings).unwrap();
        // drawings the compiler refuses (several paths, errors) have no program
        millpath(dir.path(), &["compile", &name]);
        let Some(program) = std::fs::read_dir(dir.path())
            .unwrap()
            .filter_map(|e| e.ok().map(|e| e.path()))
            .find(|p| {
                let n = p.to_string_lossy();
                n.ends_with("_Milling.gcode") || n.ends_with("_Clean.gcode")
            })
        else {
            continue;
        };
        let text = std::fs::read_to_string(&program).unwrap();
        let ends = cut_ends(&text);
        if ends.is_empty() {
            continue;
        }
        programs += 1;
        // boxes on the toolpath and high above it (hits: the holder and spindle stand above
        // the tip), and beside it (some hit by other moves, some not)
        let mut toml = settings.to_string();
        let mut boxes_here = Vec::new();
        let step = (ends.len() / 5).max(1);
        let placed = ends.iter().step_by(step).take(5).count();
        for (k, p) in ends.iter().step_by(step).take(5).enumerate() {
            let [x, y, z] = *p;
            for (kind, min, max) in [
                (
                    "on",
                    [x - 0.3, y - 0.3, z - 3.0],
                    [x + 0.3, y + 0.3, z + 0.5],
                ),
                (
                    "beside",
                    [x + 1.7, y + 0.1, z - 3.0],
                    [x + 4.0, y + 2.0, z + 0.2],
                ),
                (
                    "above",
                    [x - 1.0, y - 1.0, z + 30.0],
                    [x + 1.0, y + 1.0, z + 40.0],
                ),
            ] {
                boxes += 1;
                boxes_here.push((format!("{kind} {k}"), min, max));
                toml.push_str(&format!(
                    "[[clamp]]\nname = \"{kind} {k}\"\nmin = {min:?}\nmax = {max:?}\n"
                ));
            }
        }
        std::fs::write(dir.path().join("millpath.toml"), &toml).unwrap();
        let o = millpath(dir.path(), &["check", "--format", "json", "-q", &name]);
        let from_compile = compile_hits(&String::from_utf8_lossy(&o.stdout));
        let gcode = program.file_name().unwrap().to_string_lossy().into_owned();
        let o = millpath(
            dir.path(),
            &["verify", "--dialect", dialect, "--format", "json", &gcode],
        );
        let from_verify = verify_hits(&String::from_utf8_lossy(&o.stdout));
        assert_eq!(from_compile, from_verify, "{name} {dialect}");
        // a sampled second reading of the program: every sampled hit is found, and every hit
        // found is one when the tool is taken 0.05 mm wider and higher (the samples' spacing)
        let tool = text
            .lines()
            .find_map(|l| {
                l.split("O=")
                    .nth(1)?
                    .split([' ', ')'])
                    .next()?
                    .parse::<f64>()
                    .ok()
            })
            .expect("MILLPATH-STOCK comment");
        let path = samples(&text, 0.01);
        let strict = sampled_hits(&path, &boxes_here, tool / 2.0, 0.0);
        let loose = sampled_hits(&path, &boxes_here, tool / 2.0, 0.05);
        assert!(
            strict.is_subset(&from_verify),
            "{name}: missed {:?}",
            strict.difference(&from_verify).collect::<Vec<_>>()
        );
        assert!(
            from_verify.is_subset(&loose),
            "{name}: not hits {:?}",
            from_verify.difference(&loose).collect::<Vec<_>>()
        );
        sampled += strict.len();
        // every box placed on a cut's end or high above it is hit
        for k in 0..placed {
            for box_name in [format!("on {k}"), format!("above {k}")] {
                let hit = from_verify.iter().any(|(_, n)| *n == box_name);
                assert!(hit, "{name}: {box_name}");
            }
        }
        hits += from_verify.len();
        hit_boxes += from_verify
            .iter()
            .map(|h| &h.1)
            .collect::<BTreeSet<_>>()
            .len();
    }
    eprintln!(
        "{} drawings in linuxcnc and grbl, {programs} programs, {boxes} boxes: {hit_boxes} boxes hit, {hits} (line, box) hits, compile = verify; {sampled} of them also by sampling every 0.01 mm",
        drawings.len()
    );
}
