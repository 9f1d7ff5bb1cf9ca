//! The reader of xCAM's exchange format (`.NCC`, the `xcam` family): a line is a command and
//! its `NAME=value` pairs (strings in double quotes, numbers with a decimal point). The file
//! is a part, not a move stream: contours (`G0` start, `G1` lines, `G5` arcs with their
//! centre and `DIR`, each with its Z) are milled by a `GIN` that names them, and `B` drills.
//! The reader rebuilds the moves a machine makes of them and hands them to the machine model
//! as G-code blocks, so every check of the others families runs on them:
//!
//! * a milling: up to the rapid height, across to the contour's start, a feed move down to
//!   its Z (at `GIN_DRIVE_IN_SPEED`, else the drive speed), the contour at each element's
//!   speed (`G1_SPEED`, `G5_SPEED`, else `GIN_DRIVE_SPEED`), and up again;
//! * a drilling: across at the rapid height, a rapid down to its Z, a feed move down by its
//!   depth `TI` (a through hole to the part's bottom and `B_THV` below), and up again.
//!
//! The rapid height is an assumption (xCAM's own post plans the rapids): [`RAPID_CLEARANCE`]
//! above the part's top (`OZ` + `DZ` of the header) or above the highest Z read, whichever
//! is higher. Each move keeps the line that defines it (the plunge its contour's `G0`, an
//! element its own line, the rapids the milling's), so findings point at the line to fix.
//! What the format has and the reader does not model (tool correction, lead-ins, pockets,
//! saw cuts, grooves, macros, other work sides) is a warning; a line that cannot be read is
//! an error, never a panic. A contour is kept until the end of the file (a milling may name
//! any earlier one); the elements the millings replay are bounded by [`MAX_REPLAYED`].

use crate::finding::{FindingKind, NumberProblem, Severity};
use crate::magnitude::MAX_MAGNITUDE;
use crate::ncc_problem::NccProblem;
use crate::parse::{Block, Word};
use std::collections::HashMap;

/// Rapids run this far (mm) above the part's top or the highest Z read.
pub const RAPID_CLEARANCE: f64 = 5.0;
/// Contour elements the millings may replay in all: each element of a file as long as the
/// checker reads ([`crate::Limits::max_lines`]) once (a file that mills one long contour
/// again and again would otherwise make moves without bound).
pub const MAX_REPLAYED: usize = 1_000_000;

/// One finding of a line: where, what and how bad.
pub(crate) type Found = (usize, FindingKind, Severity);

/// A G-code block for the machine model and the line it belongs to.
pub(crate) type Step = (usize, Block);

/// One contour element: its line, its end, its arc (centre, clockwise) and its speed.
#[derive(Debug, Clone)]
struct Element {
    line: usize,
    to: [f64; 3],
    arc: Option<(f64, f64, bool)>,
    feed: Option<f64>,
}

#[derive(Debug, Clone)]
struct Contour {
    /// The `G0`: its line and point.
    start: (usize, [f64; 3]),
    elements: Vec<Element>,
}

/// What the reader knows after the lines read so far.
#[derive(Debug, Default)]
pub(crate) struct Ncc {
    contours: HashMap<String, Contour>,
    /// The contour `G1`/`G5` add to.
    current: Option<String>,
    /// A standard contour not milled yet (a file cut after it is truncated).
    unmilled: Option<String>,
    header: bool,
    /// A line with a command was read.
    started: bool,
    /// The part's top and bottom from the header; the highest Z read.
    top: Option<f64>,
    bottom: Option<f64>,
    highest: Option<f64>,
    /// The machine model's state has been set (units, plane, modes).
    set_up: bool,
    replayed: usize,
    replay_reported: bool,
    /// The last line could be read whole.
    last_ok: bool,
}

/// A line's `NAME=value` pairs.
struct Pairs<'a> {
    command: &'a str,
    values: Vec<(&'a str, Value<'a>)>,
}

