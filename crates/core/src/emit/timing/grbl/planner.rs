//! GRBL's planner over the blocks: the speed allowed at each junction from the junction
//! deviation `$11`, and the look-ahead of its buffer. GRBL plans only the blocks in its
//! buffer (16 slots, one always free: the running block and 14 behind it) and must be able
//! to stop at the end of the last one, so the speed at which a block is left is what the
//! next 14 blocks can still brake from (a backward pass over that window); a forward pass
//! gives what the block reaches from its entry, and it takes its trapezoid. The blocks pass
//! through a window of 15: memory stays constant however many chords the arcs become, the
//! time linear in the blocks.

use super::blocks::{along, Block};
use super::Grbl;
use crate::emit::timing::{trapezoid, Bucket};
use std::collections::VecDeque;

/// GRBL 1.1h's planner buffer (BLOCK_BUFFER_SIZE without line numbers).
pub const BUFFER_BLOCKS: usize = 16;

/// The blocks planned behind the running one: the buffer holds one block less than its
/// slots, and one of those is running.
const AHEAD: usize = BUFFER_BLOCKS - 2;

/// Beyond this (or its opposite) the cosine of a junction counts as straight on (or as a
/// reversal), as in GRBL.
const STRAIGHT: f64 = 0.999_999;

/// The highest speed (mm/s) at the junction into `next` from `prev`, by the junction
/// deviation: a circle of deviation `$11` tangent to both moves, taken at the acceleration
/// the axes allow along the change of direction.
fn junction(prev: &Block, next: &Block, g: &Grbl) -> f64 {
    let cos = -(0..3).map(|i| prev.unit[i] * next.unit[i]).sum::<f64>();
    if cos > STRAIGHT {
        return 0.0;
    }
    if cos < -STRAIGHT {
        return f64::INFINITY;
    }
    let d: [f64; 3] = std::array::from_fn(|i| next.unit[i] - prev.unit[i]);
    let dl = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let acc = along(
        [g.acceleration.x, g.acceleration.y, g.acceleration.z],
        d.map(|c| c / dl),
    );
    let sin_half = (0.5 * (1.0 - cos)).sqrt();
    (acc * g.junction_deviation * sin_half / (1.0 - sin_half)).sqrt()
}

/// The planner as the blocks arrive: the blocks not yet left, with the highest speed each
/// may be entered at, and the times of those done (per item, in program order).
pub(super) struct Planner<'a> {
    g: &'a Grbl,
    window: VecDeque<(Block, f64)>,
    /// The speed the first block of the window is entered at.
    entry: f64,
    pub done: Vec<(usize, Bucket, f64)>,
}

impl<'a> Planner<'a> {
    /// The tool at rest.
    pub fn new(g: &'a Grbl) -> Planner<'a> {
        Planner {
            g,
            window: VecDeque::with_capacity(AHEAD + 2),
            entry: 0.0,
            done: Vec::new(),
        }
    }

    /// The next block; the oldest is timed once the buffer behind it is full.
    pub fn push(&mut self, b: Block) {
        // GRBL enters a block no faster than its junction, its own and the previous block's
        // speed (the window keeps the last block until the end); the first starts at rest
        let max_entry = match self.window.back() {
            Some((p, _)) => junction(p, &b, self.g).min(p.nominal).min(b.nominal),
            None => 0.0,
        };
        self.window.push_back((b, max_entry));
        if self.window.len() > AHEAD {
            self.leave_first();
        }
    }

    /// Times every block left, the last ending at rest; the times per item.
    pub fn finish(mut self) -> Vec<(usize, Bucket, f64)> {
        while !self.window.is_empty() {
            self.leave_first();
        }
        self.done
    }

    /// The first block of the window: left at what the blocks behind it can brake from and
    /// what it reaches from its entry.
    fn leave_first(&mut self) {
        let mut v: f64 = 0.0;
        for (b, max_entry) in self.window.iter().skip(1).rev() {
            v = max_entry.min((v * v + 2.0 * b.acc * b.len).sqrt());
        }
        let Some((b, _)) = self.window.pop_front() else {
            return;
        };
        let exit = v.min((self.entry * self.entry + 2.0 * b.acc * b.len).sqrt());
        let t = trapezoid(b.len, b.nominal, b.acc, self.entry, exit);
        self.entry = exit;
        match self.done.last_mut() {
            Some((item, _, sum)) if *item == b.item => *sum += t,
            _ => self.done.push((b.item, b.bucket, t)),
        }
    }
}
