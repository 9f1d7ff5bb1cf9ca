//! The traversal a build takes of a path (reference-input.md §5.2): the walk (`walk.rs`),
//! through the editor's memo of walks when there is one (`traverse_memo.rs`), with a warning
//! where the drawing's order chose (`order_choice.rs`).

use crate::build::order_choice;
use crate::build::traverse_memo::TraversalMemo;
use crate::build::walk::{walk, Step};
use crate::diag::Diags;
use crate::front::drawing::RawPath;
use crate::geom::P2;

/// Traversal order of a path's segments (§5.2), with turn markers (seed manual §4.2.15).
/// Where the drawing's order had to decide between equally good segments, a warning with
/// the value that pins the choice (`order_choice`).
pub fn traverse(raw: &RawPath, start: P2, end: P2, diags: &mut Diags) -> Vec<Step> {
    traverse_in(None, raw, start, end, diags)
}

/// [`traverse`] through the editor's memo of walks, when there is one.
pub fn traverse_in(
    memo: Option<&TraversalMemo>,
    raw: &RawPath,
    start: P2,
    end: P2,
    diags: &mut Diags,
) -> Vec<Step> {
    let (steps, ties) = match memo {
        Some(m) => m.walk(raw, start, end, diags),
        None => walk(raw, start, end, diags),
    };
    order_choice::warn(raw, &ties, diags);
    steps
}
