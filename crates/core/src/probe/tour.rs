//! Z probes of a model and of everything it embeds, placed in output coordinates, and the
//! order the machine visits them (reference-output.md §12.1).

use crate::geom::{Transform, P2};
use crate::model::*;

/// One probe placed in output coordinates.
#[derive(Debug, Clone)]
pub struct PlacedProbe {
    pub probe: Probe,
    pub pos: P2,
    /// Accumulated H of the enclosing embeddings.
    pub h: f64,
}

impl PlacedProbe {
    /// Probe height `T + H + h`.
    pub fn height(&self) -> f64 {
        self.probe.t + self.probe.h + self.h
    }
}

/// Collects the probes of a model and of everything it embeds (reference-output.md §12.1).
pub fn collect_probes(model: &Model, t: &Transform, h: f64, out: &mut Vec<PlacedProbe>) {
    for p in &model.probes {
        let placed = PlacedProbe {
            probe: p.clone(),
            pos: t.apply(p.center),
            h,
        };
        if !out
            .iter()
            .any(|q| q.probe == placed.probe && q.pos == placed.pos && q.h == placed.h)
        {
            out.push(placed);
        }
    }
    for e in &model.elements {
        if let Element::Subpath(emb) = e {
            if let Some(target) = &emb.target {
                if let Some(sub) = sub_transform(target, emb, t) {
                    collect_probes(target, &sub, h + emb.h, out);
                }
            }
        }
    }
}

/// Orders probes by greedy nearest neighbour from (0, 0).
pub fn probe_tour(mut probes: Vec<PlacedProbe>) -> Vec<PlacedProbe> {
    let mut out = Vec::with_capacity(probes.len());
    let mut cur = P2::default();
    while !probes.is_empty() {
        let mut best = 0;
        for (i, p) in probes.iter().enumerate() {
            if p.pos.dist(cur) < probes[best].pos.dist(cur) {
                best = i;
            }
        }
        let p = probes.remove(best);
        cur = p.pos;
        out.push(p);
    }
    out
}
