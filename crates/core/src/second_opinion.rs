//! A second opinion on every program `compile` writes: the independent G-code checker
//! (`millpath-verify`, which knows nothing of this compiler) simulates the program against a
//! stock model, and each finding comes back located at the element that wrote the line.

use crate::args;
use crate::diag::{Diagnostic, Lang, Msg};
use crate::emit::dialect::lowest_depth;
use crate::emit::program::LineSources;
use crate::emit::{LineSink, MAX_ITEMS, MAX_LINES};
use crate::model::{Element, Model};
use millpath_verify::{
    line_texts, verify, Clamp, Dialect, FindingKind, Limits, Options, Severity, Verifier,
};
use std::collections::HashMap;

/// The material top, tool diameter and deepest drawn depth the checker needs. The checker's
/// stock is one block, but a subpath's H moves its material top (T + H): every part of the
/// program comes down to its own top, so the block's top is the lowest of them. A block as
/// high as the highest would put the rest's approaches "into material" and refuse valid
/// programs (found by fuzzing); above a raised part the block is air, as it is above any cut.
pub fn stock_of(model: &Model) -> (f64, f64, Option<f64>) {
    fn lowest_top(m: &Model, h: f64, depth: usize) -> f64 {
        m.elements
            .iter()
            .filter_map(|e| match e {
                Element::Subpath(emb) if depth < 10 => emb
                    .target
                    .as_ref()
                    .map(|t| lowest_top(t, h + emb.h, depth + 1)),
                _ => None,
            })
            .fold(h + m.params.t, f64::min)
    }
    (
        lowest_top(model, 0.0, 0),
        model.params.o,
        lowest_depth(model, 0.0, 0),
    )
}

/// Checks one written program; findings become diagnostics at the element of their line. In
/// the reference dialect they are warnings (its output must stay byte-identical to the
/// reference tool's); for a real controller an error stops the write. A move into a clamp
/// is an error in every dialect (no program may run into a fixture). `clamps_only`: the
/// editor's quick check, without the stock model, reports the clamps alone.
pub fn review(
    program: &str,
    model: &Model,
    line_sources: &LineSources,
    lang: Lang,
    dialect: crate::emit::dialect::Dialect,
    clamps: &[Clamp],
    clamps_only: bool,
) -> Review {
    let mut reviewer = Reviewer::new(model, dialect, clamps, clamps_only);
    let body = program.strip_suffix('\n').unwrap_or(program);
    for line in body.split('\n') {
        if !reviewer.verifier.line(line) {
            break;
        }
    }
    reviewer.finish(model, line_sources, lang, |wanted| {
        line_texts(body.split('\n'), wanted)
    })
}

/// The checker of one program as it is written: a [`LineSink`] the emitter feeds line by
/// line, so a check never holds the program ([`review`] feeds it a written text).
pub struct Reviewer {
    verifier: Verifier,
    strict: bool,
    tool: f64,
    clamps_only: bool,
}

impl LineSink for Reviewer {
    fn line(&mut self, text: &str, _source: u32) {
        // one written line is one program line; split as a text would be, should one hold more
        for part in text.split('\n') {
            self.verifier.line(part);
        }
    }
}

impl Reviewer {
    pub fn new(
        model: &Model,
        dialect: crate::emit::dialect::Dialect,
        clamps: &[Clamp],
        clamps_only: bool,
    ) -> Reviewer {
        use crate::emit::dialect::Dialect as Ours;
        let (checked_as, strict) = match dialect {
            Ours::Reference => (Dialect::Reference, false),
            Ours::LinuxCnc => (Dialect::LinuxCnc, true),
            Ours::Grbl => (Dialect::Grbl, true),
        };
        let (top, tool, bottom) = stock_of(model);
        let verifier = Verifier::new(Options {
            dialect: checked_as,
            top: Some(top),
            tool: Some(tool),
            bottom,
            clamps: clamps.to_vec(),
            skip_stock: clamps_only,
            limits: Limits {
                // every program the emitter may write (it stops at its own bounds)
                max_lines: MAX_LINES + 1_000,
                // the stock model of the longest program: a few hundred cell visits a move
                max_work: 500 * MAX_ITEMS as u64,
                ..Limits::default()
            },
            ..Options::default()
        });
        Reviewer {
            verifier,
            strict,
            tool,
            clamps_only,
        }
    }

