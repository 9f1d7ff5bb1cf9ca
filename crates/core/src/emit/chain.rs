//! Milling chains (reference-output.md §7): pass depths, the greedy order of fast milling, sweepless runs with back-milling, and one pass of one segment.
//!
//! Pass depths (reference-output.md §7.1; per chain one shared list of levels, 4 bytes a segment),
//! fast milling (§7.2, its order kept as 4 bytes a pass), sweepless runs and back-milling (§7.3,
//! walked twice instead of listed), one pass of a segment (§7.4); geometries transformed on demand.

use crate::args;
use crate::diag::{Diagnostic, Msg};
use crate::emit::chain_order::{FastOrder, PassSource};
use crate::emit::{bounded_passes, missing, Emitter, Frame, Shape, Skip, MAX_ITEMS};
use crate::front::drawing::Style;
use crate::geom::{ge, lt, near, Geom, Transform, P2};
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
        let mut passes = SharedPasses::new(first, infeed, ch.segs.len());
        let mut total = 0.0;
        let mut passes_total = 0;
        for s in &ch.segs {
            let bottom = seg_bottom(s, h).ok_or_else(|| {
                missing(if s.style == Style::Mark { "D" } else { "B" }, &s.origin)
            })?;
            total += bounded_passes(first, bottom, infeed, &s.origin)?;
            if total > MAX_ITEMS as f64 {
                self.full = true;
                return Ok(());
            }
            passes.push(bottom);
            // the true count too: levels within the bottom's tolerance (`ge`) can outnumber
            // the estimate
            passes_total += passes.count(passes.counts.len() - 1);
            if passes_total > MAX_ITEMS {
                self.full = true;
                return Ok(());
            }
        }
        if ch.segs.is_empty() {
            return Ok(());
        }
        // the quick check visits each segment once a level: its geometries transformed once
        // (a list as long as the chain, only in the editor, kept for the next chain; compile
        // transforms on demand)
        let geoms = self.quick_order.then(|| {
            let mut g = std::mem::take(&mut self.chain_geoms);
            g.clear();
            g.extend(ch.segs.iter().map(|s| s.geom.transform(&fr.t)));
            g
        });
        let view = ChainView {
            segs: &ch.segs,
            t: fr.t,
            h,
            passes: &passes,
            geoms,
        };
        let th = h + p.t;
        // every move of a pass belongs to its own segment, not to the chain's first
        let chain_source = self.source;
        // (one after the other: segment `si`'s is `first_source + si`)
        let first_source = self.sources.len() as u32;
        for s in &ch.segs {
            self.add_source(&s.origin);
        }
        let r = if ch.w.is_some() {
            self.sweepless(fr, &view, th, first_source)
        } else {
            self.fast(fr, &view, th, first_source)
        };
        if let Some(g) = view.geoms {
            self.chain_geoms = g;
        }
        self.source = chain_source;
        self.shape = Shape::Mill;
        r
    }

    fn fast(
        &mut self,
        fr: Frame,
        view: &ChainView,
        th: f64,
        first_source: u32,
    ) -> Result<(), Skip> {
        let p = &fr.model.params;
        let n = view.segments();
        let head = view.geom(0).start().with_z(view.depth(0, 0));
        let s = fr.h + p.s;
        if self.quick_order {
            self.quick_steps += (0..n).map(|si| view.passes(si)).sum::<usize>();
            self.fast_passes(fr, view, th, s, first_source, level_order(view));
        } else {
            // the order first, 4 bytes a pass, and its k-d tree gone before the moves grow
            let total = (0..n).map(|si| view.passes(si)).sum::<usize>();
            let mut steps = Vec::with_capacity(total);
            steps.extend(FastOrder::new(view, head).map(|(si, fwd)| pack(si, fwd)));
            let mut done = vec![0u32; n];
            let order = steps.into_iter().map(move |step| {
                let (si, forward) = unpack(step);
                done[si] += 1;
                (si, done[si] as usize - 1, forward)
            });
            self.fast_passes(fr, view, th, s, first_source, order);
        }
        let end = view.geom(n - 1).end();
        self.safe_sweep(self.pos, end.with_z(s), p.t, s, p.f, false);
        Ok(())
    }

    /// The passes of a fast-milled chain in `order` (segment, pass, forward), each after a
    /// safe sweep to its start.
    fn fast_passes(
        &mut self,
        fr: Frame,
        view: &ChainView,
        th: f64,
        s: f64,
        first_source: u32,
        order: impl Iterator<Item = (usize, usize, bool)>,
    ) {
        for (si, k, forward) in order {
            if self.full || self.stop_now() {
                break;
            }
            let z = view.depth(si, k);
            let g = view.geom(si);
            let g = if forward { g } else { g.reversed() };
            let seg = &view.segs[si];
            self.enter_segment(seg, first_source + si as u32);
            self.safe_sweep(self.pos, g.start().with_z(z), th, s, seg.f, false);
            self.segment_pass(fr, seg, &g, forward, z, th);
        }
    }

    fn sweepless(
        &mut self,
        fr: Frame,
        view: &ChainView,
        th: f64,
        first_source: u32,
    ) -> Result<(), Skip> {
        // first only the walk's checks: a chain that does not connect emits nothing
        sweepless_walk(view, |_, _, _| true)?;
        sweepless_walk(view, |si, z, forward| {
            if self.full || self.stop_now() {
                return false;
            }
            let seg = &view.segs[si];
            self.enter_segment(seg, first_source + si as u32);
            let g = view.geom(si);
            let g = if forward { g } else { g.reversed() };
            self.drill_or_pull(self.pos.xy(), self.pos.z, z, th, seg.f);
            // the tool is now at the entry depth: the segment's own DrillOrPullZ is a no-op
            self.pos.z = z;
            self.segment_pass(fr, seg, &g, forward, z, th);
            true
        })
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

/// The bottom of a chain segment (`B`, for a mark `D`), raised by `h`.
fn seg_bottom(s: &ChainSeg, h: f64) -> Option<f64> {
    let depth = if s.style == Style::Mark { s.d } else { s.b };
    depth.map(|d| h + d)
}

/// The pass depths of every segment of one chain, without a list per segment: all share
/// `first` and `infeed`, so one list of levels `first, first − infeed, …` (the same repeated
/// subtraction as [`pass_depths`], so the same bits) serves all; a segment keeps how many
/// levels it takes and whether its bottom follows them. 4 bytes a segment.
pub struct SharedPasses {
    first: f64,
    infeed: f64,
    levels: Vec<f64>,
    /// Per segment: levels taken (low bits) and [`BOTTOM_ADDED`].
    counts: Vec<u32>,
}

/// In [`SharedPasses::counts`]: the segment's bottom is its last pass.
const BOTTOM_ADDED: u32 = 1 << 31;
/// Levels one segment takes at most ([`pass_depths`]'s bound).
const MAX_LEVELS: usize = 100_000;

impl SharedPasses {
    pub fn new(first: f64, infeed: f64, segments: usize) -> Self {
        SharedPasses {
            first,
            infeed,
            levels: Vec::new(),
            counts: Vec::with_capacity(segments),
        }
    }

    /// Adds the next segment, whose bottom is `bottom`.
    pub fn push(&mut self, bottom: f64) {
        let mut n = 0;
        while n < MAX_LEVELS {
            if n == self.levels.len() {
                let z = match self.levels.last() {
                    Some(l) => l - self.infeed,
                    None => self.first,
                };
                self.levels.push(z);
            }
            if !ge(self.levels[n], bottom) {
                break;
            }
            n += 1;
        }
        let added = n == 0 || !near(self.levels[n - 1], bottom);
        self.counts
            .push(n as u32 | if added { BOTTOM_ADDED } else { 0 });
    }

    /// Passes of segment `si`.
    pub fn count(&self, si: usize) -> usize {
        let c = self.counts[si];
        (c & !BOTTOM_ADDED) as usize + usize::from(c & BOTTOM_ADDED != 0)
    }

    /// Depth of pass `k` of segment `si`, whose bottom is `bottom`.
    pub fn depth(&self, si: usize, k: usize, bottom: f64) -> f64 {
        if k < (self.counts[si] & !BOTTOM_ADDED) as usize {
            self.levels[k]
        } else {
            bottom
        }
    }
}

/// One step of the order in 4 bytes: the segment (< 2³¹: a chain's passes are counted in
/// 32 bits) and the direction in the top bit.
fn pack(si: usize, forward: bool) -> u32 {
    si as u32 | u32::from(forward) << 31
}

fn unpack(step: u32) -> (usize, bool) {
    ((step & !(1 << 31)) as usize, step >> 31 != 0)
}

/// One chain as the order and the passes see it: geometries transformed on demand
/// ([`Geom::transform`] is deterministic, so every call gives the same bits).
struct ChainView<'a> {
    segs: &'a [ChainSeg],
    t: Transform,
    h: f64,
    passes: &'a SharedPasses,
    /// Every segment's geometry transformed already (the editor's quick check), the same bits.
    geoms: Option<Vec<Geom>>,
}

