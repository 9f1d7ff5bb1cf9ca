//! Moves that follow a measured surface: the nominal `_Clean.gcode` of a height-map set
//! becomes a `_Milling.gcode` whose cuts keep their drawn depth below the surface everywhere
//! (linuxcnc and grbl dialects; the manual's probing chapter says the same in words).
//!
//! * The **safe height** is the Z of the program's first `G00 Z`. A move that stays at or
//!   above it is written as it is: sweeps stay at the height the user set.
//! * Every point of the other moves gets Z + the surface's offset from the nominal top at
//!   its XY, the bilinear interpolation of the four measured corners of its grid cell.
//!   Plunges and retracts take the offset at their XY, up to the safe height and down from
//!   it, so a piece's straight Z never cuts a corner of the surface.
//! * Lines and arcs (and rapids below the safe height) are split where they cross a grid
//!   line, and each part again until the straight (or helical) Z between two written
//!   points stays within [`CHORD_TOL`] of the surface: inside a cell the offset is
//!   bilinear, so its second derivative along the move is bounded (`cell_curvature`), and a
//!   function with |f''| ≤ M departs from its chord over a length L by at most M·L²/8.
//! * A cutting move or plunge that leaves the map is an error, never an extrapolation. A
//!   rapid off the map is written unchanged when it passes above the highest measured point.
//!
//! Moves that follow the measured surface (height-map sets): safe height = first `G00 Z`;
//! lines/arcs/low rapids split at grid lines and until the chord is within 0.005 mm (bound from the
//! cell's slope and twist), Z + bilinear offset, arcs stay arcs; off-map cuts refused, off-map
//! rapids only above the highest point; the `MILLPATH-SURFACE` record and the split count.

use super::bounds::line_origin;
use super::words::Words;
use crate::args;
use crate::diag::{Diags, Msg, Origin};
use crate::geom::{F3, P2};
use millpath_post::Post;
use millpath_verify::surface::HeightMap;
use millpath_verify::{parse_line, Block};
use std::f64::consts::TAU;

/// How far (mm) the Z between two written points may depart from nominal + surface.
pub const CHORD_TOL: f64 = 0.005;
/// At most this many lines are written (a bound for any grid and program).
pub const MAX_LINES: usize = 4_000_000;
/// Grid crossings closer than this (mm) along a move are one split point.
const MIN_PIECE: f64 = 1e-4;
/// Heights within this of the safe height count as at it.
const EPS: f64 = 1e-6;

/// The adjusted program and how many moves were split into how many pieces.
#[derive(Debug, Clone, PartialEq)]
pub struct Followed {
    pub text: String,
    pub split_moves: usize,
    pub pieces: usize,
}

/// The word of the machine-readable split count in the adjusted program.
pub const SPLIT_WORD: &str = "MILLPATH-SPLIT";

