//! Valid drawings from a fuzzer's bytes: a compiled path and up to three parts it embeds, each
//! part in a file of its own, built as a connected walk (lines, arcs, holes, dead ends with
//! turn markers, closed chains, subpath lines of the part's exact length, probes) so that
//! most drawings reach the emitters. Parameter texts are mostly sane, sometimes hostile (NaN,
//! 1e300, negative counts, decimal commas, variables, letters where they do not belong): the
//! compiler must refuse those with located errors, the same in both front-ends.
//!
//! Sizes are bounded for speed (the second opinion's stock grid grows with the area over the
//! bit's diameter, its work with the passes): steps of at most 8 mm, bits of 1.5 mm and up, at
//! most 5 mm of material in passes of 1 mm and more, unless a hostile value says otherwise.
//!
//! The drawing is an `ast::File` per file, written by the formatter (the text front-end) and
//! by `text2dxf` (the DXF front-end).

use arbitrary::{Result, Unstructured};
use millpath_core::machine::Axes;
use millpath_core::{Dialect, Settings};
use millpath_syntax::ast::{Element, File, Geometry, Item, Kind, PathBlock, PathItem, Point};
use millpath_syntax::ast::{Spanned, Style};

/// One generated drawing: its files (stem, tree) with the compiled one first, and the settings
/// of the run.
#[derive(Debug)]
pub struct Case {
    pub files: Vec<(String, File)>,
    pub settings: Settings,
}

/// Values a fuzzer should throw at every number: not numbers, overflowing, tiny, huge,
/// malformed, variables that do not exist.
const HOSTILE: &[&str] = &[
    "NaN",
    "nan",
    "inf",
    "-inf",
    "1e300",
    "-1e300",
    "1e-300",
    "0",
    "-0",
    "99999999",
    "-99999999",
    "1,5,5",
    "1.5.5",
    "",
    "=Q",
    "=B",
    "0x1F",
    "12345678901234567890123",
    "1e6",
    "-1e6",
    "+3",
    ".5",
    "5.",
    "1e",
    "-3",
    "-1",
];

const LIMIT_STEPS_TOP: usize = 9;
const LIMIT_STEPS_PART: usize = 5;
const MAX_PARTS: usize = 3;

fn sp<T>(v: T) -> Spanned<T> {
    Spanned::new(v, 0..0)
}

fn pt(x: f64, y: f64) -> Point {
    Point { x, y }
}

/// A number word: from `table` mostly (with a decimal comma now and then), else hostile.
fn number(u: &mut Unstructured, table: &[f64]) -> Result<String> {
    let b: u8 = u.arbitrary()?;
    if b >= 250 {
        return Ok(u.choose(HOSTILE)?.to_string());
    }
    let i = usize::from(b) % table.len();
    let v = table[i];
    let s = format!("{v}");
    Ok(if (usize::from(b) / table.len()) % 2 == 1 {
        s.replace('.', ",")
    } else {
        s
    })
}

/// One extra parameter of any letter (legal for the element or not).
fn extra_param(u: &mut Unstructured, n: &mut u32, legal: &[u8]) -> Result<String> {
    const LETTERS: &[u8] = b"FIBDPUSZAWCEHQRNLKTOM";
    // a letter the element does not take, one time in twelve
    let letters = if legal.is_empty() || u.ratio(1, 12)? {
        LETTERS
    } else {
        legal
    };
    let l = char::from(*u.choose(letters)?);
    let value = match l {
        'N' => {
            if u.ratio(1, 6)? {
                number(u, &[1.0])?
            } else {
                *n += 1;
                n.to_string()
            }
        }
        'Q' => u
            .choose(&["pocket", "a(b)", "NaN", "x;y", "Größe", "%", "\\"])?
            .to_string(),
        'E' => u.choose(&["[LP]$", "(", ".*", "^2"])?.to_string(),
        'R' => u.choose(&["L", "_x", "", "/..", "v2"])?.to_string(),
        'K' => u
            .choose(&["10", "5+1", "0", "-3", "1e9", "2+0,5", "NaN"])?
            .to_string(),
        'L' => u.choose(&["1", "2", "A", ""])?.to_string(),
        'M' => u.choose(&["10x3", "3", "", "M"])?.to_string(),
        'F' => number(u, &[100.0, 300.0, 50.0, 1000.0])?,
        'I' | 'W' => number(u, &[0.5, 1.0, 1.5])?,
        'B' => number(u, &[0.0, -0.2, 0.5, 1.0])?,
        'D' => number(u, &[1.0, 1.5, 2.0])?,
        'S' => number(u, &[12.0, 20.0, 15.0, 30.0])?,
        'Z' => number(u, &[50.0, 20.0])?,
        'A' => number(u, &[20.0, 30.0, 8.0])?,
        'H' => number(u, &[0.5, 1.0])?,
        'C' => number(u, &[1.0, 2.0])?,
        _ => number(u, &[1.0, 2.0, 0.5, -1.0, 5.0, 10.0, 100.0, 3.0, 0.2, 20.0])?,
    };
    Ok(format!("{l}{value}"))
}

