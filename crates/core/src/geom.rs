//! Tolerances, points, line and arc geometry, rigid transformations and number formatting.
//!
//! The tolerance predicates are the reference tool's (reference-input.md §0.1): a relative
//! epsilon, and points compared by their *squared* distance. Many branches of the compiler
//! depend on them, so they are reproduced literally.
//!
//! Tolerance predicates `near/ge/gt` (reference-input.md §0.1), points, lines/arcs, sub-geometries,
//! rigid transforms, `F3` formatting.

use millpath_post::number::{f3_text, F3_LEN};
use std::fmt;

pub const EPS: f64 = 1e-6;

pub fn near_eps(a: f64, b: f64, eps: f64) -> bool {
    (a - b).abs() <= eps * (a.abs().max(b.abs()) + 0.001)
}
pub fn near(a: f64, b: f64) -> bool {
    near_eps(a, b, EPS)
}
/// `a ≥ b` with tolerance.
pub fn ge(a: f64, b: f64) -> bool {
    a >= b || near(a, b)
}
/// `a > b` beyond tolerance.
pub fn gt(a: f64, b: f64) -> bool {
    a > b && !near(a, b)
}
/// `|a − b| ≤ e`.
pub fn absnear(a: f64, b: f64, e: f64) -> bool {
    (a - b).abs() <= e
}
pub fn le(a: f64, b: f64) -> bool {
    ge(b, a)
}
pub fn lt(a: f64, b: f64) -> bool {
    gt(b, a)
}

/// Fixed-point text with three decimals; `-0.000` keeps its sign like the reference.
/// Exactly `format!("{x:.3}")` (and .NET): see [`F3`]. For new code, [`F3`] and [`write_f3`]
/// write the same text without a `String` of its own.
pub fn f3(x: f64) -> String {
    let mut s = String::new();
    write_f3(&mut s, x);
    s
}

/// Appends [`f3`]`(x)` to `out`.
pub fn write_f3(out: &mut String, x: f64) {
    let mut buf = [0; F3_LEN];
    match f3_text(x, &mut buf) {
        Some(s) => out.push_str(s),
        None => {
            use std::fmt::Write;
            // writing into a String cannot fail
            let _ = write!(out, "{x:.3}");
        }
    }
}

/// A number shown with three decimals, exactly as `format!("{x:.3}")` shows it: the exact
/// binary value rounded half to even, `-0.000` with its sign, `NaN`, `inf`. The usual values
/// (|x| < 10¹⁵) are written from integer arithmetic without allocating; the standard
/// formatter's exact path, which this replaces, is the hot spot of G-code generation.
/// Width, fill and alignment apply as to a string.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct F3(pub f64);

impl fmt::Display for F3 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut buf = [0; F3_LEN];
        match f3_text(self.0, &mut buf) {
            Some(s) => f.pad(s),
            None if f.width().is_none() && f.precision().is_none() => write!(f, "{:.3}", self.0),
            None => f.pad(&format!("{:.3}", self.0)),
        }
    }
}

/// Normalises an angle in degrees into [0, 360).
pub fn normalize_angle(a: f64) -> f64 {
    let r = a % 360.0;
    if r.abs() < 1e-12 || (r.abs() - 360.0).abs() < 1e-12 {
        0.0
    } else if r < 0.0 {
        r + 360.0
    } else {
        r
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct P2 {
    pub x: f64,
    pub y: f64,
}

impl P2 {
    pub const fn new(x: f64, y: f64) -> Self {
        P2 { x, y }
    }
    #[allow(clippy::should_implement_trait)] // plain helpers, no operator overloading needed
    pub fn sub(self, o: P2) -> P2 {
        P2::new(self.x - o.x, self.y - o.y)
    }
    #[allow(clippy::should_implement_trait)]
    pub fn add(self, o: P2) -> P2 {
        P2::new(self.x + o.x, self.y + o.y)
    }
    pub fn scale(self, f: f64) -> P2 {
        P2::new(self.x * f, self.y * f)
    }
    pub fn dot(self, o: P2) -> f64 {
        self.x * o.x + self.y * o.y
    }
    pub fn len(self) -> f64 {
        (self.x * self.x + self.y * self.y).sqrt()
    }
    pub fn dist2(self, o: P2) -> f64 {
        let d = self.sub(o);
        d.x * d.x + d.y * d.y
    }
    pub fn dist(self, o: P2) -> f64 {
        self.dist2(o).sqrt()
    }
    /// Point identity of the reference: squared distance near 0 (≈ 3.16e-5 mm).
    pub fn near(self, o: P2) -> bool {
        near(self.dist2(o), 0.0)
    }
    /// The looser identity of the reference's consistency assertions (≈ 2.83e-4 mm).
    pub fn assert_near(self, o: P2) -> bool {
        near_eps(self.dist2(o), 0.0, 8e-5)
    }
    pub fn rotate(self, a: f64) -> P2 {
        // no rotation (every top-level frame): sin ±0 and cos 1 exactly, without `sin_cos`
        let (s, c) = if a == 0.0 { (a, 1.0) } else { a.sin_cos() };
        P2::new(self.x * c - self.y * s, self.x * s + self.y * c)
    }
    pub fn with_z(self, z: f64) -> P3 {
        P3 {
            x: self.x,
            y: self.y,
            z,
        }
    }
}

/// `[x y]` with three decimals.
impl fmt::Display for P2 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{} {}]", F3(self.x), F3(self.y))
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct P3 {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

impl P3 {
    pub fn xy(self) -> P2 {
        P2::new(self.x, self.y)
    }
    pub fn dist(self, o: P3) -> f64 {
        let (dx, dy, dz) = (self.x - o.x, self.y - o.y, self.z - o.z);
        (dx * dx + dy * dy + dz * dz).sqrt()
    }
}

impl fmt::Display for P3 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{} {} {}]", F3(self.x), F3(self.y), F3(self.z))
    }
}

