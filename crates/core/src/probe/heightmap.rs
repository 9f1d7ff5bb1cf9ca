//! A height map as a setting (`[heightmap]` in millpath.toml): its bounds, and the grid of
//! probe points over an extent (`emit/extent.rs`) in serpentine order.
//! The probing program and `_Z.txt` of the grid are written by `emit/heightmap_program.rs`.

use crate::args;
use crate::diag::{Diagnostic, Msg, Origin};
use crate::geom::{F3, P2};
use crate::params::{fmt_num, MAX_MAGNITUDE};

/// The smallest grid step (mm): closer points measure the probe's own repeatability.
pub const MIN_STEP: f64 = 0.5;
/// At most this many grid points. With the names `#1000` … `#4999` they stay within
/// LinuxCNC's user parameters (#31–#5000) and never meet the drawn probes' `#51`, ….
pub const MAX_POINTS: usize = 4000;
/// The number of the first grid point's variable in `_Z.txt`.
pub const FIRST_VAR: usize = 1000;
/// How far below the nominal top the probe may travel when `probe_depth` is not set (mm).
pub const DEFAULT_PROBE_DEPTH: f64 = 5.0;

/// `[heightmap]`: where and how the probing program measures the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Heightmap {
    /// Distance between grid points on both axes (mm).
    pub step: f64,
    /// Added on every side of the extent of the cutting moves (mm); not to `area`.
    pub margin: f64,
    /// `[xmin, ymin, xmax, ymax]`: the probed area as given (it must hold every cut).
    pub area: Option<[f64; 4]>,
    /// Feed of the probing moves (mm/min); `None`: the probe feed of the settings.
    pub probe_feed: Option<f64>,
    /// How far below the nominal top (T) a probe may travel before it is an error (mm).
    pub probe_depth: f64,
}

impl Heightmap {
    /// A height map with `step` and the defaults.
    pub fn with_step(step: f64) -> Heightmap {
        Heightmap {
            step,
            margin: 0.0,
            area: None,
            probe_feed: None,
            probe_depth: DEFAULT_PROBE_DEPTH,
        }
    }

    /// Values out of bounds, each named and located by `at(name)`: the caller's spelling
    /// (`heightmap.step` in millpath.toml, `--heightmap-step` on the command line) and where
    /// the value was given (the settings file, or the options).
    pub fn errors(&self, at: &dyn Fn(&str) -> (String, Origin)) -> Vec<Diagnostic> {
        let key = |name: &str| at(name).0;
        let mut values = vec![
            ("step", self.step),
            ("margin", self.margin),
            ("probe_depth", self.probe_depth),
        ];
        values.extend(self.probe_feed.map(|v| ("probe_feed", v)));
        if let Some(a) = self.area {
            values.extend(
                ["area.xmin", "area.ymin", "area.xmax", "area.ymax"]
                    .into_iter()
                    .zip(a),
            );
        }
        let finite = |v: f64| v.is_finite() && v.abs() <= MAX_MAGNITUDE;
        let mut errors = Vec::new();
        for (name, v) in &values {
            if !finite(*v) {
                let (key, origin) = at(name);
                errors.push(Diagnostic::error(
                    Msg::SettingNotFinite,
                    origin,
                    args![key, v, MAX_MAGNITUDE],
                ));
            }
        }
        if !errors.is_empty() {
            return errors;
        }
        let mut err = |name: &str, msg, args| {
            errors.push(Diagnostic::error(msg, at(name).1, args));
        };
        if self.step < MIN_STEP {
            err(
                "step",
                Msg::HeightmapStepTooSmall,
                args![key("step"), fmt_num(self.step), fmt_num(MIN_STEP)],
            );
        }
        if self.margin < 0.0 {
            err(
                "margin",
                Msg::HeightmapNegative,
                args![key("margin"), fmt_num(self.margin)],
            );
        }
        for (name, v) in [
            ("probe_depth", Some(self.probe_depth)),
            ("probe_feed", self.probe_feed),
        ] {
            if let Some(v) = v.filter(|v| *v <= 0.0) {
                err(name, Msg::MustBePositive, args![key(name), fmt_num(v)]);
            }
        }
        if let Some([x0, y0, x1, y1]) = self.area {
            if x0 > x1 || y0 > y1 {
                err(
                    "area",
                    Msg::HeightmapAreaEmpty,
                    args![fmt_num(x0), fmt_num(y0), fmt_num(x1), fmt_num(y1)],
                );
            } else if self.step >= MIN_STEP {
                if let Err(d) = Grid::over(P2 { x: x0, y: y0 }, P2 { x: x1, y: y1 }, self.step) {
                    err("area", d.0, d.1);
                }
            }
        }
        errors
    }
}