#[derive(Debug, Clone, Copy)]
enum Value<'a> {
    Text(&'a str),
    /// A number's text (parsed where it is used).
    Number(&'a str),
}

fn block(words: &[(char, f64)]) -> Block {
    Block {
        words: words
            .iter()
            .map(|&(letter, value)| Word { letter, value })
            .collect(),
        ..Block::default()
    }
}

fn err(line: usize, p: NccProblem) -> Found {
    (line, FindingKind::Ncc(p), Severity::Error)
}

/// Splits a line into its command and pairs.
fn split(line: &str) -> Result<Pairs<'_>, NccProblem> {
    let line = line.trim_matches(|c| c == ' ' || c == '\t');
    let (command, mut rest) = match line.find([' ', '\t']) {
        Some(i) => (&line[..i], &line[i..]),
        None => (line, ""),
    };
    let mut values = Vec::new();
    loop {
        rest = rest.trim_start_matches([' ', '\t']);
        if rest.is_empty() {
            break;
        }
        let token_end = rest.find([' ', '\t']).unwrap_or(rest.len());
        let Some(eq) = rest[..token_end].find('=').or_else(|| {
            // a string value may hold blanks: NAME="a b"
            rest.find("=\"").filter(|&i| i < token_end)
        }) else {
            return Err(NccProblem::NotAPair(shorten(&rest[..token_end])));
        };
        let name = &rest[..eq];
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return Err(NccProblem::NotAPair(shorten(&rest[..token_end])));
        }
        let after = &rest[eq + 1..];
        if let Some(text) = after.strip_prefix('"') {
            let Some(close) = text.find('"') else {
                return Err(NccProblem::UnclosedString(name.to_string()));
            };
            let next = &text[close + 1..];
            if !(next.is_empty() || next.starts_with([' ', '\t'])) {
                return Err(NccProblem::NotAPair(shorten(&rest[..token_end])));
            }
            values.push((name, Value::Text(&text[..close])));
            rest = next;
        } else {
            let end = after.find([' ', '\t']).unwrap_or(after.len());
            values.push((name, Value::Number(&after[..end])));
            rest = &after[end..];
        }
    }
    Ok(Pairs { command, values })
}

/// At most 40 characters of a text shown in a finding.
fn shorten(t: &str) -> String {
    if t.chars().count() > 40 {
        t.chars().take(37).collect::<String>() + "..."
    } else {
        t.to_string()
    }
}

/// A number of the format: an optional sign, digits, an optional decimal point and digits.
fn number(name: &str, text: &str) -> Result<f64, NccProblem> {
    let digits = text.strip_prefix(['-', '+']).unwrap_or(text);
    let plain = !digits.is_empty()
        && digits.chars().any(|c| c.is_ascii_digit())
        && digits.chars().all(|c| c.is_ascii_digit() || c == '.')
        && digits.matches('.').count() <= 1;
    let problem = |problem| NccProblem::Number {
        name: name.to_string(),
        text: shorten(text),
        problem,
    };
    if !plain {
        return Err(match text.parse::<f64>() {
            Ok(v) if !v.is_finite() => problem(NumberProblem::NonFinite),
            Ok(_) if text.contains(['e', 'E']) => problem(NumberProblem::Exponent),
            _ => NccProblem::NotANumber {
                name: name.to_string(),
                text: shorten(text),
            },
        });
    }
    match text.parse::<f64>() {
        Ok(v) if v.abs() > MAX_MAGNITUDE => Err(problem(NumberProblem::Absurd)),
        Ok(v) => Ok(v),
        Err(_) => Err(NccProblem::NotANumber {
            name: name.to_string(),
            text: shorten(text),
        }),
    }
}

impl Pairs<'_> {
    fn get(&self, name: &str) -> Option<Value<'_>> {
        self.values
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
            .map(|(_, v)| *v)
    }

    /// A number, if given.
    fn num(&self, name: &str) -> Result<Option<f64>, NccProblem> {
        match self.get(name) {
            None => Ok(None),
            Some(Value::Number(t)) => number(name, t).map(Some),
            Some(Value::Text(t)) => Err(NccProblem::NotANumber {
                name: name.to_string(),
                text: format!("\"{}\"", shorten(t)),
            }),
        }
    }

    /// A number the command needs.
    fn need(&self, name: &str) -> Result<f64, NccProblem> {
        self.num(name)?.ok_or_else(|| NccProblem::Missing {
            command: self.command.to_string(),
            name: name.to_string(),
        })
    }

    /// A text (or a number's text: names are often written without quotes).
    fn text(&self, name: &str) -> Option<&str> {
        match self.get(name)? {
            Value::Text(t) | Value::Number(t) => Some(t),
        }
    }

    fn duplicate(&self) -> Option<&str> {
        let v = &self.values;
        (1..v.len())
            .find(|&i| v[..i].iter().any(|(n, _)| n.eq_ignore_ascii_case(v[i].0)))
            .map(|i| v[i].0)
    }
}

