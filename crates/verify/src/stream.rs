//! The checker fed one line at a time: a compiler hands it each line as it writes it, so a
//! program of millions of lines is checked without ever being held as text. Only the moves
//! (for the stock model, which needs the program's extent) are kept; the texts of the lines
//! findings point at are asked for at the end ([`Verifier::finish`]).

use crate::adjusted;
use crate::machine::{Machine, MoveKind, Raw};
use crate::{
    check_clamps, parse, run_stock, stock_view, surface_frame, to_drawing_frame, AdjustedProblem,
    Finding, FindingKind, HeightMap, Limit, Options, Report, Severity, StockParams, StockSkip,
    SurfaceProblem, SyntaxError, Z_TOLERANCE,
};
use std::collections::HashMap;

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
}

impl Verifier {
    /// A checker for a program that carries no adjustment (`(==…)`, `MILLPATH-PROBES`) and
    /// no `(MILLPATH-SURFACE …)` record: what a compiler writes.
    pub fn new(options: Options) -> Verifier {
        Verifier::scanned(options, adjusted::Surface::default(), Vec::new(), Ok(None))
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
            m: Machine::new(options.dialect),
            rise: surface.max_rise(),
            surface,
            map,
            extra,
            line_count: 0,
            last_text: None,
            done: false,
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
            self.done = true;
            return false;
        }
        let l = raw.strip_suffix('\r').unwrap_or(raw);
        self.line_count = no;
        if !l.trim().is_empty() {
            self.last_text = Some(no);
        }
        let parsed = if l.len() > limits.max_line_len {
            Err(FindingKind::Syntax(SyntaxError::LineTooLong(
                limits.max_line_len,
            )))
        } else {
            parse::parse_line(l)
        };
        let m = &mut self.m;
        match parsed {
            Ok(mut b) if self.surface.adjusted => {
                if let Err(kind) = to_drawing_frame(&mut b, &self.surface, self.rise) {
                    self.extra.push(Raw {
                        line: Some(no),
                        kind: FindingKind::Adjusted(kind),
                        severity: Severity::Error,
                    });
                }
                m.exec(no, &b)
            }
            Ok(b) => m.exec(no, &b),
            Err(kind) => {
                if m.ended {
                    // the controller does not read past the end
                    m.after_end(no);
                } else {
                    m.findings.push(Raw {
                        line: Some(no),
                        kind,
                        severity: Severity::Error,
                    });
                }
            }
        }
        if m.findings.len() > limits.max_findings {
            self.done = true;
        }
        !self.done
    }

    /// The report: the end of the program, the clamps, the depths and the stock model.
    /// `texts(lines)` gives the texts of the lines findings point at (sorted, 1-based; a
    /// line it leaves out gets no text).
    pub fn finish(self, texts: impl FnOnce(&[usize]) -> HashMap<usize, String>) -> Report {
        let Verifier {
            options,
            mut m,
            map,
            extra,
            line_count,
            last_text,
            ..
        } = self;
        let limits = options.limits;
        if !m.ended && !m.percent_closed && m.findings.len() <= limits.max_findings {
            m.findings.push(Raw {
                line: last_text,
                kind: FindingKind::MissingProgramEnd,
                severity: Severity::Error,
            });
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
        // on a height map: the moves back to the drawing's frame, within the roundings; cuts
        // also sampled inside (a piece whose straight Z misses the surface between its ends)
        check_clamps(&m.moves, &options, params.tool, &mut findings);
        let mut ztol = Z_TOLERANCE;
        let mut inside: Vec<Option<(f64, f64, f64)>> = Vec::new();
        if let Some(map) = &map {
            let frame = surface_frame::Frame::new(map);
            ztol += surface_frame::ROUNDING;
            if params.bottom.is_some() {
                inside = m.moves.iter().map(|mv| frame.lowest_inside(mv)).collect();
            }
            frame.to_drawing(&mut m.moves);
        }
        if let Some(bottom) = params.bottom {
            let inside_tol = ztol + surface_frame::SPLIT_TOLERANCE;
            for (k, mv) in m.moves.iter().enumerate() {
                if mv.kind != MoveKind::Cut {
                    continue;
                }
                let ends = mv.from[2].min(mv.to[2]);
                let low_inside = inside.get(k).copied().flatten().map(|l| l.0);
                let below_ends = ends < bottom - ztol;
                let below_inside = low_inside.is_some_and(|z| z < bottom - inside_tol);
                if below_ends || below_inside {
                    let z = match low_inside {
                        Some(z) if below_inside => z.min(ends),
                        _ => ends,
                    };
                    findings.push(Raw {
                        line: Some(mv.line),
                        kind: FindingKind::BelowBottom { z, bottom },
                        severity: Severity::Error,
                    });
                }
            }
        }
        let mut report = Report {
            params,
            lines: line_count,
            moves: m.moves.len(),
            surface: map,
            ..Default::default()
        };
        match (params.top, params.tool) {
            _ if options.skip_stock => {}
            (Some(top), Some(tool)) => {
                let stock = (top, tool, ztol);
                run_stock(&m.moves, stock, &limits, &mut findings, &mut report);
            }
            (top, tool) => findings.push(Raw {
                line: None,
                kind: FindingKind::StockSkipped(StockSkip::MissingParams {
                    top: top.is_none(),
                    tool: tool.is_none(),
                }),
                severity: Severity::Note,
            }),
        }
        if let (Some(req), Some(top), Some(tool)) = (&options.view, params.top, params.tool) {
            let cell = report.stock.map(|s| s.cell);
            report.view = stock_view::stock_view(&m.moves, top, tool, cell, req);
        }
        drop(m);
        findings.sort_by_key(|f| f.line.unwrap_or(0));
        if findings.len() > limits.max_findings {
            findings.truncate(limits.max_findings);
            findings.push(Raw {
                line: None,
                kind: FindingKind::Limit(Limit::Findings(limits.max_findings)),
                severity: Severity::Note,
            });
        }
        let mut wanted: Vec<usize> = findings.iter().filter_map(|f| f.line).collect();
        wanted.dedup();
        let texts = if wanted.is_empty() {
            HashMap::new()
        } else {
            texts(&wanted)
        };
        report.findings = findings
            .into_iter()
            .map(|f| Finding {
                text: f
                    .line
                    .and_then(|l| texts.get(&l))
                    .map(|t| t.trim().chars().take(200).collect())
                    .unwrap_or_default(),
                line: f.line,
                kind: f.kind,
                severity: f.severity,
            })
            .collect();
        report
    }
}
