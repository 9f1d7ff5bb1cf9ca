//! Programs adjusted to a measured height map: every move back to the drawing's frame.
//!
//! adjust-z writes each point below the safe height that lies on the map at its nominal Z
//! plus the surface offset there ([`HeightMap::offset`]); it splits cuts so that the straight
//! Z between piece ends stays within [`SPLIT_TOLERANCE`] of that along the piece. The checker
//! undoes it: a point on the map loses the offset at its XY, a point off the map the largest
//! rise of the measured surface above the nominal top (as if the surface were that high
//! there: a rapid that leaves the map must clear the highest point). A correct program then
//! lies where the drawing put it, and the stock model, "below the deepest drawn depth" and
//! "rapid into material" judge it unchanged. A program adjusted to another surface (or the
//! right one with a wrong program) lands elsewhere and is found.
//!
//! Programs on a height map (the record, or `verify_on_surface`'s map): every move's end points
//! back to the drawing's frame (z − offset on the map, z − the highest rise off it), cuts sampled
//! inside against the drawn depth (adjust-z's 0.005 mm + rounding).

use crate::machine::{Move, MoveKind};
use crate::surface::HeightMap;

/// adjust-z's own bound on the straight Z of a piece against the surface along it, mm.
pub const SPLIT_TOLERANCE: f64 = 0.005;
/// Three-decimal rounding on both sides: the written Z and the record's heights, mm.
pub const ROUNDING: f64 = 0.002;
/// Most samples along one cutting move (besides its ends).
const MAX_SAMPLES: usize = 64;

/// The map a program is judged against, and its rise for points off the map.
pub struct Frame<'a> {
    map: &'a HeightMap,
    rise: f64,
    /// Sample spacing along cuts: a quarter of the smallest grid step.
    spacing: f64,
}

impl<'a> Frame<'a> {
    pub fn new(map: &'a HeightMap) -> Frame<'a> {
        let step = |v: &[f64]| {
            v.windows(2)
                .map(|w| w[1] - w[0])
                .fold(f64::INFINITY, f64::min)
        };
        let smallest = step(map.xs()).min(step(map.ys()));
        Frame {
            map,
            rise: (map.max_height() - map.top()).max(0.0),
            spacing: if smallest.is_finite() {
                (smallest / 4.0).max(0.05)
            } else {
                f64::INFINITY
            },
        }
    }

    /// How far the surface at (x, y) lies above the nominal top, as the checker takes it.
    pub fn shift(&self, x: f64, y: f64) -> f64 {
        self.map.offset(x, y).unwrap_or(self.rise)
    }

    /// The lowest drawing-frame height inside a cutting move as written (ends excluded: they
    /// are judged after [`Frame::to_drawing`]), with its XY; `None` for other moves.
    pub fn lowest_inside(&self, mv: &Move) -> Option<(f64, f64, f64)> {
        if mv.kind != MoveKind::Cut || mv.from.iter().chain(&mv.to).any(|v| !v.is_finite()) {
            return None;
        }
        let point = |s: f64| match &mv.arc {
            Some(a) => a.point(s),
            None => (
                mv.from[0] + (mv.to[0] - mv.from[0]) * s,
                mv.from[1] + (mv.to[1] - mv.from[1]) * s,
            ),
        };
        let length = match &mv.arc {
            Some(a) => (a.r * a.sweep).abs(),
            None => (mv.to[0] - mv.from[0]).hypot(mv.to[1] - mv.from[1]),
        };
        let n = ((length / self.spacing).ceil() as usize).clamp(1, MAX_SAMPLES);
        (1..n)
            .map(|k| {
                let s = k as f64 / n as f64;
                let (x, y) = point(s);
                let z = mv.from[2] + (mv.to[2] - mv.from[2]) * s;
                (z - self.shift(x, y), x, y)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// Every move's end points back to the drawing's frame (unknown coordinates stay NaN).
    pub fn to_drawing(&self, moves: &mut [Move]) {
        for mv in moves {
            for p in [&mut mv.from, &mut mv.to] {
                p[2] -= self.shift(p[0], p[1]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine::ArcGeo;

    fn tilted() -> HeightMap {
        // z = 3 + 0.01·x on x 0..20, y 0..10 (step 10)
        let xs = vec![0.0, 10.0, 20.0];
        let ys = vec![0.0, 10.0];
        let z = ys
            .iter()
            .flat_map(|_| xs.iter().map(|x| 3.0 + 0.01 * x))
            .collect();
        HeightMap::new(xs, ys, z, 3.0).unwrap()
    }

    fn cut(from: [f64; 3], to: [f64; 3], arc: Option<ArcGeo>) -> Move {
        Move {
            line: 1,
            kind: MoveKind::Cut,
            from,
            to,
            arc: arc.map(Box::new),
        }
    }

    #[test]
    fn points_lose_the_offset_on_the_map_and_the_rise_off_it() {
        let m = tilted();
        let f = Frame::new(&m);
        assert!((f.shift(5.0, 5.0) - 0.05).abs() < 1e-12);
        assert!((f.shift(-5.0, 5.0) - 0.2).abs() < 1e-12);
        assert!((f.shift(f64::NAN, 5.0) - 0.2).abs() < 1e-12);
        let mut moves = [cut([0.0, 0.0, 2.9], [20.0, 0.0, 3.1], None)];
        f.to_drawing(&mut moves);
        assert!((moves[0].from[2] - 2.9).abs() < 1e-12);
        assert!((moves[0].to[2] - 2.9).abs() < 1e-12);
    }

    #[test]
    fn a_straight_cut_over_a_curved_surface_dips_inside() {
        // a ridge: the middle column 0.1 higher than the edges
        let xs = vec![0.0, 10.0, 20.0];
        let ys = vec![0.0, 10.0];
        let z = vec![3.0, 3.1, 3.0, 3.0, 3.1, 3.0];
        let m = HeightMap::new(xs, ys, z, 3.0).unwrap();
        let f = Frame::new(&m);
        // written straight from edge to edge at the edges' depth: 0.1 too deep in the middle
        let (low, x, _) = f
            .lowest_inside(&cut([0.0, 0.0, 2.0], [20.0, 0.0, 2.0], None))
            .unwrap();
        assert!(
            (low - 1.9).abs() < 1e-9 && (x - 10.0).abs() < 1e-9,
            "{low} {x}"
        );
        // an arc's inside follows the arc
        let arc = ArcGeo {
            cx: 10.0,
            cy: 0.0,
            r: 10.0,
            a0: std::f64::consts::PI,
            sweep: -std::f64::consts::PI,
        };
        let (low, x, y) = f
            .lowest_inside(&cut([0.0, 0.0, 2.0], [20.0, 0.0, 2.0], Some(arc)))
            .unwrap();
        assert!(
            low < 2.0 && (0.0..=20.0).contains(&x) && y > 0.0,
            "{low} {x} {y}"
        );
        // rapids are not sampled
        let mut rapid = cut([0.0, 0.0, 2.0], [20.0, 0.0, 2.0], None);
        rapid.kind = MoveKind::Rapid;
        assert!(f.lowest_inside(&rapid).is_none());
    }
}