impl Ncc {
    /// Did the file end where a file may end: a header read, every standard contour milled,
    /// the last line whole? (Else the file is probably truncated.)
    pub(crate) fn complete(&self) -> bool {
        self.header && self.unmilled.is_none() && self.last_ok
    }

    /// Reads line `no` (without its line end): the machine's blocks and the findings.
    pub(crate) fn line(&mut self, no: usize, text: &str) -> (Vec<Step>, Vec<Found>) {
        let mut steps = Vec::new();
        let mut found = Vec::new();
        if text.trim().is_empty() {
            return (steps, found);
        }
        if !self.set_up {
            self.set_up = true;
            // millimetres, XY plane, absolute, feed per minute
            let setup = [('G', 17.0), ('G', 21.0), ('G', 90.0), ('G', 94.0)];
            steps.push((no, block(&setup)));
        }
        self.last_ok = false;
        match split(text) {
            Err(p) => found.push(err(no, p)),
            Ok(pairs) => match pairs.duplicate() {
                Some(d) => found.push(err(no, NccProblem::Duplicate(d.to_string()))),
                None => match self.command(no, &pairs, &mut steps, &mut found) {
                    Ok(()) => self.last_ok = true,
                    Err(p) => found.push(err(no, p)),
                },
            },
        }
        (steps, found)
    }

    fn command(
        &mut self,
        no: usize,
        p: &Pairs,
        steps: &mut Vec<Step>,
        found: &mut Vec<Found>,
    ) -> Result<(), NccProblem> {
        let command = p.command.to_ascii_uppercase();
        let first = !self.started;
        self.started = true;
        if command == "H" {
            if self.header {
                return Err(NccProblem::SecondHeader);
            }
            if !first {
                found.push(err(no, NccProblem::HeaderNotFirst));
            }
            self.header = true;
            let (dz, oz) = (p.need("DZ")?, p.num("OZ")?.unwrap_or(0.0));
            p.need("DX")?;
            p.need("DY")?;
            self.top = Some(oz + dz);
            self.bottom = Some(oz);
            return Ok(());
        }
        if first {
            found.push(err(no, NccProblem::HeaderNotFirst));
        }
        let unmodelled = |what: String| (no, FindingKind::Unsupported { what }, Severity::Warning);
        match command.as_str() {
            "COM" => {
                // the text is a comment for the machine model: it may be our stock comment
                let text = p.text("TEXT").unwrap_or("");
                let comment = Block {
                    comments: vec![text.replace("_C_N_L_", " ")],
                    ..Block::default()
                };
                steps.push((no, comment));
            }
            "F" => {
                let side = p.need("F")?;
                if side != 1.0 {
                    found.push(unmodelled(format!("the work side F={side}")));
                }
            }
            "G0" => {
                let to = self.point(p)?;
                let name = p.text("N").ok_or_else(|| NccProblem::Missing {
                    command: command.clone(),
                    name: "N".into(),
                })?;
                if self.contours.contains_key(name) {
                    return Err(NccProblem::DuplicateContour(shorten(name)));
                }
                let ctype = p.num("CTYPE")?.unwrap_or(0.0);
                self.contours.insert(
                    name.to_string(),
                    Contour {
                        start: (no, to),
                        elements: Vec::new(),
                    },
                );
                self.current = Some(name.to_string());
                if ctype == 0.0 {
                    self.unmilled = Some(name.to_string());
                }
            }
            "G1" | "G5" => {
                let to = self.point(p)?;
                let arc = if command == "G5" {
                    let (cx, cy) = (p.need("I")?, p.need("J")?);
                    let dir = p.need("DIR")?;
                    if dir != 1.0 && dir != -1.0 {
                        let t = p.text("DIR").unwrap_or("");
                        return Err(NccProblem::BadDirection(shorten(t)));
                    }
                    let cw = dir == 1.0;
                    Some((cx, cy, cw))
                } else {
                    None
                };
                let speed = if command == "G5" {
                    "G5_SPEED"
                } else {
                    "G1_SPEED"
                };
                let feed = p.num(speed)?;
                let contour = self
                    .current
                    .as_ref()
                    .and_then(|n| self.contours.get_mut(n))
                    .ok_or_else(|| NccProblem::NoContour(command.clone()))?;
                contour.elements.push(Element {
                    line: no,
                    to,
                    arc,
                    feed,
                });
            }
            "GIN" => self.milling(no, p, steps, found)?,
            "B" => self.drilling(no, p, steps, found)?,
            "PO" | "CUT" | "GROOVE" | "RABBET" | "UNIMACRO" | "POCKET_CLEANTOOL_GIN" => {
                found.push(unmodelled(format!("the NCC command {command}")));
            }
            _ => return Err(NccProblem::UnknownCommand(shorten(p.command))),
        }
        Ok(())
    }