impl ChainView<'_> {
    fn geom(&self, si: usize) -> Geom {
        match &self.geoms {
            Some(g) => g[si],
            None => self.segs[si].geom.transform(&self.t),
        }
    }
}

impl PassSource for ChainView<'_> {
    fn segments(&self) -> usize {
        self.segs.len()
    }
    fn ends(&self, si: usize) -> (P2, P2) {
        let g = self.geom(si);
        (g.start(), g.end())
    }
    fn passes(&self, si: usize) -> usize {
        self.passes.count(si)
    }
    fn depth(&self, si: usize, k: usize) -> f64 {
        // the chain was checked to have every bottom before it is viewed
        let bottom = seg_bottom(&self.segs[si], self.h).unwrap_or(f64::NAN);
        self.passes.depth(si, k, bottom)
    }
}

/// Every pass of every segment once, level by level in list order, each forward (the
/// editor's quick check: see `emit_quick`), as (segment, pass, forward).
fn level_order<'a>(c: &'a ChainView) -> LevelOrder<'a> {
    let n = c.segments();
    LevelOrder {
        c,
        levels: (0..n).map(|si| c.passes(si)).max().unwrap_or(0),
        k: 0,
        si: 0,
    }
}

/// [`level_order`]'s walk: level `k`, segment `si` next (a step costs a comparison, where
/// a chain of iterator adapters was a twentieth of the quick check).
struct LevelOrder<'a> {
    c: &'a ChainView<'a>,
    levels: usize,
    k: usize,
    si: usize,
}

