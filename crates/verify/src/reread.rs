//! The second reading of a program, after the first has ended ([`Verifier::finish`]): the
//! texts of the lines findings name and, for a lean checker, the checks that need the whole
//! program first (clamps, depths, stock model), run move by move as a fresh machine reads
//! the lines again, on the grid of the first reading's extent.
//!
//! [`Verifier::finish`]: crate::Verifier::finish
//!
//! `Rereading`: the second reading; a lean checker's clamps, depths and stock model run move by
//! move as a fresh machine reads the lines again (whole-comment lines skipped), on the grid of the
//! first reading's extent; the findings joined in the order the keeping checker makes them, the
//! limits alike; a second reading that differs from the first is an error.

use crate::checks::{below_bottom, clamps_of, ClampCheck, Extent, StockRun};
use crate::execute::{execute, missing_params};
use crate::machine::{Machine, Move, Raw};
use crate::only_a_comment;
use crate::{
    Finding, FindingKind, Limit, Limits, Options, Report, Severity, SPLIT_TOLERANCE, Z_TOLERANCE,
};
use std::collections::HashMap;

/// What a lean checker keeps of its first reading: its moves' extent and count, and the
/// texts of the lines its findings name (the second reading skips comments).
#[derive(Debug, Default)]
pub(crate) struct Folded {
    extent: Extent,
    moves: usize,
    texts: HashMap<usize, String>,
    /// The last line that is not blank (a missing program end is found there).
    last: String,
}

impl Folded {
    pub(crate) fn fold(&mut self, moves: impl Iterator<Item = Move>) {
        for mv in moves {
            self.extent.add_move(&mv);
            self.moves += 1;
        }
    }

    /// Line `no` has a finding.
    pub(crate) fn named(&mut self, no: usize, raw: &str) {
        self.texts.entry(no).or_insert_with(|| clean(raw));
    }

    /// Every line that is not blank: a copy of its text's first bytes (the characters a
    /// finding shows), not a walk over them.
    pub(crate) fn last_text(&mut self, l: &str) {
        self.last.clear();
        self.last.push_str(shown(l));
    }

    /// The last line that is not blank, `no`, has a finding.
    pub(crate) fn last_text_named(&mut self, no: usize) {
        let last = std::mem::take(&mut self.last);
        self.texts.entry(no).or_insert(last);
    }
}

/// A finding's text: its line trimmed, at most this many characters.
const TEXT_CHARS: usize = 200;

fn clean(raw: &str) -> String {
    shown(raw.strip_suffix('\r').unwrap_or(raw)).to_string()
}

/// The part of a line a finding shows: trimmed, at most [`TEXT_CHARS`] characters.
fn shown(l: &str) -> &str {
    let t = l.trim();
    if t.len() <= TEXT_CHARS {
        return t;
    }
    t.char_indices()
        .nth(TEXT_CHARS)
        .map_or(t, |(end, _)| &t[..end])
}

/// A program's second reading: give it the lines again ([`Rereading::line`]) while it
/// [wants them](Rereading::wants_lines), then take the report ([`Rereading::finish`]).
pub(crate) struct Rereading {
    limits: Limits,
    report: Report,
    /// All findings (a checker that kept its moves), or those of the first reading.
    findings: Vec<Raw>,
    texts: Texts,
    /// Lines given again.
    read: usize,
    /// A lean checker's checks.
    pass: Option<Box<Pass>>,
}

/// The checks of a lean checker's second reading, each with its own findings (joined in the
/// order the checker that keeps its moves makes them).
struct Pass {
    options: Options,
    m: Machine,
    /// Lines and moves of the first reading.
    lines: usize,
    moves: usize,
    /// Moves of the second.
    seen: usize,
    clamps: Option<ClampCheck>,
    clamp_found: Vec<Raw>,
    bottom: Option<f64>,
    below: Vec<Raw>,
    stock: Option<StockRun>,
    stock_found: Vec<Raw>,
    /// The stock model could not run for want of top or tool.
    missing: Option<Raw>,
}

impl Rereading {
    /// A checker that kept its moves: every check has run; only texts are wanted.
    pub(crate) fn kept(limits: Limits, mut findings: Vec<Raw>, report: Report) -> Rereading {
        cap(&mut findings, limits.max_findings);
        let known: Vec<usize> = findings.iter().filter_map(|f| f.line).collect();
        Rereading {
            limits,
            report,
            findings,
            texts: Texts::new(known, 0),
            read: 0,
            pass: None,
        }
    }

    /// A lean checker: `findings` of the first reading, its moves `folded`.
    pub(crate) fn lean(
        options: Options,
        findings: Vec<Raw>,
        mut report: Report,
        folded: Folded,
    ) -> Rereading {
        let params = report.params;
        report.moves = folded.moves;
        let mut clamp_found = Vec::new();
        let clamps = ClampCheck::new(&options, params.tool, findings.len(), &mut clamp_found);
        let mut stock_found = Vec::new();
        let (stock, missing) = match (params.top, params.tool) {
            _ if options.skip_stock => (None, None),
            (Some(top), Some(tool)) => {
                let stock = (top, tool, Z_TOLERANCE);
                let run = StockRun::new(&folded.extent, stock, &options.limits, &mut stock_found);
                (run, None)
            }
            (top, tool) => (None, Some(missing_params(top, tool))),
        };
        let pass = Pass {
            m: Machine::new(options.dialect, options.arcs_as_lines),
            lines: report.lines,
            moves: folded.moves,
            seen: 0,
            clamps,
            clamp_found,
            bottom: params.bottom,
            below: Vec::new(),
            stock,
            stock_found,
            missing,
            options,
        };
        Rereading {
            limits: pass.options.limits,
            report,
            findings,
            // the lines of the first findings the checks make in line order: those a report
            // can list
            texts: Texts {
                map: folded.texts,
                ..Texts::new(Vec::new(), pass.options.limits.max_findings)
            },
            read: 0,
            pass: Some(Box::new(pass)),
        }
    }

