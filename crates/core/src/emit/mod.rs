//! G-code emission (reference-output.md §4–§14): the emitter walks a model's elements in
//! traversal order and records (`record.rs`, with the peephole optimizer) the program's lines
//! and its moves (lengths, feeds, targets and source elements), which the statistics and
//! the file layouts work on. One file per kind of element and per stage.
//!
//! The emitter and `emit` of a model; what it records of each move is in `item.rs` (kind, length,
//! feed, target, source, shape).

use crate::args;
use crate::diag::{Diagnostic, Msg, Origin};
use crate::emit::record::Record;
pub use crate::emit::record::{LineSink, NO_SOURCE};
use crate::front::drawing::Style;
use crate::geom::{Transform, F3, P2, P3};
use crate::machine::Dialect;
use crate::model::*;
use crate::params::MAX_MAGNITUDE;
use crate::probe::tour::{collect_probes, probe_tour, PlacedProbe};
use millpath_post::{Event, Value, Var};

pub mod bars;
pub mod chain;
pub mod chain_order;
pub mod comment;
mod contour;
pub mod dialect;
pub mod elements;
pub mod extent;
pub mod heightmap_program;
pub mod helix;
pub mod item;
pub mod motion;
mod pass;
mod pass_state;
pub mod probe_split;
pub mod program;
pub(crate) mod record;
pub mod stats;
pub mod timing;
pub mod toolpath;

pub use dialect::Controller;
pub use item::{Item, Kind, Shape, Target};
pub use program::{
    check, check_for, check_until, generate, generate_for, generate_into, generate_until,
    quick_check_until, Generated, Output,
};
pub use toolpath::{toolpath, toolpath_until, Move, ProbePoint, Toolpath};

/// Moves one program may hold: far beyond any real part, and a bound on the memory a hostile
/// drawing can make the emitter take (the moves are kept for the statistics and times).
pub const MAX_ITEMS: usize = 2_000_000;
/// Lines one program may have (moves and the comments between them). Elements write a few
/// comments each, so this is only reached by a drawing that is nearly all comments; the
/// lines themselves go to a file or the checker and are not kept.
pub const MAX_LINES: usize = 4 * MAX_ITEMS;
/// Passes of one chain segment or helix.
pub(crate) const MAX_PASSES: f64 = 10_000.0;

/// Checks that going from `first` down to `bottom` in steps of `infeed` takes a bounded
/// number of passes, before anything is allocated for them.
pub(crate) fn bounded_passes(
    first: f64,
    bottom: f64,
    infeed: f64,
    origin: &Origin,
) -> Result<f64, Skip> {
    if !(infeed > 0.0 && infeed.is_finite()) {
        return Err(Diagnostic::error(
            Msg::MustBePositive,
            origin.clone(),
            args!["I", crate::params::fmt_num(infeed)],
        ));
    }
    let n = ((first - bottom) / infeed).max(0.0).floor() + 2.0;
    if n.is_nan() || n > MAX_PASSES {
        return Err(Diagnostic::error(
            Msg::TooManyPasses,
            origin.clone(),
            args![n, F3(first), F3(bottom), F3(infeed), MAX_PASSES],
        ));
    }
    Ok(n)
}

/// Relative epsilon factor of the start height: guarantees that the first Z move is emitted.
pub(crate) const START_OFFSET: f64 = 1.0 + 2.0 * 1e-6;

/// A probe with its name, for Z expressions.
#[derive(Debug, Clone)]
pub struct NamedProbe {
    pub placed: PlacedProbe,
    pub name: String,
}
/// What gets emitted where: transformation into output coordinates and the extra height.
#[derive(Clone, Copy)]
pub(crate) struct Frame<'m> {
    pub(crate) model: &'m Model,
    pub(crate) t: Transform,
    pub(crate) h: f64,
}

