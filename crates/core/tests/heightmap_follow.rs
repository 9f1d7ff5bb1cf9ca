//! The oracle of the height-map adjustment (issue 21). For synthetic surfaces (a tilted
//! plane, a bilinear twist, a bowl that is not bilinear), every example and shared drawing is
//! compiled with `[heightmap]` in linuxcnc and grbl; the log the controller would write at
//! the probing program's own probe points goes through `adjust-z --probe-log`; then every
//! cutting move of the result is sampled densely, as the machine moves (straight or helical
//! Z between the written points), and the tool tip's depth below the true surface must equal
//! the depth the nominal program has at the same point below the flat top.
//!
//! This test reads the programs with its own small interpreter (not the adjuster's code).

mod support;

use millpath_core::probe::adjustz::{self, SetFile, DEFAULT_TOLERANCE};
use millpath_core::probe::heightmap::Heightmap;
use millpath_core::{compile_file, diag::Diags, Dialect, OsFileSystem, Session};
use std::collections::HashMap;
use std::path::Path;
use support::{files_in, grbl, root};

/// A synthetic surface: its height above the nominal top at (x, y), and how far the
/// adjustment may be off on it (the bilinear interpolation's own error for the bowl).
struct Surface {
    name: &'static str,
    rise: Box<dyn Fn(f64, f64) -> f64>,
    tolerance: f64,
}

/// 0.01 mm: the issue's bound for surfaces the bilinear map represents exactly.
const EXACT: f64 = 0.01;
const STEP: f64 = 10.0;

/// The surfaces over a probed box (`lo`, `hi`), scaled to it so that they stay below every
/// drawing's sweep height: a plane tilted ±0.2 mm, a twist of 0.3 mm at the corners, and a
/// bowl 0.2 mm below the top in the middle and 0.3 mm above it at the corners.
fn surfaces(lo: (f64, f64), hi: (f64, f64)) -> Vec<Surface> {
    let (cx, cy) = ((lo.0 + hi.0) / 2.0, (lo.1 + hi.1) / 2.0);
    let (w, h) = ((hi.0 - lo.0) / 2.0 + 1.0, (hi.1 - lo.1) / 2.0 + 1.0);
    let bowl = 0.25;
    // linear interpolation of k·x² over a step s is off by k·s²/4 at most, on each axis;
    // plus the chord tolerance and the rounding to 0.001 of Z and heights (in EXACT)
    let (sx, sy) = (STEP.min(hi.0 - lo.0), STEP.min(hi.1 - lo.1));
    let bowl_error = (bowl / (w * w) * sx * sx + bowl / (h * h) * sy * sy) / 4.0;
    vec![
        Surface {
            name: "tilted plane",
            rise: Box::new(move |x, y| 0.1 * (x - cx) / w - 0.1 * (y - cy) / h + 0.05),
            tolerance: EXACT,
        },
        Surface {
            name: "bilinear twist",
            rise: Box::new(move |x, y| 0.3 * (x - cx) * (y - cy) / (w * h) + 0.05 * (x - cx) / w),
            tolerance: EXACT,
        },
        Surface {
            name: "bowl",
            rise: Box::new(move |x, y| {
                bowl * (((x - cx) / w).powi(2) + ((y - cy) / h).powi(2)) - 0.2
            }),
            tolerance: bowl_error + EXACT,
        },
    ]
}

/// The program set of `file` compiled with a height map, or `None` when the drawing does not
/// compile with one (drawn probes, no cuts, errors of its own).
fn compile_set(file: &Path, dialect: Dialect) -> Option<HashMap<&'static str, String>> {
    let mut s = support::settings();
    let toml = file.parent().unwrap().join("millpath.toml");
    if let Ok(text) = std::fs::read_to_string(&toml) {
        let cfg = millpath_core::load::config::parse(&text, file.parent().unwrap()).unwrap();
        cfg.apply(&mut s, &mut Default::default());
    }
    s.dialect = dialect;
    s.heightmap = Some(Heightmap {
        margin: 1.0,
        ..Heightmap::with_step(STEP)
    });
    let fs = OsFileSystem;
    let mut session = Session::new(s, &fs).ok()?;
    let outcome = compile_file(&mut session, file, "millpath test");
    let mut set = HashMap::new();
    for o in outcome.outputs {
        let name = o.path.to_string_lossy().to_string();
        for suffix in ["_Probing.gcode", "_Z.txt", "_Clean.gcode"] {
            if name.ends_with(suffix) {
                set.insert(suffix, o.content.clone());
            }
        }
    }
    (set.len() == 3).then_some(set)
}

