//! The checker fed one line at a time: a compiler hands it each line as it writes it, so a
//! program of millions of lines is checked without ever being held as text. What needs the
//! whole program first (the clamps, the depths and the stock model: the tool and bottom a
//! stock comment may give, the grid over the program's extent) runs at the end, over the
//! moves kept ([`Verifier::new`]), or, lean ([`Verifier::lean`]), over a second reading of
//! the program while only its extent and move count are kept from the first (`reread.rs`).
//!
//! `Verifier`: one line at a time (`line`); `new` keeps the moves for the end checks, `lean` (what
//! a compiler writes, no view) keeps only their extent and count and the texts of the lines its
//! findings name; `finish(replay)` gets the program's lines again: for the texts, and for a lean
//! one's end checks.

use crate::adjusted::{self, to_drawing_frame};
use crate::checks::{below_bottom, clamps_of, ClampCheck, Extent, StockRun};
use crate::execute::{execute, missing_params};
use crate::machine::{Machine, Move, Raw};
use crate::reread::{Folded, Rereading};
use crate::{
    stock_view, surface_frame, AdjustedProblem, FindingKind, HeightMap, Limit, Options, Report,
    Severity, StockParams, SurfaceProblem, Z_TOLERANCE,
};

pub struct Verifier {
    options: Options,
    m: Machine,
    /// adjust-z's programs: heights back to the drawing's frame (adjusted.rs)
    surface: adjusted::Surface,
    rise: f64,
    map: Option<HeightMap>,
    /// Findings of the whole-program scans, and of the lines beyond the machine's.
    extra: Vec<Raw>,
    /// Lines read, and the last that is not blank.
    line_count: usize,
    last_text: Option<usize>,
    /// A limit was reached: the lines after it are not read.
    done: bool,
    /// Lean: each line's moves folded into what the second reading needs, then dropped.
    folded: Option<Folded>,
}

impl Verifier {
    /// A checker for a program that carries no adjustment (`(==…)`, `MILLPATH-PROBES`) and
    /// no `(MILLPATH-SURFACE …)` record: what a compiler writes. It keeps every move.
    pub fn new(options: Options) -> Verifier {
        Verifier::scanned(options, adjusted::Surface::default(), Vec::new(), Ok(None))
    }

    /// [`Verifier::new`] that keeps no moves: [`Verifier::finish`] reads the program a
    /// second time for the clamps, the depths and the stock model (the same report). A view
    /// of the stock ([`Options::view`]) needs every move: it keeps them then.
    pub fn lean(options: Options) -> Verifier {
        let lean = options.view.is_none();
        let mut v = Verifier::new(options);
        if lean {
            v.folded = Some(Folded::default());
        }
        v
    }

    /// A checker that knows what the whole-program scans found: the adjustment, its
    /// problems, and the height map (or the line of a broken record).
    pub(crate) fn scanned(
        options: Options,
        surface: adjusted::Surface,
        problems: Vec<(usize, FindingKind)>,
        map: Result<Option<HeightMap>, (usize, SurfaceProblem)>,
    ) -> Verifier {
        let mut extra: Vec<Raw> = problems
            .into_iter()
            .map(|(line, kind)| Raw {
                line: Some(line),
                kind,
                severity: Severity::Error,
            })
            .collect();
        if surface.adjusted && !surface.has_values() {
            extra.push(Raw {
                line: None,
                kind: FindingKind::Adjusted(AdjustedProblem::NoValues),
                severity: Severity::Warning,
            });
        }
        let map = match map {
            Ok(map) => map,
            Err((line, problem)) => {
                extra.push(Raw {
                    line: Some(line),
                    kind: FindingKind::Surface(problem),
                    severity: Severity::Error,
                });
                None
            }
        };
        Verifier {
            m: Machine::new(options.dialect, options.arcs_as_lines),
            rise: surface.max_rise(),
            surface,
            map,
            extra,
            line_count: 0,
            last_text: None,
            done: false,
            folded: None,
            options,
        }
    }

    /// Reads the next line (without its `\n`). `false` once a limit stops the reading: the
    /// lines after it need not be given.
    pub fn line(&mut self, raw: &str) -> bool {
        if self.done {
            return false;
        }
        let limits = self.options.limits;
        let no = self.line_count + 1;
        if self.line_count >= limits.max_lines {
            self.extra.push(Raw {
                line: Some(no),
                kind: FindingKind::Limit(Limit::Lines(limits.max_lines)),
                severity: Severity::Error,
            });
            if let Some(f) = &mut self.folded {
                f.named(no, raw);
            }
            self.done = true;
            return false;
        }
        let l = raw.strip_suffix('\r').unwrap_or(raw);
        self.line_count = no;
        if !l.trim().is_empty() {
            self.last_text = Some(no);
            if let Some(f) = &mut self.folded {
                f.last_text(l);
            }
        }
        let before = (self.m.findings.len(), self.extra.len());
        let (surface, rise, extra) = (&self.surface, self.rise, &mut self.extra);
        execute(&mut self.m, no, l, limits.max_line_len, |b| {
            if surface.adjusted {
                if let Err(kind) = to_drawing_frame(b, surface, rise) {
                    extra.push(Raw {
                        line: Some(no),
                        kind: FindingKind::Adjusted(kind),
                        severity: Severity::Error,
                    });
                }
            }
        });
        if let Some(f) = &mut self.folded {
            f.fold(self.m.moves.drain(..));
            // the texts of the lines found wanting now: the second reading skips comments
            let found = self.m.findings[before.0..].iter();
            if found
                .chain(&self.extra[before.1..])
                .any(|f| f.line == Some(no))
            {
                f.named(no, l);
            }
        }
        if self.m.findings.len() > limits.max_findings {
            self.done = true;
        }
        !self.done
    }

