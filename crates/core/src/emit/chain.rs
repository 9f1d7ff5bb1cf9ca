//! Milling chains (reference-output.md §7): pass depths, the greedy order of fast milling, sweepless runs with back-milling, and one pass of one segment.

use crate::args;
use crate::diag::{Diagnostic, Msg};
use crate::emit::chain_order::{fast_order, Step};
use crate::emit::{bounded_passes, missing, Emitter, Frame, Shape, Skip, MAX_ITEMS};
use crate::front::drawing::Style;
use crate::geom::{ge, lt, near, Geom, P2};
use crate::model::*;

impl Emitter<'_> {
    pub(crate) fn chain(&mut self, fr: Frame, ch: &Chain) -> Result<(), Skip> {
        let p = &fr.model.params;
        let h = fr.h;
        let infeed = ch.i.ok_or_else(|| missing("I", &ch.origin))?;
        let first = match ch.w {
            Some(w) => h + w,
            None => h + p.t - infeed,
        };
        let mut passes: Vec<Vec<f64>> = Vec::with_capacity(ch.segs.len());
        let mut geoms = Vec::with_capacity(ch.segs.len());
        let mut total = 0.0;
        for s in &ch.segs {
            let (key, depth) = if s.style == Style::Mark {
                ("D", s.d)
            } else {
                ("B", s.b)
            };
            let bottom = h + depth.ok_or_else(|| missing(key, &s.origin))?;
            total += bounded_passes(first, bottom, infeed, &s.origin)?;
            if total > MAX_ITEMS as f64 {
                self.full = true;
                return Ok(());
            }
            passes.push(pass_depths(first, bottom, infeed));
            geoms.push(s.geom.transform(&fr.t));
        }
        let th = h + p.t;
        // every move of a pass belongs to its own segment, not to the chain's first
        let chain_source = self.source;
        let seg_sources: Vec<u32> = ch.segs.iter().map(|s| self.add_source(&s.origin)).collect();
        let r = if ch.w.is_some() {
            self.sweepless(fr, ch, &passes, &geoms, th, &seg_sources)
        } else {
            self.fast(fr, ch, &passes, &geoms, th, &seg_sources)
        };
        self.source = chain_source;
        self.shape = Shape::Mill;
        r
    }

    pub(crate) fn fast(
        &mut self,
        fr: Frame,
        ch: &Chain,
        passes: &[Vec<f64>],
        geoms: &[Geom],
        th: f64,
        seg_sources: &[u32],
    ) -> Result<(), Skip> {
        let p = &fr.model.params;
        let mut done_count = vec![0usize; passes.len()];
        let head = geoms[0].start().with_z(passes[0][0]);
        let s = fr.h + p.s;
        let ends: Vec<(P2, P2)> = geoms.iter().map(|g| (g.start(), g.end())).collect();
        let order = if self.quick_order {
            let order = level_order(passes);
            self.quick_steps += order.len();
            order
        } else {
            fast_order(&ends, passes, head)
        };
        for (si, forward) in order {
            if self.full || self.stop_now() {
                break;
            }
            let z = passes[si][done_count[si]];
            done_count[si] += 1;
            let g = if forward {
                geoms[si]
            } else {
                geoms[si].reversed()
            };
            let seg = &ch.segs[si];
            self.enter_segment(seg, seg_sources[si]);
            self.safe_sweep(self.pos, g.start().with_z(z), th, s, seg.f, false);
            self.segment_pass(fr, seg, &g, forward, z, th);
        }
        let end = geoms[geoms.len() - 1].end();
        self.safe_sweep(self.pos, end.with_z(s), p.t, s, p.f, false);
        Ok(())
    }

    pub(crate) fn sweepless(
        &mut self,
        fr: Frame,
        ch: &Chain,
        passes: &[Vec<f64>],
        geoms: &[Geom],
        th: f64,
        seg_sources: &[u32],
    ) -> Result<(), Skip> {
        let runs = passes.iter().map(Vec::len).max().unwrap_or(0);
        let chain_start = geoms[0].start();
        let chain_end = geoms[geoms.len() - 1].end();
        let back = runs > 1 && !chain_start.near(chain_end);
        let mut head = chain_start;
        let mut edges: Vec<(usize, f64, bool)> = Vec::new();
        for k in 0..runs {
            let mut run = Vec::new();
            for (si, g) in geoms.iter().enumerate() {
                let z = passes[si][k.min(passes[si].len() - 1)];
                let forward = if head.near(g.start()) {
                    true
                } else if head.near(g.end()) {
                    false
                } else {
                    return Err(Diagnostic::error(
                        Msg::NotNear,
                        ch.segs[si].origin.clone(),
                        args![head, g.start()],
                    ));
                };
                head = if forward { g.end() } else { g.start() };
                run.push((si, z, forward));
            }
            edges.extend(run.iter().copied());
            if back && k + 1 < runs {
                for &(si, z, fwd) in run.iter().rev() {
                    edges.push((si, z, !fwd));
                }
                head = chain_start;
            }
        }
        for (si, z, forward) in edges {
            if self.full || self.stop_now() {
                break;
            }
            let seg = &ch.segs[si];
            self.enter_segment(seg, seg_sources[si]);
            let g = if forward {
                geoms[si]
            } else {
                geoms[si].reversed()
            };
            self.drill_or_pull(self.pos.xy(), self.pos.z, z, th, seg.f);
            // the tool is now at the entry depth: the segment's own DrillOrPullZ is a no-op
            self.pos.z = z;
            self.segment_pass(fr, seg, &g, forward, z, th);
        }
        Ok(())
    }

    /// The moves pushed from now on belong to `seg`.
    fn enter_segment(&mut self, seg: &ChainSeg, source: u32) {
        self.source = Some(source);
        self.shape = if seg.style == Style::Mark {
            Shape::Mark
        } else {
            Shape::Mill
        };
    }

    /// One pass of one chain segment (§7.4). `g` is already in pass direction.
    pub(crate) fn segment_pass(
        &mut self,
        fr: Frame,
        seg: &ChainSeg,
        g: &Geom,
        forward: bool,
        z: f64,
        th: f64,
    ) {
        if let Some(q) = &seg.q {
            self.comment(4, || format!("Q:{q}"));
        }
        // deliberate difference: the clamp uses the raised bottom (+h)
        let full_bottom = fr.h
            + if seg.style == Style::Mill {
                seg.b
            } else {
                seg.d
            }
            .unwrap_or(f64::NAN);
        if let (Style::Support, Some(pieces), Some(b), Some(d)) =
            (seg.style, &seg.bars, seg.b, seg.d)
        {
            if lt(z, full_bottom) {
                let pieces: Vec<Geom> = pieces.iter().map(|p| p.transform(&fr.t)).collect();
                self.profile(&pieces, forward, z, fr.h + b, fr.h + d, th, seg.f, seg.bt);
                return;
            }
        }
        let depth = z.max(full_bottom);
        self.mill(g, depth, depth, th, seg.f, seg.bt);
    }
}