/// Letters each kind of element takes (parameters.md).
const AT_START: &[u8] = b"FSZAWCER";
/// K (a height map) only outside the reference dialect.
const AT_START_CNC: &[u8] = b"FSZAWCERK";
const AT_SEGMENT: &[u8] = b"FBDQNIWC";
const AT_SWEEP: &[u8] = b"SN";
const AT_HOLE: &[u8] = b"FBDQ";
const AT_SUB: &[u8] = b"TOMHN";

/// Up to two extra parameters, now and then: letters from `legal` mostly.
fn extras(u: &mut Unstructured, n: &mut u32, out: &mut Vec<String>, legal: &[u8]) -> Result<()> {
    let often = if legal.is_empty() { 40 } else { 5 };
    if u.ratio(1, often)? {
        for _ in 0..u.int_in_range(1..=2)? {
            let p = extra_param(u, n, legal)?;
            // a letter given twice is refused already by text2dxf: now and then only
            let twice = out.iter().any(|q| q.chars().next() == p.chars().next());
            if !twice || u.ratio(1, 10)? {
                out.push(p);
            }
        }
    }
    Ok(())
}

/// A path being drawn: its elements and where the walk is.
struct Walk {
    items: Vec<PathItem>,
    at: Point,
    /// The N given so far (every dead end and closed chain is numbered in walk order).
    n: u32,
    /// The bit diameter when it is a plain number (holes are drawn from it).
    o: Option<f64>,
}

impl Walk {
    fn push(&mut self, kind: Kind, geometry: Geometry, params: Vec<String>) {
        self.items.push(PathItem::Element(Element {
            kind: sp(kind),
            geometry: sp(geometry),
            params: params.into_iter().map(sp).collect(),
            comment: None,
            span: 0..0,
        }));
    }

    fn next_n(&mut self) -> String {
        self.n += 1;
        format!("N{}", self.n)
    }
}

fn segment_kind(u: &mut Unstructured) -> Result<Kind> {
    Ok(match u.int_in_range(0..=14)? {
        0..=4 => Kind::Mill,
        5 => Kind::Mark,
        6 => Kind::Bars,
        7..=9 => Kind::Sweep,
        10 => Kind::Move,
        11 => Kind::Skip,
        12 => Kind::Raw("DASHED2".into()),
        _ => Kind::Mill,
    })
}

fn letters_of(kind: &Kind) -> &'static [u8] {
    match kind {
        Kind::Mill | Kind::Mark | Kind::Bars => AT_SEGMENT,
        Kind::Sweep => AT_SWEEP,
        // a move takes no text (refused, NoTextHere): the empty list means "any letter, rarely"
        _ => b"",
    }
}

fn cutting_kind(u: &mut Unstructured) -> Result<Kind> {
    Ok(match u.int_in_range(0..=5)? {
        0..=3 => Kind::Mill,
        4 => Kind::Mark,
        _ => Kind::Bars,
    })
}

/// A step on the 0.5 mm grid, never zero.
fn delta(u: &mut Unstructured) -> Result<(f64, f64)> {
    let dx = f64::from(u.int_in_range(-16i8..=16)?) / 2.0;
    let dy = f64::from(u.int_in_range(-16i8..=16)?) / 2.0;
    Ok(if dx == 0.0 && dy == 0.0 {
        (1.0, 0.0)
    } else {
        (dx, dy)
    })
}

