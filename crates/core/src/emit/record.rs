//! What the emitter records as it goes: the program's lines written straight into one text
//! (no string per line: a program can be many times the size of its drawing), the element
//! that wrote each line, and the moves (for the statistics, the times and the toolpath view;
//! comments are lines only).
//!
//! The peephole optimizer (reference-output.md §13: a horizontal sweep followed, past
//! comments, by another one is commented out) works as the lines come: a horizontal sweep is
//! held back with the comments after it until the next move says whether it stays.
//!
//! What the emitter records as it goes: the program's lines written straight into one text (no
//! string a line) or handed to a `LineSink` (check's checker: no text kept), the element of each
//! line (an index, 4 bytes), the moves without comments (statistics, times, toolpath, with their
//! lines) — or, where only the statistics read them (no planner, no height map: `fold_moves`),
//! their sums as each becomes final, bit for bit those of the list (`count_moves`: only counted,
//! for the editor's quick check, which reads none); the peephole optimizer
//! (reference-output.md §13) as the lines come: a horizontal sweep held back with the comments
//! after it until the next move decides.

use crate::emit::stats::Stats;
use crate::emit::{Item, Kind};
use millpath_post::{Event, Globals, LineWriter, Post, Value, Var};
use std::any::Any;
use std::sync::Arc;

/// Where a program's lines go instead of a text: a consumer that reads each line as it is
/// written (the checker), so a long program is never held whole.
pub trait LineSink: Any {
    /// One line (no `\n`) and the element that wrote it ([`NO_SOURCE`]: none).
    fn line(&mut self, text: &str, source: u32);
}

/// A line no element wrote (prologue, statistics, epilogue).
pub const NO_SOURCE: u32 = u32::MAX;

#[derive(Default)]
pub(crate) struct Record {
    /// The moves, in program order (no comments).
    pub(crate) items: Vec<Item>,
    /// The line of each move, counted from the first line after the prefix (0-based).
    pub(crate) item_lines: Vec<u32>,
    /// The lines written so far, each ending in `\n` (none in a dry run or with a sink).
    pub(crate) text: String,
    /// Where the lines go instead of `text`.
    pub(crate) sink: Option<Box<dyn LineSink>>,
    /// The element of every line of `text` (a dry run keeps none).
    pub(crate) line_sources: Vec<u32>,
    /// Lines recorded, held ones included, after the prefix.
    pub(crate) lines: usize,
    dry: bool,
    /// A horizontal sweep not written yet (its text and source; the last of `items`) and the
    /// comment lines after it.
    held: Option<Held>,
    /// Moves not kept but summed for the statistics as they become final (all but the last,
    /// which a following sweep may still comment out): a long program's statistics without
    /// its moves. Set by [`Record::fold_moves`], or by [`Record::count_moves`] (counted only).
    fold: Option<Fold>,
    /// The post: its `disabled` template, and its line writer (numbers, modal words, line
    /// ends) where it changes lines.
    post: Option<Arc<Post>>,
    writer: Option<LineWriter<Arc<Post>>>,
    /// A dry record's moves only counted ([`Record::count_moves`]): no move is kept at all.
    counted: Option<Counted>,
}

/// What a record whose moves are only counted knows of them: as many as a list would hold
/// (a sweep that the next sweep takes out is not one), and the last move's source, which
/// [`Record::last_move`] gives for its target. No `Item` is made: the editor's quick check
/// records a few hundred thousand moves an edit.
#[derive(Default)]
struct Counted {
    /// Final moves (all but the last).
    moves: usize,
    /// The last move's source, once there is one.
    last: Option<Option<u32>>,
    /// The last move is a horizontal sweep the next one would take out.
    held_sweep: bool,
}

struct Fold {
    sweep_speed: f64,
    /// `None`: the moves are only counted (nothing reads their statistics).
    sums: Option<Stats>,
    moves: usize,
}