/// A straight line or a circular arc, in traversal direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Geom {
    Line {
        a: P2,
        b: P2,
    },
    /// Angles in degrees, normalised; `ccw` runs from `a0` counter-clockwise to `a1`.
    Arc {
        c: P2,
        r: f64,
        a0: f64,
        a1: f64,
        ccw: bool,
    },
}

impl Geom {
    pub fn start(&self) -> P2 {
        match *self {
            Geom::Line { a, .. } => a,
            Geom::Arc { c, r, a0, .. } => arc_point(c, r, a0),
        }
    }
    pub fn end(&self) -> P2 {
        match *self {
            Geom::Line { b, .. } => b,
            Geom::Arc { c, r, a1, .. } => arc_point(c, r, a1),
        }
    }
    pub fn reversed(&self) -> Geom {
        match *self {
            Geom::Line { a, b } => Geom::Line { a: b, b: a },
            Geom::Arc { c, r, a0, a1, ccw } => Geom::Arc {
                c,
                r,
                a0: a1,
                a1: a0,
                ccw: !ccw,
            },
        }
    }
    /// Swept angle in degrees, in [0, 360).
    pub fn sweep_deg(&self) -> f64 {
        match *self {
            Geom::Line { .. } => 0.0,
            Geom::Arc { a0, a1, ccw, .. } => {
                normalize_angle(if ccw { a1 - a0 } else { -(a1 - a0) })
            }
        }
    }
    /// Length along the geometry (arc length for arcs).
    pub fn length(&self) -> f64 {
        match *self {
            Geom::Line { a, b } => a.dist(b),
            Geom::Arc { r, .. } => r * self.sweep_deg().to_radians(),
        }
    }
    /// Straight distance between the end points.
    pub fn chord(&self) -> f64 {
        self.start().dist(self.end())
    }
    /// The piece between the distances `f0` and `f1` measured along the geometry from its start.
    pub fn sub(&self, f0: f64, f1: f64) -> Geom {
        match *self {
            Geom::Line { a, b } => {
                let len = a.dist(b);
                let dir = b.sub(a).scale(1.0 / len);
                Geom::Line {
                    a: a.add(dir.scale(f0)),
                    b: a.add(dir.scale(f1)),
                }
            }
            Geom::Arc { c, r, a0, ccw, .. } => {
                let circumference = 2.0 * std::f64::consts::PI * r;
                let sign = if ccw { 1.0 } else { -1.0 };
                Geom::Arc {
                    c,
                    r,
                    a0: normalize_angle(a0 + sign * (f0 / circumference * 360.0)),
                    a1: normalize_angle(a0 + sign * (f1 / circumference * 360.0)),
                    ccw,
                }
            }
        }
    }
    pub fn transform(&self, t: &Transform) -> Geom {
        match *self {
            Geom::Line { a, b } => Geom::Line {
                a: t.apply(a),
                b: t.apply(b),
            },
            Geom::Arc { c, r, a0, a1, ccw } => {
                let d = t.angle.to_degrees();
                Geom::Arc {
                    c: t.apply(c),
                    r,
                    a0: normalize_angle(a0 + d),
                    a1: normalize_angle(a1 + d),
                    ccw,
                }
            }
        }
    }
}

pub fn arc_point(c: P2, r: f64, deg: f64) -> P2 {
    let a = deg.to_radians();
    P2::new(c.x + r * a.cos(), c.y + r * a.sin())
}

/// A rigid motion (rotation + translation) mapping one anchor pair onto another.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transform {
    pub from_start: P2,
    pub from_end: P2,
    pub to_start: P2,
    pub to_end: P2,
    /// Rotation in radians.
    pub angle: f64,
}