/// The point at `deg` degrees (a multiple of 90) on the circle around `c`: exact.
fn on_circle(c: Point, r: f64, deg: i32) -> Point {
    match deg.rem_euclid(360) {
        0 => pt(c.x + r, c.y),
        90 => pt(c.x, c.y + r),
        180 => pt(c.x - r, c.y),
        _ => pt(c.x, c.y - r),
    }
}

/// An arc from the walk's point, a quarter, half or three quarters of a circle, either way.
fn arc_from(u: &mut Unstructured, at: Point) -> Result<(Geometry, Point)> {
    let r = f64::from(u.int_in_range(1u8..=12)?) / 2.0;
    let a = 90 * i32::from(u.int_in_range(0u8..=3)?);
    let sweep = 90 * i32::from(u.int_in_range(1u8..=3)?);
    let ccw: bool = u.arbitrary()?;
    let c = on_circle(at, r, a + 180);
    let b = if ccw { a + sweep } else { a - sweep };
    let (from, to) = if ccw { (a, b) } else { (b, a) };
    let g = Geometry::Arc {
        c,
        r,
        a0: f64::from(from.rem_euclid(360)),
        a1: f64::from(to.rem_euclid(360)),
    };
    Ok((g, on_circle(c, r, b)))
}

/// A part another path embeds: its name and the vector from its start to its end marker.
#[derive(Clone)]
struct Part {
    name: String,
    span: (f64, f64),
    /// The variable its start defines (letter), if any.
    var: Option<char>,
}

/// The start text of the parameters every path shares (T, O, M are the compiled path's in
/// every part, as embedding requires).
struct Common {
    t: String,
    o: String,
    m: Option<String>,
}

fn common(u: &mut Unstructured) -> Result<Common> {
    Ok(Common {
        t: number(u, &[3.0, 2.5, 5.0, 4.0])?,
        o: number(u, &[2.0, 3.0, 1.5, 6.0])?,
        m: if u.ratio(15, 16)? {
            Some(u.choose(&["10x3", "3", "Alu"])?.to_string())
        } else {
            None
        },
    })
}

/// One path: start text, a walk of `steps` steps, the end marker, probes. `parts` are the
/// paths it may embed.
fn path(
    u: &mut Unstructured,
    name: &str,
    c: &Common,
    parts: &[Part],
    max_steps: usize,
    var: Option<char>,
    cnc: bool,
) -> Result<(PathBlock, Point)> {
    let mut start = vec![format!("T{}", c.t), format!("O{}", c.o)];
    if let Some(m) = &c.m {
        start.push(format!("M{m}"));
    }
    if var != Some('I') {
        start.push(format!("I{}", number(u, &[1.0, 1.5, 2.0, 3.0])?));
    }
    match var {
        Some(v) => {
            start.push(format!("{v}={v}"));
            let def = *u.choose(&["-0.5~3", "0,1,2", "1~0", "?12"])?;
            start.push(format!(":{v}{def}"));
        }
        None => start.push(format!("B{}", number(u, &[-0.2, 0.0, 1.0, 0.5])?)),
    }
    if u.ratio(15, 16)? && var != Some('D') {
        start.push(format!("D{}", number(u, &[2.0, 1.5, 2.5])?));
    }
    if u.ratio(15, 16)? {
        start.push(format!("P{}", number(u, &[4.0, 2.0, 1.0])?));
        start.push(format!("U{}", number(u, &[20.0, 10.0, 5.0])?));
    }
    let mut w = Walk {
        items: Vec::new(),
        at: pt(0.0, 0.0),
        n: 0,
        o: c.o
            .replace(',', ".")
            .parse::<f64>()
            .ok()
            .filter(|o| *o > 0.0),
    };
    let legal = if cnc { AT_START_CNC } else { AT_START };
    extras(u, &mut w.n, &mut start, legal)?;
    w.push(Kind::Start, Geometry::Point(w.at), start);
    let steps = u.int_in_range(1..=max_steps)?;
    for _ in 0..steps {
        if u.is_empty() {
            break;
        }
        step(u, &mut w, parts)?;
    }
    w.push(Kind::End, Geometry::Point(w.at), Vec::new());
    let end = w.at;
    if u.ratio(1, 4)? {
        for i in 0..u.int_in_range(1..=3)? {
            let (dx, dy) = delta(u)?;
            let kind = if u.ratio(1, 5)? {
                Kind::NoProbe
            } else {
                Kind::Probe
            };
            let mut params = Vec::new();
            if u.ratio(1, 2)? {
                params.push(format!("L{}", i + 1));
            }
            if u.ratio(1, 6)? {
                params.push(format!("H{}", number(u, &[0.5, 1.0, -0.5])?));
            }
            if u.ratio(1, 6)? {
                params.push(format!("Z{}", number(u, &[50.0, 20.0])?));
            }
            w.push(kind, Geometry::Point(pt(dx, dy)), params);
        }
    }
    let block = PathBlock {
        name: sp(name.to_string()),
        comment: None,
        close_comment: None,
        items: w.items,
        span: 0..0,
    };
    Ok((block, end))
}

