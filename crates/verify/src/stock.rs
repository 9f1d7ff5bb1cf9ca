//! The 2.5-D stock model: a height field on a grid of square cells. A cell is cut when its
//! centre lies under the tool's footprint (a disc of the tool radius around the tool axis);
//! its height becomes the lowest tool tip over the part of the move where that holds. Both
//! straight moves and XY arcs are handled exactly (z is linear along a move), so no sampling
//! error enters the heights.
//!
//! 2.5-D height field: cells lowered exactly to the lowest tool tip over the part of a line or XY
//! arc whose footprint covers the cell centre; rapid intrusion; removed volume.

use crate::machine::ArcGeo;

/// Grid geometry: cell (i, j) has its centre at (x0 + (i + ½)·cell, y0 + (j + ½)·cell).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridGeom {
    pub x0: f64,
    pub y0: f64,
    pub cell: f64,
    pub nx: usize,
    pub ny: usize,
}

impl GridGeom {
    fn centre(&self, i: usize, j: usize) -> (f64, f64) {
        (
            self.x0 + (i as f64 + 0.5) * self.cell,
            self.y0 + (j as f64 + 0.5) * self.cell,
        )
    }
    /// Index range of the cells whose centres lie in [lo, hi] along one axis.
    fn range(&self, origin: f64, n: usize, lo: f64, hi: f64) -> Option<(usize, usize)> {
        let a = ((lo - origin) / self.cell - 0.5).ceil();
        let b = ((hi - origin) / self.cell - 0.5).floor();
        if !(a.is_finite() && b.is_finite()) || b < 0.0 || a > (n as f64 - 1.0) || a > b {
            return None;
        }
        Some((a.max(0.0) as usize, (b.min(n as f64 - 1.0)) as usize))
    }
}

/// Calls `f(index, zmin, x, y)` for every cell whose centre the footprint (radius `r`) covers
/// during the straight move a → b; `zmin` is the lowest tool tip while it does. Returns the
/// number of cells looked at.
pub fn visit_line(
    g: &GridGeom,
    a: [f64; 3],
    b: [f64; 3],
    r: f64,
    mut f: impl FnMut(usize, f64, f64, f64),
) -> u64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let z_at = |t: f64| a[2] + t * (b[2] - a[2]);
    let mut work = 0u64;
    let Some((j0, j1)) = g.range(g.y0, g.ny, a[1].min(b[1]) - r, a[1].max(b[1]) + r) else {
        return 0;
    };
    for j in j0..=j1 {
        let yc = g.y0 + (j as f64 + 0.5) * g.cell;
        // the part of the segment within r of this row, in x
        let (t_lo, t_hi) = if dy.abs() < 1e-12 {
            if (a[1] - yc).abs() > r {
                continue;
            }
            (0.0, 1.0)
        } else {
            let t1 = (yc - r - a[1]) / dy;
            let t2 = (yc + r - a[1]) / dy;
            (t1.min(t2).max(0.0), t1.max(t2).min(1.0))
        };
        if t_lo > t_hi {
            continue;
        }
        let (xa, xb) = (a[0] + t_lo * dx, a[0] + t_hi * dx);
        let Some((i0, i1)) = g.range(g.x0, g.nx, xa.min(xb) - r, xa.max(xb) + r) else {
            continue;
        };
        for i in i0..=i1 {
            work += 1;
            let (px, py) = g.centre(i, j);
            let (wx, wy) = (a[0] - px, a[1] - py);
            let c = wx * wx + wy * wy - r * r;
            let (ta, tb) = if len2 < 1e-18 {
                if c > 0.0 {
                    continue;
                }
                (0.0, 1.0)
            } else {
                let bq = 2.0 * (dx * wx + dy * wy);
                let disc = bq * bq - 4.0 * len2 * c;
                if disc < 0.0 {
                    continue;
                }
                let sq = disc.sqrt();
                let ta = ((-bq - sq) / (2.0 * len2)).max(0.0);
                let tb = ((-bq + sq) / (2.0 * len2)).min(1.0);
                if ta > tb {
                    continue;
                }
                (ta, tb)
            };
            f(j * g.nx + i, z_at(ta).min(z_at(tb)), px, py);
        }
    }
    work
}

