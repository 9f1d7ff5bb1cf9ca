//! A second opinion on every program `compile` writes: the independent G-code checker
//! (`millpath-verify`, which knows nothing of this compiler) simulates the program against a
//! stock model, and each finding comes back located at the element that wrote the line.
//!
//! Every written program is checked by `millpath-verify`, findings located at their element,
//! read as its post's family ([`Reading`]: a custom post's like a built-in's); a family the
//! checker cannot read is an error, never a skipped check.
//! `Reviewer` is the checker as a line sink: `check` feeds it while emitting and keeps no program
//! text and no moves (verify's lean `Verifier`); its second reading (clamps, depths, stock model)
//! comes from the staged file for compile, from a `Spool` for check (the lines lz4-compressed as
//! they pass, whole-comment lines kept empty: a few bytes a move).

use crate::args;
use crate::diag::{Diagnostic, Lang, Msg};
use crate::emit::program::LineSources;
use crate::emit::{LineSink, MAX_ITEMS, MAX_LINES};
use crate::machine::{NotRead, Reading};
use crate::model::Model;
use crate::stock::stock_of;
use lz4_flex::frame::{FrameDecoder, FrameEncoder};
use millpath_verify::{
    feed_lines, only_a_comment, verify, Clamp, Dialect, FindingKind, Limits, Options, Severity,
    Verifier,
};
use std::io::{BufRead, BufReader, Write};

/// Checks one written program, read as `reading` says (its post's family; `Err`: a family
/// the checker cannot read, an error); findings become diagnostics at the element of their
/// line. In the reference dialect they are warnings (its output must stay byte-identical to
/// the reference tool's); for a real controller an error stops the write. A move into a
/// clamp is an error in every dialect (no program may run into a fixture). `clamps_only`:
/// the editor's quick check, without the stock model, reports the clamps alone.
pub fn review(
    program: &str,
    model: &Model,
    line_sources: &LineSources,
    lang: Lang,
    reading: Result<Reading, NotRead>,
    clamps: &[Clamp],
    clamps_only: bool,
) -> Review {
    let mut reviewer = Reviewer::new(model, reading, clamps, clamps_only);
    feed_lines(program, &mut |l| reviewer.verifier.line(l));
    reviewer.finish(model, line_sources, lang, |feed| feed_lines(program, feed))
}

/// The checker of one program as it is written: a [`LineSink`] the emitter feeds line by
/// line, so a check never holds the program ([`review`] feeds it a written text). It keeps
/// no moves either: the clamps, depths and stock model run on a second reading of the lines
/// ([`Reviewer::finish`]), from the written file, or from its own [`Spool`].
pub struct Reviewer {
    verifier: Verifier,
    strict: bool,
    /// The post's family the checker cannot read: the review is this error.
    unreadable: Option<NotRead>,
    tool: f64,
    clamps_only: bool,
    spool: Option<Spool>,
    /// The checker still reads (no limit reached).
    reading: bool,
}

impl LineSink for Reviewer {
    fn line(&mut self, text: &str, _source: u32) {
        // one written line is one program line; split as a text would be, should one hold more
        for part in text.split('\n') {
            if !self.reading {
                return;
            }
            self.reading = self.verifier.line(part);
            if let Some(spool) = &mut self.spool {
                spool.push(part);
            }
        }
    }
}

