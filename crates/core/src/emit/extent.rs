//! The XY extent of a program's cutting moves, arcs with the extreme points they pass: the
//! area a height map (`probe/heightmap.rs`) must cover.

use crate::emit::item::{Item, Kind};
use crate::geom::P2;

/// The XY box of a program's cutting moves (mill, mark, bars, drill, helix; not sweeps),
/// arcs with the extreme points they pass. `start` is where the program's moves start.
pub fn cut_extent(items: &[Item], start: P2) -> Option<(P2, P2)> {
    let mut pos = start;
    let mut bbox: Option<(P2, P2)> = None;
    let mut take = |p: P2| {
        bbox = Some(match bbox {
            None => (p, p),
            Some((lo, hi)) => (
                P2 {
                    x: lo.x.min(p.x),
                    y: lo.y.min(p.y),
                },
                P2 {
                    x: hi.x.max(p.x),
                    y: hi.y.max(p.y),
                },
            ),
        });
    };
    for it in items {
        let to = P2 {
            x: it.target.x.unwrap_or(pos.x),
            y: it.target.y.unwrap_or(pos.y),
        };
        if matches!(it.kind, Kind::Mill | Kind::Drill) {
            take(pos);
            take(to);
            if let Some((c, ccw)) = it.target.arc {
                arc_extremes(pos, to, c, ccw)
                    .into_iter()
                    .for_each(&mut take);
            }
        }
        pos = to;
    }
    bbox
}

/// The points of the circle around `c` at 0°, 90°, 180° and 270° that the arc from `a` to
/// `b` passes (a full circle when `a` = `b`).
pub(crate) fn arc_extremes(a: P2, b: P2, c: P2, ccw: bool) -> Vec<P2> {
    use std::f64::consts::{FRAC_PI_2, TAU};
    let r = a.dist(c);
    let ang = |p: P2| (p.y - c.y).atan2(p.x - c.x);
    let (a0, a1) = (ang(a), ang(b));
    let turn = |d: f64| d.rem_euclid(TAU);
    let full = a.dist(b) < 1e-9;
    let span = if full {
        TAU
    } else if ccw {
        turn(a1 - a0)
    } else {
        turn(a0 - a1)
    };
    (0..4)
        .map(|k| k as f64 * FRAC_PI_2)
        .filter(|&t| {
            let d = if ccw { turn(t - a0) } else { turn(a0 - t) };
            d <= span
        })
        .map(|t| P2 {
            x: c.x + r * t.cos(),
            y: c.y + r * t.sin(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::item::Target;

    fn p(x: f64, y: f64) -> P2 {
        P2 { x, y }
    }

    fn item(kind: Kind, target: Target) -> Item {
        Item {
            kind,
            len: 0.0,
            feed: 100.0,
            target,
            source: None,
            shape: Default::default(),
        }
    }

    #[test]
    fn extent_takes_cuts_not_sweeps_and_arc_extremes() {
        let items = vec![
            // a sweep far away does not count
            item(Kind::HSweep, Target::xy(-50.0, -50.0)),
            item(Kind::HSweep, Target::xy(10.0, 0.0)),
            item(Kind::VSweep, Target::z(1.0)),
            item(Kind::Drill, Target::z(-1.0)),
            // a half circle counter-clockwise from (10,0) around (0,0) to (-10,0): up to y=10
            item(
                Kind::Mill,
                Target::arc(p(-10.0, 0.0), -1.0, p(0.0, 0.0), true),
            ),
            item(Kind::VSweep, Target::z(5.0)),
            item(Kind::HSweep, Target::xy(99.0, 99.0)),
        ];
        let (lo, hi) = cut_extent(&items, p(0.0, 0.0)).unwrap();
        assert!(lo.dist(p(-10.0, 0.0)) < 1e-9, "{lo}");
        assert!(hi.dist(p(10.0, 10.0)) < 1e-9, "{hi}");
        // clockwise the same ends go through y = -10
        let cw = vec![
            item(Kind::HSweep, Target::xy(10.0, 0.0)),
            item(
                Kind::Mill,
                Target::arc(p(-10.0, 0.0), -1.0, p(0.0, 0.0), false),
            ),
        ];
        let (lo, hi) = cut_extent(&cw, p(0.0, 0.0)).unwrap();
        assert!(lo.dist(p(-10.0, -10.0)) < 1e-9 && hi.dist(p(10.0, 0.0)) < 1e-9);
        assert_eq!(cut_extent(&items[..3], p(0.0, 0.0)), None);
    }
}
