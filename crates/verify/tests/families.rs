//! Every family reads its own style, and catches what it must in it: random programs written
//! as an `rs274` post (LinuxCNC, line numbers, `;` and `( )` comments, `%`), a `grbl` post
//! (line numbers anywhere they may be, `;` comments, no `%`) and a `marlin` post (one
//! command a line, `;` comments, `G4 S`, the end at `M5`; with arcs, and with arcs as lines)
//! are clean; 600 targeted mutations per family (a deeper cut, no feed, an unreadable word,
//! a plunge as a rapid, a changed arc centre, a truncated program, a broken line number and
//! each family's own rules) are each found at error (or, for a short spindle dwell, warning)
//! severity; 600 random mutations per family never panic. `rs274_family_programs.sh`
//! writes the rs274 programs for LinuxCNC's `rs274` (`tests/rs274.sh`).

use millpath_verify::{verify, Dialect, FamilyProblem, FindingKind, Options, Report, Severity};

mod common;

use common::{mutate, Rng};

const TOP: f64 = 2.0;
const TOOL: f64 = 2.0;
const BOTTOM: f64 = -0.3;

#[derive(Clone, Copy, PartialEq, Debug)]
enum Style {
    Rs274,
    Grbl,
    Marlin,
    /// Marlin with arcs written as lines.
    MarlinLines,
}

impl Style {
    fn dialect(self) -> Dialect {
        match self {
            Style::Rs274 => Dialect::LinuxCnc,
            Style::Grbl => Dialect::Grbl,
            Style::Marlin | Style::MarlinLines => Dialect::Marlin,
        }
    }
    fn options(self) -> Options {
        Options {
            dialect: self.dialect(),
            arcs_as_lines: self == Style::MarlinLines,
            top: Some(TOP),
            tool: Some(TOOL),
            bottom: Some(BOTTOM),
            ..Default::default()
        }
    }
    fn marlin(self) -> bool {
        matches!(self, Style::Marlin | Style::MarlinLines)
    }
}

/// One random drawing: slots and circles at their own places, each at its own depth.
enum Feature {
    Slot { x: f64, y: f64, len: f64, z: f64 },
    Circle { cx: f64, cy: f64, r: f64, z: f64 },
}

fn drawing(rng: &mut Rng) -> Vec<Feature> {
    let n = 1 + rng.below(5);
    (0..n)
        .map(|k| {
            let (x, y) = (k as f64 * 25.0, rng.below(20) as f64);
            // depths from the bottom up to 0.5 below the top
            let z = BOTTOM + rng.below(19) as f64 * 0.1;
            if rng.below(2) == 0 {
                let len = 2.0 + rng.below(10) as f64;
                Feature::Slot { x, y, len, z }
            } else {
                let r = 2.0 + rng.below(6) as f64;
                Feature::Circle {
                    cx: x + 8.0,
                    cy: y,
                    r,
                    z,
                }
            }
        })
        .collect()
}