pub(crate) struct Emitter<'a> {
    /// The lines and moves emitted so far.
    pub(crate) rec: Record,
    /// The first move whose target leaves the sane range: its value and source.
    pub(crate) out_of_range: Option<(f64, Option<u32>)>,
    pub(crate) pos: P3,
    pub(crate) probes: &'a [NamedProbe],
    pub(crate) errors: Vec<Diagnostic>,
    /// Set after a skipped element: the position is no longer trustworthy.
    pub(crate) lost: bool,
    /// [`MAX_ITEMS`] reached: nothing more is recorded and every loop stops.
    pub(crate) full: bool,
    /// Check only: no texts are made.
    pub(crate) dry: bool,
    /// Comment lines get their text; without it they are empty lines (the moves' texts and
    /// lines stay as written: for the toolpath, which reads the moves only).
    pub(crate) comment_texts: bool,
    /// Origins of the elements emitted so far, and the current one.
    pub(crate) sources: Vec<Origin>,
    pub(crate) source: Option<u32>,
    /// What the moves pushed now make.
    pub(crate) shape: Shape,
    /// The controller the texts are written for (plunge feeds) and its post (the texts).
    pub(crate) ctl: Controller,
    /// The program's values for the post's templates.
    pub(crate) globals: millpath_post::Globals<'a>,
    /// Asked every [`STOP_EVERY`] elements or passes: `true` stops the emitter (the result
    /// is not wanted any more).
    pub(crate) stop: Option<&'a dyn Fn() -> bool>,
    pub(crate) stopped: bool,
    pub(crate) until_stop_check: usize,
    /// `probe_split`: moves split, and the pieces they became.
    pub(crate) split: (usize, usize),
    /// The editor's quick check: fast-milled chains in list order (see [`emit_quick`]), and
    /// the passes so emitted.
    pub(crate) quick_order: bool,
    pub(crate) quick_steps: usize,
    /// Where the moves recorded so far took the tool (the post's pass events need it).
    pub(crate) at: P3,
    /// The post's passes (`pass.rs`).
    pub(crate) passes: pass_state::Passes,
    /// The post's events that write text, one bit each ([`Emitter::writes`]).
    pub(crate) written: u32,
    /// The quick check's transformed geometries of the chain being emitted (`chain.rs`):
    /// one list for every chain, not one each.
    pub(crate) chain_geoms: Vec<crate::geom::Geom>,
}

// one bit per event in [`Emitter::written`]
const _: () = assert!(Event::ALL.len() <= 32);

/// The events `post` writes text for, one bit each: asked at every move, where a lookup in
/// the post's map of templates was a fifth of the editor's quick check.
fn written_events(post: &millpath_post::Post) -> u32 {
    Event::ALL
        .iter()
        .filter(|e| post.has(**e))
        .fold(0, |bits, e| bits | 1 << *e as u32)
}

/// Elements or passes between two questions to [`Emitter::stop`].
const STOP_EVERY: usize = 256;

/// Trace comment text as the reference dialect writes it: trimmed, `)` → `]`, `\` → `/`
/// (and `(` → `[`, see `comment.rs`).
pub fn as_comment(indent: usize, text: &str) -> String {
    comment::comment_line(Dialect::Reference, indent, text)
}

pub(crate) fn bt(b: bool) -> &'static str {
    if b {
        "True"
    } else {
        "False"
    }
}

pub(crate) type Skip = Diagnostic;