/// One step of the walk.
fn step(u: &mut Unstructured, w: &mut Walk, parts: &[Part]) -> Result<()> {
    let at = w.at;
    match u.int_in_range(0u8..=11)? {
        // a line
        0..=3 => {
            let kind = segment_kind(u)?;
            let (dx, dy) = delta(u)?;
            let to = pt(at.x + dx, at.y + dy);
            let mut params = Vec::new();
            extras(u, &mut w.n, &mut params, letters_of(&kind))?;
            w.push(kind, Geometry::Line(at, to), params);
            w.at = to;
        }
        // an arc
        4 | 5 => {
            let kind = segment_kind(u)?;
            let (g, to) = arc_from(u, at)?;
            let mut params = Vec::new();
            extras(u, &mut w.n, &mut params, letters_of(&kind))?;
            w.push(kind, g, params);
            w.at = to;
        }
        // a hole where the walk is
        6 => {
            let style = *u.choose(&[Style::Mill, Style::Mill, Style::Mark, Style::Bars])?;
            let o = w.o.unwrap_or(2.0);
            let helix = style == Style::Bars || u.ratio(1, 2)?;
            let (kind, d) = if helix {
                let f = *u.choose(&[1.5, 2.0, 3.0, 4.0, 1.25, 2.5, 3.5, 4.5])?;
                (Kind::Helix(style), o * f)
            } else {
                (Kind::Drill(style), o)
            };
            let mut params = Vec::new();
            if helix && u.ratio(1, 3)? {
                params.push(format!("I{}", number(u, &[0.5, 1.0, 0.25])?));
            }
            extras(u, &mut w.n, &mut params, AT_HOLE)?;
            w.push(kind, Geometry::Circle { c: at, d }, params);
        }
        // a dead end, numbered so that it comes first, with a turn marker
        7 => {
            let kind = match u.int_in_range(0u8..=3)? {
                0 => Kind::Sweep,
                _ => cutting_kind(u)?,
            };
            let (dx, dy) = delta(u)?;
            let to = pt(at.x + dx, at.y + dy);
            let mut params = vec![w.next_n()];
            extras(u, &mut w.n, &mut params, letters_of(&kind))?;
            w.push(kind, Geometry::Line(at, to), params);
            w.push(Kind::Turn, Geometry::Point(to), Vec::new());
        }
        // a closed chain back to the walk's point: a rectangle or a circle of two arcs
        8 => {
            let kind = cutting_kind(u)?;
            let mut first = vec![w.next_n()];
            extras(u, &mut w.n, &mut first, AT_SEGMENT)?;
            if u.arbitrary()? {
                let (dx, dy) = delta(u)?;
                let (dx, dy) = (
                    if dx == 0.0 { 1.0 } else { dx },
                    if dy == 0.0 { 1.0 } else { dy },
                );
                let corners = [
                    at,
                    pt(at.x + dx, at.y),
                    pt(at.x + dx, at.y + dy),
                    pt(at.x, at.y + dy),
                    at,
                ];
                for (i, pair) in corners.windows(2).enumerate() {
                    let params = if i == 0 { first.clone() } else { Vec::new() };
                    w.push(kind.clone(), Geometry::Line(pair[0], pair[1]), params);
                }
            } else {
                let r = f64::from(u.int_in_range(1u8..=8)?) / 2.0;
                let c = pt(at.x + r, at.y);
                w.push(
                    kind.clone(),
                    Geometry::Arc {
                        c,
                        r,
                        a0: 0.0,
                        a1: 180.0,
                    },
                    Vec::new(),
                );
                w.push(
                    kind,
                    Geometry::Arc {
                        c,
                        r,
                        a0: 180.0,
                        a1: 0.0,
                    },
                    first,
                );
            }
        }
        // a subpath line exactly as long as the part, turned by a multiple of 90°
        9 | 10 if !parts.is_empty() => {
            let part = u.choose(parts)?.clone();
            let (sx, sy) = part.span;
            let (dx, dy) = match u.int_in_range(0u8..=3)? {
                0 => (sx, sy),
                1 => (-sy, sx),
                2 => (-sx, -sy),
                _ => (sy, -sx),
            };
            let to = pt(at.x + dx, at.y + dy);
            let kind = if u.ratio(1, 8)? {
                Kind::Skip
            } else {
                Kind::Sub
            };
            let mut params = vec![format!(">{}", part.name)];
            if let Some(v) = part.var {
                if u.ratio(7, 8)? {
                    params.push(format!(":{v}{}", number(u, &[1.0, 2.0, 0.5, 0.0])?));
                }
            }
            if u.ratio(1, 5)? {
                params.push(format!("H{}", number(u, &[0.5, 1.0, 2.0, -0.5])?));
            }
            extras(u, &mut w.n, &mut params, AT_SUB)?;
            w.push(kind, Geometry::Line(at, to), params);
            w.at = to;
        }
        // a sweep elsewhere
        _ => {
            let (dx, dy) = delta(u)?;
            let to = pt(at.x + dx, at.y + dy);
            let mut params = Vec::new();
            if u.ratio(1, 4)? {
                params.push(format!("S{}", number(u, &[10.0, 8.0, 20.0, 4.0])?));
            }
            w.push(Kind::Sweep, Geometry::Line(at, to), params);
            w.at = to;
        }
    }
    Ok(())
}

