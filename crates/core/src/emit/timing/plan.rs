//! A program's estimated times: its moves' limits (`segments.rs`), planned into a velocity
//! profile (`profile.rs`), summed by statistics line.

use super::{profile, segments, Bucket};
use crate::emit::Item;
use crate::geom::P3;
use crate::machine::Machine;

/// Estimated times in seconds, by statistics line.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Times {
    pub mill: f64,
    pub drill: f64,
    pub sweep: f64,
}

/// The estimated times of a program's items, the tool starting at rest at `start`.
pub fn plan(items: &[Item], start: P3, m: &Machine) -> Times {
    let mut times = Times::default();
    for (_, bucket, t) in planned(items, start, m, 1.0) {
        match bucket {
            Bucket::Mill => times.mill += t,
            Bucket::Drill => times.drill += t,
            Bucket::Sweep => times.sweep += t,
        }
    }
    times
}

/// The estimated time (seconds) of every item, the tool starting at rest at `start`
/// (comments and moves without length: 0).
pub fn item_times(items: &[Item], start: P3, m: &Machine) -> Vec<f64> {
    let mut out = vec![0.0; items.len()];
    for (item, _, t) in planned(items, start, m, 1.0) {
        out[item] += t;
    }
    out
}

/// The time of each planned move with its item and statistics line, in program order;
/// `feed_override` is the operator's factor on the feeds (1: none).
pub(super) fn planned(
    items: &[Item],
    start: P3,
    m: &Machine,
    feed_override: f64,
) -> Vec<(usize, Bucket, f64)> {
    profile::times(&segments::segments(items, start, m, feed_override), m)
}
