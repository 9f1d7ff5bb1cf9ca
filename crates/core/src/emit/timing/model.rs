//! The planning of a [`TimeModel`]: LinuxCNC's planner (the modules beside this one) or
//! GRBL's (`grbl/`). The type and the statistics line that names it are settings
//! (`machine/time_model.rs`).

use super::grbl;
use super::plan::planned;
use super::{Bucket, Times};
use crate::emit::Item;
use crate::geom::P3;
pub use crate::machine::{Planner, TimeModel};

impl TimeModel {
    fn planned(&self, items: &[Item], start: P3) -> Vec<(usize, Bucket, f64)> {
        match self {
            TimeModel::LinuxCnc {
                machine,
                feed_override,
            } => planned(items, start, machine, feed_override / 100.0),
            TimeModel::Grbl {
                settings,
                feed_override,
                ..
            } => grbl::planned(items, start, settings, feed_override / 100.0),
        }
    }

    /// The estimated times of a program's moves, the tool starting at rest at `start`.
    pub fn plan(&self, items: &[Item], start: P3) -> Times {
        let mut times = Times::default();
        for (_, bucket, t) in self.planned(items, start) {
            match bucket {
                Bucket::Mill => times.mill += t,
                Bucket::Drill => times.drill += t,
                Bucket::Sweep => times.sweep += t,
            }
        }
        times
    }

    /// The estimated time (seconds) of every item (comments and moves without length: 0).
    pub fn item_times(&self, items: &[Item], start: P3) -> Vec<f64> {
        let mut out = vec![0.0; items.len()];
        for (item, _, t) in self.planned(items, start) {
            out[item] += t;
        }
        out
    }
}