/// Pass depths from `first` down to `bottom` in steps of `infeed` (§7.1).
pub fn pass_depths(first: f64, bottom: f64, infeed: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut z = first;
    while ge(z, bottom) && out.len() < 100_000 {
        out.push(z);
        z -= infeed;
    }
    if out.last().is_none_or(|l| !near(*l, bottom)) {
        out.push(bottom);
    }
    out
}

/// Every pass of every segment once, level by level in list order, each forward (the
/// editor's quick check: see `emit_quick`).
fn level_order(passes: &[Vec<f64>]) -> Vec<Step> {
    let levels = passes.iter().map(Vec::len).max().unwrap_or(0);
    (0..levels)
        .flat_map(|k| {
            passes
                .iter()
                .enumerate()
                .filter(move |(_, p)| k < p.len())
                .map(|(si, _)| (si, true))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::f3;

    #[test]
    fn pass_depths_follow_the_reference() {
        let p = pass_depths(2.0 - 1.2, -0.3, 1.2);
        assert_eq!(p.len(), 2);
        assert!((p[0] - 0.8).abs() < 1e-12 && p[1] == -0.3);
        let p = pass_depths(1.0 - 0.6, -0.1, 0.6);
        assert_eq!(
            p.iter().map(|z| f3(*z)).collect::<Vec<_>>(),
            ["0.400", "-0.100"]
        );
        // a mark below the first pass gets a single pass at D
        assert_eq!(pass_depths(0.8, 1.5, 1.2), vec![1.5]);
    }
}
