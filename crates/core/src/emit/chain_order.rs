//! Order of the passes ("edges") of a fast-milled chain (§7.2): greedy nearest edge.
//!
//! [`fast_order_reference`] is the spec's sequential scan, quadratic in the number of
//! segments. [`fast_order`] gives the identical order in about O(n log n): the end points of
//! all passes, as 3-D points `[x, y, z_pass]`, sit in a static k-d tree that a pass leaves
//! once it is milled; the candidate of a segment is its next pass (points of deeper passes
//! are skipped). Each step runs the spec's scan over only the candidates nearest the head.
//!
//! Why that is exact. Let S be a set of candidates such that every tip in S is `lt` every
//! tip outside S. In the full scan a candidate outside S never replaces a best from S (its
//! tip is larger), and the first member of S met replaces any best from outside S; from
//! there on the best stays in S and changes exactly as in a scan over S alone, in list
//! order. So scanning S alone gives the full scan's answer. S is grown nearest-first until
//! the next point is at least `L` away with `L − M > 2·eps·(L + 0.001)`, `M` the largest tip
//! in S. A candidate not yet met has both its points at ≥ `L`, so its tip `f ≥ L`, and for
//! every tip `a ≤ M` of S: `f − a ≥ (f − L) + (L − M) > eps·(f + 0.001) + eps·(L + 0.001)`,
//! i.e. `lt(a, f)` with a margin far above rounding. Without such a gap S ends up holding
//! every candidate: the full scan. `L` is a lower bound of the spec's distance: queue keys
//! are squared distances computed like [`P3::dist`] (bounding boxes: of the clamped head,
//! never more), shrunk by 1e-12. Non-finite input falls back to the reference scan.

use crate::geom::{lt, EPS, P2, P3};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// One step of the order: the segment whose next pass is milled, and whether it is milled
/// from its start to its end (`true`) or backwards.
pub type Step = (usize, bool);

/// The spec's scan (§7.2), verbatim: for every step all segments in list order, the
/// candidate of a segment is its next pass; entered at the start iff `lt(ds, de)`; it
/// replaces the best iff its tip is `lt` the best's tip. `ends[i]` are the start and end of
/// segment `i`, `passes[i]` its pass depths, `head` the 3-D start position.
#[doc(hidden)]
pub fn fast_order_reference(ends: &[(P2, P2)], passes: &[Vec<f64>], head: P3) -> Vec<Step> {
    let total: usize = passes.iter().map(Vec::len).sum();
    let mut done_count = vec![0usize; passes.len()];
    let mut head = head;
    let mut order = Vec::with_capacity(total);
    for _ in 0..total {
        let mut best: Option<(usize, bool, f64)> = None;
        for (si, &(a, b)) in ends.iter().enumerate() {
            let k = done_count[si];
            if k >= passes[si].len() {
                continue;
            }
            let z = passes[si][k];
            let ds = head.dist(a.with_z(z));
            let de = head.dist(b.with_z(z));
            let forward = lt(ds, de);
            let tip = ds.min(de);
            if best.is_none_or(|(_, _, bt)| lt(tip, bt)) {
                best = Some((si, forward, tip));
            }
        }
        let Some((si, forward, _)) = best else { break };
        let z = passes[si][done_count[si]];
        done_count[si] += 1;
        order.push((si, forward));
        // the end of the geometry in pass direction (a reversed geometry ends at the start)
        let (a, b) = ends[si];
        head = if forward { b } else { a }.with_z(z);
    }
    order
}