impl Transform {
    /// The top-level frame: the start marker becomes (0, 0), no rotation.
    pub fn top_level(start: P2, end: P2) -> Transform {
        Transform {
            from_start: start,
            from_end: end,
            to_start: P2::default(),
            to_end: end.sub(start),
            angle: 0.0,
        }
    }

    /// The rotation + translation that maps `from_start → to_start` and `from_end → to_end`;
    /// `None` when the distances differ or the anchors coincide (rotation undefined).
    pub fn between(from_start: P2, from_end: P2, to_start: P2, to_end: P2) -> Option<Transform> {
        let u = from_end.sub(from_start);
        let v = to_end.sub(to_start);
        let (lu, lv) = (u.len(), v.len());
        if lu == 0.0 || lv == 0.0 {
            return None;
        }
        let a = (u.dot(v) / (lu * lv)).clamp(-1.0, 1.0).acos();
        let angle = if u.rotate(a).dist(v) <= 1e-3 {
            a
        } else if u.rotate(-a).dist(v) <= 1e-3 {
            -a
        } else {
            return None;
        };
        Some(Transform {
            from_start,
            from_end,
            to_start,
            to_end,
            angle,
        })
    }

    pub fn apply(&self, p: P2) -> P2 {
        p.sub(self.from_start).rotate(self.angle).add(self.to_start)
    }

    /// `[ [fs]=>[ts] / [fe]=>[te] ]`, the form used in subpath comments.
    pub fn describe(&self) -> String {
        format!(
            "[ {}=>{} / {}=>{} ]",
            self.from_start, self.to_start, self.from_end, self.to_end
        )
    }
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

    #[test]
    fn tolerances() {
        assert!(near(1.0, 1.0 + 1e-7));
        assert!(!near(1.0, 1.0 + 2e-6));
        assert!(near(0.0, 1e-9));
        assert!(ge(1.0, 1.0 + 1e-7) && !gt(1.0 + 1e-7, 1.0));
        assert!(P2::new(0.0, 0.0).near(P2::new(3e-5, 0.0)));
        assert!(!P2::new(0.0, 0.0).near(P2::new(4e-5, 0.0)));
        assert!(!near(f64::NAN, 1.0) && !ge(f64::NAN, 1.0) && !gt(f64::NAN, 1.0));
    }

    /// `x` moved by `n` units in the last place (through zero and into infinities alike).
    fn ulps(x: f64, n: i64) -> f64 {
        // order the bit patterns as integers: negative numbers mirrored below zero
        let b = x.to_bits() as i64;
        let key = if b < 0 { i64::MIN - b } else { b };
        let key = key.saturating_add(n);
        f64::from_bits(if key < 0 { i64::MIN - key } else { key } as u64)
    }

    /// `write_f3` (so `F3` and `f3`) against the standard formatter, on 3.9 million values:
    /// arbitrary bit patterns, the exponents that matter, values a few ulps around every
    /// kind of rounding boundary k/1000 and tie (k + ½)/1000, the exact ties (odd multiples
    /// of 1/16), integers, the 10¹⁵ limit, subnormals and zeros.
    #[test]
    fn fast_f3_equals_the_standard_formatter() {
        let mut seed: u64 = 0x9E3779B97F4A7C15;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let (mut ours, mut std_text) = (String::new(), String::new());
        let mut check = |x: f64| {
            use std::fmt::Write;
            ours.clear();
            std_text.clear();
            write_f3(&mut ours, x);
            write!(std_text, "{x:.3}").unwrap();
            assert_eq!(ours, std_text, "{x:e} ({:#x})", x.to_bits());
        };
        let mut count = 0usize;
        for _ in 0..3_000_000 {
            let r = next();
            let sign = if r & 1 == 0 { 1.0 } else { -1.0 };
            let x = match (r >> 1) % 8 {
                // any bit pattern: NaN, infinities, huge, subnormal
                0 => f64::from_bits(next()),
                // exponents from 2⁻³⁰ to 2⁵⁰: random significand
                1 => {
                    let e = 1023 - 30 + next() % 81;
                    f64::from_bits((e << 52) | (next() >> 12)) * sign
                }
                // k/1000 ± a few ulps, k of up to 18 digits
                2 => {
                    let k = next() % 10u64.pow(1 + (next() % 18) as u32);
                    ulps(k as f64 / 1000.0, (next() % 9) as i64 - 4) * sign
                }
                // near ties (k + ½)/1000
                3 => {
                    let k = next() % 10u64.pow(1 + (next() % 15) as u32);
                    ulps((k as f64 + 0.5) / 1000.0, (next() % 9) as i64 - 4) * sign
                }
                // exact ties: odd multiples of 1/16, and their neighbours
                4 => {
                    let m = (next() % 10u64.pow(1 + (next() % 16) as u32)) | 1;
                    ulps(m as f64 / 16.0, (next() % 3) as i64 - 1) * sign
                }
                // integers and halves
                5 => (next() % 2_000_000_000_000_000) as f64 / 2.0 * sign,
                // around the 10¹⁵ limit and the tiny end
                6 => match next() % 4 {
                    0 => ulps(1e15, (next() % 64) as i64 - 32) * sign,
                    1 => ulps(0.0005, (next() % 64) as i64 - 32) * sign,
                    2 => f64::from_bits(next() % (1 << 52)) * sign,
                    _ => ulps(0.0, (next() % 64) as i64 - 32),
                },
                // drawing coordinates: millimetres with three decimals, computed
                _ => ((next() % 2_000_000) as f64 / 1000.0 - 1000.0) * 1.1 * sign,
            };
            check(x);
            count += 1;
        }
        let fixed = [
            0.0625,
            0.1875,
            -0.0625,
            1.0005,
            2.0005,
            0.0005,
            -0.0005,
            2.5e-4,
            -2.5e-4,
            0.0015,
            1e-300,
            -1e-300,
            5e-324,
            -5e-324,
            f64::MIN_POSITIVE,
            999_999_999_999_999.9,
            -999_999_999_999_999.9,
            999_999_999_999.999_5,
            1e15,
            -1e15,
            1e300,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.9995,
            9.9995,
            99.9995,
        ];
        for x in fixed {
            check(x);
            for n in -3..=3 {
                check(ulps(x, n));
                count += 1;
            }
        }
        // every k/1000 up to 300 and its neighbours
        for k in 0..300_000u64 {
            let x = k as f64 / 1000.0;
            check(x);
            check(ulps(x, 1));
            check(ulps(x, -1));
            count += 3;
        }
        assert!(count > 3_000_000);
    }