/// The split count an adjusted program records (`(MILLPATH-SPLIT MOVES=n PIECES=m)`).
pub fn split_summary(program: &str) -> Option<(usize, usize)> {
    let head = format!("({SPLIT_WORD} ");
    let line = program.lines().find(|l| l.starts_with(&head))?;
    let mut words = line.trim_end_matches(')').split_whitespace().skip(1);
    let mut value = |key: &str| words.next()?.strip_prefix(key)?.parse().ok();
    Some((value("MOVES=")?, value("PIECES=")?))
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Motion {
    Rapid,
    Line,
    Cw,
    Ccw,
}

/// The G and other words of a line that adjust-z can carry over, or the first that it
/// cannot (as written in the message).
fn motion_of(block: &Block) -> Result<Option<Motion>, String> {
    let mut motion = None;
    for w in block.words.iter().filter(|w| w.letter == 'G') {
        let code = (w.value * 10.0).round() as i64;
        match code {
            0 => motion = Some(Motion::Rapid),
            10 => motion = Some(Motion::Line),
            20 => motion = Some(Motion::Cw),
            30 => motion = Some(Motion::Ccw),
            // plane XY, mm, no compensation or offsets, absolute, feed per minute, dwell
            40 | 170 | 210 | 400 | 490 | 540 | 800 | 900 | 940 => {}
            _ => return Err(format!("G{}", w.value)),
        }
    }
    let axis = block.words.iter().any(|w| "XYZIJ".contains(w.letter));
    for w in &block.words {
        let ok = match w.letter {
            // N: the line number (the program is numbered again as its post numbers)
            'G' | 'X' | 'Y' | 'Z' | 'I' | 'J' | 'F' | 'N' => true,
            // spindle, tool, dwell time, program end: only on lines without a move
            'M' | 'S' | 'T' | 'P' => !axis,
            _ => false,
        };
        if !ok {
            return Err(format!("{}{}", w.letter, w.value));
        }
    }
    Ok(motion)
}

/// Bounds of the surface offset in one grid cell: the largest slope and the twist `d` of
/// `a + b·x + c·y + d·x·y`.
fn cell_shape(map: &HeightMap, at: P2) -> (f64, f64) {
    let (xs, ys) = (map.xs(), map.ys());
    let (i, j) = map.cell(at.x, at.y);
    let (i1, j1) = ((i + 1).min(xs.len() - 1), (j + 1).min(ys.len() - 1));
    let (hx, hy) = (xs[i1] - xs[i], ys[j1] - ys[j]);
    let (z00, z10, z01, z11) = (map.at(i, j), map.at(i1, j), map.at(i, j1), map.at(i1, j1));
    let gx = if hx > 0.0 {
        (z10 - z00).abs().max((z11 - z01).abs()) / hx
    } else {
        0.0
    };
    let gy = if hy > 0.0 {
        (z01 - z00).abs().max((z11 - z10).abs()) / hy
    } else {
        0.0
    };
    let d = if hx > 0.0 && hy > 0.0 {
        (z11 - z10 - z01 + z00) / (hx * hy)
    } else {
        0.0
    };
    (gx.hypot(gy), d)
}

/// How many equal parts a piece of length `len` inside one cell needs so that the chord
/// between written points stays within [`CHORD_TOL`] of a function with |f''| ≤ `m`.
fn parts_for(len: f64, m: f64) -> usize {
    let n = (len * (m / (8.0 * CHORD_TOL)).sqrt()).ceil();
    if n.is_finite() && n >= 1.0 {
        n.min(MAX_LINES as f64) as usize
    } else {
        1
    }
}

fn round3(v: f64) -> f64 {
    (v * 1000.0).round() / 1000.0
}

/// The sorted split parameters of a move (0 and 1 included) from the crossings `cuts`.
fn with_ends(mut cuts: Vec<f64>, len: f64) -> Vec<f64> {
    cuts.retain(|t| *t > 0.0 && *t < 1.0);
    cuts.push(0.0);
    cuts.push(1.0);
    cuts.sort_by(f64::total_cmp);
    let min = if len > 0.0 { MIN_PIECE / len } else { 1.0 };
    let mut out: Vec<f64> = Vec::with_capacity(cuts.len());
    for t in cuts {
        match out.last() {
            Some(&last) if t - last < min => {
                // keep the end exactly at 1
                if t == 1.0 {
                    *out.last_mut().unwrap() = 1.0;
                }
            }
            _ => out.push(t),
        }
    }
    if out.len() == 1 {
        out.push(1.0);
    }
    out
}

/// Where the tool is in the nominal program, and the Z last written.
#[derive(Default)]
struct Tool {
    x: Option<f64>,
    y: Option<f64>,
    z: Option<f64>,
    written_z: Option<f64>,
}

/// The program being written: lines (in the words of the program's post), and the bound
/// on their number.
struct Writer<'a> {
    lines: Vec<String>,
    words: Words<'a>,
    map: &'a HeightMap,
    safe: f64,
    split_moves: usize,
    pieces: usize,
}

