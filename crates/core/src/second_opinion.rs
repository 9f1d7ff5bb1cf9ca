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
    verify, Clamp, Dialect, FindingKind, Limits, Options, Rereading, Severity, Verifier,
};

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
    reviewer.finish(model, line_sources, lang, |feed| {
        for line in body.split('\n') {
            if !feed(line) {
                break;
            }
        }
    })
}

/// The checker of one program as it is written: a [`LineSink`] the emitter feeds line by
/// line, so a check never holds the program ([`review`] feeds it a written text). It keeps
/// no moves either: the clamps, depths and stock model run on a second reading
/// ([`Reviewer::reread`]).
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
        let verifier = Verifier::lean(Options {
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

    /// The findings, located at their elements. `replay(feed)`: the program's lines again,
    /// in order, to `feed` until it answers `false`.
    pub fn finish(
        self,
        model: &Model,
        line_sources: &LineSources,
        lang: Lang,
        replay: impl FnOnce(&mut dyn FnMut(&str) -> bool),
    ) -> Review {
        let mut again = self.reread();
        if again.wants_lines() {
            replay(&mut |l| again.rereading.line(l));
        }
        again.finish(model, line_sources, lang)
    }

    /// The end of the first reading; the second is a [`LineSink`] too (a check's second
    /// emission).
    pub fn reread(self) -> Rereview {
        Rereview {
            rereading: self.verifier.reread(),
            strict: self.strict,
            tool: self.tool,
            clamps_only: self.clamps_only,
        }
    }
}

/// The second reading of a program ([`Reviewer::reread`]).
pub struct Rereview {
    rereading: Rereading,
    strict: bool,
    tool: f64,
    clamps_only: bool,
}

impl LineSink for Rereview {
    fn line(&mut self, text: &str, _source: u32) {
        for part in text.split('\n') {
            self.rereading.line(part);
        }
    }
}

impl Rereview {
    /// Are the program's lines wanted again? (`false`: no second emission needed.)
    pub fn wants_lines(&self) -> bool {
        self.rereading.wants_lines()
    }

    /// The findings, located at their elements.
    pub fn finish(self, model: &Model, line_sources: &LineSources, lang: Lang) -> Review {
        let Rereview {
            rereading,
            strict,
            tool,
            clamps_only,
        } = self;
        let report = rereading.finish();
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
