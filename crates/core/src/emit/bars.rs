//! The support profile of one pass along bar pieces (reference-output.md §8.2).

use crate::emit::{Emitter, Shape};
use crate::geom::Geom;

impl Emitter<'_> {
    /// The support profile of one pass (§8.2); `b`, `d` are the bar depths.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn profile(
        &mut self,
        pieces: &[Geom],
        forward: bool,
        z: f64,
        b: f64,
        d: f64,
        th: f64,
        feed: f64,
        backtrack: bool,
    ) {
        const STEPS: [&str; 4] = ["Bar", "Down", "Between", "Up"];
        let ordered: Vec<Geom> = if forward {
            pieces.to_vec()
        } else {
            pieces.iter().rev().map(Geom::reversed).collect()
        };
        let shape = std::mem::replace(&mut self.shape, Shape::Bars);
        for (k, piece) in ordered.iter().enumerate() {
            if self.full {
                break;
            }
            let step = STEPS[k % 4];
            self.comment(2, || format!("Support.{step}"));
            let (fr, to) = match step {
                "Bar" => (z.max(d), z.max(d)),
                "Down" => (z.max(d), z.max(b)),
                "Between" => (z.max(b), z.max(b)),
                _ => (z.max(b), z.max(d)),
            };
            self.mill(piece, fr, to, th, feed, backtrack);
        }
        self.shape = shape;
    }
}