impl Writer<'_> {
    /// The Z written for nominal `z` at `p` (on the map, as the caller made sure): on the
    /// surface. Also a retract's end at the safe height: its line then stays straight.
    fn z_at(&self, z: f64, p: P2) -> f64 {
        z + self.map.offset(p.x, p.y).unwrap_or(0.0)
    }

    fn push_move(&mut self, text: String, count: &mut usize) -> bool {
        // a post's template may hold more than one line
        self.lines.extend(text.split('\n').map(str::to_string));
        *count += 1;
        self.lines.len() <= MAX_LINES
    }

    /// A straight move from (p0, z0) to (p1, z1), split; returns the last written Z.
    fn line(
        &mut self,
        m: Motion,
        feed: Option<f64>,
        from: (P2, f64),
        to: (P2, f64),
    ) -> Option<f64> {
        let ((p0, z0), (p1, z1)) = (from, to);
        let delta = p1.sub(p0);
        let len = delta.len();
        let mut count = 0;
        let mut last = self.z_at(z0, p0);
        if len < 1e-9 {
            last = self.z_at(z1, p1);
            let text = self.words.vertical(m == Motion::Rapid, feed, last);
            self.push_move(text, &mut count).then_some(())?;
            self.count(count);
            return Some(last);
        }
        let mut cuts = Vec::new();
        for (lines, a, b) in [(self.map.xs(), p0.x, p1.x), (self.map.ys(), p0.y, p1.y)] {
            if (b - a).abs() > 1e-12 {
                cuts.extend(lines.iter().map(|l| (l - a) / (b - a)));
            }
        }
        let ts = with_ends(cuts, len);
        let at = |t: f64| p0.add(delta.scale(t));
        let unit = delta.scale(1.0 / len);
        let mut first = true;
        for w in ts.windows(2) {
            let (ta, tb) = (w[0], w[1]);
            let (_, d) = cell_shape(self.map, at((ta + tb) / 2.0));
            // along a line the bilinear offset's second derivative is 2·d·ux·uy
            let n = parts_for(len * (tb - ta), (2.0 * d * unit.x * unit.y).abs());
            for k in 1..=n {
                let t = ta + (tb - ta) * k as f64 / n as f64;
                let end = tb == 1.0 && k == n;
                let (p, z) = if end {
                    (p1, z1)
                } else {
                    (at(t), z0 + (z1 - z0) * t)
                };
                last = self.z_at(z, p);
                let f = if first { feed } else { None };
                first = false;
                let text = self.words.straight(m == Motion::Rapid, f, p.x, p.y, last);
                self.push_move(text, &mut count).then_some(())?;
            }
        }
        self.count(count);
        Some(last)
    }

    /// An arc around `c` from (p0, z0) to (p1, z1), split into shorter (helical) arcs;
    /// returns the last written Z.
    fn arc(
        &mut self,
        m: Motion,
        feed: Option<f64>,
        c: P2,
        from: (P2, f64),
        to: (P2, f64),
    ) -> Option<f64> {
        let ((p0, z0), (p1, z1)) = (from, to);
        let r = p0.dist(c);
        let ccw = m == Motion::Ccw;
        let dir = if ccw { 1.0 } else { -1.0 };
        let angle = |p: P2| (p.y - c.y).atan2(p.x - c.x);
        let (a0, a1) = (angle(p0), angle(p1));
        let span = if p0.dist(p1) < 1e-9 {
            TAU
        } else {
            let s = (dir * (a1 - a0)).rem_euclid(TAU);
            if s < 1e-12 {
                TAU
            } else {
                s
            }
        };
        let t_of = |a: f64| (dir * (a - a0)).rem_euclid(TAU) / span;
        let mut cuts = Vec::new();
        for &x in self.map.xs() {
            let u = (x - c.x) / r;
            if u.abs() < 1.0 {
                let a = u.acos();
                cuts.extend([t_of(a), t_of(-a)]);
            }
        }
        for &y in self.map.ys() {
            let v = (y - c.y) / r;
            if v.abs() < 1.0 {
                let a = v.asin();
                cuts.extend([t_of(a), t_of(std::f64::consts::PI - a)]);
            }
        }
        let len = r * span;
        let ts = with_ends(cuts, len);
        let theta = |t: f64| a0 + dir * span * t;
        let on_arc = |t: f64| P2::new(c.x + r * theta(t).cos(), c.y + r * theta(t).sin());
        let mut count = 0;
        let mut last = self.z_at(z0, p0);
        // the point the machine is at: what was written last, to three decimals
        let mut at = P2::new(round3(p0.x), round3(p0.y));
        let mut first = true;
        for w in ts.windows(2) {
            let (ta, tb) = (w[0], w[1]);
            let (slope, d) = cell_shape(self.map, on_arc((ta + tb) / 2.0));
            // along a circle of radius r: |f''| ≤ slope / r + |d|
            let n = parts_for(len * (tb - ta), slope / r + d.abs());
            for k in 1..=n {
                let t = ta + (tb - ta) * k as f64 / n as f64;
                // I, J to the true centre from where the machine is; the end on the circle
                // the machine will take (its centre is that point plus the written I, J)
                let is_end = tb == 1.0 && k == n;
                let (i, j) = if is_end {
                    last_centre(at, p1, c)
                } else {
                    (round3(c.x - at.x), round3(c.y - at.y))
                };
                let end = if is_end {
                    p1
                } else {
                    let mc = P2::new(at.x + i, at.y + j);
                    let mr = at.dist(mc);
                    let th = theta(t);
                    P2::new(round3(mc.x + mr * th.cos()), round3(mc.y + mr * th.sin()))
                };
                let z = if is_end { z1 } else { z0 + (z1 - z0) * t };
                last = self.z_at(z, end);
                let f = if first { feed } else { None };
                first = false;
                let text = self
                    .words
                    .arc(m == Motion::Ccw, f, (i, j), (end.x, end.y, last));
                self.push_move(text, &mut count).then_some(())?;
                at = P2::new(round3(end.x), round3(end.y));
            }
        }
        self.count(count);
        Some(last)
    }

    fn count(&mut self, pieces: usize) {
        self.pieces += pieces;
        if pieces > 1 {
            self.split_moves += 1;
        }
    }
}