/// A whole case: the compiled path `1000.1P` in `1000`, parts `2001.1P`… each in its own file
/// (a part embeds only parts after it: no cycles), settings of one of the three dialects.
pub fn case(u: &mut Unstructured) -> Result<Case> {
    let settings = settings(u)?;
    let cnc = settings.dialect != Dialect::Reference;
    let c = common(u)?;
    let n_parts = u.int_in_range(0..=MAX_PARTS)?;
    let mut parts: Vec<Part> = Vec::new();
    let mut files = Vec::new();
    for i in (0..n_parts).rev() {
        let name = format!("{}.1P", 2001 + i);
        let var = if u.ratio(1, 3)? {
            Some(*u.choose(&['B', 'D', 'I'])?)
        } else {
            None
        };
        let (block, end) = path(u, &name, &c, &parts, LIMIT_STEPS_PART, var, cnc)?;
        files.push((format!("{}", 2001 + i), file_of(block)));
        if end.x != 0.0 || end.y != 0.0 {
            parts.push(Part {
                name,
                span: (end.x, end.y),
                var,
            });
        }
    }
    let (top, _) = path(u, "1000.1P", &c, &parts, LIMIT_STEPS_TOP, None, cnc)?;
    files.insert(0, ("1000".to_string(), file_of(top)));
    Ok(Case { files, settings })
}

fn file_of(block: PathBlock) -> File {
    File {
        items: vec![Item::Path(block)],
    }
}

fn settings(u: &mut Unstructured) -> Result<Settings> {
    let mut s = Settings {
        dialect: *u.choose(&[Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl])?,
        ..Settings::default()
    };
    if u.ratio(1, 4)? {
        s.feed = *u.choose(&[300.0, 1000.0, 1.0])?;
    }
    if u.ratio(1, 4)? {
        let a = *u.choose(&[500.0, 50.0, 3000.0])?;
        s.max_acceleration = Some(Axes {
            x: a,
            y: a,
            z: a / 2.0,
        });
    }
    if s.dialect != Dialect::Reference {
        if u.ratio(1, 3)? {
            s.spindle_rpm = Some(12000.0);
        }
        if u.ratio(1, 3)? {
            s.plunge_feed = Some(*u.choose(&[50.0, 1000.0])?);
        }
        if u.ratio(1, 4)? {
            s.probe_split = Some(*u.choose(&[0.5, 2.0, 7.5])?);
        }
    }
    Ok(s)
}