/// The probe grid: columns `xs` and rows `ys` (ascending), visited row by row from the
/// lowest, every other row backwards (serpentine).
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
}

impl Grid {
    /// The grid over the box `lo`–`hi`: points every `step` from `lo`, and the last column
    /// and row on the far edge (so the last interval may be shorter than `step`). `Err`:
    /// the message and its arguments when the grid would exceed [`MAX_POINTS`].
    pub fn over(lo: P2, hi: P2, step: f64) -> Result<Grid, (Msg, Vec<String>)> {
        let count = |w: f64| ((w / step) - 1e-9).ceil().max(0.0) + 1.0;
        let (nx, ny) = (count(hi.x - lo.x), count(hi.y - lo.y));
        let n = nx * ny;
        if n.is_nan() || n > MAX_POINTS as f64 {
            return Err((Msg::HeightmapTooManyPoints, args![nx, ny, n, MAX_POINTS]));
        }
        let axis = |lo: f64, hi: f64, n: f64| -> Vec<f64> {
            let n = n as usize;
            (0..n)
                .map(|i| {
                    if i + 1 == n && n > 1 {
                        hi
                    } else {
                        lo + i as f64 * step
                    }
                })
                .collect()
        };
        Ok(Grid {
            xs: axis(lo.x, hi.x, nx),
            ys: axis(lo.y, hi.y, ny),
        })
    }

    /// The grid of a program: over `area`, else over the cutting moves' extent plus the
    /// margin. Errors are located at `origin` (the path).
    pub fn of_program(
        hm: &Heightmap,
        extent: Option<(P2, P2)>,
        path: &str,
        origin: &Origin,
    ) -> Result<Grid, Diagnostic> {
        let err = |msg, args| Diagnostic::error(msg, origin.clone(), args);
        let (lo, hi) = match (hm.area, extent) {
            (Some([x0, y0, x1, y1]), _) => {
                let (lo, hi) = (P2 { x: x0, y: y0 }, P2 { x: x1, y: y1 });
                if let Some((a, b)) = extent {
                    let eps = 1e-6;
                    if a.x < lo.x - eps || a.y < lo.y - eps || b.x > hi.x + eps || b.y > hi.y + eps
                    {
                        let n = |v: f64| F3(v).to_string();
                        return Err(err(
                            Msg::HeightmapAreaTooSmall,
                            args![path, a, b, n(x0), n(y0), n(x1), n(y1)],
                        ));
                    }
                }
                (lo, hi)
            }
            (None, Some((a, b))) => {
                let m = hm.margin;
                (
                    P2 {
                        x: a.x - m,
                        y: a.y - m,
                    },
                    P2 {
                        x: b.x + m,
                        y: b.y + m,
                    },
                )
            }
            (None, None) => return Err(err(Msg::HeightmapNoCuts, args![path])),
        };
        Grid::over(lo, hi, hm.step).map_err(|(m, a)| err(m, a))
    }

    /// The points in the order the probing program visits them: rows from the lowest Y,
    /// the first row by ascending X, the next by descending X, and so on.
    pub fn serpentine(&self) -> Vec<P2> {
        let mut out = Vec::with_capacity(self.xs.len() * self.ys.len());
        for (j, &y) in self.ys.iter().enumerate() {
            let row = self.xs.iter().map(|&x| P2 { x, y });
            if j % 2 == 0 {
                out.extend(row);
            } else {
                out.extend(row.rev());
            }
        }
        out
    }
}