/// As `visit_line`, for an arc from height z0 to z1 (z linear in the angle).
pub fn visit_arc(
    g: &GridGeom,
    arc: &ArcGeo,
    z0: f64,
    z1: f64,
    r: f64,
    mut f: impl FnMut(usize, f64, f64, f64),
) -> u64 {
    let (bx0, by0, bx1, by1) = arc.bbox();
    let Some((j0, j1)) = g.range(g.y0, g.ny, by0 - r, by1 + r) else {
        return 0;
    };
    let Some((i0, i1)) = g.range(g.x0, g.nx, bx0 - r, bx1 + r) else {
        return 0;
    };
    let z_at = |s: f64| z0 + s * (z1 - z0);
    let big_r = arc.r;
    let sweep = arc.sweep;
    // most arcs keep their height (only helixes change it): one atan2 a cell, no acos/cos
    let flat = z0 == z1;
    let ends = (arc.point(0.0), arc.point(1.0));
    let mut work = 0u64;
    for j in j0..=j1 {
        for i in i0..=i1 {
            work += 1;
            let (px, py) = g.centre(i, j);
            // sqrt, not hypot: coordinates are bounded (±1e6), and libm's hypot is slow
            let (ux, uy) = (px - arc.cx, py - arc.cy);
            let d = (ux * ux + uy * uy).sqrt();
            let zmin = if d + big_r <= r {
                // the whole circle is under the footprint
                Some(z0.min(z1))
            } else if d < 1e-12 {
                None
            } else {
                let k = (big_r * big_r + d * d - r * r) / (2.0 * big_r * d);
                if k > 1.0 {
                    None
                } else if k <= -1.0 {
                    Some(z0.min(z1))
                } else if flat {
                    // a flat arc cuts the cell at its height when the footprint reaches it:
                    // where the cell's nearest circle point lies on the arc, or an end does
                    let phi = (py - arc.cy).atan2(px - arc.cx);
                    let rel = if sweep >= 0.0 {
                        (phi - arc.a0).rem_euclid(std::f64::consts::TAU)
                    } else {
                        (arc.a0 - phi).rem_euclid(std::f64::consts::TAU)
                    };
                    let reach = (r + 1e-12) * (r + 1e-12);
                    let near_end = |(ex, ey): (f64, f64)| {
                        (px - ex) * (px - ex) + (py - ey) * (py - ey) <= reach
                    };
                    let hit = rel <= sweep.abs() || near_end(ends.0) || near_end(ends.1);
                    hit.then_some(z0)
                } else {
                    let w = k.acos();
                    let phi = (py - arc.cy).atan2(px - arc.cx);
                    let inside = |s: f64| (arc.a0 + s * sweep - phi).cos() >= k - 1e-12;
                    let mut best: Option<f64> = None;
                    let mut take = |s: f64| {
                        let z = z_at(s);
                        best = Some(best.map_or(z, |b: f64| b.min(z)));
                    };
                    if inside(0.0) {
                        take(0.0);
                    }
                    if inside(1.0) {
                        take(1.0);
                    }
                    if sweep.abs() > 1e-15 {
                        let period = std::f64::consts::TAU / sweep.abs();
                        for target in [phi + w, phi - w] {
                            let base = (target - arc.a0) / sweep;
                            let mut n = (-base / period).ceil();
                            for _ in 0..4 {
                                let s = base + n * period;
                                if s > 1.0 {
                                    break;
                                }
                                if s >= 0.0 {
                                    take(s);
                                }
                                n += 1.0;
                            }
                        }
                    }
                    best
                }
            };
            if let Some(z) = zmin {
                f(j * g.nx + i, z, px, py);
            }
        }
    }
    work
}

/// The height field.
pub struct Stock {
    pub geom: GridGeom,
    pub top: f64,
    pub heights: Vec<f64>,
}

impl Stock {
    pub fn new(geom: GridGeom, top: f64) -> Stock {
        Stock {
            geom,
            top,
            heights: vec![top; geom.nx * geom.ny],
        }
    }

    pub fn cut_line(&mut self, a: [f64; 3], b: [f64; 3], r: f64) -> u64 {
        let h = &mut self.heights;
        visit_line(&self.geom, a, b, r, |k, z, _, _| {
            if z < h[k] {
                h[k] = z;
            }
        })
    }

    pub fn cut_arc(&mut self, arc: &ArcGeo, z0: f64, z1: f64, r: f64) -> u64 {
        let h = &mut self.heights;
        visit_arc(&self.geom, arc, z0, z1, r, |k, z, _, _| {
            if z < h[k] {
                h[k] = z;
            }
        })
    }

    /// The deepest intrusion of the tool tip below the stock surface during the straight
    /// move a → b with footprint radius r: (depth, x, y), depth > 0 only.
    pub fn intrusion(&self, a: [f64; 3], b: [f64; 3], r: f64) -> (Option<(f64, f64, f64)>, u64) {
        let mut worst: Option<(f64, f64, f64)> = None;
        let h = &self.heights;
        let work = visit_line(&self.geom, a, b, r, |k, z, x, y| {
            let depth = h[k] - z;
            if depth > 0.0 && !matches!(worst, Some(w) if w.0 >= depth) {
                worst = Some((depth, x, y));
            }
        });
        (worst, work)
    }