impl Iterator for LevelOrder<'_> {
    type Item = (usize, usize, bool);

    fn next(&mut self) -> Option<Self::Item> {
        let n = self.c.segments();
        while self.k < self.levels {
            if self.si == n {
                self.si = 0;
                self.k += 1;
                continue;
            }
            let si = self.si;
            self.si += 1;
            if self.k < self.c.passes(si) {
                return Some((si, self.k, true));
            }
        }
        None
    }
}

/// The runs of a sweepless chain (§7.3): every segment in list order per pass level, each
/// entered at the end the last one left; on an open chain every run but the last is milled
/// back. Calls `visit(segment, depth, forward)` per pass until it returns false; an error
/// where a segment does not start at the head.
fn sweepless_walk(
    c: &ChainView,
    mut visit: impl FnMut(usize, f64, bool) -> bool,
) -> Result<(), Skip> {
    let n = c.segments();
    let runs = (0..n).map(|si| c.passes(si)).max().unwrap_or(0);
    let chain_start = c.geom(0).start();
    let chain_end = c.geom(n - 1).end();
    let back = runs > 1 && !chain_start.near(chain_end);
    let mut head = chain_start;
    // the directions of the current run, for milling it back
    let mut forwards = vec![false; n];
    for k in 0..runs {
        for (si, fwd) in forwards.iter_mut().enumerate() {
            let z = c.depth(si, k.min(c.passes(si) - 1));
            let g = c.geom(si);
            let forward = if head.near(g.start()) {
                true
            } else if head.near(g.end()) {
                false
            } else {
                return Err(Diagnostic::error(
                    Msg::NotNear,
                    c.segs[si].origin.clone(),
                    args![head, g.start()],
                ));
            };
            head = if forward { g.end() } else { g.start() };
            *fwd = forward;
            if !visit(si, z, forward) {
                return Ok(());
            }
        }
        if back && k + 1 < runs {
            for si in (0..n).rev() {
                let z = c.depth(si, k.min(c.passes(si) - 1));
                if !visit(si, z, !forwards[si]) {
                    return Ok(());
                }
            }
            head = chain_start;
        }
    }
    Ok(())
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

    /// The depths of `bottoms` as [`SharedPasses`] gives them, bit for bit.
    fn shared(first: f64, infeed: f64, bottoms: &[f64]) -> Vec<Vec<u64>> {
        let mut sp = SharedPasses::new(first, infeed, bottoms.len());
        for &b in bottoms {
            sp.push(b);
        }
        (0..bottoms.len())
            .map(|si| {
                (0..sp.count(si))
                    .map(|k| sp.depth(si, k, bottoms[si]).to_bits())
                    .collect()
            })
            .collect()
    }

    fn own(first: f64, infeed: f64, bottoms: &[f64]) -> Vec<Vec<u64>> {
        bottoms
            .iter()
            .map(|&b| {
                pass_depths(first, b, infeed)
                    .iter()
                    .map(|z| z.to_bits())
                    .collect()
            })
            .collect()
    }

    #[test]
    fn shared_levels_give_pass_depths_bit_for_bit() {
        let firsts = [
            0.8,
            2.0 - 1.2,
            -0.3,
            0.0,
            -0.0,
            1e300,
            -1e300,
            1e-300,
            f64::NAN,
        ];
        let infeeds = [1.2, 0.6, 0.1, 1e-9, 1e-300, 3e299, f64::NAN];
        // per chain: bottoms in different orders (the levels grow with the deepest so far),
        // equal to a level, near one, above the first, not finite
        let bottoms = [
            -0.3,
            0.8,
            -0.1,
            0.8 - 1e-9,
            -2.5,
            1.5,
            0.0,
            -0.0,
            1e300,
            -1e300,
            0.7999995,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -0.3,
            -12.0,
        ];
        let orders: [Vec<f64>; 3] = [
            bottoms.to_vec(),
            bottoms.iter().rev().copied().collect(),
            vec![-12.0, -0.3, 0.8],
        ];
        for first in firsts {
            for infeed in infeeds {
                for bs in &orders {
                    assert_eq!(
                        shared(first, infeed, bs),
                        own(first, infeed, bs),
                        "first {first}, infeed {infeed}, bottoms {bs:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn shared_levels_keep_the_bound_of_pass_depths() {
        // an infeed below the rounding of the levels: the same level 100,000 times
        let got = shared(1.0, 1e-20, &[0.5, 1.0]);
        assert_eq!(got, own(1.0, 1e-20, &[0.5, 1.0]));
        assert_eq!(got[1].len(), MAX_LEVELS);
        assert_eq!(got[0].len(), MAX_LEVELS + 1);
    }

    #[test]
    fn packed_steps_round_trip() {
        for (si, fwd) in [(0, true), (0, false), (7, true), ((1 << 31) - 1, false)] {
            assert_eq!(unpack(pack(si, fwd)), (si, fwd));
        }
    }

    #[test]
    fn a_chain_view_orders_like_the_lists_of_its_passes() {
        use crate::diag::Origin;
        use crate::emit::chain_order::{fast_order_reference, FastOrder};
        // lines and arcs, milled and marked, in a rotated frame with a raised height
        let t = Transform::between(
            P2::new(0.0, 0.0),
            P2::new(10.0, 0.0),
            P2::new(3.0, -2.0),
            P2::new(3.0 + 6.0, -2.0 + 8.0),
        )
        .expect("a frame");
        let h = 0.25;
        let seg = |geom: Geom, style: Style, depth: f64| ChainSeg {
            geom,
            style,
            f: 100.0,
            b: Some(depth),
            d: Some(depth + 0.4),
            q: None,
            bt: false,
            bars: None,
            origin: Origin::Options,
        };
        let mut segs = Vec::new();
        for i in 0..40 {
            let x = f64::from(i);
            let (a, b) = (P2::new(x, 0.0), P2::new(x + 1.0, 0.0));
            segs.push(match i % 4 {
                0 => seg(Geom::Line { a, b }, Style::Mill, -0.3),
                1 => seg(
                    Geom::Arc {
                        c: P2::new(x + 0.5, 0.0),
                        r: 0.5,
                        a0: 180.0,
                        a1: 0.0,
                        ccw: false,
                    },
                    Style::Mill,
                    -1.7,
                ),
                2 => seg(Geom::Line { a, b }, Style::Mark, -0.9),
                _ => seg(Geom::Line { a, b }, Style::Mill, 0.1 * x - 2.0),
            });
        }
        let (first, infeed) = (h + 2.0 - 0.6, 0.6);
        let mut sp = SharedPasses::new(first, infeed, segs.len());
        let mut ends = Vec::new();
        let mut lists = Vec::new();
        for s in &segs {
            let bottom = seg_bottom(s, h).expect("a bottom");
            sp.push(bottom);
            let g = s.geom.transform(&t);
            ends.push((g.start(), g.end()));
            lists.push(pass_depths(first, bottom, infeed));
        }
        let view = ChainView {
            segs: &segs,
            t,
            h,
            passes: &sp,
            geoms: None,
        };
        let head = ends[0].0.with_z(lists[0][0]);
        let want = fast_order_reference(&ends, &lists, head);
        assert_eq!(want.len(), lists.iter().map(Vec::len).sum::<usize>());
        let mut order = FastOrder::indexed(&view, head);
        let mut done = vec![0; segs.len()];
        for &(si, forward) in &want {
            assert_eq!(order.next_pass(), Some((si, done[si], forward)));
            assert_eq!(
                view.depth(si, done[si]).to_bits(),
                lists[si][done[si]].to_bits()
            );
            done[si] += 1;
        }
        assert_eq!(order.next_pass(), None);
        assert_eq!(FastOrder::new(&view, head).collect::<Vec<_>>(), want);
        // the quick check's order: every pass once, level by level in list order
        let levels = lists.iter().map(Vec::len).max().unwrap();
        let by_level: Vec<_> = (0..levels)
            .flat_map(|k| {
                let lists = &lists;
                (0..segs.len())
                    .filter(move |&si| k < lists[si].len())
                    .map(move |si| (si, k, true))
            })
            .collect();
        assert_eq!(level_order(&view).collect::<Vec<_>>(), by_level);
        // and its geometries transformed once: the same bits
        let cached = ChainView {
            geoms: Some(segs.iter().map(|s| s.geom.transform(&t)).collect()),
            ..view
        };
        for si in 0..segs.len() {
            assert_eq!(
                format!("{:?}", cached.geom(si)),
                format!("{:?}", view.geom(si))
            );
        }
    }
}
