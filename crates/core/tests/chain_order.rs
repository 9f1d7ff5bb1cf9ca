//! The fast pass order of a chain (k-d tree, §7.2) against the spec's sequential scan on
//! thousands of random chains: polylines, closed loops, stars, grids, duplicated and
//! reversed segments, different pass counts, exact ties and near ties at scales 1e-3…1e5.
//! Deterministic: a fixed-seed SplitMix64, so every run checks the same chains.

use millpath_core::emit::chain_order::{fast_order, fast_order_indexed, fast_order_reference};
use millpath_core::geom::{P2, P3};

/// SplitMix64: tiny, deterministic, good enough to shuffle test layouts.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, n).
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }
    fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[self.below(xs.len())]
    }
}

/// Relative perturbations that land on, just inside, at and just beyond the tolerance.
const NUDGES: [f64; 9] = [0.0, 1e-12, 1e-9, 1e-7, 5e-7, 1e-6, 1.5e-6, 2e-6, 3e-6];
const SCALES: [f64; 7] = [1e-3, 1e-2, 0.1, 1.0, 37.0, 1e3, 1e5];

struct Case {
    ends: Vec<(P2, P2)>,
    passes: Vec<Vec<f64>>,
    head: P3,
}

/// Points of one layout in lattice units (small integers or halves, so many exact ties).
fn layout(rng: &mut Rng, n: usize) -> Vec<(P2, P2)> {
    let lat = |rng: &mut Rng, r: usize| {
        P2::new(
            rng.below(2 * r + 1) as f64 - r as f64,
            rng.below(2 * r + 1) as f64 - r as f64,
        )
    };
    match rng.below(6) {
        // connected polyline (random walk on a lattice)
        0 => {
            let mut p = P2::new(0.0, 0.0);
            (0..n)
                .map(|_| {
                    let q = P2::new(
                        p.x + rng.below(5) as f64 - 2.0,
                        p.y + rng.below(5) as f64 - 2.0,
                    );
                    let s = (p, q);
                    p = q;
                    s
                })
                .collect()
        }
        // closed loop: a regular-ish polygon (symmetric: many equal distances)
        1 => {
            let pts: Vec<P2> = (0..n)
                .map(|i| {
                    let a = i as f64 / n as f64 * std::f64::consts::TAU;
                    if rng.chance(0.5) {
                        P2::new(a.cos() * 4.0, a.sin() * 4.0)
                    } else {
                        // a square's outline on the lattice
                        let k = (i * 16 / n.max(1)) as f64;
                        match i * 4 / n.max(1) {
                            0 => P2::new(k, 0.0),
                            1 => P2::new(4.0, k - 4.0),
                            2 => P2::new(12.0 - k, 4.0),
                            _ => P2::new(0.0, 16.0 - k),
                        }
                    }
                })
                .collect();
            (0..n).map(|i| (pts[i], pts[(i + 1) % n])).collect()
        }
        // star: rays from one centre, out and back, some drawn twice
        2 => {
            let c = P2::new(0.0, 0.0);
            (0..n)
                .map(|_| {
                    let q = lat(rng, 3);
                    if rng.chance(0.5) {
                        (c, q)
                    } else {
                        (q, c)
                    }
                })
                .collect()
        }
        // grid: segments between lattice neighbours (exact ties everywhere)
        3 => (0..n)
            .map(|_| {
                let p = lat(rng, 3);
                let q = match rng.below(4) {
                    0 => P2::new(p.x + 1.0, p.y),
                    1 => P2::new(p.x, p.y + 1.0),
                    2 => P2::new(p.x - 1.0, p.y),
                    _ => P2::new(p.x, p.y - 1.0),
                };
                (p, q)
            })
            .collect(),
        // random segments, some of zero length
        4 => (0..n)
            .map(|_| {
                let p = lat(rng, 5);
                let q = if rng.chance(0.1) { p } else { lat(rng, 5) };
                (p, q)
            })
            .collect(),
        // a polyline traversed out and back (each segment twice, once reversed)
        _ => {
            let half = n.div_ceil(2);
            let mut pts = vec![P2::new(0.0, 0.0)];
            for _ in 0..half {
                let p = *pts.last().unwrap();
                pts.push(P2::new(
                    p.x + rng.below(3) as f64 - 1.0,
                    p.y + rng.below(3) as f64,
                ));
            }
            let mut segs: Vec<(P2, P2)> = pts.windows(2).map(|w| (w[0], w[1])).collect();
            let back: Vec<(P2, P2)> = segs.iter().rev().map(|&(a, b)| (b, a)).collect();
            segs.extend(back);
            segs.truncate(n);
            segs
        }
    }
}