/// The program of a drawing in a family's style, one line an element.
fn write(style: Style, features: &[Feature], numbered: bool) -> Vec<String> {
    let marlin = style.marlin();
    let (g0, g1, g2) = if marlin {
        ("G0", "G1", "G2")
    } else {
        ("G00", "G01", "G02")
    };
    let comment = |k: usize, text: &str| match (style, k % 2) {
        (Style::Rs274 | Style::Grbl, 0) => format!("({text})"),
        _ => format!("; {text}"),
    };
    let mut body: Vec<String> = Vec::new();
    if marlin {
        body.extend(["G21", "G90", "G1 F150"].map(String::from));
    } else {
        body.push("G17 G21 G40 G49 G54 G80 G90 G94".into());
        body.push("F150".into());
        body.push("T1".into());
    }
    body.push("M3 S1000".into());
    body.push(if marlin { "G4 S2" } else { "G4 P2" }.into());
    body.push(format!("{g0} Z5.000"));
    for (k, f) in features.iter().enumerate() {
        body.push(comment(k, &format!("element {k}")));
        match *f {
            Feature::Slot { x, y, len, z } => {
                body.push(format!("{g0} X{x:.3} Y{y:.3}"));
                body.push(format!("{g1} F75 Z{z:.3}"));
                body.push(format!(
                    "{g1} F150 X{:.3} Y{y:.3} Z{z:.3} ; slot {k}",
                    x + len
                ));
            }
            Feature::Circle { cx, cy, r, z } => {
                body.push(format!("{g0} X{:.3} Y{cy:.3}", cx + r));
                body.push(format!("{g1} F75 Z{z:.3}"));
                if style == Style::MarlinLines {
                    // chords of 24 steps
                    for s in 1..=24 {
                        let a = s as f64 * std::f64::consts::TAU / 24.0;
                        body.push(format!(
                            "{g1} F150 X{:.3} Y{:.3} Z{z:.3}",
                            cx + r * a.cos(),
                            cy + r * a.sin()
                        ));
                    }
                } else {
                    body.push(format!(
                        "{g2} F150 I{:.3} J0.000 X{:.3} Y{cy:.3} Z{z:.3}",
                        -r,
                        cx - r
                    ));
                    body.push(format!(
                        "{g2} F150 I{r:.3} J0.000 X{:.3} Y{cy:.3} Z{z:.3}",
                        cx + r
                    ));
                }
            }
        }
        body.push(format!("{g0} Z5.000"));
    }
    body.push("M5".into());
    if !marlin {
        body.push("M30".into());
    }
    let mut lines: Vec<String> = body
        .into_iter()
        .enumerate()
        .map(|(k, l)| {
            if numbered {
                format!("N{} {l}", 10 * (k + 1))
            } else {
                l
            }
        })
        .collect();
    if style == Style::Rs274 {
        lines.insert(0, "%".into());
        lines.push("%".into());
    }
    lines
}

fn text(lines: &[String]) -> String {
    lines.join("\n") + "\n"
}

/// The findings that are not notes.
fn problems(r: &Report) -> Vec<&millpath_verify::Finding> {
    r.findings
        .iter()
        .filter(|f| f.severity != Severity::Note)
        .collect()
}

/// Indices of lines that match `keep`.
fn lines_where(lines: &[String], keep: impl Fn(&str) -> bool) -> Vec<usize> {
    (0..lines.len()).filter(|&i| keep(&lines[i])).collect()
}

/// The word of `letter` in a line replaced (its number to `value`).
fn set_word(line: &str, letter: char, value: &str) -> String {
    let mut out = Vec::new();
    for w in line.split(' ') {
        if w.starts_with(letter) && w[1..].starts_with(|c: char| c.is_ascii_digit() || c == '-') {
            out.push(format!("{letter}{value}"));
        } else {
            out.push(w.to_string());
        }
    }
    out.join(" ")
}

fn is_cut(l: &str) -> bool {
    let code = l.split(';').next().unwrap_or("");
    ["G01 ", "G02 ", "G1 ", "G2 "]
        .iter()
        .any(|g| code.contains(g))
        && code.contains('Z')
}

fn is_plunge(l: &str) -> bool {
    is_cut(l) && !l.contains('X')
}

/// What one targeted mutation must be found as.
type Expect = fn(&FindingKind) -> bool;