impl<'a> Emitter<'a> {
    /// Does the post write text for `event` (a template that is not empty)?
    #[inline]
    pub(crate) fn writes(&self, event: Event) -> bool {
        self.written & 1 << event as u32 != 0
    }
    /// Texts are only made when they are written: a check needs the moves, not the words.
    #[inline]
    pub(crate) fn comment(&mut self, indent: usize, text: impl FnOnce() -> String) {
        if self.at_capacity() {
            return;
        }
        if self.dry {
            // a dry record only counts its comment lines
            self.rec.lines += 1;
            return;
        }
        let text = if self.comment_texts {
            self.ctl.post.comment(indent, &text(), &self.globals)
        } else {
            String::new()
        };
        let source = self.source.unwrap_or(NO_SOURCE);
        self.rec.comment(text, source);
    }
    #[inline]
    pub(crate) fn push(
        &mut self,
        kind: Kind,
        text: impl FnOnce(&Self) -> String,
        len: f64,
        feed: f64,
    ) {
        if self.at_capacity() {
            return;
        }
        self.pass_before(kind, feed);
        if self.rec.counts_only() {
            self.rec.count_move(kind == Kind::HSweep, self.source);
            return;
        }
        let text = if self.dry { String::new() } else { text(self) };
        let item = Item {
            kind,
            len,
            feed,
            target: Target::default(),
            source: self.source,
            shape: self.shape,
        };
        self.rec.moved(item, text, self.source.unwrap_or(NO_SOURCE));
    }
    /// Asks [`Emitter::stop`] now and then; once it says stop, every loop ends (as when
    /// the list is full) and [`emit_until`] returns no result.
    #[inline]
    pub(crate) fn stop_now(&mut self) -> bool {
        if let Some(stop) = self.stop {
            self.until_stop_check = self.until_stop_check.saturating_sub(1);
            if self.until_stop_check == 0 {
                self.until_stop_check = STOP_EVERY;
                if stop() {
                    self.stopped = true;
                    self.full = true;
                }
            }
        }
        self.stopped
    }
    #[inline]
    fn at_capacity(&mut self) -> bool {
        // a dry record writes a line for every move: below MAX_ITEMS lines neither bound is
        // near
        if self.dry && self.rec.lines < MAX_ITEMS {
            return self.full;
        }
        if self.rec.move_count() >= MAX_ITEMS || self.rec.lines >= MAX_LINES {
            self.full = true;
        }
        self.full
    }
    /// A horizontal rapid with its recorded length.
    pub(crate) fn move_xy(&mut self, x: f64, y: f64, len: f64) {
        let vars = [(Var::X, Value::Num(x)), (Var::Y, Value::Num(y))];
        self.push(
            Kind::HSweep,
            |e: &Emitter| e.text(Event::RapidXy, &vars),
            len,
            0.0,
        );
        self.to(Target::xy(x, y));
    }
    /// The post's text of an event.
    pub(crate) fn text(&self, event: Event, vars: &[(Var, Value)]) -> String {
        self.ctl.post.text(event, vars, &self.globals)
    }
    /// A vertical rapid from `from` to `z` (a retract when it goes up), its Z corrected for
    /// the probes at `xy`.
    pub(crate) fn rapid_z(&mut self, from: f64, z: f64, xy: P2) {
        self.rapid_z_len(from, z, xy, (from - z).abs());
    }
    /// [`Emitter::rapid_z`] recorded with the length `len`.
    pub(crate) fn rapid_z_len(&mut self, from: f64, z: f64, xy: P2, len: f64) {
        let event = if z > from {
            Event::Retract
        } else {
            Event::RapidZ
        };
        let t = |e: &Emitter| {
            let expr = e.zexpr(z, xy).probe_text();
            e.text(
                event,
                &[(Var::Z, Value::Num(z)), (Var::ZProbe, Value::Text(&expr))],
            )
        };
        self.push(Kind::VSweep, t, len, 0.0);
        self.to(Target::z(z));
    }
    /// Records an element's origin; its index for [`Item::source`].
    pub(crate) fn add_source(&mut self, o: &Origin) -> u32 {
        self.sources.push(o.clone());
        self.sources.len() as u32 - 1
    }
    /// Sets where the last move goes.
    #[inline]
    pub(crate) fn to(&mut self, t: Target) {
        self.pass_moved(&t);
        let Some(source) = self.rec.last_move(&t) else {
            return;
        };
        // each value was in range, but sums of them (T + O, S·(1 + 2e-6), h + depth,
        // placed subpaths) may not be: no program leaves the sane range (the first such
        // move is reported)
        if self.out_of_range.is_none() {
            if let Some(v) = out_of_range(&t) {
                self.out_of_range = Some((v, source));
            }
        }
    }

    pub(crate) fn emit_model(&mut self, fr: Frame) {
        for e in &fr.model.elements {
            if self.stop_now() {
                return;
            }
            self.source = Some(self.add_source(element_origin(e)));
            self.shape = match e {
                Element::Drill(_) => Shape::Drill,
                Element::Helix(_) => Shape::Helix,
                _ => Shape::Mill,
            };
            self.contour_start(fr, e);
            let r = match e {
                Element::Chain(c) => self.chain(fr, c),
                Element::Drill(d) => self.drill(fr, d),
                Element::Helix(h) => self.helix(fr, h),
                Element::Sweep(s) => self.sweep(fr, s),
                Element::Subpath(s) => {
                    self.subpath(fr, s);
                    Ok(())
                }
            };
            if let Err(d) = r {
                self.errors.push(d);
                self.lost = true;
            }
            self.contour_end(fr, e);
        }
    }
}