    /// Are more lines wanted? `false`: the rest need not be given.
    pub(crate) fn wants_lines(&self) -> bool {
        let checks = self
            .pass
            .as_ref()
            .is_some_and(|p| p.runs() && self.read < p.lines);
        checks || self.texts.wants_after(self.read)
    }

    /// The next line of the program again (without its `\n`); `false` once no more are
    /// wanted.
    pub(crate) fn line(&mut self, raw: &str) -> bool {
        if !self.wants_lines() {
            return false;
        }
        self.read += 1;
        let no = self.read;
        let named = match &mut self.pass {
            Some(p) if p.runs() && no <= p.lines => p.line(no, raw),
            _ => false,
        };
        self.texts.offer(no, raw, named);
        self.wants_lines()
    }

    /// The report: the findings in line order (at most the limit), with their lines' texts.
    pub(crate) fn finish(self) -> Report {
        let Rereading {
            limits,
            mut report,
            mut findings,
            texts,
            read,
            pass,
        } = self;
        if let Some(p) = pass {
            let runs = p.runs();
            let Pass {
                lines,
                moves,
                seen,
                clamp_found,
                below,
                stock,
                stock_found,
                missing,
                ..
            } = *p;
            findings.extend(clamp_found);
            findings.extend(below);
            findings.extend(stock_found);
            if let Some(run) = stock {
                run.finish(&mut report);
            }
            findings.extend(missing);
            let read = read.min(lines);
            if runs && (read != lines || seen != moves) {
                findings.push(Raw {
                    line: None,
                    kind: FindingKind::RereadDiffers {
                        lines: (read, lines),
                        moves: (seen, moves),
                    },
                    severity: Severity::Error,
                });
            }
            cap(&mut findings, limits.max_findings);
        }
        report.findings = findings
            .into_iter()
            .map(|f| Finding {
                text: f
                    .line
                    .and_then(|l| texts.map.get(&l).cloned())
                    .unwrap_or_default(),
                line: f.line,
                kind: f.kind,
                severity: f.severity,
            })
            .collect();
        report
    }
}

impl Pass {
    /// Does a check need the moves?
    fn runs(&self) -> bool {
        self.clamps.is_some() || self.bottom.is_some() || self.stock.is_some()
    }

    /// Line `no` read again: its moves through the checks. `true` when a check found
    /// something on it.
    fn line(&mut self, no: usize, raw: &str) -> bool {
        let l = raw.strip_suffix('\r').unwrap_or(raw);
        // blank lines and comments move nothing (a spool keeps comments blank)
        if l.is_empty() || only_a_comment(l) {
            return false;
        }
        execute(&mut self.m, no, l, self.options.limits.max_line_len, |_| {});
        // the first reading reported these
        self.m.findings.clear();
        let from = (
            self.clamp_found.len(),
            self.below.len(),
            self.stock_found.len(),
        );
        let clamps = clamps_of(&self.options);
        for mv in self.m.moves.drain(..) {
            self.seen += 1;
            if let Some(check) = &mut self.clamps {
                check.step(&mv, clamps, &mut self.clamp_found);
            }
            if let Some(bottom) = self.bottom {
                let tols = (Z_TOLERANCE, Z_TOLERANCE + SPLIT_TOLERANCE);
                self.below.extend(below_bottom(&mv, bottom, tols, None));
            }
            if let Some(run) = &mut self.stock {
                run.step(&mv, &mut self.stock_found);
            }
        }
        let at = |found: &[Raw], from: usize| found[from..].iter().any(|f| f.line == Some(no));
        at(&self.clamp_found, from.0) || at(&self.below, from.1) || at(&self.stock_found, from.2)
    }
}

/// Sorted by line (the program's whole first), at most `max` and a note saying so.
fn cap(findings: &mut Vec<Raw>, max: usize) {
    findings.sort_by_key(|f| f.line.unwrap_or(0));
    if findings.len() > max {
        findings.truncate(max);
        findings.push(Raw {
            line: None,
            kind: FindingKind::Limit(Limit::Findings(max)),
            severity: Severity::Note,
        });
    }
}

/// The texts of the lines findings name, taken as the lines pass: those `known` beforehand,
/// and the first `cap` lines a check names as it reads them. Findings are listed in line
/// order up to a limit, so those lines hold every line of theirs a report of at most `cap`
/// findings names.
struct Texts {
    known: Vec<usize>,
    next: usize,
    cap: usize,
    /// Lines taken as named by a check.
    named: usize,
    map: HashMap<usize, String>,
}

impl Texts {
    fn new(mut known: Vec<usize>, cap: usize) -> Texts {
        known.dedup();
        Texts {
            known,
            next: 0,
            cap,
            named: 0,
            map: HashMap::new(),
        }
    }

    /// A known line after line `read`?
    fn wants_after(&self, read: usize) -> bool {
        self.known.last().is_some_and(|&k| k > read)
    }

    fn offer(&mut self, no: usize, raw: &str, named: bool) {
        while self.known.get(self.next).is_some_and(|&k| k < no) {
            self.next += 1;
        }
        if self.known.get(self.next) == Some(&no) {
            self.map.insert(no, clean(raw));
        } else if named && self.named < self.cap && !self.map.contains_key(&no) {
            self.named += 1;
            self.map.insert(no, clean(raw));
        }
    }
}
