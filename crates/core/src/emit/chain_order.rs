//! Order of the passes ("edges") of a fast-milled chain (§7.2): greedy nearest edge.
//!
//! [`fast_order_reference`] is the spec's sequential scan, quadratic in the number of
//! segments. [`FastOrder`] gives the identical order in about O(n log n), one step at a time
//! over a [`PassSource`] (the chain answers for its ends and depths; no lists of them): the
//! end points of all passes, as 3-D points `[x, y, z_pass]`, sit in a static k-d tree; the
//! candidate of a segment is its next pass (points of deeper passes, and of passes already
//! milled, are skipped). Each step runs the spec's scan over only the candidates nearest the
//! head.
//!
//! Why that is exact. Let S be a set of candidates such that every tip in S is `lt` every
//! tip outside S. In the full scan a candidate outside S never replaces a best from S (its
//! tip is larger), and the first member of S met replaces any best from outside S; from
//! there on the best stays in S and changes exactly as in a scan over S alone, in list
//! order. So scanning S alone gives the full scan's answer (a segment met at both ends of
//! its pass is in S twice with the same tip: the scan keeps the first, no difference). S is
//! grown nearest-first until the next point is at least `L` away with
//! `L − M > 2·eps·(L + 0.001)`, `M` the largest tip in S. A candidate not yet met has both
//! its points at ≥ `L`, so its tip `f ≥ L`, and for every tip `a ≤ M` of S:
//! `f − a ≥ (f − L) + (L − M) > eps·(f + 0.001) + eps·(L + 0.001)`, i.e. `lt(a, f)` with a
//! margin far above rounding. Without such a gap S ends up holding every candidate: the
//! full scan. `L` is a lower bound of the spec's distance: queue keys are squared distances
//! computed like [`P3::dist`] (of a box: to the head clamped into the box, which holds all
//! the node's points as it is rounded outwards to `f32`, so never more), shrunk by 1e-12.
//! Tips are computed from the chain's own end points and depths, exactly as the scan does;
//! the tree's copies of the points (the same bits) only decide which candidates are met.
//! Node counts of the points left only prune: a milled pass leaves the tree by the point it
//! was met at at once, by its other point when a later query meets that (until then its
//! nodes count one point too many, which costs a visit, never a candidate). A first ball may
//! start below the root only where no point outside is within reach (the leaf anchors).
//! Non-finite input falls back to the scan.
//!
//! Memory, for a chain of a million passes: 32 bytes a point (two a pass), 3 to 4 for the
//! nodes (16 to 32 points a leaf, 44 bytes a node), 4 a segment for its passes milled.
//!
//! The order of fast milling (§7.2) without the quadratic scan, over a `PassSource` (a chain's ends
//! and depths), step by step: pass end points in a k-d tree (32 bytes a point, f32 boxes), small
//! ball queries around the head (nearest-first walk as fallback), small chains scanned directly;
//! always the spec's order (property test `tests/chain_order.rs`).

use crate::geom::{lt, EPS, P2, P3};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// One step of the order: the segment whose next pass is milled, and whether it is milled
/// from its start to its end (`true`) or backwards.
pub type Step = (usize, bool);

/// What the order needs of a chain: per segment its end points and its pass depths (a
/// chain's emission answers from its model without a list per segment).
pub trait PassSource {
    /// Number of segments.
    fn segments(&self) -> usize;
    /// Start and end of segment `si` in traversal direction.
    fn ends(&self, si: usize) -> (P2, P2);
    /// Number of passes of segment `si`.
    fn passes(&self, si: usize) -> usize;
    /// Depth of pass `k < passes(si)` of segment `si`.
    fn depth(&self, si: usize, k: usize) -> f64;
}

/// The spec's form: `ends[i]` are the start and end of segment `i`, `passes[i]` its depths.
pub struct Lists<'a> {
    pub ends: &'a [(P2, P2)],
    pub passes: &'a [Vec<f64>],
}

impl PassSource for Lists<'_> {
    fn segments(&self) -> usize {
        self.ends.len().min(self.passes.len())
    }
    fn ends(&self, si: usize) -> (P2, P2) {
        self.ends[si]
    }
    fn passes(&self, si: usize) -> usize {
        self.passes[si].len()
    }
    fn depth(&self, si: usize, k: usize) -> f64 {
        self.passes[si][k]
    }
}