/// The end points of all passes of all segments in a static k-d tree, from which points
/// are only removed: a pass leaves when it is milled. Nodes know how many of their points
/// are left, so emptied parts of the drawing cost nothing.
struct PassPoints {
    /// Points in tree order: `[x, y, z]` and the segment and pass they belong to.
    pts: Vec<[f64; 3]>,
    /// 32-bit indices (the emitter stops at two million moves): a long chain has millions
    /// of points, and these lists live while its passes are ordered.
    owner: Vec<(u32, u32)>,
    alive: Vec<bool>,
    /// Tree position of the start (end) point of pass `k` of segment `si`:
    /// `pos[2 · (first[si] + k)]` (`+ 1`).
    pos: Vec<u32>,
    first: Vec<usize>,
    nodes: Vec<KdNode>,
    /// Per point: the node a ball of [`FIRST_RADIUS`] around it may start from (see
    /// [`PassPoints::anchor_leaves`]); in a chain the head is such a point at most steps.
    anchor: Vec<u32>,
    /// Per point: its leaf (removal walks up from there).
    leaf: Vec<u32>,
}

/// Best-first queue of a query: (squared distance or its lower bound, node or point).
type Queue = BinaryHeap<Reverse<(u64, usize)>>;

struct KdNode {
    lo: [f64; 3],
    hi: [f64; 3],
    /// The node's points are `pts[start..end]`; `left` is 0 for a leaf, else the children
    /// are `left` and `left + 1`.
    start: usize,
    end: usize,
    left: usize,
    alive: usize,
    /// The parent node (the root's is 0).
    parent: usize,
}

const LEAF: usize = 8;
/// Marks a point (rather than a node) in the query heap.
const POINT: usize = 1 << (usize::BITS - 1);

/// Squared distance between two bounding boxes: a lower bound for any two of their points.
fn box_gap2(a: &KdNode, b: &KdNode) -> f64 {
    (0..3)
        .map(|i| {
            let gap = (b.lo[i] - a.hi[i]).max(a.lo[i] - b.hi[i]).max(0.0);
            gap * gap
        })
        .sum()
}

/// Squared distance, the same expression as [`P3::dist`] before its square root.
fn dist2(h: P3, p: [f64; 3]) -> f64 {
    let (dx, dy, dz) = (h.x - p[0], h.y - p[1], h.z - p[2]);
    dx * dx + dy * dy + dz * dz
}

impl PassPoints {
    fn new(ends: &[(P2, P2)], passes: &[Vec<f64>]) -> Self {
        // slot 2·j (+ 1): the start (end) point of the j-th pass of all segments
        let mut first = Vec::with_capacity(passes.len());
        let total: usize = passes.iter().map(Vec::len).sum();
        let mut owner_of_pass: Vec<(u32, u32)> = Vec::with_capacity(total);
        let mut items: Vec<([f64; 3], usize)> = Vec::with_capacity(2 * total);
        for (si, &(a, b)) in ends.iter().enumerate() {
            first.push(owner_of_pass.len());
            for (k, &z) in passes[si].iter().enumerate() {
                let slot = 2 * owner_of_pass.len();
                owner_of_pass.push((si as u32, k as u32));
                items.push(([a.x, a.y, z], slot));
                items.push(([b.x, b.y, z], slot + 1));
            }
        }
        let mut nodes = Vec::new();
        if !items.is_empty() {
            nodes.push(KdNode {
                lo: [0.0; 3],
                hi: [0.0; 3],
                start: 0,
                end: items.len(),
                left: 0,
                alive: items.len(),
                parent: 0,
            });
            Self::build(&mut nodes, &mut items, 0);
        }
        let mut pos = vec![0; items.len()];
        let mut pts = Vec::with_capacity(items.len());
        let mut owner = Vec::with_capacity(items.len());
        for (i, &(p, slot)) in items.iter().enumerate() {
            pos[slot] = i as u32;
            pts.push(p);
            owner.push(owner_of_pass[slot / 2]);
        }
        // gone before the next lists are made (a chain of a million passes)
        drop((items, owner_of_pass));
        let mut anchor = vec![0; pts.len()];
        let mut leaf = vec![0; pts.len()];
        if !nodes.is_empty() {
            Self::anchor_leaves(&nodes, 0, &mut Vec::new(), &mut anchor, &mut leaf);
        }
        PassPoints {
            alive: vec![true; pts.len()],
            pts,
            owner,
            pos,
            first,
            nodes,
            anchor,
            leaf,
        }
    }