    /// X, Y and Z of a contour line (the highest Z read is kept for the rapids).
    fn point(&mut self, p: &Pairs) -> Result<[f64; 3], NccProblem> {
        let to = [p.need("X")?, p.need("Y")?, p.need("Z")?];
        self.highest = Some(self.highest.map_or(to[2], |h| h.max(to[2])));
        Ok(to)
    }

    fn rapid_height(&self) -> f64 {
        let base = match (self.top, self.highest) {
            (Some(t), Some(h)) => t.max(h),
            (t, h) => t.or(h).unwrap_or(0.0),
        };
        base + RAPID_CLEARANCE
    }

    /// Up to the rapid height and across to `xy`, on line `no`.
    fn rapid_to(&self, no: usize, xy: [f64; 3], steps: &mut Vec<Step>) {
        let z = self.rapid_height();
        steps.push((no, block(&[('G', 0.0), ('Z', z)])));
        steps.push((no, block(&[('G', 0.0), ('X', xy[0]), ('Y', xy[1])])));
    }

    fn milling(
        &mut self,
        no: usize,
        p: &Pairs,
        steps: &mut Vec<Step>,
        found: &mut Vec<Found>,
    ) -> Result<(), NccProblem> {
        let name = p.text("N").ok_or_else(|| NccProblem::Missing {
            command: "GIN".into(),
            name: "N".into(),
        })?;
        if p.get("T").is_none() {
            return Err(NccProblem::Missing {
                command: "GIN".into(),
                name: "T".into(),
            });
        }
        let Some(contour) = self.contours.get(name) else {
            return Err(NccProblem::UnknownContour(shorten(name)));
        };
        for (key, what) in [
            ("C", "tool correction"),
            ("IN", "lead-in"),
            ("OUT", "lead-out"),
        ] {
            if let Some(v) = p.num(key)?.filter(|v| *v != 0.0) {
                found.push((
                    no,
                    FindingKind::Unsupported {
                        what: format!("the {what} {key}={v}"),
                    },
                    Severity::Warning,
                ));
            }
        }
        if p.num("DFC")? == Some(0.0) {
            found.push((
                no,
                FindingKind::Unsupported {
                    what: "a milling depth TI apart from its contour (DFC=0)".into(),
                },
                Severity::Warning,
            ));
        }
        let drive = p.num("GIN_DRIVE_SPEED")?;
        let plunge = p.num("GIN_DRIVE_IN_SPEED")?.or(drive);
        let contour = contour.clone();
        if self.replayed.saturating_add(contour.elements.len()) > MAX_REPLAYED {
            if !self.replay_reported {
                self.replay_reported = true;
                found.push(err(no, NccProblem::ReplayLimit(MAX_REPLAYED)));
            }
            return Ok(());
        }
        self.replayed += contour.elements.len();
        if self.unmilled.as_deref() == Some(name) {
            self.unmilled = None;
        }
        let (start_line, start) = contour.start;
        self.rapid_to(no, start, steps);
        let mut down = vec![('G', 1.0), ('Z', start[2])];
        down.extend(plunge.map(|f| ('F', f)));
        steps.push((start_line, block(&down)));
        let mut at = start;
        for e in &contour.elements {
            let mut words = match e.arc {
                None => vec![('G', 1.0)],
                Some((_, _, cw)) => vec![('G', if cw { 2.0 } else { 3.0 })],
            };
            words.extend([('X', e.to[0]), ('Y', e.to[1]), ('Z', e.to[2])]);
            if let Some((cx, cy, _)) = e.arc {
                words.extend([('I', cx - at[0]), ('J', cy - at[1])]);
            }
            words.extend(e.feed.or(drive).map(|f| ('F', f)));
            steps.push((e.line, block(&words)));
            at = e.to;
        }
        steps.push((no, block(&[('G', 0.0), ('Z', self.rapid_height())])));
        Ok(())
    }