    /// Reads a whole program text and finishes with the same text as its second reading.
    pub fn read_text(mut self, program: &str) -> Report {
        feed_lines(program, &mut |l| self.line(l));
        self.finish(|feed| feed_lines(program, feed))
    }

    /// The report: the end of the program, the clamps, the depths and the stock model.
    /// `replay(feed)` gives the program's lines again, in order, to `feed` until it answers
    /// `false`: for the texts of the lines findings name, and for a lean checker's checks
    /// (it is not called when nothing needs it).
    pub fn finish(self, replay: impl FnOnce(&mut dyn FnMut(&str) -> bool)) -> Report {
        let mut again = self.reread();
        if again.wants_lines() {
            replay(&mut |l| again.line(l));
        }
        again.finish()
    }

    /// The end of the first reading: what the second needs ([`Rereading::line`]).
    fn reread(self) -> Rereading {
        let Verifier {
            options,
            mut m,
            map,
            extra,
            line_count,
            last_text,
            mut folded,
            ..
        } = self;
        let limits = options.limits;
        if !m.ended
            && !m.percent_closed
            && !m.last_code_ends
            && m.findings.len() <= limits.max_findings
        {
            // an xCAM file has no end code: it ends where nothing it started is pending
            let kind = if options.dialect == crate::Dialect::Xcam {
                FindingKind::Ncc(crate::NccProblem::Incomplete)
            } else {
                FindingKind::MissingProgramEnd
            };
            m.findings.push(Raw {
                line: last_text,
                kind,
                severity: Severity::Error,
            });
            if let (Some(f), Some(no)) = (&mut folded, last_text) {
                f.last_text_named(no);
            }
        }
        // the values: options over the comment
        let comment = m.stock.unwrap_or_default();
        let params = StockParams {
            top: options.top.or(comment.top).filter(|v| v.is_finite()),
            tool: options
                .tool
                .or(comment.tool)
                .filter(|v| v.is_finite() && *v > 0.0),
            bottom: options.bottom.or(comment.bottom).filter(|v| v.is_finite()),
        };
        let mut findings = std::mem::take(&mut m.findings);
        findings.extend(extra);
        let mut report = Report {
            params,
            lines: line_count,
            ..Default::default()
        };
        match folded {
            Some(folded) => Rereading::lean(options, findings, report, folded),
            None => {
                let moves = std::mem::take(&mut m.moves);
                drop(m);
                kept_checks(&options, moves, map, &mut findings, &mut report);
                Rereading::kept(options.limits, findings, report)
            }
        }
    }
}

/// The end checks over the moves kept: clamps (machine coordinates), then on a height map
/// the moves back to the drawing's frame, within the roundings (cuts also sampled inside: a
/// piece whose straight Z misses the surface between its ends), the depths, the stock
/// model and its view.
fn kept_checks(
    options: &Options,
    mut moves: Vec<Move>,
    map: Option<HeightMap>,
    findings: &mut Vec<Raw>,
    report: &mut Report,
) {
    let params = report.params;
    if let Some(mut check) = ClampCheck::new(options, params.tool, 0, findings) {
        for mv in &moves {
            check.step(mv, clamps_of(options), findings);
        }
    }
    let mut ztol = Z_TOLERANCE;
    let mut inside: Vec<Option<(f64, f64, f64)>> = Vec::new();
    if let Some(map) = &map {
        let frame = surface_frame::Frame::new(map);
        ztol += surface_frame::ROUNDING;
        if params.bottom.is_some() {
            inside = moves.iter().map(|mv| frame.lowest_inside(mv)).collect();
        }
        frame.to_drawing(&mut moves);
    }
    if let Some(bottom) = params.bottom {
        let tols = (ztol, ztol + surface_frame::SPLIT_TOLERANCE);
        for (k, mv) in moves.iter().enumerate() {
            let low_inside = inside.get(k).copied().flatten().map(|l| l.0);
            findings.extend(below_bottom(mv, bottom, tols, low_inside));
        }
    }
    report.moves = moves.len();
    report.surface = map;
    match (params.top, params.tool) {
        _ if options.skip_stock => {}
        (Some(top), Some(tool)) => {
            let mut extent = Extent::default();
            moves.iter().for_each(|mv| extent.add_move(mv));
            if let Some(mut run) =
                StockRun::new(&extent, (top, tool, ztol), &options.limits, findings)
            {
                for mv in &moves {
                    run.step(mv, findings);
                }
                run.finish(report);
            }
        }
        (top, tool) => findings.push(missing_params(top, tool)),
    }
    if let (Some(req), Some(top), Some(tool)) = (&options.view, params.top, params.tool) {
        let cell = report.stock.map(|s| s.cell);
        report.view = stock_view::stock_view(&moves, top, tool, cell, req);
    }
}

/// The lines of a program text (a final `\n` ends its last line) to `feed` until it answers
/// `false`: how a written program is given to a [`Verifier`], and again to its
/// [`Verifier::finish`].
pub fn feed_lines(program: &str, feed: &mut dyn FnMut(&str) -> bool) {
    let body = program.strip_suffix('\n').unwrap_or(program);
    for line in body.split('\n') {
        if !feed(line) {
            break;
        }
    }
}
