//! The editor's memo of traversals: an edit that leaves a path's geometry, kinds, orders and
//! markers alone (a parameter typed in the start line) cannot change its walk (§5.2), so
//! the walk of the previous analysis is taken again instead of walking 20,000 segments.
//!
//! The key is exactly what the walk reads: each segment's shape (bit for bit), kind and
//! order key, the turn markers' positions, start and end; and the parameter tokens of the
//! segments that were ever one of several candidates (only there does the walk compare
//! texts, to tell duplicates from rivals). With all of that equal the walk takes the same
//! steps one by one, so its steps and ties are the same. A walk that reported an error is
//! not kept (its messages point into the text that had it).

use crate::build::walk::{walk_with, Step, Tie};
use crate::diag::Diags;
use crate::front::drawing::{RawPath, SegKind, Shape};
use crate::geom::{Geom, P2};
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// A shape bit for bit (−0.0 and 0.0 differ: the canonical duplicate compares totally).
type ShapeBits = (u8, [u64; 5]);

fn p(q: P2) -> [u64; 2] {
    [q.x.to_bits(), q.y.to_bits()]
}

fn shape_bits(s: &Shape) -> ShapeBits {
    let b = f64::to_bits;
    match *s {
        Shape::Circle { c, r } => (0, [b(c.x), b(c.y), b(r), 0, 0]),
        Shape::Path(Geom::Line { a, b: e }) => (1, [b(a.x), b(a.y), b(e.x), b(e.y), 0]),
        Shape::Path(Geom::Arc { c, r, a0, a1, ccw }) => {
            (2 + u8::from(ccw), [b(c.x), b(c.y), b(r), b(a0), b(a1)])
        }
    }
}

/// What the walk reads of one segment (besides the tokens of contested ones).
#[derive(Debug, Clone, PartialEq, Eq)]
struct SegKey {
    shape: ShapeBits,
    kind: SegKind,
    order: u64,
}

#[derive(Debug, PartialEq, Eq)]
struct WalkKey {
    start: [u64; 2],
    end: [u64; 2],
    turns: Vec<[u64; 2]>,
    segs: Vec<SegKey>,
}

impl WalkKey {
    fn of(raw: &RawPath, start: P2, end: P2) -> WalkKey {
        WalkKey {
            start: p(start),
            end: p(end),
            turns: raw.turns.iter().map(|m| p(m.pos)).collect(),
            segs: raw
                .segments
                .iter()
                .map(|s| SegKey {
                    shape: shape_bits(&s.shape),
                    kind: s.kind,
                    order: s.order().to_bits(),
                })
                .collect(),
        }
    }
}

/// One remembered walk.
#[derive(Debug)]
struct Entry {
    key: WalkKey,
    /// The contested segments (several candidates at one step) and their tokens.
    tokens: Vec<(usize, Vec<String>)>,
    steps: Vec<Step>,
    ties: Vec<Tie>,
}

impl Entry {
    fn fits(&self, key: &WalkKey, raw: &RawPath) -> bool {
        self.key == *key
            && self.tokens.iter().all(|(i, t)| {
                let now = raw.segments[*i]
                    .text
                    .as_ref()
                    .map_or(&[][..], |x| &x.tokens[..]);
                now == &t[..]
            })
    }
}

/// The walks of one analysis, seeded with those of the previous one (of the same document).
/// Holds only the paths walked by the analysis that made it, so it stays as small as they.
#[derive(Debug, Default)]
pub struct TraversalMemo {
    previous: HashMap<String, Arc<Entry>>,
    current: Mutex<HashMap<String, Arc<Entry>>>,
    /// Walks taken from the memo instead of walking.
    reused: AtomicUsize,
}

impl TraversalMemo {
    /// A memo for the next analysis that may take the walks of `prev`'s.
    pub fn after(prev: Option<&TraversalMemo>) -> TraversalMemo {
        let previous = prev
            .and_then(|m| m.current.lock().ok().map(|c| c.clone()))
            .unwrap_or_default();
        TraversalMemo {
            previous,
            current: Mutex::default(),
            reused: AtomicUsize::new(0),
        }
    }

    /// How many walks were taken from the memo (for tests).
    pub fn reused(&self) -> usize {
        self.reused.load(Ordering::Relaxed)
    }

    /// The remembered walk of a path: its steps and ties (for tests).
    pub fn remembered(&self, name: &str) -> Option<(Vec<Step>, Vec<Tie>)> {
        let c = self.current.lock().ok()?;
        c.get(name).map(|e| (e.steps.clone(), e.ties.clone()))
    }

    /// How many walks this memo holds (for tests).
    pub fn len(&self) -> usize {
        self.current.lock().map_or(0, |c| c.len())
    }

    /// Whether it holds none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The walk of `raw` (§5.2), or the remembered one when nothing it reads changed.
    pub fn walk(
        &self,
        raw: &RawPath,
        start: P2,
        end: P2,
        diags: &mut Diags,
    ) -> (Vec<Step>, Vec<Tie>) {
        let key = WalkKey::of(raw, start, end);
        let known = self
            .current
            .lock()
            .ok()
            .and_then(|c| c.get(&raw.name).cloned())
            .or_else(|| self.previous.get(&raw.name).cloned())
            .filter(|e| e.fits(&key, raw));
        if let Some(e) = known {
            self.reused.fetch_add(1, Ordering::Relaxed);
            self.keep(&raw.name, e.clone());
            return (e.steps.clone(), e.ties.clone());
        }
        let errors = diags.errors_reported();
        let mut contested = Vec::new();
        let (steps, ties) = walk_noting(raw, start, end, diags, &mut contested);
        if diags.errors_reported() == errors {
            let tokens = contested
                .into_iter()
                .map(|i| {
                    let t = raw.segments[i].text.as_ref();
                    (i, t.map_or_else(Vec::new, |t| t.tokens.clone()))
                })
                .collect();
            let e = Entry {
                key,
                tokens,
                steps: steps.clone(),
                ties: ties.clone(),
            };
            self.keep(&raw.name, Arc::new(e));
        }
        (steps, ties)
    }

    fn keep(&self, name: &str, e: Arc<Entry>) {
        if let Ok(mut c) = self.current.lock() {
            c.insert(name.to_string(), e);
        }
    }
}

/// The walk, also noting the segments that were one of several candidates at a step.
fn walk_noting(
    raw: &RawPath,
    start: P2,
    end: P2,
    diags: &mut Diags,
    contested: &mut Vec<usize>,
) -> (Vec<Step>, Vec<Tie>) {
    let r = walk_with(raw, start, end, diags, Some(contested));
    contested.sort_unstable();
    contested.dedup();
    r
}