/// Pass depths as §7.1 makes them, with per-segment bottoms, plus odd shapes
/// (single passes, repeated depths, a shallower pass below a deeper one).
fn passes_for(rng: &mut Rng, n: usize, unit: f64) -> Vec<Vec<f64>> {
    let top = rng.pick(&[2.0, 1.0, 20.0, 0.0]) * unit;
    let infeed = rng.pick(&[1.2, 0.6, 1.0, 0.5, 2.0]) * unit;
    let common_bottom = rng.pick(&[-0.3, -0.1, 0.0, 18.5, -2.0]) * unit;
    (0..n)
        .map(|_| {
            let bottom = if rng.chance(0.7) {
                common_bottom
            } else {
                common_bottom + (rng.below(7) as f64 - 3.0) * 0.5 * unit
            };
            let mut out = Vec::new();
            let mut z = top - infeed;
            while z >= bottom || (z - bottom).abs() <= 1e-6 * (z.abs().max(bottom.abs()) + 0.001) {
                out.push(z);
                z -= infeed;
                if out.len() > 12 {
                    break;
                }
            }
            if out
                .last()
                .is_none_or(|&l| (l - bottom).abs() > 1e-6 * (l.abs().max(bottom.abs()) + 0.001))
            {
                out.push(bottom);
            }
            match rng.below(12) {
                0 => out.truncate(1),
                1 => {
                    let l = *out.last().unwrap();
                    out.push(l); // a zero-length pass difference
                }
                2 => {
                    // nudge one depth by a near-tolerance amount
                    let i = rng.below(out.len());
                    out[i] += rng.pick(&NUDGES) * unit * if rng.chance(0.5) { 1.0 } else { -1.0 };
                }
                _ => {}
            }
            out
        })
        .collect()
}

fn make_case(rng: &mut Rng, max_n: usize) -> Case {
    let n = 1 + rng.below(max_n);
    let scale = rng.pick(&SCALES);
    let offset = P2::new(
        rng.pick(&[0.0, 1.0, -3.5, 1e3, 7e4]) * if scale >= 1.0 { 1.0 } else { scale },
        rng.pick(&[0.0, 2.0, -1e2, 5e4]) * if scale >= 1.0 { 1.0 } else { scale },
    );
    let nudge_p = rng.pick(&[0.0, 0.05, 0.3]);
    let mut ends = layout(rng, n);
    // reverse some segments, duplicate some, nudge some points by near-tolerance amounts
    for s in ends.iter_mut() {
        if rng.chance(0.2) {
            *s = (s.1, s.0);
        }
    }
    if rng.chance(0.3) {
        for _ in 0..1 + rng.below(3) {
            let i = rng.below(ends.len());
            let s = ends[i];
            let j = rng.below(ends.len() + 1);
            ends.insert(j, s);
        }
    }
    let place = |rng: &mut Rng, p: P2| {
        let mut q = P2::new(p.x * scale + offset.x, p.y * scale + offset.y);
        if rng.chance(nudge_p) {
            let mag = q.x.abs().max(q.y.abs()).max(scale);
            q.x += rng.pick(&NUDGES) * mag * if rng.chance(0.5) { 1.0 } else { -1.0 };
        }
        if rng.chance(nudge_p) {
            let mag = q.x.abs().max(q.y.abs()).max(scale);
            q.y += rng.pick(&NUDGES) * mag * if rng.chance(0.5) { 1.0 } else { -1.0 };
        }
        q
    };
    let ends: Vec<(P2, P2)> = ends
        .into_iter()
        .map(|(a, b)| (place(rng, a), place(rng, b)))
        .collect();
    let n = ends.len();
    let passes = passes_for(rng, n, scale);
    let head = if rng.chance(0.85) {
        ends[0].0.with_z(passes[0][0])
    } else {
        let (a, b) = ends[rng.below(n)];
        P3 {
            x: (a.x + b.x) / 2.0,
            y: a.y,
            z: passes[0][0] + scale,
        }
    };
    Case { ends, passes, head }
}