impl Fold {
    /// A move that is final now.
    fn add(&mut self, it: &Item) {
        if let Some(sums) = &mut self.sums {
            sums.add(it, self.sweep_speed);
        }
        self.moves += 1;
    }
}

struct Held {
    sweep: (String, u32),
    comments: Vec<(String, u32)>,
}

impl Record {
    /// A record whose text starts with `prefix` (lines no element wrote).
    /// `moves`: a first guess of their number (the list grows beyond it; a guess too large
    /// only reserves address space, while growing a long list copies it each time).
    pub(crate) fn new<S: AsRef<str>>(
        dry: bool,
        prefix: &[S],
        moves: usize,
        sink: Option<Box<dyn LineSink>>,
        post: Arc<Post>,
    ) -> Record {
        let writer = Some(LineWriter::new(post.clone())).filter(|w| !w.is_plain());
        let text_too = !dry && sink.is_none();
        let mut r = Record {
            items: Vec::with_capacity(moves),
            item_lines: Vec::with_capacity(moves),
            // the lines, a comment and a move of about 40 bytes each a move: reserved, not
            // touched, so that a long text is not copied each time it grows (on 64 bits,
            // where reserving is free; the browser's memory is what it reserves)
            text: String::with_capacity(if text_too && cfg!(target_pointer_width = "64") {
                moves.saturating_mul(48)
            } else {
                0
            }),
            sink,
            dry,
            post: Some(post),
            writer,
            ..Record::default()
        };
        for l in prefix {
            r.write(l.as_ref(), NO_SOURCE);
        }
        r
    }

    /// The post writes the lines as they are (no numbers, modal words or other line ends).
    pub(crate) fn plain(&self) -> bool {
        self.writer.is_none()
    }

    /// From now on the moves are summed for the statistics (at `sweep_speed`) instead of
    /// kept; only the last stays in `items`. For a program whose statistics are all that is
    /// asked of its moves (no planner, no height map, no toolpath).
    pub(crate) fn fold_moves(&mut self, sweep_speed: f64) {
        self.fold_into(Some(Stats::default()), sweep_speed);
    }

    /// From now on the moves are only counted, not kept (only the last stays in `items`, for
    /// its target): for a dry run whose moves nothing reads (the editor's quick check without
    /// a height map), the list of a long program is neither written nor its pages touched.
    /// [`Record::stats`] is not asked of such a record.
    pub(crate) fn count_moves(&mut self) {
        if !self.dry {
            // lines are written: the held sweep and its comments need the list
            self.fold_into(None, 0.0);
            return;
        }
        let mut counted = Counted {
            moves: self.items.len(),
            ..Counted::default()
        };
        if let Some(last) = self.items.pop() {
            counted.moves -= 1;
            counted.last = Some(last.source);
            counted.held_sweep = self.held.is_some();
        }
        self.held = None;
        self.items = Vec::new();
        self.item_lines = Vec::new();
        self.counted = Some(counted);
    }

    /// Whether moves are only counted ([`Record::count_move`] instead of [`Record::moved`]).
    #[inline]
    pub(crate) fn counts_only(&self) -> bool {
        self.counted.is_some()
    }

    /// A move of a record that only counts them ([`Record::count_moves`]): what
    /// [`Record::moved`] does to the count and the lines of a dry record, without the move.
    #[inline]
    pub(crate) fn count_move(&mut self, sweep: bool, source: Option<u32>) {
        let Some(c) = &mut self.counted else {
            return;
        };
        // a sweep after a held sweep takes it out (§13); else the last is final now
        if c.last.is_some() && !(c.held_sweep && sweep) {
            c.moves += 1;
        }
        c.last = Some(source);
        c.held_sweep = sweep;
        // dry: every move is a line (none is silent)
        self.lines += 1;
    }