    /// Sets `anchor` of the points below node `n` (`path`: its ancestors): the highest
    /// ancestor of a point's leaf whose other child's bounding box comes within
    /// `4 · FIRST_RADIUS` of the leaf's box, else the leaf. Every point outside the anchor's
    /// subtree is farther than that from every point of the leaf (boxes never change), so a
    /// first ball around a point of the leaf finds all its points below the anchor.
    /// Also sets `leaf` of these points.
    fn anchor_leaves(
        nodes: &[KdNode],
        n: usize,
        path: &mut Vec<usize>,
        anchor: &mut [u32],
        leaf: &mut [u32],
    ) {
        let left = nodes[n].left;
        if left != 0 {
            // depth ≤ log2 of the point count: the tree is balanced
            path.push(n);
            Self::anchor_leaves(nodes, left, path, anchor, leaf);
            Self::anchor_leaves(nodes, left + 1, path, anchor, leaf);
            path.pop();
            return;
        }
        leaf[nodes[n].start..nodes[n].end].fill(n as u32);
        let reach2 = (4.0 * FIRST_RADIUS) * (4.0 * FIRST_RADIUS);
        let (mut at, mut child) = (n, n);
        for &x in path.iter().rev() {
            let l = nodes[x].left;
            let sibling = if child == l { l + 1 } else { l };
            if box_gap2(&nodes[n], &nodes[sibling]) <= reach2 {
                at = x;
            }
            child = x;
        }
        anchor[nodes[n].start..nodes[n].end].fill(at as u32);
    }

    fn build(nodes: &mut Vec<KdNode>, items: &mut [([f64; 3], usize)], at: usize) {
        let (start, end) = (nodes[at].start, nodes[at].end);
        let part = &mut items[start..end];
        let (mut lo, mut hi) = (part[0].0, part[0].0);
        for (p, _) in part.iter() {
            for i in 0..3 {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        }
        nodes[at].lo = lo;
        nodes[at].hi = hi;
        if part.len() <= LEAF {
            return;
        }
        let axis = (0..3)
            .max_by(|&i, &j| (hi[i] - lo[i]).total_cmp(&(hi[j] - lo[j])))
            .unwrap_or(0);
        let mid = part.len() / 2;
        part.select_nth_unstable_by(mid, |p, q| p.0[axis].total_cmp(&q.0[axis]));
        let left = nodes.len();
        nodes[at].left = left;
        for (s, e) in [(start, start + mid), (start + mid, end)] {
            nodes.push(KdNode {
                lo,
                hi,
                start: s,
                end: e,
                left: 0,
                alive: e - s,
                parent: at,
            });
        }
        Self::build(nodes, items, left);
        Self::build(nodes, items, left + 1);
    }

    /// Takes out both end points of pass `k` of segment `si`.
    fn remove(&mut self, si: usize, k: usize) {
        for slot in [2 * (self.first[si] + k), 2 * (self.first[si] + k) + 1] {
            let at = self.pos[slot] as usize;
            debug_assert!(self.alive[at], "a pass is milled once");
            self.alive[at] = false;
            // up from the point's leaf to the root
            let mut n = self.leaf[at] as usize;
            loop {
                self.nodes[n].alive -= 1;
                if n == 0 {
                    break;
                }
                n = self.nodes[n].parent;
            }
        }
    }

    /// Lower bound of the squared distance from `h` to the points of node `n`.
    fn node_dist2(&self, h: P3, n: usize) -> f64 {
        let KdNode { lo, hi, .. } = self.nodes[n];
        dist2(
            h,
            [
                h.x.clamp(lo[0], hi[0]),
                h.y.clamp(lo[1], hi[1]),
                h.z.clamp(lo[2], hi[2]),
            ],
        )
    }

    fn push_node(&self, queue: &mut Queue, h: P3, n: usize) {
        if self.nodes[n].alive > 0 {
            let d2 = self.node_dist2(h, n);
            queue.push(Reverse((d2.to_bits(), n)));
        }
    }

    /// Calls `visit(point)` for every point left below node `from` whose squared distance
    /// from `h` is at most `r2` (in tree order). A depth-first walk with a reused stack: no
    /// heap, no allocation.
    fn within(
        &self,
        stack: &mut Vec<usize>,
        from: usize,
        h: P3,
        r2: f64,
        mut visit: impl FnMut(usize),
    ) {
        stack.clear();
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
            } = self.nodes[n];
            if alive == 0 || self.node_dist2(h, n) > r2 {
                continue;
            }
            if left != 0 {
                stack.push(left + 1);
                stack.push(left);
                continue;
            }
            for i in start..end {
                if self.alive[i] && dist2(h, self.pts[i]) <= r2 {
                    visit(i);
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
                self.push_node(queue, h, left);
                self.push_node(queue, h, left + 1);
            } else {
                for i in start..end {
                    if self.alive[i] {
                        let d2 = dist2(h, self.pts[i]);
                        queue.push(Reverse((d2.to_bits(), i | POINT)));
                    }
                }
            }
        }
    }
}