impl Reviewer {
    pub fn new(
        model: &Model,
        reading: Result<Reading, NotRead>,
        clamps: &[Clamp],
        clamps_only: bool,
    ) -> Reviewer {
        let (checked_as, unreadable) = match reading {
            Ok(r) => (r, None),
            // read as rs274 meanwhile; the review is the error
            Err(not_read) => (
                Reading {
                    dialect: Dialect::LinuxCnc,
                    strict: true,
                    arcs_as_lines: false,
                },
                Some(not_read),
            ),
        };
        let (top, tool, bottom) = stock_of(model);
        let verifier = Verifier::lean(Options {
            dialect: checked_as.dialect,
            arcs_as_lines: checked_as.arcs_as_lines,
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
            strict: checked_as.strict,
            unreadable,
            tool,
            clamps_only,
            spool: None,
            reading: true,
        }
    }

    /// The lines read are kept in a [`Spool`] for the second reading
    /// ([`Reviewer::finish_spooled`]): for a check, which writes no file.
    pub fn spooling(self) -> Reviewer {
        Reviewer {
            spool: Some(Spool::new()),
            ..self
        }
    }

    /// [`Reviewer::finish`] with the lines of the spool.
    pub fn finish_spooled(
        mut self,
        model: &Model,
        line_sources: &LineSources,
        lang: Lang,
    ) -> Review {
        let spool = self.spool.take();
        self.finish(model, line_sources, lang, |feed| {
            if let Some(spool) = spool {
                spool.replay(feed);
            }
        })
    }

    /// The findings, located at their elements. `replay(feed)`: the program's lines again,
    /// in order, to `feed` until it answers `false` (the checker says when a second reading
    /// falls short).
    pub fn finish(
        self,
        model: &Model,
        line_sources: &LineSources,
        lang: Lang,
        replay: impl FnOnce(&mut dyn FnMut(&str) -> bool),
    ) -> Review {
        let Reviewer {
            verifier,
            strict,
            unreadable,
            tool,
            clamps_only,
            ..
        } = self;
        let report = verifier.finish(replay);
        let vlang = match lang {
            Lang::En => millpath_verify::Lang::En,
            Lang::De => millpath_verify::Lang::De,
        };
        let not_read = unreadable.map(|n| {
            Diagnostic::error(
                Msg::PostNotVerifiable,
                model.raw.start_origin(),
                args![n.post, n.family.name()],
            )
        });
        let diagnostics = not_read
            .into_iter()
            .chain(
                report
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
                    }),
            )
            .collect();
        Review {
            diagnostics,
            removed_volume: report.stock.map(|_| report.removed_volume_mm3),
        }
    }
}

/// The lines of a program as the emitter writes them, kept compressed (lz4) for the
/// checker's second reading: a check has no file to read again, and a second emission would
/// take as long as the first. A line that is only a comment is kept empty: it moves nothing,
/// and the checker took the texts of those it names on the first reading. So what is kept is
/// mostly the moves, a few bytes each.
pub struct Spool {
    /// `None` once a write failed (the second reading then falls short, and says so).
    out: Option<FrameEncoder<Vec<u8>>>,
}

impl Spool {
    fn new() -> Spool {
        Spool {
            out: Some(FrameEncoder::new(Vec::new())),
        }
    }

    fn push(&mut self, line: &str) {
        let Some(out) = &mut self.out else { return };
        let kept = if only_a_comment(line) { "" } else { line };
        if out
            .write_all(kept.as_bytes())
            .and_then(|()| out.write_all(b"\n"))
            .is_err()
        {
            self.out = None;
        }
    }

    fn replay(self, feed: &mut dyn FnMut(&str) -> bool) {
        if let Some(Ok(packed)) = self.out.map(FrameEncoder::finish) {
            replay_lines(BufReader::new(FrameDecoder::new(&packed[..])), feed);
        }
    }
}

/// The lines of `reader` (without their `\n`) to `feed` until it answers `false`, through one
/// buffer; a line that is only a comment is given blank (it moves nothing: the checker took
/// the texts it names on the first reading), unchecked; a line that cannot be read ends them.
pub(crate) fn replay_lines(mut reader: impl BufRead, feed: &mut dyn FnMut(&str) -> bool) {
    let mut line = Vec::new();
    loop {
        line.clear();
        if !matches!(reader.read_until(b'\n', &mut line), Ok(n) if n > 0) {
            return;
        }
        let bytes = line.strip_suffix(b"\n").unwrap_or(&line);
        let text = if only_a_comment(bytes) {
            ""
        } else {
            match std::str::from_utf8(bytes) {
                Ok(text) => text,
                Err(_) => return,
            }
        };
        if !feed(text) {
            return;
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
    dialect: crate::machine::Dialect,
    post: &millpath_post::Post,
    clamps: &[Clamp],
) -> Vec<(usize, usize)> {
    if clamps.is_empty() {
        return Vec::new();
    }
    // the post's family, not the dialect's built-in post (a custom post of the grbl family
    // is read as grbl)
    let reading = Reading::of(dialect, post).ok();
    let report = verify(
        program,
        &Options {
            dialect: reading.map_or(Dialect::LinuxCnc, |r| r.dialect),
            arcs_as_lines: reading.is_some_and(|r| r.arcs_as_lines),
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
