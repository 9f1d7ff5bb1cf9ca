//! Keep-out boxes (clamps, fixtures): does the tool touch one during a move?
//!
//! The tool is a vertical cylinder of radius O/2 from its tip upward without end: the
//! holder, collet and spindle stand above the cutter, so anything above the tip within the
//! radius is hit (a clamp the tip passes over by 0.1 mm is cleared; a clamp whose top is
//! above the tip anywhere within the radius is not). So the tool at (x, y, z) touches the
//! box when its XY distance to the box's rectangle is at most O/2 and z is at most the
//! box's top; the box's bottom does not matter.
//!
//! Geometry is exact: a line's or arc's part below the box top (Z is linear along both),
//! then its XY distance to the rectangle against the radius. Contact counts, within
//! [`TOUCH`] (the program's numbers carry three decimals; a hair's breadth is a hit).

use crate::machine::{ArcGeo, Move};
use std::f64::consts::TAU;

/// Closer than this (mm) beyond contact still counts as touching.
pub const TOUCH: f64 = 1e-6;
/// At most this many boxes (each is checked against every move).
pub const MAX_CLAMPS: usize = 64;

/// A keep-out box in machine coordinates (mm), `min < max` on every axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Clamp {
    pub name: String,
    pub min: [f64; 3],
    pub max: [f64; 3],
}

impl Clamp {
    /// Why the box is not usable (not finite, beyond `max_magnitude`, `min ≥ max`), in
    /// English; `None` when it is.
    pub fn problem(&self, max_magnitude: f64) -> Option<String> {
        let all = self.min.iter().chain(self.max.iter());
        if all
            .clone()
            .any(|v| !v.is_finite() || v.abs() > max_magnitude)
        {
            return Some(format!(
                "coordinates must be finite and within ±{max_magnitude}"
            ));
        }
        (0..3)
            .find(|&k| self.min[k] >= self.max[k])
            .map(|k| format!("min must be below max on {}", ["x", "y", "z"][k]))
    }
}

/// The first clamp (index) the tool of radius `r` touches during `mv`. A move from an
/// unknown place is judged at its end; a move to an unknown place is not judged (nothing
/// is known of where the tool goes).
pub fn hit(mv: &Move, r: f64, clamps: &[Clamp]) -> Option<usize> {
    let known = |p: &[f64; 3]| p.iter().all(|v| v.is_finite());
    if !known(&mv.to) {
        return None;
    }
    let (from, arc) = if known(&mv.from) {
        (mv.from, mv.arc.as_deref())
    } else {
        (mv.to, None)
    };
    clamps.iter().position(|c| touches(from, mv.to, arc, r, c))
}

/// The part `[s0, s1]` of a move whose Z (linear from `z0` to `z1`) is at most `top`.
fn below(z0: f64, z1: f64, top: f64) -> Option<(f64, f64)> {
    let top = top + TOUCH;
    let dz = z1 - z0;
    if dz.abs() < 1e-12 {
        return (z0 <= top).then_some((0.0, 1.0));
    }
    let s = ((top - z0) / dz).clamp(0.0, 1.0);
    let (s0, s1) = if dz > 0.0 { (0.0, s) } else { (s, 1.0) };
    // an end exactly at the top counts (s0 == s1)
    let ok = if dz > 0.0 { z0 <= top } else { z1 <= top };
    ok.then_some((s0, s1))
}

fn touches(a: [f64; 3], b: [f64; 3], arc: Option<&ArcGeo>, r: f64, c: &Clamp) -> bool {
    let Some((s0, s1)) = below(a[2], b[2], c.max[2]) else {
        return false;
    };
    let rect = Rect {
        x0: c.min[0],
        y0: c.min[1],
        x1: c.max[0],
        y1: c.max[1],
    };
    let reach = r + TOUCH;
    match arc {
        Some(g) => {
            let part = ArcGeo {
                a0: g.a0 + s0 * g.sweep,
                sweep: (s1 - s0) * g.sweep,
                ..*g
            };
            arc_near_rect(&part, &rect, reach)
        }
        None => {
            let at = |s: f64| (a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]));
            segment_rect_distance(at(s0), at(s1), &rect) <= reach
        }
    }
}

#[derive(Debug, Clone, Copy)]
struct Rect {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
}

impl Rect {
    fn contains(&self, (x, y): (f64, f64)) -> bool {
        (self.x0..=self.x1).contains(&x) && (self.y0..=self.y1).contains(&y)
    }
    fn distance(&self, (x, y): (f64, f64)) -> f64 {
        let dx = (self.x0 - x).max(x - self.x1).max(0.0);
        let dy = (self.y0 - y).max(y - self.y1).max(0.0);
        dx.hypot(dy)
    }
    fn corners(&self) -> [(f64, f64); 4] {
        [
            (self.x0, self.y0),
            (self.x1, self.y0),
            (self.x1, self.y1),
            (self.x0, self.y1),
        ]
    }
}