/// The spec's scan (§7.2), verbatim: for every step all segments in list order, the
/// candidate of a segment is its next pass; entered at the start iff `lt(ds, de)`; it
/// replaces the best iff its tip is `lt` the best's tip. `ends[i]` are the start and end of
/// segment `i`, `passes[i]` its pass depths, `head` the 3-D start position.
#[doc(hidden)]
pub fn fast_order_reference(ends: &[(P2, P2)], passes: &[Vec<f64>], head: P3) -> Vec<Step> {
    scan(&Lists { ends, passes }, head)
}

/// [`fast_order_reference`] over any [`PassSource`].
fn scan<C: PassSource + ?Sized>(c: &C, head: P3) -> Vec<Step> {
    let n = c.segments();
    let total: usize = (0..n).map(|si| c.passes(si)).sum();
    let mut done_count = vec![0usize; n];
    let mut head = head;
    let mut order = Vec::with_capacity(total);
    for _ in 0..total {
        let mut best: Option<(usize, bool, f64)> = None;
        for (si, &k) in done_count.iter().enumerate() {
            if k >= c.passes(si) {
                continue;
            }
            let (a, b) = c.ends(si);
            let z = c.depth(si, k);
            let ds = head.dist(a.with_z(z));
            let de = head.dist(b.with_z(z));
            let forward = lt(ds, de);
            let tip = ds.min(de);
            if best.is_none_or(|(_, _, bt)| lt(tip, bt)) {
                best = Some((si, forward, tip));
            }
        }
        let Some((si, forward, _)) = best else { break };
        let z = c.depth(si, done_count[si]);
        done_count[si] += 1;
        order.push((si, forward));
        // the end of the geometry in pass direction (a reversed geometry ends at the start)
        let (a, b) = c.ends(si);
        head = if forward { b } else { a }.with_z(z);
    }
    order
}

/// One end point of one pass, in tree order.
#[derive(Clone, Copy)]
struct Point {
    p: [f64; 3],
    seg: u32,
    /// `2 · pass + 1` for the pass's end point, `2 · pass` for its start; [`GONE`] once the
    /// point has left the tree.
    pass: u32,
}

const GONE: u32 = u32::MAX;

/// The end points of all passes of all segments in a static k-d tree. Nodes count the
/// points left below them (see the module docs), so emptied parts of the drawing cost
/// nothing. 32 bytes a point, the nodes about 4 more (no per-point index lists: a point's
/// leaf is found by descending by its position).
struct PassPoints {
    pts: Vec<Point>,
    nodes: Vec<KdNode>,
}

/// Best-first queue of a query: (squared distance or its lower bound, node or point).
type Queue = BinaryHeap<Reverse<(u64, usize)>>;

struct KdNode {
    /// Bounding box of the node's points, rounded outwards to `f32` (it still holds them:
    /// distances to it are still lower bounds, and the node takes 40 bytes, not 64).
    lo: [f32; 3],
    hi: [f32; 3],
    /// The node's points are `pts[start..end]`; `left` is 0 for a leaf, else the children
    /// are `left` and `left + 1`.
    start: u32,
    end: u32,
    left: u32,
    alive: u32,
    /// Of a leaf: the node a ball of [`FIRST_RADIUS`] around a point in the leaf's box may
    /// start from (see [`PassPoints::anchor_leaves`]).
    anchor: u32,
}

/// Points per leaf at most: a leaf holds 16 to 32 points.
const LEAF: usize = 32;
/// Marks a point (rather than a node) in the query heap.
const POINT: usize = 1 << (usize::BITS - 1);

/// Squared distance between two bounding boxes: a lower bound for any two of their points.
fn box_gap2(a: &KdNode, b: &KdNode) -> f64 {
    (0..3)
        .map(|i| {
            let (alo, ahi) = (f64::from(a.lo[i]), f64::from(a.hi[i]));
            let (blo, bhi) = (f64::from(b.lo[i]), f64::from(b.hi[i]));
            let gap = (blo - ahi).max(alo - bhi).max(0.0);
            gap * gap
        })
        .sum()
}