/// One targeted mutation of a clean program; `None` when the program has no line for it.
fn targeted(
    style: Style,
    lines: &[String],
    rng: &mut Rng,
    kind: usize,
) -> Option<(&'static str, Vec<String>, Expect, Severity)> {
    let mut p = lines.to_vec();
    let pick = |v: Vec<usize>, rng: &mut Rng| (!v.is_empty()).then(|| v[rng.below(v.len())]);
    let err = Severity::Error;
    Some(match kind {
        0 => {
            let i = pick(lines_where(lines, is_cut), rng)?;
            let deeper = BOTTOM - 0.1 - rng.below(20) as f64 * 0.1;
            p[i] = set_word(&p[i], 'Z', &format!("{deeper:.3}"));
            (
                "a deeper cut",
                p,
                |k| matches!(k, FindingKind::BelowBottom { .. }),
                err,
            )
        }
        1 => {
            for l in &mut p {
                let kept: Vec<&str> = l.split(' ').filter(|w| !w.starts_with('F')).collect();
                *l = kept.join(" ");
            }
            // a Marlin line `G1 F150` is now `G1` alone: still one command
            (
                "no feed",
                p,
                |k| matches!(k, FindingKind::NoFeed { .. }),
                err,
            )
        }
        2 => {
            let i = pick(lines_where(lines, |l| l.contains(" X")), rng)?;
            let garbage = ["1..5", "", "#1", "1,5"][rng.below(4)];
            p[i] = set_word(&p[i], 'X', garbage);
            (
                "an unreadable word",
                p,
                |k| matches!(k, FindingKind::Syntax(_) | FindingKind::BadNumber { .. }),
                err,
            )
        }
        3 => {
            let i = pick(lines_where(lines, is_plunge), rng)?;
            let g0 = if style.marlin() { "G0 " } else { "G00 " };
            p[i] = p[i].replace("G01 ", g0).replace("G1 ", g0);
            (
                "a plunge as a rapid",
                p,
                |k| matches!(k, FindingKind::RapidIntoMaterial { .. }),
                err,
            )
        }
        4 => {
            let i = pick(lines_where(lines, |l| l.contains(" I")), rng)?;
            let old: f64 = p[i]
                .split(' ')
                .find_map(|w| w.strip_prefix('I'))?
                .parse()
                .ok()?;
            p[i] = set_word(&p[i], 'I', &format!("{:.3}", old + 0.7));
            (
                "a moved arc centre",
                p,
                |k| matches!(k, FindingKind::ArcRadiusMismatch { .. }),
                err,
            )
        }
        5 => {
            // cut before the end (M5 in Marlin, M30 and % elsewhere)
            let end = lines.iter().rposition(|l| l.contains("M5"))?;
            p.truncate(1 + rng.below(end));
            (
                "a truncated program",
                p,
                |k| matches!(k, FindingKind::MissingProgramEnd),
                err,
            )
        }
        6 => {
            let i = pick(lines_where(lines, |l| l.starts_with('N')), rng)?;
            let n = ["-10", "15.5", "2000000", "-0.5"][rng.below(4)];
            let rest = p[i].split_once(' ').map_or("", |(_, r)| r).to_string();
            p[i] = format!("N{n} {rest}");
            (
                "a broken line number",
                p,
                |k| {
                    matches!(
                        k,
                        FindingKind::Family {
                            problem: FamilyProblem::LineNumber { .. },
                            ..
                        } | FindingKind::BadNumber { .. }
                    )
                },
                err,
            )
        }
        _ => return family_own(style, lines, rng),
    })
}