/// Does the segment cross the rectangle (Liang–Barsky clipping)?
fn segment_crosses(p: (f64, f64), q: (f64, f64), r: &Rect) -> bool {
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (den, num) in [
        (-dx, p.0 - r.x0),
        (dx, r.x1 - p.0),
        (-dy, p.1 - r.y0),
        (dy, r.y1 - p.1),
    ] {
        if den == 0.0 {
            if num < 0.0 {
                return false;
            }
        } else {
            let t = num / den;
            if den < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    t0 <= t1
}

fn point_segment_distance(c: (f64, f64), p: (f64, f64), q: (f64, f64)) -> f64 {
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((c.0 - p.0) * dx + (c.1 - p.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 + t * dx - c.0).hypot(p.1 + t * dy - c.1)
}

/// XY distance of a segment to a rectangle: 0 when they meet, else attained at an end of
/// the segment or a corner of the rectangle (both are convex).
fn segment_rect_distance(p: (f64, f64), q: (f64, f64), r: &Rect) -> f64 {
    if segment_crosses(p, q, r) {
        return 0.0;
    }
    let ends = r.distance(p).min(r.distance(q));
    r.corners()
        .iter()
        .map(|&c| point_segment_distance(c, p, q))
        .fold(ends, f64::min)
}

/// Is angle `theta` on the arc (its start at `a0`, signed `sweep`)?
fn on_arc(g: &ArcGeo, theta: f64) -> bool {
    if g.sweep.abs() >= TAU {
        return true;
    }
    let rel = if g.sweep >= 0.0 {
        (theta - g.a0).rem_euclid(TAU)
    } else {
        (g.a0 - theta).rem_euclid(TAU)
    };
    rel <= g.sweep.abs() + 1e-12 || rel >= TAU - 1e-12
}

/// Does the arc come within `reach` of the rectangle? The rectangle grown by `reach` is two
/// crossed rectangles and four corner discs; the arc meets it when it meets one of them.
fn arc_near_rect(g: &ArcGeo, r: &Rect, reach: f64) -> bool {
    let wide = Rect {
        x0: r.x0 - reach,
        x1: r.x1 + reach,
        ..*r
    };
    let tall = Rect {
        y0: r.y0 - reach,
        y1: r.y1 + reach,
        ..*r
    };
    arc_meets_rect(g, &wide)
        || arc_meets_rect(g, &tall)
        || r.corners()
            .iter()
            .any(|&c| arc_point_distance(g, c) <= reach)
}

/// Does the arc meet the (closed) rectangle: an end inside, or a crossing of an edge?
fn arc_meets_rect(g: &ArcGeo, r: &Rect) -> bool {
    if r.contains(g.point(0.0)) || r.contains(g.point(1.0)) {
        return true;
    }
    // crossings of the circle with the edge lines, kept when on the edge and on the arc
    let mut hits = Vec::with_capacity(8);
    for x in [r.x0, r.x1] {
        let d = g.r * g.r - (x - g.cx).powi(2);
        if d >= 0.0 {
            for y in [g.cy - d.sqrt(), g.cy + d.sqrt()] {
                if (r.y0..=r.y1).contains(&y) {
                    hits.push((x, y));
                }
            }
        }
    }
    for y in [r.y0, r.y1] {
        let d = g.r * g.r - (y - g.cy).powi(2);
        if d >= 0.0 {
            for x in [g.cx - d.sqrt(), g.cx + d.sqrt()] {
                if (r.x0..=r.x1).contains(&x) {
                    hits.push((x, y));
                }
            }
        }
    }
    hits.into_iter()
        .any(|(x, y)| on_arc(g, (y - g.cy).atan2(x - g.cx)))
}

/// Distance from a point to the arc: to its circle where the point's direction is on the
/// arc, else to the nearer end.
fn arc_point_distance(g: &ArcGeo, c: (f64, f64)) -> f64 {
    let (dx, dy) = (c.0 - g.cx, c.1 - g.cy);
    let d = dx.hypot(dy);
    let ends = |p: (f64, f64)| (p.0 - c.0).hypot(p.1 - c.1);
    let to_ends = ends(g.point(0.0)).min(ends(g.point(1.0)));
    if d > 0.0 && on_arc(g, dy.atan2(dx)) {
        (d - g.r).abs().min(to_ends)
    } else if d == 0.0 {
        g.r
    } else {
        to_ends
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine::MoveKind;

    fn clamp() -> Clamp {
        Clamp {
            name: "c".into(),
            min: [0.0, 0.0, 0.0],
            max: [10.0, 10.0, 5.0],
        }
    }
    fn line(a: [f64; 3], b: [f64; 3]) -> Move {
        Move {
            line: 1,
            kind: MoveKind::Cut,
            from: a,
            to: b,
            arc: None,
        }
    }

    #[test]
    fn lines_pass_beside_over_and_through() {
        let c = [clamp()];
        // beside at exactly the radius: contact is a hit; a hair farther is not
        assert_eq!(
            hit(&line([-1.0, -5.0, 0.0], [-1.0, 15.0, 0.0]), 1.0, &c),
            Some(0)
        );
        assert_eq!(
            hit(&line([-1.01, -5.0, 0.0], [-1.01, 15.0, 0.0]), 1.0, &c),
            None
        );
        // over the top: at the top is contact, above is clear
        assert_eq!(
            hit(&line([-5.0, 5.0, 5.0], [15.0, 5.0, 5.0]), 1.0, &c),
            Some(0)
        );
        assert_eq!(
            hit(&line([-5.0, 5.0, 5.01], [15.0, 5.0, 5.01]), 1.0, &c),
            None
        );
        // a ramp that is below the top only far from the box
        assert_eq!(
            hit(&line([-20.0, 5.0, 0.0], [-2.0, 5.0, 10.0]), 1.0, &c),
            None
        );
        // at a corner the distance is diagonal
        assert_eq!(
            hit(&line([-0.7, -0.7, 0.0], [-0.7, -0.7, 0.0]), 1.0, &c),
            Some(0)
        );
        assert_eq!(
            hit(&line([-0.71, -0.71, 0.0], [-0.71, -0.71, 0.0]), 1.0, &c),
            None
        );
        assert_eq!(
            hit(&line([-3.0, -3.0, 0.0], [-3.0, -3.0, 0.0]), 1.0, &c),
            None
        );
        assert_eq!(
            hit(&line([-0.6, -0.6, 0.0], [-0.6, -0.6, 0.0]), 1.0, &c),
            Some(0)
        );
    }

    #[test]
    fn arcs_near_and_around() {
        let c = [clamp()];
        let arc = |cx: f64, cy: f64, r: f64, a0: f64, sweep: f64, z: f64| {
            let g = ArcGeo {
                cx,
                cy,
                r,
                a0,
                sweep,
            };
            let (x0, y0) = g.point(0.0);
            let (x1, y1) = g.point(1.0);
            Move {
                line: 1,
                kind: MoveKind::Cut,
                from: [x0, y0, z],
                to: [x1, y1, z],
                arc: Some(Box::new(g)),
            }
        };
        // a circle around the box, farther than the radius from its corners
        let around = 50f64.sqrt() + 1.01;
        assert_eq!(hit(&arc(5.0, 5.0, around, 0.0, TAU, 0.0), 1.0, &c), None);
        assert_eq!(
            hit(&arc(5.0, 5.0, around - 0.02, 0.0, TAU, 0.0), 1.0, &c),
            Some(0)
        );
        // a half circle on the far side of a corner: only its end nears the box
        assert_eq!(
            hit(
                &arc(-5.0, 5.0, 4.5, 0.5 * TAU / 2.0, TAU / 2.0, 0.0),
                1.0,
                &c
            ),
            None
        );
        assert_eq!(
            hit(&arc(-5.0, 5.0, 4.5, -TAU / 4.0, TAU / 2.0, 0.0), 1.0, &c),
            Some(0)
        );
        // a helix that rises above the box top before it nears it
        assert_eq!(
            hit(&arc(-5.0, 5.0, 4.5, -TAU / 4.0, TAU / 2.0, 0.0), 0.5, &c),
            Some(0)
        );
        let mut h = arc(-5.0, 5.0, 4.5, -TAU / 4.0, TAU / 2.0, 0.0);
        h.to[2] = 12.0;
        assert_eq!(hit(&h, 0.5, &c), None);
        // crossing through the box
        assert_eq!(hit(&arc(5.0, 5.0, 3.0, 0.0, 1.0, 0.0), 1.0, &c), Some(0));
    }

    #[test]
    fn bad_boxes() {
        let mut c = clamp();
        assert_eq!(c.problem(1e6), None);
        c.max[1] = 0.0;
        assert!(c.problem(1e6).unwrap().contains("on y"));
        c.max[1] = f64::NAN;
        assert!(c.problem(1e6).unwrap().contains("finite"));
    }
}