    /// The last move's source, and its target set to `target` where it is kept; `None`
    /// before the first move.
    #[inline]
    pub(crate) fn last_move(&mut self, target: &crate::emit::Target) -> Option<Option<u32>> {
        if let Some(c) = &self.counted {
            return c.last;
        }
        self.items.last_mut().map(|it| {
            it.target = *target;
            it.source
        })
    }

    fn fold_into(&mut self, sums: Option<Stats>, sweep_speed: f64) {
        let mut fold = Fold {
            sweep_speed,
            sums,
            moves: 0,
        };
        // the room reserved for a list is given back, not kept
        for it in std::mem::replace(&mut self.items, Vec::with_capacity(2)) {
            fold.add(&it);
        }
        self.item_lines = Vec::with_capacity(2);
        self.fold = Some(fold);
    }

    /// Moves recorded so far (folded ones included).
    #[inline]
    pub(crate) fn move_count(&self) -> usize {
        if let Some(c) = &self.counted {
            return c.moves + usize::from(c.last.is_some());
        }
        self.items.len() + self.fold.as_ref().map_or(0, |f| f.moves)
    }

    /// The statistics of the moves (reference model): the folded sums and the moves kept.
    pub(crate) fn stats(&self, sweep_speed: f64) -> Stats {
        match &self.fold {
            Some(Fold {
                sums: Some(sums),
                sweep_speed: folded_at,
                ..
            }) => {
                let mut s = sums.clone();
                for it in &self.items {
                    s.add(it, *folded_at);
                }
                s.scaled()
            }
            // counted moves have no statistics: only the kept ones count
            Some(Fold { sums: None, .. }) | None => Stats::of(&self.items, sweep_speed),
        }
    }

    /// Records a comment line.
    pub(crate) fn comment(&mut self, text: String, source: u32) {
        self.lines += 1;
        // a dry run writes no line: nothing to hold behind a sweep either
        if self.dry {
            return;
        }
        match &mut self.held {
            Some(h) => h.comments.push((text, source)),
            None => self.write(&text, source),
        }
    }

    /// Records a move and its line (none for an empty text outside a dry run: the post
    /// writes nothing for this move).
    pub(crate) fn moved(&mut self, item: Item, text: String, source: u32) {
        let sweep = item.kind == Kind::HSweep;
        if self.counted.is_some() {
            self.count_move(sweep, item.source);
            return;
        }
        // a post that writes nothing for this move (xcam's rapids): no line
        let silent = !self.dry && text.is_empty();
        // the held sweep stays unless this one follows it (past comments)
        if let Some(h) = self.held.take() {
            let written = !h.sweep.0.is_empty();
            if sweep {
                // no move was recorded after it
                self.items.pop();
                self.item_lines.pop();
                if written {
                    self.write_commented(&h.sweep.0, h.sweep.1);
                }
            } else if written {
                self.write(&h.sweep.0, h.sweep.1);
            }
            for (c, s) in &h.comments {
                self.write(c, *s);
            }
        }
        if let Some(f) = &mut self.fold {
            // the last move is final now: a sweep that could comment it out was handled above
            if let Some(done) = self.items.pop() {
                f.add(&done);
                self.item_lines.pop();
            }
        }
        self.item_lines.push(self.lines as u32);
        self.items.push(item);
        if !silent {
            self.lines += 1;
        }
        if sweep {
            self.held = Some(Held {
                sweep: (text, source),
                comments: Vec::new(),
            });
        } else if !silent {
            self.write(&text, source);
        }
    }

    /// Writes what is held: the end of the body.
    pub(crate) fn finish(&mut self) {
        if let Some(h) = self.held.take() {
            if !h.sweep.0.is_empty() {
                self.write(&h.sweep.0, h.sweep.1);
            }
            for (c, s) in &h.comments {
                self.write(c, *s);
            }
        }
    }

    /// Lines after the body that no element wrote (the statistics, the epilogue).
    pub(crate) fn write_tail<S: AsRef<str>>(&mut self, lines: &[S]) {
        for l in lines {
            self.write(l.as_ref(), NO_SOURCE);
        }
    }