/// The words of a G-code line, comments dropped.
fn words(line: &str) -> Vec<(char, f64)> {
    let mut text = String::new();
    let mut depth = 0;
    for c in line.chars() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            ';' if depth == 0 => break,
            _ if depth == 0 => text.push(c),
            _ => {}
        }
    }
    static WORD: std::sync::OnceLock<regex::Regex> = std::sync::OnceLock::new();
    let re =
        WORD.get_or_init(|| regex::Regex::new(r"([A-Za-z])\s*([-+]?[0-9]*\.?[0-9]+)").unwrap());
    re.captures_iter(&text)
        .map(|c| {
            (
                c[1].chars().next().unwrap().to_ascii_uppercase(),
                c[2].parse().unwrap(),
            )
        })
        .collect()
}

/// One move as the machine makes it.
#[derive(Debug, Clone, Copy)]
struct Move {
    code: u8,
    from: [f64; 3],
    to: [f64; 3],
    /// Arc centre (absolute) for G2/G3.
    centre: Option<(f64, f64)>,
}

impl Move {
    /// The point at `s` (0..=1) along the move: XY on its line or arc, Z straight.
    fn at(&self, s: f64) -> [f64; 3] {
        let z = self.from[2] + (self.to[2] - self.from[2]) * s;
        match self.centre {
            None => [
                self.from[0] + (self.to[0] - self.from[0]) * s,
                self.from[1] + (self.to[1] - self.from[1]) * s,
                z,
            ],
            Some(c) => {
                let (a0, span, r) = self.arc(c);
                let a = a0 + span * s;
                [c.0 + r * a.cos(), c.1 + r * a.sin(), z]
            }
        }
    }

    /// Start angle, signed sweep and radius around `c`.
    fn arc(&self, c: (f64, f64)) -> (f64, f64, f64) {
        let tau = std::f64::consts::TAU;
        let a0 = (self.from[1] - c.1).atan2(self.from[0] - c.0);
        let a1 = (self.to[1] - c.1).atan2(self.to[0] - c.0);
        let r = (self.from[0] - c.0).hypot(self.from[1] - c.1);
        let full = (self.from[0] - self.to[0]).hypot(self.from[1] - self.to[1]) < 1e-6;
        let mut span = if self.code == 3 {
            (a1 - a0).rem_euclid(tau)
        } else {
            -(a0 - a1).rem_euclid(tau)
        };
        if full || span.abs() < 1e-9 {
            span = if self.code == 3 { tau } else { -tau };
        }
        (a0, span, r)
    }

    /// The nominal Z of this (nominal) move at the point of it nearest to (x, y).
    fn z_near(&self, x: f64, y: f64, s_hint: f64) -> f64 {
        let s = match self.centre {
            None => {
                let (dx, dy) = (self.to[0] - self.from[0], self.to[1] - self.from[1]);
                let l2 = dx * dx + dy * dy;
                if l2 < 1e-12 {
                    s_hint
                } else {
                    (((x - self.from[0]) * dx + (y - self.from[1]) * dy) / l2).clamp(0.0, 1.0)
                }
            }
            Some(c) => {
                let (a0, span, _) = self.arc(c);
                let a = (y - c.1).atan2(x - c.0);
                let tau = std::f64::consts::TAU;
                let d = if span > 0.0 {
                    (a - a0).rem_euclid(tau)
                } else {
                    -(a0 - a).rem_euclid(tau)
                };
                // the full circle's start and end are the same point: take the nearer end
                let s = d / span;
                if s > 1.0 + 1e-9 || (s - s_hint).abs() > 0.5 {
                    if s_hint > 0.5 {
                        1.0
                    } else {
                        0.0
                    }
                } else {
                    s.clamp(0.0, 1.0)
                }
            }
        };
        self.from[2] + (self.to[2] - self.from[2]) * s
    }
}

/// The moves of a program, in order (lines without axis words skipped).
fn moves(program: &str) -> Vec<Move> {
    let mut pos = [f64::NAN; 3];
    let mut code = 0u8;
    let mut out = Vec::new();
    for line in program.lines() {
        let w = words(line);
        if !w.iter().any(|(l, _)| "XYZIJ".contains(*l)) {
            continue;
        }
        for (l, v) in &w {
            if *l == 'G' && *v < 4.0 {
                code = *v as u8;
            }
        }
        let get = |c: char| w.iter().find(|(l, _)| *l == c).map(|(_, v)| *v);
        let to = [
            get('X').unwrap_or(pos[0]),
            get('Y').unwrap_or(pos[1]),
            get('Z').unwrap_or(pos[2]),
        ];
        let centre = (code >= 2).then(|| {
            (
                pos[0] + get('I').unwrap_or(0.0),
                pos[1] + get('J').unwrap_or(0.0),
            )
        });
        out.push(Move {
            code,
            from: pos,
            to,
            centre,
        });
        pos = to;
    }
    out
}