/// Squared distance, the same expression as [`P3::dist`] before its square root.
fn dist2(h: P3, p: [f64; 3]) -> f64 {
    let (dx, dy, dz) = (h.x - p[0], h.y - p[1], h.z - p[2]);
    dx * dx + dy * dy + dz * dz
}

/// The largest `f32` at most `x` (finite `x`; beyond the `f32` range: `−∞` or `f32::MAX`).
fn down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x {
        f.next_down()
    } else {
        f
    }
}

/// The smallest `f32` at least `x` (finite `x`).
fn up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x {
        f.next_up()
    } else {
        f
    }
}

/// Nodes of the tree over `n` points (built exactly so: one allocation, no slack).
fn node_count(n: usize) -> usize {
    if n <= LEAF {
        1
    } else {
        1 + node_count(n / 2) + node_count(n - n / 2)
    }
}

impl PassPoints {
    /// The tree over every pass end point of `c`; None if a coordinate is not finite or the
    /// chain has more points than 32-bit indices count.
    fn new<C: PassSource + ?Sized>(c: &C) -> Option<Self> {
        let n = c.segments();
        let total: usize = (0..n).map(|si| c.passes(si)).sum();
        let count = total.checked_mul(2).filter(|&t| t < GONE as usize)?;
        let mut pts = Vec::with_capacity(count);
        let finite = |p: P2| p.x.is_finite() && p.y.is_finite();
        for si in 0..n {
            let (a, b) = c.ends(si);
            if !(finite(a) && finite(b)) {
                return None;
            }
            for k in 0..c.passes(si) {
                let z = c.depth(si, k);
                if !z.is_finite() {
                    return None;
                }
                let (seg, pass) = (si as u32, 2 * k as u32);
                pts.push(Point {
                    p: [a.x, a.y, z],
                    seg,
                    pass,
                });
                pts.push(Point {
                    p: [b.x, b.y, z],
                    seg,
                    pass: pass + 1,
                });
            }
        }
        let mut nodes = Vec::with_capacity(if pts.is_empty() {
            0
        } else {
            node_count(pts.len())
        });
        if !pts.is_empty() {
            nodes.push(KdNode {
                lo: [0.0; 3],
                hi: [0.0; 3],
                start: 0,
                end: pts.len() as u32,
                left: 0,
                alive: pts.len() as u32,
                anchor: 0,
            });
            Self::build(&mut nodes, &mut pts, 0);
            Self::anchor_leaves(&mut nodes, 0, &mut Vec::new());
        }
        Some(PassPoints { pts, nodes })
    }

    /// Sets the `anchor` of the leaves below node `n` (`path`: its ancestors): the highest
    /// ancestor of the leaf whose other child's bounding box comes within
    /// `4 · FIRST_RADIUS` of the leaf's box, else the leaf. Every point outside the anchor's
    /// subtree is farther than that from the leaf's box (boxes never change), so a first
    /// ball around a point in the box finds all its points below the anchor.
    fn anchor_leaves(nodes: &mut [KdNode], n: usize, path: &mut Vec<usize>) {
        let left = nodes[n].left as usize;
        if left != 0 {
            // depth ≤ log2 of the point count: the tree is balanced
            path.push(n);
            Self::anchor_leaves(nodes, left, path);
            Self::anchor_leaves(nodes, left + 1, path);
            path.pop();
            return;
        }
        let reach2 = (4.0 * FIRST_RADIUS) * (4.0 * FIRST_RADIUS);
        let (mut at, mut child) = (n, n);
        for &x in path.iter().rev() {
            let l = nodes[x].left as usize;
            let sibling = if child == l { l + 1 } else { l };
            if box_gap2(&nodes[n], &nodes[sibling]) <= reach2 {
                at = x;
            }
            child = x;
        }
        nodes[n].anchor = at as u32;
    }

    /// Whether `h` lies in the bounding box of node `n`.
    fn in_box(&self, h: P3, n: usize) -> bool {
        let KdNode { lo, hi, .. } = self.nodes[n];
        [h.x, h.y, h.z]
            .iter()
            .enumerate()
            .all(|(i, &v)| f64::from(lo[i]) <= v && v <= f64::from(hi[i]))
    }