/// The first value of a target (X, Y, Z, the arc centre's X and Y) outside the sane range.
fn out_of_range(t: &Target) -> Option<f64> {
    // `abs() <= MAX_MAGNITUDE` is false for NaN and the infinities: one test a value
    let sane = |v: Option<f64>| v.is_none_or(|v| v.abs() <= MAX_MAGNITUDE);
    let centre_sane = t
        .arc
        .is_none_or(|(c, _)| sane(Some(c.x)) && sane(Some(c.y)));
    if sane(t.x) && sane(t.y) && sane(t.z) && centre_sane {
        return None;
    }
    let bad = |v: &f64| !(v.is_finite() && v.abs() <= MAX_MAGNITUDE);
    let centre = t.arc.map(|(c, _)| c);
    t.x.filter(bad)
        .or_else(|| t.y.filter(bad))
        .or_else(|| t.z.filter(bad))
        .or_else(|| centre.map(|c| c.x).filter(bad))
        .or_else(|| centre.map(|c| c.y).filter(bad))
}

pub(crate) fn element_origin(e: &Element) -> &Origin {
    match e {
        Element::Chain(c) => &c.origin,
        Element::Drill(d) => &d.origin,
        Element::Helix(h) => &h.origin,
        Element::Sweep(s) => &s.origin,
        Element::Subpath(s) => &s.origin,
    }
}

pub(crate) fn missing(key: &str, origin: &Origin) -> Diagnostic {
    Diagnostic::error(Msg::ValueMissing, origin.clone(), args![key])
}

/// The "value missing" errors the emitter reports, in its order, without emitting: one per
/// element at most, as the emitter skips an element at its first missing value.
fn missing_values(model: &Model, out: &mut Vec<Diagnostic>, depth: usize) {
    let key_of = |mark: bool| if mark { "D" } else { "B" };
    for e in &model.elements {
        let first_missing = match e {
            Element::Chain(ch) => match ch.i {
                None => Some(("I", &ch.origin)),
                Some(_) => ch.segs.iter().find_map(|s| {
                    let mark = s.style == Style::Mark;
                    let v = if mark { s.d } else { s.b };
                    v.is_none().then(|| (key_of(mark), &s.origin))
                }),
            },
            Element::Drill(d) => {
                let mark = d.style == Style::Mark;
                let v = if mark { d.d } else { d.b };
                v.is_none().then(|| (key_of(mark), &d.origin))
            }
            Element::Helix(hx) => {
                let mill = hx.style == Style::Mill;
                let v = if mill { hx.b } else { hx.d };
                if v.is_none() {
                    Some((if mill { "B" } else { "D" }, &hx.origin))
                } else if hx.i.is_none() {
                    Some(("I", &hx.origin))
                } else if hx.style == Style::Support && hx.bars.is_some() && hx.b.is_none() {
                    Some(("B", &hx.origin))
                } else {
                    None
                }
            }
            Element::Subpath(emb) => {
                if let Some(t) = &emb.target {
                    if depth < 10 {
                        missing_values(t, out, depth + 1);
                    }
                }
                None
            }
            Element::Sweep(_) => None,
        };
        if let Some((key, origin)) = first_missing {
            out.push(missing(key, origin));
        }
    }
}

/// The body moves of a model (dry: without texts; comment lines empty) for a controller, its
/// probes and start height; gives up when `stop()` turns true: `Err` without diagnostics then.
pub(crate) fn emit_until(
    model: &Model,
    dry: bool,
    ctl: &Controller,
    stop: Option<&dyn Fn() -> bool>,
) -> Result<Emitted, Vec<Diagnostic>> {
    // its callers read the moves (and their lines), never a comment's text
    let no_prefix: &[&str] = &[];
    emit_with(
        model,
        dry,
        ctl,
        stop,
        no_prefix,
        false,
        None,
        Moves::Kept,
        false,
    )
}

/// The start height of a model's program (the start height S, a little above).
pub(crate) fn start_height(model: &Model) -> f64 {
    model.params.s * START_OFFSET
}