fn check(rng: &mut Rng, cases: usize, max_n: usize) {
    for case_no in 0..cases {
        let c = make_case(rng, max_n);
        let want = fast_order_reference(&c.ends, &c.passes, c.head);
        let got = fast_order(&c.ends, &c.passes, c.head);
        let total: usize = c.passes.iter().map(Vec::len).sum();
        assert_eq!(want.len(), total);
        // the tree also on chains small enough for `fast_order` to scan them directly
        // (the random chains are finite)
        let indexed = fast_order_indexed(&c.ends, &c.passes, c.head);
        assert_eq!(indexed, want, "case {case_no}: the tree's order");
        if got != want {
            let i = got.iter().zip(&want).take_while(|(g, w)| g == w).count();
            panic!(
                "case {case_no}: orders differ at step {i} of {total}: fast {:?}, reference {:?}\n\
                 ends {:?}\npasses {:?}\nhead {:?}",
                got.get(i),
                want.get(i),
                c.ends,
                c.passes,
                c.head
            );
        }
    }
}

#[test]
fn fast_order_equals_the_sequential_scan_on_small_chains() {
    check(&mut Rng(0x6D69_6C6C_7061_7468), 6000, 24);
}

#[test]
fn fast_order_equals_the_sequential_scan_on_larger_chains() {
    check(&mut Rng(0x0DE5_1DE5), 60, 300);
}

#[test]
fn open_line_alternates_and_closed_loop_keeps_direction() {
    // §7.2's consequences, as a readable anchor for the random test
    let line: Vec<(P2, P2)> = (0..3)
        .map(|i| (P2::new(i as f64, 0.0), P2::new(i as f64 + 1.0, 0.0)))
        .collect();
    let passes = vec![vec![0.8, -0.3]; 3];
    let head = line[0].0.with_z(0.8);
    let want = vec![
        (0, true),
        (1, true),
        (2, true),
        (2, false),
        (1, false),
        (0, false),
    ];
    assert_eq!(fast_order(&line, &passes, head), want);
    assert_eq!(fast_order_reference(&line, &passes, head), want);

    let sq = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let loop_: Vec<(P2, P2)> = (0..4)
        .map(|i| {
            let (a, b) = (sq[i], sq[(i + 1) % 4]);
            (P2::new(a.0, a.1), P2::new(b.0, b.1))
        })
        .collect();
    let passes = vec![vec![0.8, -0.3]; 4];
    let head = loop_[0].0.with_z(0.8);
    let got = fast_order(&loop_, &passes, head);
    assert!(got.iter().all(|&(_, fwd)| fwd), "{got:?}");
    assert_eq!(got, fast_order_reference(&loop_, &passes, head));
}

#[test]
fn non_finite_input_falls_back_to_the_scan() {
    let ends = vec![
        (P2::new(0.0, 0.0), P2::new(1.0, 0.0)),
        (P2::new(1.0, 0.0), P2::new(f64::NAN, 0.0)),
    ];
    let passes = vec![vec![1.0, 0.0], vec![1.0]];
    let head = ends[0].0.with_z(1.0);
    assert_eq!(
        fast_order(&ends, &passes, head),
        fast_order_reference(&ends, &passes, head)
    );
}

#[test]
fn long_zigzag_and_long_loop() {
    // the shape the timing example draws, open and closed, with uneven pass counts
    let n = 1500;
    let pt = |i: usize| P2::new(i as f64 * 2.0, (i % 2) as f64 * 3.0);
    let mut ends: Vec<(P2, P2)> = (0..n).map(|i| (pt(i), pt(i + 1))).collect();
    let passes: Vec<Vec<f64>> = (0..n)
        .map(|i| match i % 7 {
            0 => vec![0.8],
            3 => vec![0.8, -0.3, -1.0],
            _ => vec![0.8, -0.3],
        })
        .collect();
    let head = ends[0].0.with_z(0.8);
    assert_eq!(
        fast_order(&ends, &passes, head),
        fast_order_reference(&ends, &passes, head)
    );
    ends.push((pt(n), pt(0)));
    let mut passes = passes;
    passes.push(vec![0.8, -0.3]);
    assert_eq!(
        fast_order(&ends, &passes, head),
        fast_order_reference(&ends, &passes, head)
    );
}
