//! The three-way merge of two versions of a text with their common base, by path and
//! element identity (`doc.rs`): changes to different paths, to different elements of a
//! path, or to different fields of one element (its kind, position, parameters, comment)
//! merge; the same thing changed both ways differently is a conflict, written with git's
//! markers around the element lines (or the whole path, when a path was deleted on one
//! side and changed on the other). The merged text is canonical (as `fmt` writes it),
//! except when one side holds no change: then the other side is taken as it is.

mod compiles;
pub mod doc;
pub mod drawing;
pub use compiles::failing_paths;
mod sequence;

use doc::{doc_of, Doc, Line, PathDoc};
use sequence::{slots, Slot};

/// What happened to the thing a conflict is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConflictKind {
    /// Changed on both sides, differently.
    BothChanged,
    /// Added on both sides, differently.
    AddedBoth,
    /// Deleted on our side, changed on theirs.
    DeletedByOurs,
    /// Changed on our side, deleted on theirs.
    DeletedByTheirs,
}

/// One conflict of a merged text.
#[derive(Debug, Clone, PartialEq)]
pub struct Conflict {
    /// The path it is in.
    pub path: String,
    /// The element line (ours, or theirs where ours has none); `None` for the path as a
    /// whole or the comments after the last path.
    pub element: Option<String>,
    pub kind: ConflictKind,
    /// 1-based line of its `<<<<<<<` in the merged text.
    pub line: usize,
}

/// The merged text, with conflict markers where `conflicts` says.
#[derive(Debug, Clone, PartialEq)]
pub struct TextMerge {
    pub text: String,
    pub conflicts: Vec<Conflict>,
}

/// Merges `ours` and `theirs` with their common `base` (an empty base: both added the
/// file). The texts must parse: a caller refuses one with syntax errors before.
pub fn merge_texts(base: &str, ours: &str, theirs: &str) -> TextMerge {
    let clean = |text: &str| TextMerge {
        text: text.to_string(),
        conflicts: Vec::new(),
    };
    if ours == theirs || base == theirs {
        return clean(ours);
    }
    if base == ours {
        return clean(theirs);
    }
    let doc = |s: &str| doc_of(&millpath_syntax::parse(s).0);
    merge_docs(&doc(base), &doc(ours), &doc(theirs))
}

/// The three-way merge of parsed texts.
pub fn merge_docs(base: &Doc, ours: &Doc, theirs: &Doc) -> TextMerge {
    let mut w = Writer::default();
    let mut first = true;
    for slot in slots(&base.paths, &ours.paths, &theirs.paths) {
        let Some(p) = decide(&slot) else { continue };
        if !first {
            w.out.push('\n');
        }
        first = false;
        match p {
            Decision::Take(p) => p.render(&mut w.out),
            Decision::Merge(b, o, t) => w.path(b, o, t),
            Decision::Conflict(kind) => {
                let name = slot.ours.or(slot.theirs).map(|p| p.name.clone());
                let render = |p: Option<&PathDoc>| {
                    let mut s = String::new();
                    if let Some(p) = p {
                        p.render(&mut s);
                    }
                    s
                };
                w.conflict(
                    name.unwrap_or_default(),
                    None,
                    kind,
                    &render(slot.ours),
                    &render(slot.theirs),
                );
            }
        }
    }
    match pick(&base.tail, &ours.tail, &theirs.tail) {
        Some(tail) => tail.iter().for_each(|c| w.line(c)),
        None => {
            let lines = |v: &[String]| v.iter().map(|c| format!("{c}\n")).collect::<String>();
            w.conflict(
                String::new(),
                None,
                ConflictKind::BothChanged,
                &lines(&ours.tail),
                &lines(&theirs.tail),
            );
        }
    }
    TextMerge {
        text: w.out,
        conflicts: w.conflicts,
    }
}

/// The value both sides agree on, or the one side's change; `None` when both changed it
/// differently.
fn pick<'a, T: PartialEq>(base: &'a T, ours: &'a T, theirs: &'a T) -> Option<&'a T> {
    if ours == theirs || base == theirs {
        Some(ours)
    } else if base == ours {
        Some(theirs)
    } else {
        None
    }
}

/// What a slot of a sequence becomes.
enum Decision<'a, V> {
    /// This version, as it is.
    Take(&'a V),
    /// Changed on both sides: merged inside.
    Merge(&'a V, &'a V, &'a V),
    Conflict(ConflictKind),
}

/// `None`: the item is gone (deleted where the other side left it unchanged).
fn decide<'a, V: PartialEq>(s: &Slot<'a, V>) -> Option<Decision<'a, V>> {
    use ConflictKind::*;
    Some(match (s.base, s.ours, s.theirs) {
        (Some(b), Some(o), Some(t)) => match pick(b, o, t) {
            Some(v) => Decision::Take(v),
            None => Decision::Merge(b, o, t),
        },
        (None, Some(o), Some(t)) if o == t => Decision::Take(o),
        (None, Some(_), Some(_)) => Decision::Conflict(AddedBoth),
        (Some(b), Some(o), None) if o == b => return None,
        (Some(_), Some(_), None) => Decision::Conflict(DeletedByTheirs),
        (Some(b), None, Some(t)) if t == b => return None,
        (Some(_), None, Some(_)) => Decision::Conflict(DeletedByOurs),
        (None, Some(v), None) | (None, None, Some(v)) => Decision::Take(v),
        (_, None, None) => return None,
    })
}

