//! Where the traversal chose by drawing order (reference-input.md §5.2: storage order breaks
//! ties): the equally good segments that would give another result, the warning at the
//! chosen element, and the N value that pins the choice.

use crate::args;
use crate::build::eval::with_pos;
use crate::build::walk::{walk, Key, Step, Tie};
use crate::diag::{Diagnostic, Diags, Msg, Origin};
use crate::front::drawing::{RawPath, RawSegment, SegKind, SweepKind};
use crate::geom::P2;
use crate::params::ParamText;

/// Rivals named as related locations of one warning.
const MAX_RELATED: usize = 3;

/// Storage classes (§5.1): circles, then lines, then arcs, whatever the drawing's order.
/// Between classes the order is fixed; only inside one the drawing's order decides.
/// One warning per tie, at the chosen element where the choice was made.
pub(crate) fn warn(raw: &RawPath, ties: &[Tie], diags: &mut Diags) {
    for tie in ties {
        let seg = &raw.segments[tie.chosen];
        let value = pin(raw, tie);
        let count = tie.rivals.len() + 1;
        let (msg, args) = match value {
            None => (Msg::OrderDecidesNoPin, args![count]),
            Some(v) if matches!(seg.origin, Origin::Span { .. }) => {
                (Msg::OrderDecidesText, args![count, format!("N{v}")])
            }
            Some(v) if piece_of_one_entity(raw, seg).is_some() => {
                let line = piece_of_one_entity(raw, seg).unwrap_or_default();
                (Msg::OrderDecidesPiece, args![count, line, format!("N{v}")])
            }
            Some(v) => (Msg::OrderDecides, args![count, format!("N{v}")]),
        };
        let mut d = Diagnostic::warning(msg, with_pos(&seg.origin, tie.at), args);
        // the count is in the message; a few locations are enough to find them
        for &r in tie.rivals.iter().take(MAX_RELATED) {
            let rival = &raw.segments[r];
            d = d.with_related(with_pos(&rival.origin, tie.at), "just as good");
        }
        diags.push(d);
    }
}

/// The DXF line of the entity `seg` is a piece of, when other segments come from it too (a
/// polyline or block resolved in the extended mode): one text there sets N on every piece.
fn piece_of_one_entity(raw: &RawPath, seg: &RawSegment) -> Option<usize> {
    let Origin::Entity(e) = &seg.origin else {
        return None;
    };
    raw.segments
        .iter()
        .any(|s| {
            !std::ptr::eq(s, seg)
                && matches!(&s.origin, Origin::Entity(o) if o.line == e.line && o.file == e.file)
        })
        .then_some(e.line)
}

/// Segment kinds whose N takes part in the traversal (HIDDEN sweeps are always 9998).
fn takes_n(kind: SegKind) -> bool {
    matches!(
        kind,
        SegKind::Mill(_)
            | SegKind::Subpath
            | SegKind::Sweep(SweepKind::Dashed)
            | SegKind::Sweep(SweepKind::Dot)
    )
}

/// The text with `N<value>` instead of its N (or with it added).
pub fn with_n(text: Option<&ParamText>, value: i64, origin: &Origin) -> Option<ParamText> {
    let mut toks: Vec<String> = text.map(|t| t.tokens.clone()).unwrap_or_default();
    let n = format!("N{value}");
    match toks.iter_mut().find(|t| t.starts_with('N')) {
        Some(t) => *t = n,
        None => toks.push(n),
    }
    ParamText::parse(&toks.join(" "), origin.clone()).ok()
}

/// The N value one below the chosen segment's order: it wins the tie whatever the drawing's
/// order. `None` when the segment takes no N, or when with that value it would have won at
/// an earlier step where it lost (the walk would change there). Where it never would, the
/// walk is the same up to the tie, takes it there (its key is below every other candidate's,
/// all of which have an order ≥ its old one) and is not affected after.
pub fn pin(raw: &RawPath, tie: &Tie) -> Option<i64> {
    let value = pin_value(raw, tie)?;
    let seg = &raw.segments[tie.chosen];
    let pinned: Key = (
        value as f64,
        seg.kind.preference(),
        seg.shape.start().dist(seg.shape.end()),
    );
    let still_loses = match tie.lost_to {
        Some(w) => pinned > w,
        None => true,
    };
    still_loses.then_some(value)
}

/// [`pin`] the long way: walking again with the pinned text (for tests).
pub fn pin_by_walking(raw: &RawPath, start: P2, end: P2, steps: &[Step], tie: &Tie) -> Option<i64> {
    let value = pin_value(raw, tie)?;
    let seg = &raw.segments[tie.chosen];
    let mut pinned = raw.clone();
    pinned.segments[tie.chosen].text =
        Some(Box::new(with_n(seg.text.as_deref(), value, &seg.origin)?));
    let (again, ties) = walk(&pinned, start, end, &mut Diags::default());
    (again == steps && !ties.iter().any(|t| t.step == tie.step)).then_some(value)
}

/// The value [`pin`] tries: one below the order (5555, "backtracking" in comments, skipped).
fn pin_value(raw: &RawPath, tie: &Tie) -> Option<i64> {
    let seg = &raw.segments[tie.chosen];
    let order = seg.order();
    if !takes_n(seg.kind) || order.fract() != 0.0 || order.abs() > 1e9 {
        return None;
    }
    let value = order as i64 - 1;
    Some(if value == 5555 { value - 1 } else { value })
}