    fn build(nodes: &mut Vec<KdNode>, pts: &mut [Point], at: usize) {
        let (start, end) = (nodes[at].start as usize, nodes[at].end as usize);
        let part = &mut pts[start..end];
        let (mut lo, mut hi) = (part[0].p, part[0].p);
        for q in part.iter() {
            for i in 0..3 {
                lo[i] = lo[i].min(q.p[i]);
                hi[i] = hi[i].max(q.p[i]);
            }
        }
        nodes[at].lo = lo.map(down);
        nodes[at].hi = hi.map(up);
        if part.len() <= LEAF {
            return;
        }
        let axis = (0..3)
            .max_by(|&i, &j| (hi[i] - lo[i]).total_cmp(&(hi[j] - lo[j])))
            .unwrap_or(0);
        let mid = part.len() / 2;
        part.select_nth_unstable_by(mid, |p, q| p.p[axis].total_cmp(&q.p[axis]));
        let left = nodes.len();
        nodes[at].left = left as u32;
        for (s, e) in [(start, start + mid), (start + mid, end)] {
            nodes.push(KdNode {
                lo: [0.0; 3],
                hi: [0.0; 3],
                start: s as u32,
                end: e as u32,
                left: 0,
                alive: (e - s) as u32,
                anchor: 0,
            });
        }
        Self::build(nodes, pts, left);
        Self::build(nodes, pts, left + 1);
    }

    /// Takes point `i` out (once): down from the root to its leaf, counting it off.
    /// Returns the leaf.
    fn remove(&mut self, i: usize) -> usize {
        let gone = self.pts[i].pass == GONE;
        self.pts[i].pass = GONE;
        let mut n = 0;
        loop {
            let node = &mut self.nodes[n];
            if !gone {
                node.alive -= 1;
            }
            let left = node.left as usize;
            if left == 0 {
                return n;
            }
            // depth ≤ log2 of the point count: the tree is balanced
            n = if i < self.nodes[left].end as usize {
                left
            } else {
                left + 1
            };
        }
    }

    /// Lower bound of the squared distance from `h` to the points of node `n`.
    fn node_dist2(&self, h: P3, n: usize) -> f64 {
        let KdNode { lo, hi, .. } = self.nodes[n];
        let at = |v: f64, i: usize| v.clamp(f64::from(lo[i]), f64::from(hi[i]));
        dist2(h, [at(h.x, 0), at(h.y, 1), at(h.z, 2)])
    }

    fn push_node(&self, queue: &mut Queue, h: P3, n: usize) {
        if self.nodes[n].alive > 0 {
            let d2 = self.node_dist2(h, n);
            queue.push(Reverse((d2.to_bits(), n)));
        }
    }

    /// Puts into `hits` every point left below node `from` whose squared distance from `h`
    /// is at most `r2` (in tree order). A depth-first walk with a reused stack.
    fn within(&self, stack: &mut Vec<u32>, from: u32, h: P3, r2: f64, hits: &mut Vec<u32>) {
        stack.clear();
        hits.clear();
        if !self.nodes.is_empty() {
            stack.push(from);
        }
        while let Some(n) = stack.pop() {
            let KdNode {
                start,
                end,
                left,
                alive,
                ..
            } = self.nodes[n as usize];
            if alive == 0 || self.node_dist2(h, n as usize) > r2 {
                continue;
            }
            if left != 0 {
                stack.push(left + 1);
                stack.push(left);
                continue;
            }
            for i in start..end {
                let q = &self.pts[i as usize];
                if q.pass != GONE && dist2(h, q.p) <= r2 {
                    hits.push(i);
                }
            }
        }
    }

