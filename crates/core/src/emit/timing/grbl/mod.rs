//! Time estimates for a GRBL controller: the model of GRBL 1.1's planner (planner.c,
//! motion_control.c), held within 2 % of GRBL's own firmware run on its simulator by
//! `tests/grbl_oracle.sh` and the test `grbl_oracle`. In mm and seconds.
//!
//! * **Blocks** (`blocks.rs`): arcs become chords by the arc tolerance `$12`, end points are
//!   rounded to whole steps; a block's top speed and acceleration are the axis limits
//!   (`$110–$112`, `$120–$122`) along it, its speed the feed (a rapid: that top speed).
//! * **Planner** (`planner.rs`): the junction speed from the junction deviation `$11`; the
//!   buffer's look-ahead of 14 blocks behind the running one; a trapezoid per block.
//!
//! GRBL does not stop between rapids and cuts: the moves flow on unless a junction reverses.

mod blocks;
mod planner;

pub use planner::BUFFER_BLOCKS;

use super::Bucket;
use crate::emit::Item;
use crate::geom::P3;
pub use crate::machine::grbl::{Grbl, GrblValues};

/// The time of the planned blocks of each item with the item and statistics line, in program order, the
/// tool starting at rest at `start`; `feed_override` is the operator's factor on the feeds
/// (1: none).
pub(super) fn planned(
    items: &[Item],
    start: P3,
    g: &Grbl,
    feed_override: f64,
) -> Vec<(usize, Bucket, f64)> {
    let mut planner = planner::Planner::new(g);
    blocks::blocks(items, start, g, feed_override, |b| planner.push(b));
    planner.finish()
}