/// The candidates of one step, found in the k-d tree.
struct Candidates<'a> {
    ends: &'a [(P2, P2)],
    passes: &'a [Vec<f64>],
    done_count: Vec<usize>,
    /// The round in which a segment was last met (0 = never): each segment counts once.
    met_in: Vec<usize>,
    round: usize,
    /// (segment, forward, tip) of the candidates met in this round.
    met: Vec<(usize, bool, f64)>,
    max_tip: f64,
}

impl Candidates<'_> {
    fn start_round(&mut self) {
        self.round += 1;
        self.met.clear();
        self.max_tip = f64::NEG_INFINITY;
    }

    /// Point `i` of the tree was reached: its segment is a candidate if the point belongs
    /// to the segment's next pass (deeper passes are no candidates yet).
    fn meet(&mut self, tree: &PassPoints, head: P3, i: usize) {
        let (si, k) = tree.owner[i];
        let (si, k) = (si as usize, k as usize);
        if k != self.done_count[si] || self.met_in[si] == self.round {
            return;
        }
        self.met_in[si] = self.round;
        let (a, b) = self.ends[si];
        let z = self.passes[si][k];
        let ds = head.dist(a.with_z(z));
        let de = head.dist(b.with_z(z));
        let tip = ds.min(de);
        self.max_tip = self.max_tip.max(tip);
        self.met.push((si, lt(ds, de), tip));
    }

    /// Whether every candidate not met (all its points at least `reach` away) has a tip
    /// `lt` every tip met (the gap of the module docs).
    fn separated(&self, reach: f64) -> bool {
        !self.met.is_empty() && reach - self.max_tip > 2.0 * EPS * (reach + 0.001)
    }

    /// The spec's scan over the met candidates, in list order.
    fn best(&mut self) -> Option<(usize, bool)> {
        self.met.sort_unstable_by_key(|m| m.0);
        let mut best: Option<(usize, bool, f64)> = None;
        for &(si, forward, tip) in &self.met {
            if best.is_none_or(|(_, _, bt)| lt(tip, bt)) {
                best = Some((si, forward, tip));
            }
        }
        best.map(|(si, forward, _)| (si, forward))
    }
}

/// Chains up to this many segments are ordered by the spec's scan directly.
const SMALL_CHAIN: usize = 8;
/// First ball radius: separates a candidate at the head (tip 0) from all others.
const FIRST_RADIUS: f64 = 1e-8;
/// Balls tried per step before the nearest-first walk takes over.
const BALL_ROUNDS: usize = 8;