    fn drilling(
        &mut self,
        no: usize,
        p: &Pairs,
        steps: &mut Vec<Step>,
        found: &mut Vec<Found>,
    ) -> Result<(), NccProblem> {
        let at = self.point(p)?;
        p.need("DU")?;
        let through = p.num("B_IS_TH")?.is_some_and(|v| v != 0.0);
        let bottom = if through {
            let part_bottom = self.bottom.unwrap_or(at[2]);
            part_bottom.min(at[2]) - p.num("B_THV")?.unwrap_or(0.0)
        } else {
            at[2] - p.need("TI")?
        };
        for key in ["B_RASTER_X", "B_RASTER_Y"] {
            if p.num(key)?.is_some_and(|v| v != 0.0) {
                found.push((
                    no,
                    FindingKind::Unsupported {
                        what: format!("a row of drillings ({key})"),
                    },
                    Severity::Warning,
                ));
            }
        }
        if p.num("B_MODE")? == Some(3.0) {
            found.push((
                no,
                FindingKind::Unsupported {
                    what: "a drilling milled as a spiral (B_MODE=3)".into(),
                },
                Severity::Warning,
            ));
        }
        let feed = p.num("B_WORKSPEED")?;
        self.rapid_to(no, at, steps);
        steps.push((no, block(&[('G', 0.0), ('Z', at[2])])));
        let mut down = vec![('G', 1.0), ('Z', bottom)];
        down.extend(feed.map(|f| ('F', f)));
        steps.push((no, block(&down)));
        steps.push((no, block(&[('G', 0.0), ('Z', self.rapid_height())])));
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> (Ncc, Vec<Step>, Vec<Found>) {
        let mut n = Ncc::default();
        let (mut steps, mut found) = (Vec::new(), Vec::new());
        for (i, l) in text.lines().enumerate() {
            let (s, f) = n.line(i + 1, l);
            steps.extend(s);
            found.extend(f);
        }
        (n, steps, found)
    }

    #[test]
    fn a_contour_milled_becomes_rapids_a_plunge_and_its_elements() {
        let (n, steps, found) = read(
            "H DX=10.000 DY=10.000 DZ=2.000 OZ=-2.000 T=3.000 FIELD=\"\"\n\
             G0 X=0.000 Y=0.000 Z=-1.000 N=\"P1\" CTYPE=0\n\
             G1 X=10.000 Y=0.000 Z=-1.000 G1_SPEED=300.000\n\
             G5 X=10.000 Y=10.000 Z=-1.000 I=10.000 J=5.000 DIR=-1 G5_SPEED=300.000\n\
             GIN T=\"3.000\" N=\"P1\" CS=\"0\" CE=\"0\" C=0 IN=0 OUT=0 DFC=1 TI=1.000 GIN_DRIVE_SPEED=300.000",
        );
        assert!(found.is_empty(), "{found:?}");
        assert!(n.complete());
        let lines: Vec<(usize, String)> = steps
            .iter()
            .map(|(l, b)| {
                let w: Vec<String> = b
                    .words
                    .iter()
                    .map(|w| format!("{}{}", w.letter, w.value))
                    .collect();
                (*l, w.join(" "))
            })
            .collect();
        assert_eq!(
            lines,
            [
                (1, "G17 G21 G90 G94".to_string()),
                (5, "G0 Z5".into()),
                (5, "G0 X0 Y0".into()),
                (2, "G1 Z-1 F300".into()),
                (3, "G1 X10 Y0 Z-1 F300".into()),
                (4, "G3 X10 Y10 Z-1 I0 J5 F300".into()),
                (5, "G0 Z5".into()),
            ]
        );
    }

    #[test]
    fn broken_lines_are_located_findings() {
        let cases = [
            ("G1 X=1.000 Y=2.000 Z=0.000", NccProblem::HeaderNotFirst),
            (
                "H DX=1.0 DY=1.0",
                NccProblem::Missing {
                    command: "H".into(),
                    name: "DZ".into(),
                },
            ),
            (
                "H DX=1.0 DY=1.0 DZ=nan",
                NccProblem::Number {
                    name: "DZ".into(),
                    text: "nan".into(),
                    problem: NumberProblem::NonFinite,
                },
            ),
            (
                "H DX=1.0 DY=1.0 DZ=1e3",
                NccProblem::Number {
                    name: "DZ".into(),
                    text: "1e3".into(),
                    problem: NumberProblem::Exponent,
                },
            ),
            (
                "H DX=1.0 DY=1.0 DZ=1e300",
                NccProblem::Number {
                    name: "DZ".into(),
                    text: "1e300".into(),
                    problem: NumberProblem::Exponent,
                },
            ),
            (
                "H DX=1.0 DY=1.0 DZ=9999999.0",
                NccProblem::Number {
                    name: "DZ".into(),
                    text: "9999999.0".into(),
                    problem: NumberProblem::Absurd,
                },
            ),
            (
                "H DX=1.0 DY=1.0 DZ=1.0 TEXT=\"open",
                NccProblem::UnclosedString("TEXT".into()),
            ),
            (
                "H DX=1.0 DX=1.0 DY=1.0 DZ=1.0",
                NccProblem::Duplicate("DX".into()),
            ),
            ("H DX DY=1.0", NccProblem::NotAPair("DX".into())),
            (
                "H DX=1.0 DY=1.0 DZ=--1",
                NccProblem::NotANumber {
                    name: "DZ".into(),
                    text: "--1".into(),
                },
            ),
        ];
        for (line, want) in cases {
            let (_, _, found) = read(line);
            assert!(
                found
                    .iter()
                    .any(|f| f.0 == 1 && f.1 == FindingKind::Ncc(want.clone())),
                "{line}: {found:?}"
            );
        }
        let header = "H DX=1.0 DY=1.0 DZ=1.0\n";
        for (rest, want) in [
            ("G1 X=1.0 Y=1.0 Z=0.0", NccProblem::NoContour("G1".into())),
            (
                "GIN T=\"1\" N=\"Q\"",
                NccProblem::UnknownContour("Q".into()),
            ),
            (
                "G0 X=1.0 Y=1.0 Z=0.0 N=\"A\"\nG0 X=1.0 Y=1.0 Z=0.0 N=\"A\"",
                NccProblem::DuplicateContour("A".into()),
            ),
            (
                "G0 X=1.0 Y=1.0 Z=0.0 N=\"A\"\nG5 X=1.0 Y=1.0 Z=0.0 I=0.0 J=0.0 DIR=2",
                NccProblem::BadDirection("2".into()),
            ),
            ("XYZ A=1", NccProblem::UnknownCommand("XYZ".into())),
            ("H DX=1.0 DY=1.0 DZ=1.0", NccProblem::SecondHeader),
        ] {
            let text = format!("{header}{rest}");
            let (_, _, found) = read(&text);
            let last = text.lines().count();
            assert!(
                found
                    .iter()
                    .any(|f| f.0 == last && f.1 == FindingKind::Ncc(want.clone())),
                "{rest}: {found:?}"
            );
        }
    }

    #[test]
    fn a_file_cut_after_a_contour_is_not_complete() {
        let (n, _, _) = read("H DX=1.0 DY=1.0 DZ=1.0\nG0 X=0.0 Y=0.0 Z=0.0 N=\"A\" CTYPE=0");
        assert!(!n.complete());
        let (n, _, _) = read("H DX=1.0 DY=1.0 DZ=1.0\nG0 X=0.0 Y=0.0 Z=0.0 N=\"A\" CTYPE=1");
        assert!(n.complete(), "a help contour need not be milled");
        let (n, _, _) = read("H DX=1.0 DY=1.0 DZ=1.0\nB X=0.0 Y=0.0 Z=0.0 DU=3.0 TI=");
        assert!(!n.complete(), "the last line is cut");
        let (n, _, _) = read("");
        assert!(!n.complete());
    }
}