    /// Calls `visit(point, squared distance)` for the points left, nearest first, until it
    /// returns false. (Squared distances are ≥ +0, so their bits order like their values.)
    fn nearest(&self, queue: &mut Queue, h: P3, mut visit: impl FnMut(usize, f64) -> bool) {
        queue.clear();
        if self.nodes.is_empty() {
            return;
        }
        self.push_node(queue, h, 0);
        while let Some(Reverse((bits, item))) = queue.pop() {
            if item & POINT != 0 {
                if !visit(item & !POINT, f64::from_bits(bits)) {
                    return;
                }
                continue;
            }
            let KdNode {
                start, end, left, ..
            } = self.nodes[item];
            if left != 0 {
                self.push_node(queue, h, left as usize);
                self.push_node(queue, h, left as usize + 1);
            } else {
                for i in start as usize..end as usize {
                    let q = &self.pts[i];
                    if q.pass != GONE {
                        queue.push(Reverse((dist2(h, q.p).to_bits(), i | POINT)));
                    }
                }
            }
        }
    }
}

/// A candidate met in a round.
#[derive(Clone, Copy)]
struct Met {
    seg: u32,
    forward: bool,
    tip: f64,
    /// The tree point it was met at.
    at: u32,
    /// The end of the pass in its direction: the next head if it is milled.
    exit: P3,
}

/// The candidates of one step, found in the k-d tree.
struct Candidates {
    done_count: Vec<u32>,
    /// The candidates met in this round; a segment met at both ends of its pass is in twice,
    /// with the same tip (the scan keeps the first of equal tips: no difference).
    met: Vec<Met>,
    max_tip: f64,
    /// Points met whose pass is milled: they leave the tree after the step.
    milled: Vec<u32>,
}

impl Candidates {
    fn start_round(&mut self) {
        self.met.clear();
        self.max_tip = f64::NEG_INFINITY;
    }

    /// Point `i` of the tree was reached: its segment is a candidate if the point belongs
    /// to the segment's next pass (deeper passes are no candidates yet).
    fn meet<C: PassSource + ?Sized>(&mut self, c: &C, tree: &PassPoints, head: P3, i: usize) {
        let Point { seg, pass, .. } = tree.pts[i];
        let (si, k) = (seg as usize, pass / 2);
        if k < self.done_count[si] {
            self.milled.push(i as u32);
            return;
        }
        if k != self.done_count[si] {
            return;
        }
        let (a, b) = c.ends(si);
        let z = c.depth(si, k as usize);
        let ds = head.dist(a.with_z(z));
        let de = head.dist(b.with_z(z));
        let tip = ds.min(de);
        self.max_tip = self.max_tip.max(tip);
        let forward = lt(ds, de);
        // the end of the geometry in pass direction (a reversed geometry ends at the start)
        let exit = if forward { b } else { a }.with_z(z);
        self.met.push(Met {
            seg,
            forward,
            tip,
            at: i as u32,
            exit,
        });
    }

    /// Whether every candidate not met (all its points at least `reach` away) has a tip
    /// `lt` every tip met (the gap of the module docs).
    fn separated(&self, reach: f64) -> bool {
        !self.met.is_empty() && reach - self.max_tip > 2.0 * EPS * (reach + 0.001)
    }

    /// The spec's scan over the met candidates, in list order.
    fn best(&mut self) -> Option<Met> {
        self.met.sort_unstable_by_key(|m| m.seg);
        let mut best: Option<Met> = None;
        for &m in &self.met {
            if best.is_none_or(|b| lt(m.tip, b.tip)) {
                best = Some(m);
            }
        }
        best
    }
}

/// Chains up to this many segments are ordered by the spec's scan directly.
const SMALL_CHAIN: usize = 8;
/// First ball radius: separates a candidate at the head (tip 0) from all others.
const FIRST_RADIUS: f64 = 1e-8;
/// Balls tried per step before the nearest-first walk takes over.
const BALL_ROUNDS: usize = 8;

/// The order of [`fast_order_reference`] over a [`PassSource`], one step at a time: an
/// iterator of `(segment, forward)`; [`FastOrder::next_pass`] also names the pass.
pub struct FastOrder<'a, C: ?Sized> {
    c: &'a C,
    way: Way,
}

enum Way {
    /// Small or non-finite chains: the scan's list, and the passes handed out per segment.
    Scan(std::vec::IntoIter<Step>, Vec<u32>),
    Tree(Box<TreeOrder>),
}