/// The LinuxCNC log the probing program would write: one line of nine numbers per G38.
fn linuxcnc_log(probing: &str, top: f64, rise: &dyn Fn(f64, f64) -> f64) -> String {
    let mut log = String::new();
    let (mut x, mut y) = (f64::NAN, f64::NAN);
    for line in probing.lines() {
        let w = words(line);
        if let Some((_, v)) = w.iter().find(|(l, _)| *l == 'X') {
            x = *v;
        }
        if let Some((_, v)) = w.iter().find(|(l, _)| *l == 'Y') {
            y = *v;
        }
        if line.starts_with("G38") {
            let z = top + rise(x, y);
            log.push_str(&format!("{x:.6} {y:.6} {z:.6} 0 0 0 0 0 0\n"));
        }
    }
    log
}

#[derive(Default, Debug)]
struct Counts {
    programs: usize,
    nominal_cuts: usize,
    pieces: usize,
    samples: usize,
    /// The largest difference per surface, and the largest allowed on the bowl.
    worst: HashMap<&'static str, f64>,
    bowl_bound: f64,
}

/// Checks one adjusted program against its nominal program on `surface`.
fn check_against(
    clean: &str,
    milling: &str,
    top: f64,
    surface: &Surface,
    what: &str,
    counts: &mut Counts,
) {
    let nominal = moves(clean);
    let adjusted = moves(milling);
    let safe = nominal
        .iter()
        .find(|m| m.code == 0 && m.from[0].is_nan())
        .map(|m| m.to[2])
        .unwrap();
    // controllers refuse an arc whose radii to its ends differ (verify: by more than 0.002)
    for a in &adjusted {
        if let Some(c) = a.centre {
            let r0 = (a.from[0] - c.0).hypot(a.from[1] - c.1);
            let r1 = (a.to[0] - c.0).hypot(a.to[1] - c.1);
            assert!(
                (r0 - r1).abs() <= 0.0015,
                "{what}: arc radii {r0} and {r1}: {a:?}"
            );
        }
    }
    let mut k = 0;
    for n in &nominal {
        // the pieces of this nominal move: as long as it, and ending where it ends (a
        // full circle's pieces pass its end only at the end); one for a vertical move
        let len = arc_len(n);
        // a move that starts from a sweep first takes the surface's offset where it is
        if let Some(a) = adjusted.get(k) {
            let same_xy = (a.from[0] - n.from[0]).hypot(a.from[1] - n.from[1]) < 0.003
                && (a.to[0] - a.from[0]).hypot(a.to[1] - a.from[1]) < 1e-9;
            let rise = (surface.rise)(n.from[0], n.from[1]);
            let onto_start = (a.to[2] - (n.from[2] + rise)).abs() <= surface.tolerance;
            let not_the_move = len >= 1e-9 || (n.to[2] - n.from[2]).abs() > 0.02;
            if a.code == 0 && same_xy && onto_start && not_the_move && !n.from[0].is_nan() {
                k += 1;
            }
        }
        let first = k;
        let mut done = 0.0;
        loop {
            assert!(
                k < adjusted.len(),
                "{what}: the adjusted program ends early"
            );
            done += arc_len(&adjusted[k]);
            k += 1;
            let e = adjusted[k - 1].to;
            let at_end = (e[0] - n.to[0]).hypot(e[1] - n.to[1]) < 0.003;
            if len.is_nan() || len < 1e-9 || (done >= len - 0.01 && at_end) {
                break;
            }
        }
        let below = n.from[2].min(n.to[2]) < safe - 1e-6;
        if !below || n.from[0].is_nan() {
            continue;
        }
        let cut = n.code != 0;
        if cut {
            counts.nominal_cuts += 1;
            counts.pieces += k - first;
        }
        let mut before = 0.0;
        for piece in &adjusted[first..k] {
            let piece_len = arc_len(piece);
            for i in 0..=16 {
                let s = i as f64 / 16.0;
                let [x, y, z] = piece.at(s);
                // where along the nominal move the sample is, roughly (for full circles)
                let hint = if len >= 1e-9 {
                    (before + s * piece_len) / len
                } else {
                    s
                };
                let zn = n.z_near(x, y, hint);
                if zn >= safe - 1e-6 {
                    continue;
                }
                let rise = (surface.rise)(x, y);
                if cut {
                    // depth below the true surface = depth below the flat top
                    let err = ((top + rise - z) - (top - zn)).abs();
                    counts.samples += 1;
                    let worst = counts.worst.entry(surface.name).or_default();
                    *worst = worst.max(err);
                    if surface.tolerance > EXACT {
                        counts.bowl_bound = counts.bowl_bound.max(surface.tolerance);
                    }
                    assert!(
                        err <= surface.tolerance,
                        "{what}: at X{x:.3} Y{y:.3} the tip is {:.4} below the surface, the nominal {:.4} below the top ({} → {:?})",
                        top + rise - z,
                        top - zn,
                        surface.name,
                        piece
                    );
                } else if zn >= top && !(len < 1e-9 && n.to[2] > n.from[2]) {
                    // a rapid above the top stays above the surface (a retract rises out
                    // of the hole it is in: it may start below the surface)
                    assert!(z >= top + rise - surface.tolerance, "{what}: rapid into the surface at X{x:.3} Y{y:.3} Z{z:.3}: {piece:?} of {n:?}");
                }
            }
            before += piece_len;
        }
    }
    counts.programs += 1;
}