    /// The findings, located at their elements. `texts(lines)`: the texts of the program's
    /// lines the findings point at.
    pub fn finish(
        self,
        model: &Model,
        line_sources: &LineSources,
        lang: Lang,
        texts: impl FnOnce(&[usize]) -> HashMap<usize, String>,
    ) -> Review {
        let Reviewer {
            verifier,
            strict,
            tool,
            clamps_only,
        } = self;
        let report = verifier.finish(texts);
        let vlang = match lang {
            Lang::En => millpath_verify::Lang::En,
            Lang::De => millpath_verify::Lang::De,
        };
        let diagnostics = report
            .findings
            .iter()
            .filter(|f| f.severity != Severity::Note)
            .filter(|f| !clamps_only || matches!(f.kind, FindingKind::ClampHit { .. }))
            .map(|f| {
                let origin = f
                    .line
                    .and_then(|l| line_sources.origin(l).cloned())
                    .unwrap_or_else(|| model.raw.start_origin());
                if let FindingKind::ClampHit { name, .. } = &f.kind {
                    let at = args![
                        name,
                        f.line.unwrap_or(0),
                        f.text,
                        crate::params::fmt_num(tool)
                    ];
                    return Diagnostic::error(Msg::ClampHit, origin, at);
                }
                let args = args![f.line.unwrap_or(0), f.text, f.message(vlang)];
                if strict && f.severity == Severity::Error {
                    Diagnostic::error(Msg::SecondOpinion, origin, args)
                } else {
                    Diagnostic::warning(Msg::SecondOpinion, origin, args)
                }
            })
            .collect();
        Review {
            diagnostics,
            removed_volume: report.stock.map(|_| report.removed_volume_mm3),
        }
    }
}

/// The texts of some lines of a program as the emitter writes it again (a check keeps no
/// text: the few lines findings point at are taken from a second emission).
pub struct LineCapture {
    wanted: Vec<usize>,
    next: usize,
    line: usize,
    pub texts: HashMap<usize, String>,
}

impl LineCapture {
    /// `wanted`: 1-based line numbers, sorted.
    pub fn new(wanted: &[usize]) -> LineCapture {
        LineCapture {
            wanted: wanted.to_vec(),
            next: 0,
            line: 0,
            texts: HashMap::new(),
        }
    }
}

impl LineSink for LineCapture {
    fn line(&mut self, text: &str, _source: u32) {
        for part in text.split('\n') {
            self.line += 1;
            while self.wanted.get(self.next).is_some_and(|&w| w < self.line) {
                self.next += 1;
            }
            if self.wanted.get(self.next) == Some(&self.line) {
                let part = part.strip_suffix('\r').unwrap_or(part);
                self.texts.insert(self.line, part.to_string());
                self.next += 1;
            }
        }
    }
}

/// What the second opinion says about one program.
pub struct Review {
    /// Findings located at their elements.
    pub diagnostics: Vec<Diagnostic>,
    /// Material the program removes, mm³, by the checker's stock model.
    pub removed_volume: Option<f64>,
}

/// The moves of a written program that touch a clamp: (G-code line, index of the clamp),
/// by the independent checker (for the toolpath view's red marks).
pub fn clamp_hits(
    program: &str,
    model: &Model,
    dialect: crate::emit::dialect::Dialect,
    clamps: &[Clamp],
) -> Vec<(usize, usize)> {
    use crate::emit::dialect::Dialect as Ours;
    if clamps.is_empty() {
        return Vec::new();
    }
    let report = verify(
        program,
        &Options {
            dialect: match dialect {
                Ours::Reference => Dialect::Reference,
                Ours::LinuxCnc => Dialect::LinuxCnc,
                Ours::Grbl => Dialect::Grbl,
            },
            tool: Some(model.params.o),
            clamps: clamps.to_vec(),
            skip_stock: true,
            ..Options::default()
        },
    );
    report
        .findings
        .iter()
        .filter_map(|f| match &f.kind {
            FindingKind::ClampHit { name, min, max, .. } => {
                let k = clamps
                    .iter()
                    .position(|c| c.name == *name && c.min == *min && c.max == *max)?;
                Some((f.line?, k))
            }
            _ => None,
        })
        .collect()
}