struct TreeOrder {
    tree: PassPoints,
    cand: Candidates,
    queue: Queue,
    stack: Vec<u32>,
    hits: Vec<u32>,
    head: P3,
    /// The leaf of the point the last pass was met at: the head is often in its box.
    last_leaf: Option<usize>,
    steps_left: usize,
}

impl<'a, C: PassSource + ?Sized> FastOrder<'a, C> {
    /// The order of `c` from `head`: the scan for small chains (cheaper than a tree) and for
    /// non-finite input, else the k-d tree.
    pub fn new(c: &'a C, head: P3) -> Self {
        Self::with(c, head, c.segments() <= SMALL_CHAIN)
    }

    /// Through the k-d tree whatever the size (finite input; the property test runs it on
    /// small chains as well).
    #[doc(hidden)]
    pub fn indexed(c: &'a C, head: P3) -> Self {
        Self::with(c, head, false)
    }

    fn with(c: &'a C, head: P3, small: bool) -> Self {
        let finite_head = head.x.is_finite() && head.y.is_finite() && head.z.is_finite();
        let tree = if small || !finite_head {
            None
        } else {
            PassPoints::new(c)
        };
        let way = match tree {
            Some(tree) => {
                let n = c.segments();
                Way::Tree(Box::new(TreeOrder {
                    steps_left: tree.pts.len() / 2,
                    tree,
                    cand: Candidates {
                        done_count: vec![0; n],
                        met: Vec::new(),
                        max_tip: f64::NEG_INFINITY,
                        milled: Vec::new(),
                    },
                    queue: Queue::new(),
                    stack: Vec::new(),
                    hits: Vec::new(),
                    head,
                    last_leaf: None,
                }))
            }
            None => Way::Scan(scan(c, head).into_iter(), vec![0; c.segments()]),
        };
        FastOrder { c, way }
    }

    /// The next step as (segment, pass, forward).
    pub fn next_pass(&mut self) -> Option<(usize, usize, bool)> {
        match &mut self.way {
            Way::Scan(steps, done) => {
                let (si, forward) = steps.next()?;
                let k = done[si];
                done[si] += 1;
                Some((si, k as usize, forward))
            }
            Way::Tree(t) => t.step(self.c),
        }
    }
}

impl<C: PassSource + ?Sized> Iterator for FastOrder<'_, C> {
    type Item = Step;
    fn next(&mut self) -> Option<Step> {
        self.next_pass().map(|(si, _, forward)| (si, forward))
    }
}

impl TreeOrder {
    /// Each step first tries balls around the head: all points within radius `r` are met,
    /// and when the candidates met are separated from every point outside (`reach = r`,
    /// shrunk like the queue keys), they form a valid set `S`. In a chain the next segment
    /// usually starts at the head, so one small ball settles the step. A ball without
    /// candidates grows 16-fold, one whose candidates are not yet separated grows to the
    /// radius that would separate them; after [`BALL_ROUNDS`] balls the nearest-first walk
    /// decides.
    fn step<C: PassSource + ?Sized>(&mut self, c: &C) -> Option<(usize, usize, bool)> {
        if self.steps_left == 0 {
            return None;
        }
        let TreeOrder {
            tree,
            cand,
            queue,
            stack,
            hits,
            head,
            last_leaf,
            ..
        } = self;
        let head = *head;
        // a first ball around a head in the box of a leaf starts at the leaf's anchor
        let anchor = last_leaf
            .filter(|&l| tree.in_box(head, l))
            .map_or(0, |l| tree.nodes[l].anchor);
        let mut settled = false;
        let mut r = FIRST_RADIUS;
        for _ in 0..BALL_ROUNDS {
            cand.start_round();
            let r2 = r * r;
            let from = if r == FIRST_RADIUS { anchor } else { 0 };
            tree.within(stack, from, head, r2, hits);
            for &i in hits.iter() {
                cand.meet(c, tree, head, i as usize);
            }
            let reach = r2.sqrt() * (1.0 - 1e-12);
            if cand.separated(reach) {
                settled = true;
                break;
            }
            r = if cand.met.is_empty() {
                r * 16.0
            } else {
                // the reach that would separate the tips met so far, with room to spare
                let need = (cand.max_tip + 2.0 * EPS * 0.001) / (1.0 - 2.0 * EPS);
                (need * (1.0 + 1e-6)).max(r * (1.0 + 1e-6))
            };
            if !r.is_finite() {
                break;
            }
        }
        if !settled {
            cand.start_round();
            tree.nearest(queue, head, |i, d2| {
                let reach = d2.sqrt() * (1.0 - 1e-12);
                if cand.separated(reach) {
                    return false;
                }
                cand.meet(c, tree, head, i);
                true
            });
        }
        for i in cand.milled.drain(..) {
            tree.remove(i as usize);
        }
        let best = cand.best()?;
        let si = best.seg as usize;
        let k = cand.done_count[si];
        *last_leaf = Some(tree.remove(best.at as usize));
        cand.done_count[si] = k + 1;
        self.head = best.exit;
        self.steps_left -= 1;
        Some((si, k as usize, best.forward))
    }
}