/// The emission's diagnostics for the editor's quick check, without the order of fast
/// milling (§7.2: a nearest-first walk, half the time of a long chain's check): each chain's
/// passes are emitted level by level in list order. The diagnostics are the same: every
/// pass of every segment is emitted once either way, so the same moves are checked (their
/// ends are the segments' ends, their depths the passes'), and only the sweeps between them
/// differ, at most [`SWEEP_LINES`] lines a pass: where that could reach [`MAX_ITEMS`], the
/// true order is emitted. The moves' order and times are not the program's.
pub(crate) fn emit_quick(
    model: &Model,
    ctl: &Controller,
    stop: Option<&dyn Fn() -> bool>,
) -> Result<Emitted, Vec<Diagnostic>> {
    let no_prefix: &[&str] = &[];
    // nothing reads the moves but a height map's grid: without one they are only counted
    let moves = if ctl.heightmap.is_some() {
        Moves::Kept
    } else {
        Moves::Counted
    };
    match emit_with(model, true, ctl, stop, no_prefix, true, None, moves, true) {
        Ok(e)
            if e.quick_steps.saturating_mul(SWEEP_LINES)
                < MAX_ITEMS - e.rec.move_count().min(MAX_ITEMS) =>
        {
            return Ok(e)
        }
        Ok(_) => {}
        // the quick order's own sweeps may be what reached the bound
        Err(errs) if errs.iter().any(|d| d.msg == Msg::TooManyMoves) => {}
        Err(errs) => return Err(errs),
    }
    emit_with(model, true, ctl, stop, no_prefix, false, None, moves, true)
}

/// Lines one sweep between two passes can take at most (`safe_sweep`: its comment, two
/// drills or pulls of a comment and three moves each, the rapid), with room to spare.
const SWEEP_LINES: usize = 16;

/// A program's emission after the lines `prefix` (its prologue), its lines going to `sink`
/// instead of a text (it comes back in the record). `fold`: the moves are summed for the
/// statistics at this sweep speed instead of kept ([`Record::fold_moves`]).
pub(crate) fn emit_into<S: AsRef<str>>(
    model: &Model,
    ctl: &Controller,
    stop: Option<&dyn Fn() -> bool>,
    prefix: &[S],
    sink: Option<Box<dyn LineSink>>,
    fold: Option<f64>,
) -> Result<Emitted, Vec<Diagnostic>> {
    let moves = fold.map_or(Moves::Kept, Moves::Folded);
    emit_with(model, false, ctl, stop, prefix, false, sink, moves, true)
}

/// What the record keeps of the moves.
#[derive(Clone, Copy)]
enum Moves {
    /// Every move (statistics, times, toolpath, height map).
    Kept,
    /// Summed for the statistics at this sweep speed ([`Record::fold_moves`]).
    Folded(f64),
    /// Counted only ([`Record::count_moves`]): nothing reads them.
    Counted,
}