/// The `_Z.txt` name of the `k`-th point of the tour.
pub fn var_name(k: usize) -> String {
    format!("#{}", FIRST_VAR + k)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> P2 {
        P2 { x, y }
    }

    #[test]
    fn grid_covers_the_extent_plus_margin_with_the_last_line_on_the_edge() {
        let hm = Heightmap {
            margin: 2.0,
            ..Heightmap::with_step(10.0)
        };
        let o = Origin::Options;
        let g = Grid::of_program(&hm, Some((p(0.0, 0.0), p(25.0, 10.0))), "P", &o).unwrap();
        assert_eq!(g.xs, vec![-2.0, 8.0, 18.0, 27.0]);
        assert_eq!(g.ys, vec![-2.0, 8.0, 12.0]);
        // an exact multiple gets no extra line
        let g = Grid::over(p(0.0, 0.0), p(20.0, 0.0), 10.0).unwrap();
        assert_eq!((g.xs, g.ys), (vec![0.0, 10.0, 20.0], vec![0.0]));
        // an explicit area is taken as it is and must hold the cuts
        let area = Heightmap {
            area: Some([-5.0, -5.0, 30.0, 15.0]),
            ..hm
        };
        let g = Grid::of_program(&area, Some((p(0.0, 0.0), p(25.0, 10.0))), "P", &o).unwrap();
        assert_eq!((g.xs[0], *g.xs.last().unwrap()), (-5.0, 30.0));
        let e = Grid::of_program(&area, Some((p(0.0, 0.0), p(31.0, 10.0))), "P", &o);
        assert_eq!(e.unwrap_err().msg, Msg::HeightmapAreaTooSmall);
        let e = Grid::of_program(&hm, None, "P", &o);
        assert_eq!(e.unwrap_err().msg, Msg::HeightmapNoCuts);
    }

    #[test]
    fn serpentine_order() {
        let g = Grid {
            xs: vec![0.0, 1.0, 2.0],
            ys: vec![0.0, 5.0, 9.0],
        };
        let v: Vec<(f64, f64)> = g.serpentine().iter().map(|q| (q.x, q.y)).collect();
        assert_eq!(
            v,
            vec![
                (0.0, 0.0),
                (1.0, 0.0),
                (2.0, 0.0),
                (2.0, 5.0),
                (1.0, 5.0),
                (0.0, 5.0),
                (0.0, 9.0),
                (1.0, 9.0),
                (2.0, 9.0)
            ]
        );
        // each step of the tour is one grid step: no long diagonal runs
        for w in g.serpentine().windows(2) {
            assert!(w[0].dist(w[1]) <= 5.0 + 1e-9);
        }
    }

    #[test]
    fn bounds_are_refused() {
        let at = |n: &str| (format!("heightmap.{n}"), Origin::Options);
        let msgs = |h: Heightmap| -> Vec<Msg> { h.errors(&at).iter().map(|d| d.msg).collect() };
        assert!(msgs(Heightmap::with_step(10.0)).is_empty());
        assert_eq!(
            msgs(Heightmap::with_step(0.0)),
            [Msg::HeightmapStepTooSmall]
        );
        assert_eq!(
            msgs(Heightmap::with_step(-3.0)),
            [Msg::HeightmapStepTooSmall]
        );
        assert_eq!(
            msgs(Heightmap::with_step(f64::NAN)),
            [Msg::SettingNotFinite]
        );
        assert_eq!(
            msgs(Heightmap::with_step(f64::INFINITY)),
            [Msg::SettingNotFinite]
        );
        let neg = Heightmap {
            margin: -1.0,
            ..Heightmap::with_step(10.0)
        };
        assert_eq!(msgs(neg), [Msg::HeightmapNegative]);
        let depth = Heightmap {
            probe_depth: 0.0,
            probe_feed: Some(-5.0),
            ..Heightmap::with_step(10.0)
        };
        assert_eq!(msgs(depth), [Msg::MustBePositive, Msg::MustBePositive]);
        let flipped = Heightmap {
            area: Some([10.0, 0.0, 0.0, 10.0]),
            ..Heightmap::with_step(1.0)
        };
        assert_eq!(msgs(flipped), [Msg::HeightmapAreaEmpty]);
        // 101 × 101 points
        let big = Heightmap {
            area: Some([0.0, 0.0, 100.0, 100.0]),
            ..Heightmap::with_step(1.0)
        };
        assert_eq!(msgs(big), [Msg::HeightmapTooManyPoints]);
        // the largest square allowed: 63 × 63 = 3969
        let ok = Heightmap {
            area: Some([0.0, 0.0, 62.0, 62.0]),
            ..Heightmap::with_step(1.0)
        };
        assert!(msgs(ok).is_empty());
        // the message names the key as the user wrote it
        let d = &Heightmap::with_step(0.1).errors(&at)[0];
        assert!(d.message(crate::Lang::En).contains("heightmap.step=0.1"));
        // a huge extent is refused before anything is allocated
        let e = Grid::over(p(0.0, 0.0), p(1e9, 1e9), 0.5).unwrap_err();
        assert_eq!(e.0, Msg::HeightmapTooManyPoints);
    }

    #[test]
    fn variable_names_stay_in_the_user_range() {
        assert_eq!(var_name(0), "#1000");
        assert_eq!(var_name(MAX_POINTS - 1), "#4999");
    }
}