    fn write(&mut self, line: &str, source: u32) {
        if self.dry {
            return;
        }
        // a template of several lines: each its own, from the same element
        if line.contains('\n') {
            for l in line.split('\n') {
                self.write(l, source);
            }
            return;
        }
        let written;
        let (line, end) = match &mut self.writer {
            Some(w) => {
                written = w.line(line);
                (written.as_str(), w.end())
            }
            None => (line, "\n"),
        };
        match &mut self.sink {
            Some(sink) => sink.line(line, source),
            None => {
                self.text.push_str(line);
                self.text.push_str(end);
            }
        }
        self.line_sources.push(source);
    }

    /// A sweep the optimizer took out, as the post's `disabled` template writes it.
    fn write_commented(&mut self, line: &str, source: u32) {
        if self.dry {
            return;
        }
        let disabled = match &self.post {
            Some(post) => post.text(
                Event::Disabled,
                &[(Var::Line, Value::Text(line))],
                &Globals::default(),
            ),
            None => format!("; {line}"),
        };
        self.write(&disabled, source)
    }
}

#[cfg(test)]
fn post() -> Arc<Post> {
    crate::emit::Dialect::LinuxCnc.shared_post()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::Target;

    fn item(kind: Kind) -> Item {
        Item {
            kind,
            len: 1.0,
            feed: 1.0,
            target: Target::default(),
            source: None,
            shape: Default::default(),
        }
    }

    #[test]
    fn only_the_last_sweep_of_a_run_stays() {
        let mut r = Record::new(false, &["%"], 4, None, post());
        r.moved(item(Kind::HSweep), "G00 X1 Y1".into(), 0);
        r.comment("(c)".into(), 1);
        r.moved(item(Kind::HSweep), "G00 X2 Y2".into(), 2);
        r.moved(item(Kind::VSweep), "G00 Z1".into(), 3);
        r.moved(item(Kind::HSweep), "G00 X3 Y3".into(), 4);
        r.comment("(d)".into(), 5);
        r.finish();
        assert_eq!(
            r.text,
            "%\n; G00 X1 Y1\n(c)\nG00 X2 Y2\nG00 Z1\nG00 X3 Y3\n(d)\n"
        );
        assert_eq!(r.line_sources, [NO_SOURCE, 0, 1, 2, 3, 4, 5]);
        // the commented sweep is no move any more; each move knows its line
        assert_eq!(r.items.len(), 3);
        assert_eq!(r.item_lines, [2, 3, 4]);
        assert_eq!(r.lines, 6);
    }

    /// Collects what a sink is given.
    #[derive(Default)]
    struct Lines(Vec<(String, u32)>);
    impl LineSink for Lines {
        fn line(&mut self, text: &str, source: u32) {
            self.0.push((text.to_string(), source));
        }
    }

    #[test]
    fn a_sink_gets_the_lines_the_text_would_hold() {
        let run = |r: &mut Record| {
            r.moved(item(Kind::HSweep), "G00 X1 Y1".into(), 0);
            r.comment("(c)".into(), 1);
            r.moved(item(Kind::HSweep), "G00 X2 Y2".into(), 2);
            r.moved(item(Kind::Mill), "G01 X3".into(), 3);
            r.finish();
            r.write_tail(&["M30"]);
        };
        let mut text = Record::new(false, &["%"], 4, None, post());
        run(&mut text);
        let mut sunk = Record::new(false, &["%"], 4, Some(Box::new(Lines::default())), post());
        run(&mut sunk);
        assert!(sunk.text.is_empty(), "no text is kept beside a sink");
        let any: Box<dyn Any> = sunk.sink.take().unwrap();
        let lines = any.downcast::<Lines>().unwrap().0;
        let joined: String = lines.iter().map(|(l, _)| format!("{l}\n")).collect();
        assert_eq!(joined, text.text);
        let sources: Vec<u32> = lines.iter().map(|(_, s)| *s).collect();
        assert_eq!(sources, text.line_sources);
        assert_eq!(sunk.line_sources, text.line_sources);
        assert_eq!(sunk.item_lines, text.item_lines);
    }

    #[test]
    fn a_dry_record_counts_lines_and_keeps_moves_only() {
        let mut r = Record::new(true, &["%"], 4, None, post());
        r.moved(item(Kind::HSweep), "G00 X1 Y1".into(), 0);
        r.moved(item(Kind::HSweep), "G00 X2 Y2".into(), 0);
        r.comment("(c)".into(), 0);
        r.finish();
        assert!(r.text.is_empty() && r.line_sources.is_empty());
        assert_eq!(r.lines, 3);
        assert_eq!(r.items.len(), 1, "the first sweep is commented out");
    }
}