/// A mutation against a family's own rules.
fn family_own(
    style: Style,
    lines: &[String],
    rng: &mut Rng,
) -> Option<(&'static str, Vec<String>, Expect, Severity)> {
    let mut p = lines.to_vec();
    let err = Severity::Error;
    let pick = |v: Vec<usize>, rng: &mut Rng| (!v.is_empty()).then(|| v[rng.below(v.len())]);
    Some(match style {
        Style::Rs274 => {
            // the line number after the command
            let i = pick(
                lines_where(lines, |l| l.starts_with('N') && l.contains(" G0")),
                rng,
            )?;
            let (n, rest) = p[i].split_once(' ')?;
            let (g, rest) = rest.split_once(' ')?;
            p[i] = format!("{g} {n} {rest}");
            (
                "a line number after the command",
                p,
                |k| {
                    matches!(
                        k,
                        FindingKind::Family {
                            problem: FamilyProblem::LineNumberNotFirst,
                            ..
                        }
                    )
                },
                err,
            )
        }
        Style::Grbl => {
            p.insert(rng.below(2) * p.len(), "%".into());
            (
                "a % line",
                p,
                |k| {
                    matches!(
                        k,
                        FindingKind::Family {
                            problem: FamilyProblem::Percent,
                            ..
                        }
                    )
                },
                err,
            )
        }
        Style::Marlin | Style::MarlinLines => match rng.below(6) {
            0 => {
                let i = rng.below(p.len());
                p[i] = match p[i].split_once(';') {
                    Some((code, rest)) => format!("{code}(a comment) ;{rest}"),
                    None => format!("{} (a comment)", p[i]),
                };
                (
                    "a ( ) comment",
                    p,
                    |k| {
                        matches!(
                            k,
                            FindingKind::Family {
                                problem: FamilyProblem::ParenComment,
                                ..
                            }
                        )
                    },
                    err,
                )
            }
            1 => {
                // G21 and G90 on one line
                let i = lines.iter().position(|l| l.ends_with("G21"))?;
                p[i] = format!("{} G90", p[i]);
                p.remove(i + 1);
                (
                    "two commands on a line",
                    p,
                    |k| {
                        matches!(
                            k,
                            FindingKind::Family {
                                problem: FamilyProblem::SecondCommand { .. },
                                ..
                            }
                        )
                    },
                    err,
                )
            }
            2 => {
                let i = pick(
                    lines_where(lines, |l| l.contains("G1 ") && l.contains('X')),
                    rng,
                )?;
                p[i] = p[i].replace("G1 ", "");
                (
                    "a move without its command",
                    p,
                    |k| {
                        matches!(
                            k,
                            FindingKind::Family {
                                problem: FamilyProblem::CommandNotFirst { .. },
                                ..
                            }
                        )
                    },
                    err,
                )
            }
            3 => {
                let i = lines.iter().rposition(|l| l.ends_with("M5"))?;
                p[i] = p[i].replace("M5", "M30");
                (
                    "M30 as the end",
                    p,
                    |k| {
                        matches!(
                            k,
                            FindingKind::Family {
                                problem: FamilyProblem::M30DeletesFile,
                                ..
                            }
                        )
                    },
                    err,
                )
            }
            4 => {
                let i = lines.iter().position(|l| l.ends_with("G4 S2"))?;
                p[i] = p[i].replace("G4 S2", "G4 P2");
                (
                    "seconds as G4 P",
                    p,
                    |k| {
                        matches!(
                            k,
                            FindingKind::Family {
                                problem: FamilyProblem::ShortSpindleDwell { .. },
                                ..
                            }
                        )
                    },
                    Severity::Warning,
                )
            }
            _ => {
                if style == Style::Marlin {
                    // the same program read as one whose post writes no arcs
                    if !lines.iter().any(|l| l.contains("G2 ")) {
                        return None;
                    }
                    let expect: Expect = |k| {
                        matches!(
                            k,
                            FindingKind::Family {
                                problem: FamilyProblem::ArcNotAllowed { .. },
                                ..
                            }
                        )
                    };
                    return Some(("an arc where the post writes lines", p, expect, err));
                }
                let i = pick(lines_where(lines, |l| l.contains("G1 F150 X")), rng)?;
                let (code, comment) = p[i].split_once(" ;").unwrap_or((&p[i], ""));
                let comment = if comment.is_empty() {
                    String::new()
                } else {
                    format!(" ;{comment}")
                };
                p[i] = format!("{} R100{comment}", code.replace("G1 ", "G2 "));
                (
                    "an arc where the post writes lines",
                    p,
                    |k| {
                        matches!(
                            k,
                            FindingKind::Family {
                                problem: FamilyProblem::ArcNotAllowed { .. },
                                ..
                            }
                        )
                    },
                    err,
                )
            }
        },
    })
}

const STYLES: [Style; 4] = [Style::Rs274, Style::Grbl, Style::Marlin, Style::MarlinLines];

#[test]
fn each_family_reads_its_own_style_clean() {
    let mut rng = Rng(0x5EED_F00D);
    for style in STYLES {
        for round in 0..50 {
            let lines = write(style, &drawing(&mut rng), round % 2 == 0);
            let r = verify(&text(&lines), &style.options());
            assert!(
                problems(&r).is_empty(),
                "{style:?}:\n{}\n{:#?}",
                text(&lines),
                problems(&r)
            );
            assert!(r.stock.is_some() && r.removed_volume_mm3 > 0.0);
        }
    }
}