/// I, J of the last piece of an arc, from `at` (where the machine is) to the arc's own end
/// `p1` around `c`: of the written centres near the one equidistant from both ends, the one
/// whose radii to the two ends differ least (controllers refuse more than a few µm).
fn last_centre(at: P2, p1: P2, c: P2) -> (f64, f64) {
    let chord = p1.sub(at);
    let centre = if chord.len() < 1e-6 {
        c
    } else {
        // the point of the ends' perpendicular bisector nearest to c
        let mid = at.add(chord.scale(0.5));
        let u = P2::new(-chord.y, chord.x).scale(1.0 / chord.len());
        mid.add(u.scale(c.sub(mid).dot(u)))
    };
    let (i0, j0) = (round3(centre.x - at.x), round3(centre.y - at.y));
    let mut best = (f64::INFINITY, f64::INFINITY, i0, j0);
    for di in [-1.0, 0.0, 1.0] {
        for dj in [-1.0, 0.0, 1.0] {
            let (i, j) = (round3(i0 + di * 0.001), round3(j0 + dj * 0.001));
            let mc = P2::new(at.x + i, at.y + j);
            let key = ((at.dist(mc) - p1.dist(mc)).abs(), mc.dist(c));
            if key < (best.0, best.1) {
                best = (key.0, key.1, i, j);
            }
        }
    }
    (best.2, best.3)
}