#[allow(clippy::too_many_arguments)]
fn emit_with<S: AsRef<str>>(
    model: &Model,
    dry: bool,
    ctl: &Controller,
    stop: Option<&dyn Fn() -> bool>,
    prefix: &[S],
    quick_order: bool,
    sink: Option<Box<dyn LineSink>>,
    moves: Moves,
    comments: bool,
) -> Result<Emitted, Vec<Diagnostic>> {
    if model.elements.is_empty() {
        return Err(vec![Diagnostic::error(
            Msg::NoSegments,
            model.raw.start_origin(),
            vec![],
        )]);
    }
    if model.has_errors {
        // its errors are reported already and its values may be absurd: the emitter does not
        // run, but the values it would find missing are reported as it would report them
        let mut missing = Vec::new();
        missing_values(model, &mut missing, 0);
        return Err(missing);
    }
    let top = Transform::top_level(model.start, model.end);
    let mut placed = Vec::new();
    collect_probes(model, &top, 0.0, &mut placed);
    let probes: Vec<NamedProbe> = probe_tour(placed)
        .into_iter()
        .enumerate()
        .map(|(i, p)| NamedProbe {
            placed: p,
            name: format!("#{}", 51 + i),
        })
        .collect();
    let sx = start_height(model);
    // (a folded record's guess also sizes its text)
    let expected = match moves {
        Moves::Kept | Moves::Folded(_) => expected_moves(model),
        Moves::Counted => 2,
    };
    let mut rec = Record::new(dry, prefix, expected, sink, ctl.post.clone());
    match moves {
        Moves::Kept => {}
        Moves::Folded(sweep_speed) => rec.fold_moves(sweep_speed),
        Moves::Counted => rec.count_moves(),
    }
    // a post that numbers its lines numbers the comments too: their lines are written
    let comment_texts = comments || !rec.plain();
    let mut em = Emitter {
        rec,
        comment_texts,
        out_of_range: None,
        pos: P3 {
            x: 0.0,
            y: 0.0,
            z: sx,
        },
        probes: &probes,
        errors: Vec::new(),
        lost: false,
        full: false,
        dry,
        // one per element and one per chain segment: a long chain's list not copied as it grows
        sources: Vec::with_capacity(model.elements.len() + segments(model)),
        source: None,
        shape: Shape::Mill,
        ctl: ctl.clone(),
        globals: Controller::globals(model, &model.raw.file.name),
        stop,
        stopped: false,
        until_stop_check: 1,
        split: (0, 0),
        quick_order,
        quick_steps: 0,
        at: pass_state::start_position(sx),
        passes: pass_state::Passes::default(),
        written: written_events(&ctl.post),
        chain_geoms: Vec::new(),
    };
    em.comment(2, || format!("Model {}", model.label()));
    em.emit_model(Frame {
        model,
        t: top,
        h: 0.0,
    });
    let last_z = em.pos.z;
    let vars = [(Var::Z, Value::Num(sx)), (Var::ZProbe, Value::Text(""))];
    let event = if sx > last_z {
        Event::Retract
    } else {
        Event::RapidZ
    };
    em.push(
        Kind::VSweep,
        |e: &Emitter| e.text(event, &vars),
        (last_z - sx).abs(),
        0.0,
    );
    // where it goes: a planner's estimate times it (GRBL's oracle, 8999.31P: 0.5 s missing)
    em.to(Target::z(sx));
    let out_of_range = em.out_of_range;
    let sx_bad = !(sx.is_finite() && sx.abs() <= MAX_MAGNITUDE);
    if let Some((v, source)) = out_of_range.or(sx_bad.then_some((sx, None))) {
        let origin = source
            .and_then(|i| em.sources.get(i as usize).cloned())
            .unwrap_or_else(|| model.raw.start_origin());
        em.errors.push(Diagnostic::error(
            Msg::MoveOutOfRange,
            origin,
            args![F3(v), MAX_MAGNITUDE],
        ));
    }
    if em.stopped {
        return Err(Vec::new());
    }
    if em.full {
        let (msg, bound) = if em.rec.lines >= MAX_LINES {
            (Msg::TooManyLines, MAX_LINES)
        } else {
            (Msg::TooManyMoves, MAX_ITEMS)
        };
        em.errors.push(Diagnostic::error(
            msg,
            model.raw.start_origin(),
            args![bound],
        ));
    }
    if !em.errors.is_empty() {
        return Err(em.errors);
    }
    em.rec.finish();
    let split = em.split;
    let quick_steps = em.quick_steps;
    Ok(Emitted {
        rec: em.rec,
        sources: em.sources,
        probes,
        sx,
        split,
        quick_steps,
    })
}

/// A first guess of the moves of a model: about twelve per chain segment (three passes of a
/// cut, a drill and sweeps), at most two million. Reserving is free on 64 bits (pages are
/// only taken when written); the browser's memory is what it reserves: four, at most 65,536.
fn expected_moves(model: &Model) -> usize {
    let (per_segment, most) = if cfg!(target_pointer_width = "32") {
        (4, 1 << 16)
    } else {
        (12, 1 << 21)
    };
    segments(model).saturating_mul(per_segment).min(most)
}

/// A model's chain segments and other elements (subpaths' not counted).
fn segments(model: &Model) -> usize {
    model
        .elements
        .iter()
        .map(|e| match e {
            Element::Chain(c) => c.segs.len(),
            _ => 1,
        })
        .sum()
}

pub(crate) struct Emitted {
    /// The moves and the program's lines.
    pub(crate) rec: Record,
    pub(crate) sources: Vec<Origin>,
    pub(crate) probes: Vec<NamedProbe>,
    pub(crate) sx: f64,
    /// `probe_split`: moves split, and the pieces they became.
    pub(crate) split: (usize, usize),
    /// Passes emitted in list order by [`emit_quick`].
    pub(crate) quick_steps: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_are_sanitised() {
        assert_eq!(as_comment(2, " a)b\\c "), "  (a]b/c)");
    }
}