#[cfg(test)]
mod fold_tests {
    use super::*;
    use crate::emit::Target;

    /// Moves of every kind with lengths and feeds whose sums round differently in another
    /// order, sweeps in runs (the peephole comments all but the last out) and comments.
    fn program(r: &mut Record) {
        for k in 0..1000u32 {
            let kind = match k % 7 {
                0 | 1 => Kind::HSweep,
                2 => Kind::VSweep,
                3 | 4 => Kind::Mill,
                _ => Kind::Drill,
            };
            let item = Item {
                kind,
                len: 0.1 + f64::from(k).sqrt() / 3.0,
                feed: 150.0 + f64::from(k % 13) * 77.7,
                target: Target::default(),
                source: Some(k),
                shape: Default::default(),
            };
            r.moved(item, format!("move {k}"), k);
            if k % 5 == 0 {
                r.comment(format!("(c{k})"), k);
            }
        }
        r.finish();
    }

    #[test]
    fn folded_moves_give_the_statistics_of_kept_ones_bit_for_bit() {
        let sweep_speed = 1234.5;
        let mut kept = Record::new(false, &["%"], 16, None, post());
        program(&mut kept);
        let mut folded = Record::new(false, &["%"], 16, None, post());
        folded.fold_moves(sweep_speed);
        program(&mut folded);
        let (a, b) = (kept.stats(sweep_speed), folded.stats(sweep_speed));
        assert!(
            a.count > 500 && a.count < 1000,
            "some sweeps were commented out"
        );
        assert_eq!(a.count, b.count);
        for (x, y) in [
            (a.mill, b.mill),
            (a.mill_min, b.mill_min),
            (a.drill, b.drill),
            (a.drill_min, b.drill_min),
            (a.sweep, b.sweep),
            (a.sweep_min, b.sweep_min),
        ] {
            assert_eq!(x.to_bits(), y.to_bits());
        }
        assert_eq!(kept.move_count(), folded.move_count());
        assert_eq!(kept.text, folded.text, "the program is the same");
        assert!(folded.items.len() <= 1, "only the last move is held");
    }

    #[test]
    fn counted_moves_are_as_many_as_a_dry_list_holds() {
        let mut kept = Record::new(true, &["%"], 16, None, post());
        program(&mut kept);
        let mut counted = Record::new(true, &["%"], 16, None, post());
        counted.count_moves();
        assert!(counted.counts_only());
        program(&mut counted);
        assert!(kept.items.len() > 500, "some sweeps were commented out");
        assert_eq!(counted.move_count(), kept.items.len());
        assert_eq!(counted.lines, kept.lines);
        assert!(counted.items.is_empty(), "no move is kept");
        // the last move's source, for its target's range check
        let last = kept.items.last().map(|it| it.source);
        assert_eq!(counted.last_move(&Target::default()), last);
        // a record that writes lines keeps its moves' list (the held sweep needs it)
        let mut written = Record::new(false, &["%"], 16, None, post());
        written.count_moves();
        assert!(!written.counts_only());
    }
}