/// The adjusted program of `clean` on `map`, or `None` after errors (each at its line of
/// `file`). Nothing is produced unless every move could follow the surface. The lines it
/// writes are `post`'s, the post of the program it adjusts.
pub fn follow(
    clean: &str,
    file: &str,
    map: &HeightMap,
    post: &Post,
    diags: &mut Diags,
) -> Option<Followed> {
    let before = diags.error_count();
    let eol = if clean.contains("\r\n") { "\r\n" } else { "\n" };
    let mut w = Writer {
        lines: Vec::new(),
        words: Words { post },
        map,
        safe: f64::NAN,
        split_moves: 0,
        pieces: 0,
    };
    let mut tool = Tool::default();
    let mut modal: Option<Motion> = None;
    let mut stock_line = None;
    let mut stats_line = None;
    let max_height = map.max_height();
    for (n, line) in clean.lines().enumerate() {
        let at = line_origin(file, n + 1);
        if line.contains("(MILLPATH-SURFACE") {
            diags.error(Msg::HeightMapAlreadyAdjusted, at, args![file]);
            return None;
        }
        let line = w.words.unnumbered(line);
        // a comment's text, after `(` or `;`
        let comment = line
            .trim_start()
            .strip_prefix(['(', ';'])
            .map(str::trim_start);
        if comment.is_some_and(|c| c.starts_with("MILLPATH-STOCK")) {
            stock_line = Some(w.lines.len());
        }
        if let Some(c) =
            comment.filter(|c| c.starts_with("Command count:") || c.starts_with("Befehlszahl:"))
        {
            stats_line = Some((w.lines.len(), c.starts_with("Befehlszahl")));
        }
        let block = match parse_line(line) {
            Ok(b) => b,
            Err(_) => {
                diags.error(Msg::SurfaceLineUnsupported, at, args![line.trim()]);
                return None;
            }
        };
        let motion = match motion_of(&block) {
            Ok(m) => m,
            Err(word) => {
                diags.error(Msg::SurfaceLineUnsupported, at, args![word]);
                return None;
            }
        };
        modal = motion.or(modal);
        let has = |l: char| block.has(l);
        let axis = ['X', 'Y', 'Z', 'I', 'J'].into_iter().any(has);
        if !axis {
            w.lines.push(line.to_string());
            continue;
        }
        let Some(m) = modal else {
            diags.error(Msg::SurfaceLineUnsupported, at, args![line.trim()]);
            return None;
        };
        let feed = block.get('F');
        // the prologue's first G00 Z sets the safe height
        if w.safe.is_nan() {
            match (m, block.get('Z')) {
                (Motion::Rapid, Some(z)) if !['X', 'Y', 'I', 'J'].into_iter().any(has) => {
                    w.safe = z;
                    // sweeps stay at the safe height: the whole surface must lie below it
                    if max_height >= z {
                        let (x, y) = highest_point(map);
                        let args = args![F3(max_height), F3(x), F3(y), F3(z)];
                        diags.error(Msg::SurfaceAboveSafeHeight, at, args);
                        return None;
                    }
                }
                _ => {
                    diags.error(Msg::SurfaceNoSafeHeight, at, vec![]);
                    return None;
                }
            }
        }
        let target = (
            block.get('X').or(tool.x),
            block.get('Y').or(tool.y),
            block.get('Z').or(tool.z),
        );
        let high = |z: Option<f64>| z.is_some_and(|z| z >= w.safe - EPS);
        if high(tool.z.or(target.2)) && high(target.2) {
            w.lines.push(line.to_string());
            if has('Z') {
                tool.written_z = target.2;
            }
            (tool.x, tool.y, tool.z) = target;
            continue;
        }
        let (Some(x0), Some(y0), Some(z0), Some(x1), Some(y1), Some(z1)) =
            (tool.x, tool.y, tool.z, target.0, target.1, target.2)
        else {
            diags.error(Msg::SurfaceNoSafeHeight, at, vec![]);
            return None;
        };
        let mut written = tool.written_z.unwrap_or(z0);
        let (p0, p1) = (P2::new(x0, y0), P2::new(x1, y1));
        let off_map = |p: P2| !map.contains(p.x, p.y);
        // after a move written as it was (a sweep at the safe height, a rapid off the map)
        // the tool first takes the surface's offset where it is, so that the next move's
        // straight Z starts on the surface too; it is above the surface there
        if !off_map(p0) {
            let want = round3(w.z_at(z0, p0));
            if (written - want).abs() >= 0.0005 {
                w.lines.push(w.words.vertical(true, None, want));
                w.pieces += 1;
                written = want;
            }
        }
        let last = match m {
            Motion::Rapid | Motion::Line => {
                let off = [p1, p0].into_iter().find(|p| off_map(*p));
                match off {
                    None => w.line(m, feed, (p0, z0), (p1, z1)),
                    Some(_) if m == Motion::Rapid => {
                        // off the map a rapid keeps its height, and must pass above the surface
                        let end = if has('Z') { z1 } else { written };
                        if written.min(end) <= max_height {
                            let args = args![F3(written.min(end)), F3(max_height)];
                            diags.error(Msg::SurfaceRapidOffMapLow, at, args);
                            return None;
                        }
                        w.lines.push(line.to_string());
                        Some(end)
                    }
                    Some(p) => {
                        off_map_error(map, p, at, diags);
                        return None;
                    }
                }
            }
            Motion::Cw | Motion::Ccw => {
                if block.has('P') {
                    diags.error(Msg::SurfaceLineUnsupported, at, args!["P"]);
                    return None;
                }
                let c = P2::new(
                    x0 + block.get('I').unwrap_or(0.0),
                    y0 + block.get('J').unwrap_or(0.0),
                );
                if p0.dist(c) < 1e-6 {
                    diags.error(Msg::SurfaceLineUnsupported, at, args![line.trim()]);
                    return None;
                }
                let mut reach = vec![p0, p1];
                reach.extend(crate::geom::arc_extremes(p0, p1, c, m == Motion::Ccw));
                if let Some(p) = reach.into_iter().find(|p| off_map(*p)) {
                    off_map_error(map, p, at, diags);
                    return None;
                }
                w.arc(m, feed, c, (p0, z0), (p1, z1))
            }
        };
        let Some(last) = last else {
            diags.error(Msg::SurfaceTooManyLines, at, args![MAX_LINES]);
            return None;
        };
        tool.written_z = Some(last);
        (tool.x, tool.y, tool.z) = (Some(x1), Some(y1), Some(z1));
    }
    if diags.error_count() > before {
        return None;
    }
    let (moves, pieces) = (w.split_moves, w.pieces);
    let mut lines = std::mem::take(&mut w.lines);
    if let Some((k, german)) = stats_line {
        let text = if german {
            format!("Geteilte Wege: {moves} in {pieces} Teile")
        } else {
            format!("Split moves:  {moves} into {pieces} pieces")
        };
        lines.insert(k + 1, w.words.statistics(&text));
    }
    let mut record = map.comment_lines();
    record.push(format!("({SPLIT_WORD} MOVES={moves} PIECES={pieces})"));
    let at = stock_line.map_or(2.min(lines.len()), |k| k + 1);
    lines.splice(at..at, record);
    let mut text = w.words.finish(lines).join(eol);
    text.push_str(eol);
    Some(Followed {
        text,
        split_moves: moves,
        pieces,
    })
}