/// The same order as [`fast_order_reference`], in about O(n log n) (see the module docs).
pub fn fast_order(ends: &[(P2, P2)], passes: &[Vec<f64>], head: P3) -> Vec<Step> {
    FastOrder::new(&Lists { ends, passes }, head).collect()
}

/// [`fast_order`] through the k-d tree whatever the size (finite input only; the property
/// test runs it on small chains as well).
#[doc(hidden)]
pub fn fast_order_indexed(ends: &[(P2, P2)], passes: &[Vec<f64>], head: P3) -> Vec<Step> {
    FastOrder::indexed(&Lists { ends, passes }, head).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boxes_round_outwards_to_the_nearest_f32() {
        let xs = [
            0.0,
            -0.0,
            0.1,
            -0.1,
            1.0,
            1e-50,
            -1e-50,
            123_456.789,
            -7e4,
            1e6,
            3.4e38,
            1e300,
            -1e300,
            f64::MAX,
            f64::MIN,
        ];
        for x in xs {
            let (lo, hi) = (down(x), up(x));
            assert!(f64::from(lo) <= x && x <= f64::from(hi), "{x}: {lo} {hi}");
            // the nearest such: one step further inwards crosses `x`
            assert!(lo == f32::MAX || f64::from(lo.next_up()) > x, "{x}: {lo}");
            assert!(hi == f32::MIN || f64::from(hi.next_down()) < x, "{x}: {hi}");
        }
        // values an f32 holds stay as they are
        assert_eq!((down(0.5), up(0.5)), (0.5, 0.5));
    }

    #[test]
    fn a_tree_holds_every_point_once_and_counts_them() {
        let ends: Vec<(P2, P2)> = (0..200)
            .map(|i| {
                let x = f64::from(i) * 0.37;
                (P2::new(x, (x * 3.0).sin()), P2::new(x + 0.37, 0.5))
            })
            .collect();
        let passes: Vec<Vec<f64>> = (0..200).map(|i| vec![1.0; 1 + i % 3]).collect();
        let lists = Lists {
            ends: &ends,
            passes: &passes,
        };
        let mut tree = PassPoints::new(&lists).expect("finite");
        let total: usize = passes.iter().map(Vec::len).sum();
        assert_eq!(tree.pts.len(), 2 * total);
        assert_eq!(tree.nodes.len(), node_count(2 * total));
        // boxes hold their points; leaves 16 to 32 points
        for (i, n) in tree.nodes.iter().enumerate() {
            for q in &tree.pts[n.start as usize..n.end as usize] {
                let [x, y, z] = q.p;
                assert!(tree.in_box(P3 { x, y, z }, i), "node {i}");
            }
            if n.left == 0 {
                assert!((LEAF / 2..=LEAF).contains(&((n.end - n.start) as usize)));
            }
        }
        // removing a point twice counts it off once
        let leaf = tree.remove(5);
        assert_eq!(tree.remove(5), leaf);
        assert_eq!(tree.nodes[0].alive as usize, 2 * total - 1);
        assert_eq!(tree.nodes[leaf].left, 0);
        assert!((tree.nodes[leaf].start..tree.nodes[leaf].end).contains(&5));
    }
}