    /// ∫ (top − height) over the grid, mm³.
    pub fn removed_volume(&self) -> f64 {
        let area = self.geom.cell * self.geom.cell;
        self.heights
            .iter()
            .map(|h| (self.top - h).max(0.0))
            .sum::<f64>()
            * area
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> Stock {
        Stock::new(
            GridGeom {
                x0: -10.0,
                y0: -10.0,
                cell: 0.1,
                nx: 200,
                ny: 200,
            },
            2.0,
        )
    }

    #[test]
    fn a_slot_removes_its_volume() {
        let mut s = grid();
        s.cut_line([-5.0, 0.0, -1.0], [5.0, 0.0, -1.0], 1.0);
        // 10 × 2 rectangle + a disc of radius 1, 3 deep
        let want = (20.0 + std::f64::consts::PI) * 3.0;
        assert!(
            (s.removed_volume() - want).abs() / want < 0.02,
            "{}",
            s.removed_volume()
        );
        assert!(s
            .intrusion([-5.0, 0.0, -1.0], [5.0, 0.0, -1.0], 0.8)
            .0
            .is_none());
        let (hit, _) = s.intrusion([-5.0, 0.0, -1.0], [-5.0, 5.0, -1.0], 0.8);
        assert!((hit.unwrap().0 - 3.0).abs() < 1e-9);
    }

    #[test]
    fn a_ramp_cuts_each_cell_at_its_lowest_tool_tip() {
        let mut s = grid();
        s.cut_line([0.0, 0.0, 2.0], [4.0, 0.0, -2.0], 0.5);
        // at x = 4.5 only the end disc reaches: lowest tip −2
        let k = 100 * 200 + 144; // centre (4.45, 0.05)
        assert!((s.heights[k] + 2.0).abs() < 1e-9, "{}", s.heights[k]);
        // at x = 1.05 the tip is lowest at the front edge of the footprint: t = (1.05+r)/4
        let k = 100 * 200 + 110; // centre (1.05, 0.05)
        let t = (1.05 + (0.25f64 - 0.0025).sqrt()) / 4.0;
        assert!((s.heights[k] - (2.0 - 4.0 * t)).abs() < 1e-9);
    }

    #[test]
    fn flat_arcs_cut_the_cells_the_general_rule_cuts() {
        // the flat shortcut against the general rule (a tiny rise makes the arc not flat):
        // the same cells, apart from cells exactly on the footprint's edge
        let g = GridGeom {
            x0: -10.0,
            y0: -10.0,
            cell: 0.25,
            nx: 80,
            ny: 80,
        };
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut cells = 0;
        for _ in 0..300 {
            let arc = ArcGeo {
                cx: rnd() * 8.0 - 4.0,
                cy: rnd() * 8.0 - 4.0,
                r: 0.2 + rnd() * 5.0,
                a0: rnd() * 7.0 - 3.5,
                sweep: (rnd() * 2.0 - 1.0) * 7.0,
            };
            let r = 0.1 + rnd() * 2.0;
            let collect = |z1: f64| {
                let mut m = std::collections::BTreeMap::new();
                visit_arc(&g, &arc, -1.0, z1, r, |k, z, _, _| {
                    m.insert(k, z);
                });
                m
            };
            let (flat, general) = (collect(-1.0), collect(-1.0 + 1e-9));
            cells += flat.len();
            for k in flat.keys().chain(general.keys()) {
                match (flat.get(k), general.get(k)) {
                    (Some(a), Some(b)) => assert!((a - b).abs() < 1e-8),
                    _ => {
                        // on the edge: the cell centre's distance to the arc is r
                        let (px, py) = g.centre(k % g.nx, k / g.nx);
                        let dist = (0..=20000)
                            .map(|i| {
                                let (x, y) = arc.point(f64::from(i) / 20000.0);
                                (px - x).hypot(py - y)
                            })
                            .fold(f64::INFINITY, f64::min);
                        assert!(
                            (dist - r).abs() < 1e-3,
                            "{arc:?} r {r}: cell {k} at distance {dist}"
                        );
                    }
                }
            }
        }
        assert!(cells > 10_000, "{cells}");
    }

    #[test]
    fn a_helix_clears_its_disc() {
        let mut s = grid();
        let arc = ArcGeo {
            cx: 0.0,
            cy: 0.0,
            r: 0.5,
            a0: -std::f64::consts::FRAC_PI_2,
            sweep: -std::f64::consts::TAU,
        };
        s.cut_arc(&arc, 1.0, -0.5, 1.0);
        s.cut_arc(&arc, -0.5, -0.5, 1.0);
        // the whole disc of radius 1.5 is at −0.5
        assert!(s
            .intrusion([0.0, -0.5, -0.5], [0.0, 0.0, -0.5], 0.89)
            .0
            .is_none());
        let want = std::f64::consts::PI * 1.5 * 1.5 * 2.5;
        assert!((s.removed_volume() - want).abs() / want < 0.02);
    }
}