fn arc_len(m: &Move) -> f64 {
    match m.centre {
        None => (m.to[0] - m.from[0]).hypot(m.to[1] - m.from[1]),
        Some(c) => {
            let (_, span, r) = m.arc(c);
            (span * r).abs()
        }
    }
}

#[test]
fn every_cut_keeps_its_depth_below_the_measured_surface() {
    let mut drawings = files_in(&root().join("examples/plate"), &["dxf"]);
    drawings.extend(files_in(&root().join("examples/text"), &["mpath"]));
    let shared = root().join("../shared");
    if shared.is_dir() {
        for dir in ["conformance/fixtures", "samples"] {
            drawings.extend(files_in(&shared.join(dir), &["dxf"]));
        }
    } else {
        eprintln!("../shared is absent: only the examples are checked");
    }
    let mut counts = Counts::default();
    let mut sets = 0;
    for file in &drawings {
        for dialect in [Dialect::LinuxCnc, Dialect::Grbl] {
            let Some(set) = compile_set(file, dialect) else {
                continue;
            };
            sets += 1;
            let clean = &set["_Clean.gcode"];
            let z = &set["_Z.txt"];
            let top: f64 = z
                .split("/T=")
                .nth(1)
                .unwrap()
                .split(')')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            // the surface's features sit in the middle of the probed area
            let hm = set["_Probing.gcode"]
                .lines()
                .find(|l| l.starts_with("(MILLPATH-HEIGHTMAP"))
                .unwrap()
                .to_string();
            let val = |k: &str| -> f64 {
                hm.split(&format!(" {k}="))
                    .nth(1)
                    .unwrap()
                    .split([' ', ')'])
                    .next()
                    .unwrap()
                    .parse()
                    .unwrap()
            };
            let box_ = ((val("X0"), val("Y0")), (val("X1"), val("Y1")));
            for surface in surfaces(box_.0, box_.1) {
                let log = linuxcnc_log(&set["_Probing.gcode"], top, &*surface.rise);
                let mut diags = Diags::default();
                let what = format!("{} {} {}", file.display(), dialect.name(), surface.name);
                let milling = adjustz::adjust_with_log(
                    [
                        SetFile {
                            name: "c",
                            text: clean,
                        },
                        SetFile { name: "z", text: z },
                    ],
                    Some(SetFile {
                        name: "p",
                        text: &set["_Probing.gcode"],
                    }),
                    SetFile {
                        name: "log",
                        text: &log,
                    },
                    DEFAULT_TOLERANCE,
                    5.0,
                    dialect.post(),
                    &mut diags,
                )
                .unwrap_or_else(|| panic!("{what}: {:?}", diags.list));
                check_against(clean, &milling, top, &surface, &what, &mut counts);
                if dialect == Dialect::Grbl {
                    if let Err(e) = grbl::check_program(&milling) {
                        panic!("{what}: {e}");
                    }
                }
                let (split, pieces) = adjustz::split_summary(&milling).unwrap();
                assert!(pieces >= split, "{what}");
            }
        }
    }
    eprintln!(
        "{sets} program sets, {} adjusted programs: {} nominal cuts in {} pieces, {} samples; worst difference (mm): {:?}; largest bowl bound {:.4} mm",
        counts.programs, counts.nominal_cuts, counts.pieces, counts.samples, counts.worst, counts.bowl_bound
    );
    assert!(sets >= 4, "{sets}");
    assert!(counts.samples > 1000);
}