/// The merged text as it is written, and its conflicts.
#[derive(Default)]
struct Writer {
    out: String,
    conflicts: Vec<Conflict>,
    /// Lines of `out[..counted]` (counted as conflicts come, not again from the start).
    lines: usize,
    counted: usize,
}

impl Writer {
    fn line(&mut self, s: &str) {
        self.out.push_str(s);
        self.out.push('\n');
    }

    /// Writes both sides between git's markers (each side's text ends in `\n` or is empty).
    fn conflict(
        &mut self,
        path: String,
        element: Option<String>,
        kind: ConflictKind,
        ours: &str,
        theirs: &str,
    ) {
        self.lines += self.out[self.counted..].matches('\n').count();
        self.counted = self.out.len();
        let line = self.lines + 1;
        self.conflicts.push(Conflict {
            path,
            element,
            kind,
            line,
        });
        self.line("<<<<<<< ours");
        self.out.push_str(ours);
        self.line("=======");
        self.out.push_str(theirs);
        self.line(">>>>>>> theirs");
    }

    /// A path changed on both sides: its head, comments and elements merged one by one.
    fn path(&mut self, b: &PathDoc, o: &PathDoc, t: &PathDoc) {
        let comment_lines = |v: &[String], indent: &str| {
            v.iter()
                .map(|c| format!("{indent}{c}\n"))
                .collect::<String>()
        };
        match pick(&b.lead, &o.lead, &t.lead) {
            Some(lead) => lead.iter().for_each(|c| self.line(c)),
            None => self.conflict(
                o.name.clone(),
                None,
                ConflictKind::BothChanged,
                &comment_lines(&o.lead, ""),
                &comment_lines(&t.lead, ""),
            ),
        }
        match pick(&b.comment, &o.comment, &t.comment) {
            Some(c) => self.line(&doc::head(&o.name, c)),
            None => self.conflict(
                o.name.clone(),
                None,
                ConflictKind::BothChanged,
                &format!("{}\n", o.head()),
                &format!("{}\n", t.head()),
            ),
        }
        for slot in slots(&b.elements, &o.elements, &t.elements) {
            match decide(&slot) {
                None => {}
                Some(Decision::Take(l)) => l.render(&mut self.out),
                Some(Decision::Merge(lb, lo, lt)) => match merge_line(lb, lo, lt) {
                    Some(l) => l.render(&mut self.out),
                    None => self.element_conflict(&o.name, ConflictKind::BothChanged, &slot),
                },
                Some(Decision::Conflict(kind)) => self.element_conflict(&o.name, kind, &slot),
            }
        }
        match pick(&b.tail, &o.tail, &t.tail) {
            Some(tail) => tail.iter().for_each(|c| self.line(&format!("  {c}"))),
            None => self.conflict(
                o.name.clone(),
                None,
                ConflictKind::BothChanged,
                &comment_lines(&o.tail, "  "),
                &comment_lines(&t.tail, "  "),
            ),
        }
        match pick(&b.close, &o.close, &t.close) {
            Some(c) => self.line(&doc::close(c)),
            None => self.conflict(
                o.name.clone(),
                None,
                ConflictKind::BothChanged,
                &format!("{}\n", doc::close(&o.close)),
                &format!("{}\n", doc::close(&t.close)),
            ),
        }
    }

    fn element_conflict(&mut self, path: &str, kind: ConflictKind, slot: &Slot<Line>) {
        let render = |l: Option<&Line>| {
            let mut s = String::new();
            if let Some(l) = l {
                l.render(&mut s);
            }
            s
        };
        let element = slot
            .ours
            .or(slot.theirs)
            .map(|l| format!("{} {}", l.kind, l.geometry));
        self.conflict(
            path.to_string(),
            element,
            kind,
            &render(slot.ours),
            &render(slot.theirs),
        );
    }
}

/// One element changed on both sides: merged field by field, `None` when a field was
/// changed both ways differently.
fn merge_line(b: &Line, o: &Line, t: &Line) -> Option<Line> {
    Some(Line {
        lead: pick(&b.lead, &o.lead, &t.lead)?.clone(),
        kind: pick(&b.kind, &o.kind, &t.kind)?.clone(),
        geometry: pick(&b.geometry, &o.geometry, &t.geometry)?.clone(),
        params: pick(&b.params, &o.params, &t.params)?.clone(),
        comment: pick(&b.comment, &o.comment, &t.comment)?.clone(),
    })
}

/// The paths of the merged text that fail to compile while they compiled on both sides
/// (a path only one side holds: on that side), in name order; each version compiled alone.
pub fn broken_paths(
    ours: &str,
    theirs: &str,
    merged: &str,
    settings: &millpath_core::Settings,
) -> Vec<String> {
    broken_paths_at(ours, theirs, merged, settings, None)
}

/// [`broken_paths`] with each version standing at `at` (the drawing's place in the work
/// tree, as a `.mpath`): its subpaths in other files and `millpath.toml` are found there.
pub fn broken_paths_at(
    ours: &str,
    theirs: &str,
    merged: &str,
    settings: &millpath_core::Settings,
    at: Option<&std::path::Path>,
) -> Vec<String> {
    // one side's text as it is compiles as it did there
    if merged == ours || merged == theirs {
        return Vec::new();
    }
    let after = failing_paths(merged, settings, at);
    if after.is_empty() {
        return Vec::new();
    }
    let (o, t) = (
        failing_paths(ours, settings, at),
        failing_paths(theirs, settings, at),
    );
    after
        .into_iter()
        .filter(|p| !o.contains(p) && !t.contains(p))
        .collect()
}
