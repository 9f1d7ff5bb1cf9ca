//! The controller's modal state, line by line: motion mode, plane, units, distance modes,
//! feed rate and feed mode, position. Produces the moves for the stock model and the
//! findings that need no stock (feed, arcs, codes, program end).

use crate::dialect::{DwellUnit, Rules};
use crate::finding::{ArcProblem, FamilyProblem, FindingKind, NoFeedReason, Severity, SyntaxError};
use crate::parse::Block;
use crate::{Dialect, StockParams};
use std::f64::consts::TAU;

/// Allowed difference of an arc's start and end radius, mm.
pub const ARC_RADIUS_TOLERANCE: f64 = 0.002;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MoveKind {
    Rapid,
    Cut,
    Probe,
}

/// An arc in the XY plane: centre, radius, start angle and signed sweep (radians, ccw > 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcGeo {
    pub cx: f64,
    pub cy: f64,
    pub r: f64,
    pub a0: f64,
    pub sweep: f64,
}

impl ArcGeo {
    pub fn point(&self, s: f64) -> (f64, f64) {
        let a = self.a0 + s * self.sweep;
        (self.cx + self.r * a.cos(), self.cy + self.r * a.sin())
    }
    /// Bounding box (x0, y0, x1, y1).
    pub fn bbox(&self) -> (f64, f64, f64, f64) {
        let (sx, sy) = self.point(0.0);
        let (ex, ey) = self.point(1.0);
        let mut b = (sx.min(ex), sy.min(ey), sx.max(ex), sy.max(ey));
        for k in 0..4 {
            let theta = f64::from(k) * TAU / 4.0;
            let rel = if self.sweep >= 0.0 {
                (theta - self.a0).rem_euclid(TAU)
            } else {
                (self.a0 - theta).rem_euclid(TAU)
            };
            if rel <= self.sweep.abs() {
                let (x, y) = (
                    self.cx + self.r * theta.cos(),
                    self.cy + self.r * theta.sin(),
                );
                b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
            }
        }
        b
    }
}

/// One executed move. Unknown coordinates are NaN.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// 1-based line.
    pub line: usize,
    pub kind: MoveKind,
    pub from: [f64; 3],
    pub to: [f64; 3],
    /// Boxed: most moves are lines, and a program can have millions of moves.
    pub arc: Option<Box<ArcGeo>>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Motion {
    Rapid,
    Line,
    Arc {
        cw: bool,
    },
    Probe(u32),
    /// A canned cycle: reported once; its axis words move the tool somewhere.
    Unmodelled,
}