/// Marlin's G92 (set position, marlinfw.org/docs/gcode/G092.html) and G92.1 are Marlin
/// commands: read as in the rs274 family (the position is not followed: a warning, and the
/// next move must name every axis), not refused as codes Marlin lacks; LinuxCNC's G92.2
/// and G92.3 are.
#[test]
fn marlin_reads_g92_as_marlin_does() {
    let mut rng = Rng(0x0000_6092);
    let lines = write(Style::Marlin, &drawing(&mut rng), false);
    let at = lines.iter().position(|l| l == "G0 Z5.000").unwrap() + 1;
    let no_such = |r: &Report| {
        r.findings.iter().any(|f| {
            matches!(
                &f.kind,
                FindingKind::Family {
                    problem: FamilyProblem::NoSuchCode { .. },
                    ..
                }
            )
        })
    };
    for set in ["G92 X0 Y0 Z5", "G92 Z5", "G92.1"] {
        let mut with = lines.clone();
        with.insert(at, set.to_string());
        with.insert(at + 1, "G0 X0.000 Y0.000 Z5.000".into());
        let r = verify(&text(&with), &Style::Marlin.options());
        assert!(!no_such(&r), "{set}: {:#?}", r.findings);
        assert!(
            r.findings.iter().all(|f| f.severity != Severity::Error),
            "{set}: {:#?}",
            r.findings
        );
        assert!(
            r.findings
                .iter()
                .any(|f| matches!(f.kind, FindingKind::Unsupported { .. })),
            "{set}: the position after it is not followed, said so"
        );
    }
    for lacking in ["G92.2", "G92.3"] {
        let mut with = lines.clone();
        with.insert(at, lacking.to_string());
        let r = verify(&text(&with), &Style::Marlin.options());
        assert!(no_such(&r), "{lacking}: {:#?}", r.findings);
    }
}

#[test]
fn six_hundred_mutations_per_family_are_caught() {
    for style in STYLES {
        let mut rng = Rng(0xC0FF_EE00 + style as u64);
        let mut counts: std::collections::BTreeMap<&str, usize> = Default::default();
        let mut done = 0;
        let mut tries = 0;
        while done < 600 {
            tries += 1;
            assert!(tries < 5000, "{style:?}: too few applicable mutations");
            let lines = write(style, &drawing(&mut rng), rng.below(3) > 0);
            let kind = rng.below(8);
            let Some((what, mutated, expect, severity)) = targeted(style, &lines, &mut rng, kind)
            else {
                continue;
            };
            let mut o = style.options();
            if what == "an arc where the post writes lines" {
                o.arcs_as_lines = true;
            }
            let r = verify(&text(&mutated), &o);
            assert!(
                r.findings
                    .iter()
                    .any(|f| expect(&f.kind) && f.severity == severity),
                "{style:?}: {what} not caught in\n{}\n{:#?}",
                text(&mutated),
                r.findings
            );
            *counts.entry(what).or_default() += 1;
            done += 1;
        }
        eprintln!("{style:?}: {done} mutations caught: {counts:?}");
    }
}

#[test]
fn six_hundred_random_mutations_per_family_never_panic() {
    const ALPHABET: &[u8] = b"GMXYZIJKRFPNST0123456789.-+ ()[];%#=eE*\n\t/";
    for style in STYLES {
        let mut rng = Rng(0xBAD_5EED + style as u64);
        for round in 0..600 {
            let mut lines = write(style, &drawing(&mut rng), round % 2 == 0);
            for _ in 0..1 + rng.below(6) {
                mutate(&mut lines, &mut rng, ALPHABET);
            }
            let sep = if round % 3 == 0 { "\r\n" } else { "\n" };
            let r = verify(&lines.join(sep), &style.options());
            assert!(r.removed_volume_mm3.is_finite() && r.removed_volume_mm3 >= 0.0);
            for f in &r.findings {
                assert!(!f.message(millpath_verify::Lang::De).is_empty());
                assert!(f.line.is_none_or(|l| l >= 1 && l <= r.lines + 1), "{f:?}");
            }
        }
    }
}

/// `MILLPATH_RS274_DIR=DIR cargo test -p millpath-verify --test families -- --ignored`:
/// the clean rs274-family programs (line numbers, `;` comments) into DIR, for LinuxCNC's
/// `rs274` (`tests/rs274.sh` runs it on them).
#[test]
#[ignore]
fn write_rs274_family_programs() {
    let Ok(dir) = std::env::var("MILLPATH_RS274_DIR") else {
        eprintln!("MILLPATH_RS274_DIR not set: nothing written");
        return;
    };
    let mut rng = Rng(0x0027_4274);
    for k in 0..40 {
        let lines = write(Style::Rs274, &drawing(&mut rng), k % 4 != 3);
        let program = text(&lines);
        assert!(problems(&verify(&program, &Style::Rs274.options())).is_empty());
        std::fs::write(format!("{dir}/family_{k:02}.ngc"), program).unwrap();
    }
}