    #[test]
    fn f3_display_and_writer() {
        assert_eq!(F3(-0.0).to_string(), "-0.000");
        assert_eq!(format!("[{}]", F3(12.3456)), "[12.346]");
        assert_eq!(
            format!("{:>9}|{:<8}|{:^9}", F3(1.5), F3(-2.0), F3(0.25)),
            "    1.500|-2.000  |  0.250  "
        );
        assert_eq!(format!("{:>6}", F3(f64::NAN)), "   NaN");
        assert_eq!(format!("{}", F3(1e20)), format!("{:.3}", 1e20));
        let mut s = String::from("X");
        write_f3(&mut s, 1.0005);
        s.push_str(" Y");
        write_f3(&mut s, -1e16);
        assert_eq!(s, "X1.000 Y-10000000000000000.000");
        assert_eq!(f3(f64::NEG_INFINITY), "-inf");
        assert_eq!(
            P3 {
                x: 1.0,
                y: -0.0004,
                z: 2.5e-4
            }
            .to_string(),
            "[1.000 -0.000 0.000]"
        );
    }

    #[test]
    fn formatting_keeps_negative_zero_and_rounds_to_even() {
        assert_eq!(f3(-1e-15), "-0.000");
        assert_eq!(f3(0.0625), "0.062");
        assert_eq!(f3(1.0005), "1.000"); // binary value is below the tie
        assert_eq!(format!("{:.0}", 2.5), "2");
    }

    #[test]
    fn angles_and_arcs() {
        assert_eq!(normalize_angle(-90.0), 270.0);
        assert_eq!(normalize_angle(360.0), 0.0);
        assert_eq!(normalize_angle(725.0), 5.0);
        let arc = Geom::Arc {
            c: P2::new(0.0, 0.0),
            r: 2.0,
            a0: 0.0,
            a1: 90.0,
            ccw: true,
        };
        assert!((arc.length() - std::f64::consts::PI).abs() < 1e-12);
        let rev = arc.reversed();
        assert!((rev.length() - arc.length()).abs() < 1e-12);
        assert!(rev.start().near(arc.end()));
        let half = arc.sub(0.0, arc.length() / 2.0);
        assert!(half.end().near(P2::new(2f64.sqrt(), 2f64.sqrt())));
    }

    #[test]
    fn transform_maps_anchors() {
        let t = Transform::between(
            P2::new(120.0, 170.0),
            P2::new(120.0, 100.0),
            P2::new(20.0, 0.0),
            P2::new(20.0, 70.0),
        )
        .unwrap();
        assert!(t.apply(P2::new(120.0, 170.0)).near(P2::new(20.0, 0.0)));
        assert!(t.apply(P2::new(120.0, 100.0)).near(P2::new(20.0, 70.0)));
        assert!(Transform::between(
            P2::new(0.0, 0.0),
            P2::new(1.0, 0.0),
            P2::new(0.0, 0.0),
            P2::new(2.0, 0.0)
        )
        .is_none());
    }
}