/// The same order as [`fast_order_reference`], in about O(n log n) (see the module docs).
///
/// Each step first tries balls around the head: all points within radius `r` are met, and
/// when the candidates met are separated from every point outside (`reach = r`, shrunk like
/// the queue keys), they form a valid set `S`. In a chain the next segment usually starts
/// at the head, so one small ball settles the step. A ball without candidates grows 16-fold,
/// one whose candidates are not yet separated grows to the radius that would separate them;
/// after [`BALL_ROUNDS`] balls the nearest-first walk decides.
pub fn fast_order(ends: &[(P2, P2)], passes: &[Vec<f64>], head: P3) -> Vec<Step> {
    let finite = |p: P2| p.x.is_finite() && p.y.is_finite();
    let all_finite = finite(head.xy())
        && head.z.is_finite()
        && ends.iter().all(|&(a, b)| finite(a) && finite(b))
        && passes.iter().flatten().all(|z| z.is_finite());
    if !all_finite {
        return fast_order_reference(ends, passes, head);
    }
    assert_eq!(ends.len(), passes.len(), "one pass list per segment");
    if ends.len() <= SMALL_CHAIN {
        // a handful of segments: the scan itself is cheaper than building a tree
        return fast_order_reference(ends, passes, head);
    }
    fast_order_indexed(ends, passes, head)
}

/// [`fast_order`] through the k-d tree whatever the size (finite input only; the property
/// test runs it on small chains as well).
#[doc(hidden)]
pub fn fast_order_indexed(ends: &[(P2, P2)], passes: &[Vec<f64>], head: P3) -> Vec<Step> {
    let n = ends.len();
    let total: usize = passes.iter().map(Vec::len).sum();
    let mut tree = PassPoints::new(ends, passes);
    let mut c = Candidates {
        ends,
        passes,
        done_count: vec![0usize; n],
        met_in: vec![0usize; n],
        round: 0,
        met: Vec::new(),
        max_tip: f64::NEG_INFINITY,
    };
    let mut queue = Queue::new();
    let mut stack = Vec::new();
    // the tree position of the point the head is at: the end of the pass just milled
    let mut head_point: Option<usize> = None;
    let mut head = head;
    let mut order = Vec::with_capacity(total);
    for _ in 0..total {
        let mut settled = false;
        let mut r = FIRST_RADIUS;
        for _ in 0..BALL_ROUNDS {
            c.start_round();
            let r2 = r * r;
            // a first ball around the end of the last pass starts at that point's anchor
            let from = match head_point {
                Some(p) if r == FIRST_RADIUS => tree.anchor[p] as usize,
                _ => 0,
            };
            tree.within(&mut stack, from, head, r2, |i| c.meet(&tree, head, i));
            let reach = r2.sqrt() * (1.0 - 1e-12);
            if c.separated(reach) {
                settled = true;
                break;
            }
            r = if c.met.is_empty() {
                r * 16.0
            } else {
                // the reach that would separate the tips met so far, with room to spare
                let need = (c.max_tip + 2.0 * EPS * 0.001) / (1.0 - 2.0 * EPS);
                (need * (1.0 + 1e-6)).max(r * (1.0 + 1e-6))
            };
            if !r.is_finite() {
                break;
            }
        }
        if !settled {
            c.start_round();
            tree.nearest(&mut queue, head, |i, d2| {
                let reach = d2.sqrt() * (1.0 - 1e-12);
                if c.separated(reach) {
                    return false;
                }
                c.meet(&tree, head, i);
                true
            });
        }
        let Some((si, forward)) = c.best() else { break };
        let (a, b) = ends[si];
        let k = c.done_count[si];
        let z = passes[si][k];
        tree.remove(si, k);
        c.done_count[si] = k + 1;
        order.push((si, forward));
        head = if forward { b } else { a }.with_z(z);
        head_point = Some(tree.pos[2 * (tree.first[si] + k) + usize::from(forward)] as usize);
    }
    order
}