impl Motion {
    fn name(self) -> String {
        match self {
            Motion::Rapid => "G00".into(),
            Motion::Line => "G01".into(),
            Motion::Arc { cw: true } => "G02".into(),
            Motion::Arc { cw: false } => "G03".into(),
            Motion::Probe(c) if c % 10 == 0 => format!("G{}", c / 10),
            Motion::Probe(c) => format!("G{}.{}", c / 10, c % 10),
            Motion::Unmodelled => "a canned cycle".into(),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum FeedMode {
    InverseTime,
    PerMinute,
    PerRev,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Group {
    Motion,
    Plane,
    Distance,
    ArcDistance,
    FeedMode,
    Units,
    CutterComp,
    ToolLength,
    CoordSystem,
    PathControl,
    NonModal,
    Other,
}

/// G codes ×10 Marlin reads (G17–G19, G20, G38, G53–G59 and G80 with their options; G92 set
/// position and, with `CNC_COORDINATE_SYSTEMS`, G92.1: marlinfw.org/docs/gcode/G092.html).
const MARLIN_G: [u32; 25] = [
    0, 10, 20, 30, 40, 170, 180, 190, 200, 210, 280, 382, 383, 530, 540, 550, 560, 570, 580, 590,
    800, 900, 910, 920, 921,
];

/// The M codes a family's checker knows besides the program end; others are not modelled.
fn known_m(dialect: Dialect) -> &'static [u32] {
    match dialect {
        Dialect::Marlin => &[0, 1, 3, 4, 5, 7, 8, 9, 17, 18, 84, 400],
        _ => &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 30, 48, 49, 60],
    }
}

/// A spindle dwell shorter than this (s) in a family whose `G4 P` is milliseconds is
/// probably seconds written as P.
pub const SHORT_SPINDLE_DWELL: f64 = 0.1;

/// G code ×10 (G38.3 → 383) → its modal group; `None`: unknown to any controller. G31 is
/// the probe move of Mach3/4 and UCCNC (rs274 family; GRBL and Marlin refuse it).
fn g_group(code: u32) -> Option<Group> {
    Some(match code {
        0 | 10 | 20 | 30 | 310 | 382..=385 | 800 | 730 | 760 | 810..=890 => Group::Motion,
        170 | 180 | 190 => Group::Plane,
        900 | 910 => Group::Distance,
        901 | 911 => Group::ArcDistance,
        930 | 940 | 950 => Group::FeedMode,
        200 | 210 => Group::Units,
        400 | 410 | 411 | 420 | 421 => Group::CutterComp,
        430 | 431 | 432 | 490 => Group::ToolLength,
        540 | 550 | 560 | 570 | 580 | 590 | 591 | 592 | 593 => Group::CoordSystem,
        610 | 611 | 640 => Group::PathControl,
        40 | 100 | 280 | 281 | 300 | 301 | 530 | 920..=923 => Group::NonModal,
        70 | 80 | 960 | 970 | 980 | 990 => Group::Other,
        _ => return None,
    })
}

fn g_name(code: u32) -> String {
    if code.is_multiple_of(10) {
        format!("G{:02}", code / 10)
    } else {
        format!("G{}.{}", code / 10, code % 10)
    }
}

/// A finding before the line text is attached.
pub struct Raw {
    pub line: Option<usize>,
    pub kind: FindingKind,
    pub severity: Severity,
}

pub struct Machine {
    dialect: Dialect,
    rules: Rules,
    /// The post writes arcs as lines: a G02/G03 is a finding.
    arcs_as_lines: bool,
    /// A spindle start (M3/M4) not yet followed by a dwell or a cut.
    spindle_starting: bool,
    /// The last line with code ends the program by [`Rules::end_codes`] (families without
    /// M2/M30).
    pub last_code_ends: bool,
    pub moves: Vec<Move>,
    pub findings: Vec<Raw>,
    pub stock: Option<StockParams>,
    /// mm per program unit.
    scale: f64,
    plane: u32,
    absolute: bool,
    arc_absolute: bool,
    feed_mode: FeedMode,
    motion: Option<Motion>,
    feed: f64,
    /// A NoFeed or FeedNotPositive was reported for the feed now in effect.
    feed_reported: bool,
    feed_reset: Option<(String, usize)>,
    pos: [f64; 3],
    coord_system: u32,
    pub ended: bool,
    after_end_reported: bool,
    unknown_reported: bool,
    pub percent_open: bool,
    pub percent_closed: bool,
    pub seen_code: bool,
    /// The `xcam` family's reader: its lines become this machine's blocks (`ncc.rs`).
    pub(crate) ncc: crate::ncc::Ncc,
}

impl Machine {
    /// The machine of `dialect`'s family; `arcs_as_lines`: a G02/G03 is a finding.
    pub fn new(dialect: Dialect, arcs_as_lines: bool) -> Machine {
        Machine {
            dialect,
            rules: dialect.rules(),
            arcs_as_lines,
            spindle_starting: false,
            last_code_ends: false,
            moves: Vec::new(),
            findings: Vec::new(),
            stock: None,
            scale: 1.0,
            plane: 170,
            absolute: true,
            arc_absolute: false,
            feed_mode: FeedMode::PerMinute,
            // grbl starts in G00; LinuxCNC's start-up code has G80 (axis words alone are an
            // error), and so does our strict reading of the reference.
            motion: if dialect == Dialect::Grbl {
                Some(Motion::Rapid)
            } else {
                None
            },
            feed: 0.0,
            feed_reported: false,
            feed_reset: None,
            pos: [f64::NAN; 3],
            coord_system: 540,
            ended: false,
            after_end_reported: false,
            unknown_reported: false,
            percent_open: false,
            percent_closed: false,
            seen_code: false,
            ncc: crate::ncc::Ncc::default(),
        }
    }

    pub(crate) fn dialect(&self) -> Dialect {
        self.dialect
    }

    fn report(&mut self, line: usize, kind: FindingKind, severity: Severity) {
        self.findings.push(Raw {
            line: Some(line),
            kind,
            severity,
        });
    }

    fn family(&mut self, line: usize, problem: FamilyProblem, severity: Severity) {
        let dialect = self.dialect;
        self.report(line, FindingKind::Family { problem, dialect }, severity);
    }

    fn unsupported(&mut self, line: usize, what: String) {
        self.report(line, FindingKind::Unsupported { what }, Severity::Warning);
    }

    /// Code after M2/M30 (reported once).
    pub fn after_end(&mut self, line: usize) {
        if !self.after_end_reported {
            self.after_end_reported = true;
            self.report(line, FindingKind::AfterProgramEnd, Severity::Warning);
        }
    }

    /// Executes one parsed line.
    pub fn exec(&mut self, line: usize, b: &Block) {
        if b.nested_comment {
            let severity = if self.dialect == Dialect::LinuxCnc {
                Severity::Error
            } else {
                Severity::Warning
            };
            self.report(
                line,
                FindingKind::Syntax(SyntaxError::NestedComment),
                severity,
            );
        }
        for c in &b.comments {
            self.stock_comment(line, c);
        }
        if let Some(c) = &b.semicolon {
            self.stock_comment(line, c);
        }
        if !self.rules.paren_comments && !b.comments.is_empty() {
            self.family(line, FamilyProblem::ParenComment, Severity::Error);
        }
        if b.percent && !self.rules.percent {
            self.family(line, FamilyProblem::Percent, Severity::Error);
            return;
        }
        if b.percent {
            if self.seen_code || self.percent_open {
                if self.percent_open {
                    self.percent_closed = true;
                }
            } else {
                self.percent_open = true;
            }
            return;
        }
        if b.words.is_empty() {
            return;
        }
        if self.ended {
            self.after_end(line);
            return;
        }
        self.seen_code = true;
        if !self.line_numbers(line, b) {
            return;
        }
        if !self.rules.modal_motion {
            self.motion = None;
        }
        if self.rules.one_command_per_line && !self.one_command(line, b) {
            return;
        }

        // G codes: check and group them
        let mut gs: Vec<(u32, Group)> = Vec::new();
        for w in b.words.iter().filter(|w| w.letter == 'G') {
            let code10 = (w.value * 10.0).round();
            let known = if (w.value * 10.0 - code10).abs() > 1e-6 || code10 < 0.0 {
                None
            } else {
                g_group(code10 as u32).map(|g| (code10 as u32, g))
            };
            let Some((code, group)) = known else {
                self.report(
                    line,
                    FindingKind::Syntax(SyntaxError::UnknownCode(format!("G{}", w.value))),
                    Severity::Error,
                );
                return;
            };
            if group != Group::NonModal && group != Group::Other {
                if let Some((other, _)) = gs.iter().find(|(_, g)| *g == group) {
                    self.report(
                        line,
                        FindingKind::Syntax(SyntaxError::SameModalGroup(
                            g_name(*other),
                            g_name(code),
                        )),
                        Severity::Error,
                    );
                    return;
                }
            }
            if self.dialect == Dialect::Marlin && !MARLIN_G.contains(&code) {
                let code = g_name(code);
                self.family(line, FamilyProblem::NoSuchCode { code }, Severity::Error);
                return;
            }
            gs.push((code, group));
        }
        let mut ms: Vec<u32> = Vec::new();
        for w in b.words.iter().filter(|w| w.letter == 'M') {
            let m = w.value.round();
            if (w.value - m).abs() > 1e-6 || !(0.0..=199.0).contains(&m) {
                self.report(
                    line,
                    FindingKind::Syntax(SyntaxError::UnknownCode(format!("M{}", w.value))),
                    Severity::Error,
                );
                return;
            }
            ms.push(m as u32);
        }
        let has_g = |c: u32| gs.iter().any(|(g, _)| *g == c);
        let g_of = |group: Group| gs.iter().find(|(_, g)| *g == group).map(|(c, _)| *c);
        // GRBL refuses more than the others, and drops a refused line whole
        if self.dialect == Dialect::Grbl {
            let codes: Vec<u32> = gs.iter().map(|(c, _)| *c).collect();
            let arc = matches!(self.motion, Some(Motion::Arc { .. }));
            let plane = g_of(Group::Plane).unwrap_or(self.plane);
            if let Some(why) = crate::grbl::refusal(b, &codes, &ms, arc, plane) {
                self.report(line, FindingKind::Syntax(why), Severity::Error);
                return;
            }
        }

        // other letters
        for w in &b.words {
            match w.letter {
                'G' | 'M' | 'X' | 'Y' | 'Z' | 'I' | 'J' | 'K' | 'R' | 'F' | 'P' | 'S' | 'T'
                | 'N' => {}
                l => self.unsupported(line, format!("the word {l}")),
            }
        }

        // 1. feed mode (before F, as in LinuxCNC's order of execution)
        if let Some(code) = g_of(Group::FeedMode) {
            let mode = match code {
                930 => FeedMode::InverseTime,
                950 => FeedMode::PerRev,
                _ => FeedMode::PerMinute,
            };
            let reset = match self.dialect {
                Dialect::LinuxCnc => true,
                Dialect::Grbl => {
                    self.feed_mode == FeedMode::InverseTime && mode != FeedMode::InverseTime
                }
                Dialect::Reference | Dialect::Marlin | Dialect::Xcam => false,
            };
            if mode == FeedMode::PerRev && self.dialect == Dialect::Grbl {
                self.unsupported(line, "G95 (grbl has no feed per revolution)".into());
            }
            if reset {
                if self.feed > 0.0 {
                    self.feed_reset = Some((g_name(code), line));
                }
                self.feed = 0.0;
                self.feed_reported = false;
            }
            self.feed_mode = mode;
        }
        // 2. F
        if let Some(f) = b.get('F') {
            self.feed = f * if self.feed_mode == FeedMode::PerMinute {
                self.scale
            } else {
                1.0
            };
            self.feed_reset = None;
            self.feed_reported = false;
            if f <= 0.0 {
                self.feed_reported = true;
                self.report(
                    line,
                    FindingKind::FeedNotPositive { value: f },
                    Severity::Error,
                );
            }
        }
        // 3. M codes that need no motion
        for &m in &ms {
            match m {
                30 if self.dialect == Dialect::Marlin => {
                    self.family(line, FamilyProblem::M30DeletesFile, Severity::Error)
                }
                2 if self.dialect == Dialect::Marlin => self.family(
                    line,
                    FamilyProblem::NoSuchCode { code: "M2".into() },
                    Severity::Warning,
                ),
                3 | 4 => self.spindle_starting = true,
                m if known_m(self.dialect).contains(&m) => {}
                other => self.unsupported(line, format!("M{other}")),
            }
        }
        if !self.rules.m2_m30_end {
            let ends = self.rules.end_codes();
            self.last_code_ends = ms.iter().any(|m| ends.contains(m));
        }
        // 4. dwell
        if has_g(40) {
            self.dwell(line, b);
        }
        // 5. plane, units, comp, length, coordinate system, distance modes
        if let Some(p) = g_of(Group::Plane) {
            self.plane = p;
        }
        if let Some(u) = g_of(Group::Units) {
            self.scale = if u == 200 { 25.4 } else { 1.0 };
        }
        if let Some(c) = g_of(Group::CutterComp) {
            if c != 400 {
                self.unsupported(line, format!("cutter radius compensation {}", g_name(c)));
            }
        }
        if let Some(c) = g_of(Group::ToolLength) {
            if c != 490 {
                self.unsupported(line, format!("tool length offset {}", g_name(c)));
            }
        }
        if let Some(c) = g_of(Group::CoordSystem) {
            if c != self.coord_system && self.pos.iter().any(|v| !v.is_nan()) {
                self.unsupported(
                    line,
                    format!("a change of coordinate system to {}", g_name(c)),
                );
                self.pos = [f64::NAN; 3];
            }
            self.coord_system = c;
        }
        if let Some(d) = g_of(Group::Distance) {
            self.absolute = d == 900;
        }
        if let Some(d) = g_of(Group::ArcDistance) {
            self.arc_absolute = d == 901;
        }
        // 6. non-modal codes that take the axis words
        let mut axes_taken = false;
        for &(code, group) in &gs {
            if group == Group::NonModal && code != 40 {
                self.unsupported(line, g_name(code));
                axes_taken = true;
                if code != 100 {
                    // G28/G30 go home, G53 moves in machine coordinates, G92 shifts the
                    // coordinates: the position is unknown afterwards
                    self.pos = [f64::NAN; 3];
                }
            }
        }
        // 7. motion
        if let Some(code) = g_of(Group::Motion).filter(|c| *c == 20 || *c == 30) {
            if self.arcs_as_lines {
                let code = g_name(code);
                self.family(line, FamilyProblem::ArcNotAllowed { code }, Severity::Error);
            }
        }
        if let Some(code) = g_of(Group::Motion) {
            self.motion = match code {
                0 => Some(Motion::Rapid),
                10 => Some(Motion::Line),
                20 => Some(Motion::Arc { cw: true }),
                30 => Some(Motion::Arc { cw: false }),
                310 | 382..=385 => Some(Motion::Probe(code)),
                800 => None,
                other => {
                    self.unsupported(line, format!("the canned cycle {}", g_name(other)));
                    Some(Motion::Unmodelled)
                }
            };
        }
        let has_axes = ['X', 'Y', 'Z'].iter().any(|&l| b.has(l));
        if has_axes && !axes_taken {
            match self.motion {
                Some(m) => self.motion(line, m, b),
                None if !self.rules.modal_motion => {
                    self.family(line, FamilyProblem::NoMotionWord, Severity::Error)
                }
                None => self.report(
                    line,
                    FindingKind::Syntax(SyntaxError::AxesWithoutMotion),
                    Severity::Error,
                ),
            }
        }
        // 8. program end
        if self.rules.m2_m30_end && ms.iter().any(|&m| m == 2 || m == 30) {
            self.ended = true;
        }
    }

    /// The line numbers of a line by the family's rules; `false`: the line is not run.
    fn line_numbers(&mut self, line: usize, b: &Block) -> bool {
        let mut run = true;
        for (k, w) in b.words.iter().enumerate().filter(|(_, w)| w.letter == 'N') {
            let max = self.rules.max_line_number;
            if w.value < 0.0 || w.value.fract() != 0.0 || w.value > f64::from(max) {
                let text = format!("N{}", w.value);
                self.family(
                    line,
                    FamilyProblem::LineNumber { text, max },
                    Severity::Error,
                );
                run = false;
            } else if k > 0 && self.rules.line_number_first {
                self.family(line, FamilyProblem::LineNumberNotFirst, Severity::Error);
                run = false;
            }
        }
        run
    }

    /// One command a line, first after the line number (Marlin); `false`: the line is not
    /// run as written.
    fn one_command(&mut self, line: usize, b: &Block) -> bool {
        let mut words = b.words.iter().filter(|w| w.letter != 'N');
        let Some(first) = words.next() else {
            return true;
        };
        if !matches!(first.letter, 'G' | 'M' | 'T') {
            let word = first.letter.to_string();
            self.family(
                line,
                FamilyProblem::CommandNotFirst { word },
                Severity::Error,
            );
            return false;
        }
        if let Some(second) = words.find(|w| matches!(w.letter, 'G' | 'M' | 'T')) {
            let code = format!("{}{}", second.letter, second.value);
            self.family(line, FamilyProblem::SecondCommand { code }, Severity::Error);
            return false;
        }
        true
    }

    /// `G4`: P (and in Marlin S) not negative, P required where S is not read; a short
    /// dwell after a spindle start where P is milliseconds.
    fn dwell(&mut self, line: usize, b: &Block) {
        let p = b.get('P');
        let s = b.get('S').filter(|_| self.rules.dwell_s);
        let ok = match (p, s) {
            (None, None) => self.rules.dwell_s,
            _ => p.is_none_or(|p| p >= 0.0) && s.is_none_or(|s| s >= 0.0),
        };
        if !ok {
            self.report(
                line,
                FindingKind::Syntax(SyntaxError::BadDwell),
                Severity::Error,
            );
            return;
        }
        let seconds = match (s, p, self.rules.dwell_p) {
            (Some(s), _, _) => s,
            (None, Some(p), DwellUnit::Milliseconds) => p / 1000.0,
            (None, Some(p), DwellUnit::Seconds) => p,
            (None, None, _) => 0.0,
        };
        if std::mem::take(&mut self.spindle_starting)
            && self.rules.dwell_p == DwellUnit::Milliseconds
            && seconds < SHORT_SPINDLE_DWELL
        {
            self.family(
                line,
                FamilyProblem::ShortSpindleDwell { seconds },
                Severity::Warning,
            );
        }
    }

    /// A usable feed for `motion` on this line? Reports at most once per feed setting.
    fn check_feed(&mut self, line: usize, motion: Motion, b: &Block) {
        let inverse = self.feed_mode == FeedMode::InverseTime && self.dialect != Dialect::Reference;
        if inverse {
            if !b.has('F') {
                self.report(
                    line,
                    FindingKind::NoFeed {
                        motion: motion.name(),
                        reason: NoFeedReason::InverseTime,
                    },
                    Severity::Error,
                );
            }
            return;
        }
        if self.feed > 0.0 || self.feed_reported {
            return;
        }
        self.feed_reported = true;
        let reason = match &self.feed_reset {
            Some((code, l)) => NoFeedReason::ResetBy {
                code: code.clone(),
                line: *l,
                dialect: self.dialect,
            },
            None => NoFeedReason::NeverSet,
        };
        self.report(
            line,
            FindingKind::NoFeed {
                motion: motion.name(),
                reason,
            },
            Severity::Error,
        );
    }

    fn motion(&mut self, line: usize, m: Motion, b: &Block) {
        if m == Motion::Unmodelled {
            self.pos = [f64::NAN; 3];
            return;
        }
        let from = self.pos;
        let mut to = from;
        for (k, l) in ['X', 'Y', 'Z'].iter().enumerate() {
            if let Some(v) = b.get(*l) {
                let v = v * self.scale;
                to[k] = if self.absolute { v } else { from[k] + v };
            }
        }
        if m != Motion::Rapid {
            self.check_feed(line, m, b);
            self.spindle_starting = false;
        }
        let known = from.iter().all(|v| !v.is_nan());
        match m {
            Motion::Unmodelled => {}
            Motion::Rapid => self.moves.push(Move {
                line,
                kind: MoveKind::Rapid,
                from,
                to,
                arc: None,
            }),
            Motion::Probe(_) => {
                self.moves.push(Move {
                    line,
                    kind: MoveKind::Probe,
                    from,
                    to,
                    arc: None,
                });
                // the probe stops somewhere on the way
                for (k, l) in ['X', 'Y', 'Z'].iter().enumerate() {
                    if b.has(*l) {
                        to[k] = f64::NAN;
                    }
                }
            }
            Motion::Line => {
                if known {
                    self.moves.push(Move {
                        line,
                        kind: MoveKind::Cut,
                        from,
                        to,
                        arc: None,
                    });
                } else {
                    self.unknown_start(line, m);
                }
            }
            Motion::Arc { cw } => {
                if self.plane != 170 {
                    self.report(
                        line,
                        FindingKind::ArcPlane {
                            plane: g_name(self.plane),
                        },
                        Severity::Warning,
                    );
                } else if from[0].is_nan() || from[1].is_nan() {
                    self.unknown_start(line, m);
                } else if let Some(arc) = self.arc(line, cw, from, to, b) {
                    if known {
                        self.moves.push(Move {
                            line,
                            kind: MoveKind::Cut,
                            from,
                            to,
                            arc: Some(Box::new(arc)),
                        });
                    } else {
                        self.unknown_start(line, m);
                    }
                }
            }
        }
        self.pos = to;
    }

    fn unknown_start(&mut self, line: usize, m: Motion) {
        if !self.unknown_reported {
            self.unknown_reported = true;
            self.report(
                line,
                FindingKind::UnknownPosition { motion: m.name() },
                Severity::Warning,
            );
        }
    }

    /// The arc's geometry, or a finding.
    fn arc(
        &mut self,
        line: usize,
        cw: bool,
        from: [f64; 3],
        to: [f64; 3],
        b: &Block,
    ) -> Option<ArcGeo> {
        let (sx, sy, ex, ey) = (from[0], from[1], to[0], to[1]);
        if ex.is_nan() || ey.is_nan() {
            self.unknown_start(line, Motion::Arc { cw });
            return None;
        }
        if b.has('P') {
            self.unsupported(line, "an arc with P (several turns)".into());
        }
        let (cx, cy) = if let Some(r) = b.get('R').filter(|_| !b.has('I') && !b.has('J')) {
            let r = r * self.scale;
            let (dx, dy) = (ex - sx, ey - sy);
            let d = dx.hypot(dy);
            if d < 1e-9 || r.abs() < 1e-9 {
                self.report(
                    line,
                    FindingKind::ArcInvalid(ArcProblem::ZeroRadius),
                    Severity::Error,
                );
                return None;
            }
            let half = d / 2.0;
            if r.abs() < half - ARC_RADIUS_TOLERANCE {
                self.report(
                    line,
                    FindingKind::ArcInvalid(ArcProblem::RadiusTooSmall),
                    Severity::Error,
                );
                return None;
            }
            let h = (r * r - half * half).max(0.0).sqrt();
            // ccw with r > 0: the centre is to the left of start → end
            let left = cw != (r > 0.0);
            let (nx, ny) = (-dy / d, dx / d);
            let side = if left { h } else { -h };
            (sx + dx / 2.0 + side * nx, sy + dy / 2.0 + side * ny)
        } else if b.has('I') || b.has('J') {
            let i = b.get('I').unwrap_or(0.0) * self.scale;
            let j = b.get('J').unwrap_or(0.0) * self.scale;
            if self.arc_absolute {
                (i, j)
            } else {
                (sx + i, sy + j)
            }
        } else {
            self.report(
                line,
                FindingKind::ArcInvalid(ArcProblem::NoCentre),
                Severity::Error,
            );
            return None;
        };
        let r0 = (sx - cx).hypot(sy - cy);
        let r1 = (ex - cx).hypot(ey - cy);
        if r0 < 1e-9 {
            self.report(
                line,
                FindingKind::ArcInvalid(ArcProblem::ZeroRadius),
                Severity::Error,
            );
            return None;
        }
        if (r0 - r1).abs() > ARC_RADIUS_TOLERANCE {
            self.report(
                line,
                FindingKind::ArcRadiusMismatch { start: r0, end: r1 },
                Severity::Error,
            );
        }
        let a0 = (sy - cy).atan2(sx - cx);
        let a1 = (ey - cy).atan2(ex - cx);
        let full = (ex - sx).hypot(ey - sy) < 1e-9;
        let mut sweep = if cw {
            (a0 - a1).rem_euclid(TAU)
        } else {
            (a1 - a0).rem_euclid(TAU)
        };
        if full {
            sweep = TAU;
        }
        if cw {
            sweep = -sweep;
        }
        Some(ArcGeo {
            cx,
            cy,
            r: r0,
            a0,
            sweep,
        })
    }

    /// `(MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300)`
    fn stock_comment(&mut self, line: usize, text: &str) {
        let parsed = match crate::parse_stock_comment(text) {
            None => return,
            Some(Ok(p)) => p,
            Some(Err(problem)) => {
                self.report(line, FindingKind::StockComment(problem), Severity::Warning);
                return;
            }
        };
        match &self.stock {
            None => self.stock = Some(parsed),
            Some(first) if *first != parsed => self.report(
                line,
                FindingKind::StockComment(crate::finding::StockCommentProblem::Conflicting),
                Severity::Warning,
            ),
            Some(_) => {}
        }
    }
}