/// Where the map is highest (the first such point).
fn highest_point(map: &HeightMap) -> (f64, f64) {
    let top = map.max_height();
    for (j, &y) in map.ys().iter().enumerate() {
        for (i, &x) in map.xs().iter().enumerate() {
            if map.at(i, j) == top {
                return (x, y);
            }
        }
    }
    (map.xs()[0], map.ys()[0])
}

fn off_map_error(map: &HeightMap, p: P2, at: Origin, diags: &mut Diags) {
    let (xs, ys) = (map.xs(), map.ys());
    let args = args![
        F3(p.x),
        F3(p.y),
        F3(xs[0]),
        F3(xs[xs.len() - 1]),
        F3(ys[0]),
        F3(ys[ys.len() - 1])
    ];
    diags.error(Msg::SurfaceMoveOffMap, at, args);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 0–20 × 0–10 map rising 0.01 per mm in X from the top 2.
    fn map() -> HeightMap {
        let xs = vec![0.0, 10.0, 20.0];
        let ys = vec![0.0, 10.0];
        let z = vec![2.0, 2.1, 2.2, 2.0, 2.1, 2.2];
        HeightMap::new(xs, ys, z, 2.0).unwrap()
    }

    const PROLOGUE: &str = "%\n(millpath V.1)\n(MILLPATH-STOCK T=2.000 O=1.000)\nG17 G21 G90\nG00 Z5.000\nG00 X0.000 Y0.000\n";

    fn linuxcnc() -> &'static Post {
        millpath_post::builtin::get("linuxcnc").unwrap()
    }

    #[test]
    fn a_numbered_posts_program_is_numbered_again_in_its_words() {
        let text = millpath_post::builtin::source("linuxcnc")
            .unwrap()
            .replace("modal = []", "modal = [\"F\", \"motion\"]")
            .replace(
                "[comments]",
                "[line_numbers]\nstart = 10\nstep = 10\n\n[comments]",
            );
        let post = millpath_post::load("n.toml", &text).unwrap();
        let body =
            "G00 Z3.000\nG01 F100.000 Z1.500\nG01 F300.000 X20.000 Y0.000 Z1.500\nG00 Z5.000\n";
        let program: String = format!("{PROLOGUE}{body}M30\n%\n")
            .lines()
            .enumerate()
            .map(|(k, l)| match l {
                "%" => "%\n".to_string(),
                l => format!("N{} {l}\n", 10 * k),
            })
            .collect();
        let mut d = Diags::default();
        let out = follow(&program, "c", &map(), &post, &mut d).unwrap().text;
        assert!(d.list.is_empty(), "{:?}", d.list);
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines[0], "%");
        for (k, l) in lines[1..lines.len() - 1].iter().enumerate() {
            assert!(l.starts_with(&format!("N{} ", 10 * (k + 1))), "{out}");
        }
        // modal words as the post leaves them out: G01 after the plunge, the feed on the
        // split line's second piece
        assert!(out.contains("N130 G01 F100.000 Z1.500\n"), "{out}");
        assert!(
            out.contains("N140 F300.000 X10.000 Y0.000 Z1.600\n"),
            "{out}"
        );
        assert!(out.contains("N150 X20.000 Y0.000 Z1.700\n"), "{out}");
    }

    fn run(body: &str) -> (Option<Followed>, Vec<(Msg, String)>) {
        let mut d = Diags::default();
        let program = format!("{PROLOGUE}{body}M30\n%\n");
        let out = follow(&program, "c", &map(), linuxcnc(), &mut d);
        let msgs = d.list.iter().map(|x| (x.msg, x.origin.context())).collect();
        (out, msgs)
    }

    fn moves(text: &str) -> Vec<&str> {
        text.lines()
            .filter(|l| l.starts_with('G') && !l.starts_with("G17"))
            .collect()
    }

    #[test]
    fn a_groove_is_split_at_the_grid_lines_and_follows_the_slope() {
        let (out, msgs) = run(
            "G00 Z3.000\nG01 F100.000 Z1.500\nG01 F300.000 X20.000 Y0.000 Z1.500\nG00 Z5.000\n",
        );
        assert!(msgs.is_empty(), "{msgs:?}");
        let out = out.unwrap();
        assert_eq!(
            moves(&out.text),
            [
                "G00 Z5.000",
                "G00 X0.000 Y0.000",
                "G00 Z3.000",
                "G01 F100.000 Z1.500",
                "G01 F300.000 X10.000 Y0.000 Z1.600",
                "G01 X20.000 Y0.000 Z1.700",
                // the retract takes the offset too: the line stays straight
                "G00 Z5.200",
            ]
        );
        assert_eq!((out.split_moves, out.pieces), (1, 5));
        assert_eq!(split_summary(&out.text), Some((1, 5)));
        // the record follows the stock comment, and reads back as the map
        let lines: Vec<&str> = out.text.lines().collect();
        assert_eq!(lines[3], "(MILLPATH-SURFACE T=2.000 NX=3 NY=2)");
        let back = HeightMap::read_comments(out.text.lines()).unwrap().unwrap();
        assert_eq!(back, map());
    }

    #[test]
    fn arcs_are_split_into_arcs_on_the_same_circle() {
        // a half circle from (5, 5) around (10, 5) through (10, 10) to (15, 5), clockwise
        let (out, msgs) = run("G00 X5.000 Y5.000\nG00 Z3.000\nG01 F100.000 Z1.000\nG02 F300.000 I5.000 J0 X15.000 Y5.000 Z1.000\nG00 Z5.000\n");
        assert!(msgs.is_empty(), "{msgs:?}");
        let text = out.unwrap().text;
        let arcs: Vec<&str> = text.lines().filter(|l| l.starts_with("G02")).collect();
        // crossing x = 10 and y = 10 (touching the top at (10, 10)): two pieces at least
        assert!(arcs.len() >= 2, "{arcs:?}");
        assert!(
            arcs.last().unwrap().ends_with(" X15.000 Y5.000 Z1.150"),
            "{arcs:?}"
        );
        assert!(
            arcs[0].starts_with("G02 F300.000 I5.000 J0.000 "),
            "{arcs:?}"
        );
        // every piece turns around the centre (10, 5) from where the last one ended, and ends
        // on the circle (within the rounding of I, J and the point to 0.001)
        let mut at = (5.0, 5.0);
        let word = |l: &str, c: char| -> f64 {
            let w = l.split(' ').find(|w| w.starts_with(c)).unwrap();
            w[1..].parse().unwrap()
        };
        for a in &arcs {
            let centre = (at.0 + word(a, 'I'), at.1 + word(a, 'J'));
            assert!(
                (centre.0 - 10.0).abs() <= 0.001 && (centre.1 - 5.0).abs() <= 0.001,
                "{a}"
            );
            at = (word(a, 'X'), word(a, 'Y'));
            assert!(
                ((at.0 - 10.0).hypot(at.1 - 5.0) - 5.0).abs() <= 0.0015,
                "{a}"
            );
        }
    }

    #[test]
    fn a_cut_off_the_map_is_refused_at_its_line() {
        let (out, msgs) =
            run("G00 Z3.000\nG01 F100.000 Z1.500\nG01 F300.000 X25.000 Y0.000 Z1.500\n");
        assert!(out.is_none());
        assert_eq!(msgs, [(Msg::SurfaceMoveOffMap, "c:9".to_string())]);
        // an arc whose ends are on the map but whose bulge is not
        let (_, msgs) = run("G00 X3.000 Y5.000\nG00 Z3.000\nG01 F100.000 Z1.000\nG03 F300.000 I7.000 J0 X17.000 Y5.000\n");
        assert_eq!(msgs, [(Msg::SurfaceMoveOffMap, "c:10".to_string())]);
    }

    #[test]
    fn rapids_off_the_map_must_pass_above_the_surface() {
        // at Z5 (above the highest point 2.2) a sweep may leave the map; at Z2.1 not
        let (out, msgs) = run("G00 Z4.000\nG00 X30.000 Y0.000\n");
        assert!(msgs.is_empty(), "{msgs:?}");
        assert!(out.unwrap().text.contains("\nG00 X30.000 Y0.000\n"));
        let (out, msgs) = run("G00 Z2.100\nG00 X30.000 Y0.000\n");
        assert!(out.is_none());
        assert_eq!(msgs, [(Msg::SurfaceRapidOffMapLow, "c:8".to_string())]);
    }

    #[test]
    fn lines_it_cannot_carry_over_are_refused() {
        for (body, word) in [
            ("G91\n", "G91"),
            ("G20\n", "G20"),
            ("G00 Z3.000\nG02 X1.000 Y1.000 R1.000\n", "R1"),
            ("G00 Z3.000\nG01 X1.000 M3\n", "M3"),
        ] {
            let (out, msgs) = run(body);
            assert!(out.is_none(), "{body}");
            assert_eq!(msgs[0].0, Msg::SurfaceLineUnsupported, "{body}");
            let mut d = Diags::default();
            follow(
                &format!("{PROLOGUE}{body}M30\n"),
                "c",
                &map(),
                linuxcnc(),
                &mut d,
            );
            assert!(
                d.list[0]
                    .message(crate::Lang::En)
                    .contains(&format!("'{word}'")),
                "{:?}",
                d.list[0].message(crate::Lang::En)
            );
        }
        // a surface that reaches the safe height: the sweeps would hit it
        let mut d = Diags::default();
        let low = PROLOGUE.replace("G00 Z5.000", "G00 Z2.200");
        assert!(follow(&format!("{low}M30\n"), "c", &map(), linuxcnc(), &mut d).is_none());
        assert_eq!(d.list[0].msg, Msg::SurfaceAboveSafeHeight);
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "The measured surface reaches Z2.200 at X20.000 Y0.000, not below the safe height Z2.200: the sweeps would hit it (raise sweep_height, or check the log); nothing was written"
        );
        // a move before the safe height is known
        let mut d = Diags::default();
        assert!(follow(
            "%\nG01 X1.000 Z1.000\nM30\n",
            "c",
            &map(),
            linuxcnc(),
            &mut d
        )
        .is_none());
        assert_eq!(d.list[0].msg, Msg::SurfaceNoSafeHeight);
        // a program that follows a surface already
        let (out, _) = run("G00 Z3.000\n");
        let mut d = Diags::default();
        assert!(follow(&out.unwrap().text, "m", &map(), linuxcnc(), &mut d).is_none());
        assert_eq!(d.list[0].msg, Msg::HeightMapAlreadyAdjusted);
    }

    #[test]
    fn crlf_stays_crlf() {
        let program = format!("{PROLOGUE}G00 Z3.000\nM30\n").replace('\n', "\r\n");
        let mut d = Diags::default();
        let out = follow(&program, "c", &map(), linuxcnc(), &mut d).unwrap();
        assert!(out.text.ends_with("M30\r\n"));
        assert!(!out.text.replace("\r\n", "").contains('\n'));
    }
}
