//! A measured surface (height map): heights on a rectangular grid of probe points, the
//! bilinear interpolation between them, and its record in a program's comments.
//!
//! adjust-z writes the map it adjusted a program to into that program
//! ([`HeightMap::comment_lines`]); `verify` reads it back ([`HeightMap::read_comments`]) to
//! judge every move against the surface instead of the flat nominal top. Both sides share
//! this one definition of the format and of the interpolation.
//!
//! ```text
//! (MILLPATH-SURFACE T=3.000 NX=4 NY=2)
//! (MILLPATH-SURFACE-X I=0 3.000 13.000 23.000 27.000)
//! (MILLPATH-SURFACE-Y J=0 -2.000 2.000)
//! (MILLPATH-SURFACE-Z J=0 I=0 3.012 3.020 3.050 3.061)
//! (MILLPATH-SURFACE-Z J=1 I=0 3.101 3.090 3.070 3.066)
//! ```
//! `T` is the nominal top the heights were measured against; the X and Y lines give the grid
//! columns and rows (ascending); each Z line gives row `J`'s heights from column `I` on.
//! Long lists continue on further lines (LinuxCNC reads at most 255 characters a line).

use crate::magnitude::MAX_MAGNITUDE;

/// The word that starts every line of the record.
pub const SURFACE_WORD: &str = "MILLPATH-SURFACE";
/// At most this many grid points (the height-map probing program's own bound).
pub const MAX_NODES: usize = 4000;
/// A point this close outside the grid (mm) counts as on its edge: coordinates are
/// written with three decimals on both sides.
pub const EDGE: f64 = 0.002;
/// Values per comment line: 16 of at most 13 characters stay within 255.
const LINE_VALUES: usize = 16;

/// What keeps a set of heights or a record from being a height map.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceProblem {
    /// A number that is not finite or beyond ±1e6.
    BadNumber { text: String },
    /// More than [`MAX_NODES`] points, or no points.
    Size { nx: usize, ny: usize },
    /// Columns or rows not strictly ascending.
    NotAscending,
    /// The grid point (x, y) has no height.
    Missing { x: f64, y: f64 },
    /// The grid point (x, y) has two heights.
    Duplicate { x: f64, y: f64 },
    /// A record line that cannot be read, or a record that is incomplete.
    Malformed { text: String },
}

impl std::fmt::Display for SurfaceProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SurfaceProblem::BadNumber { text } => write!(f, "'{text}' is not a sane number"),
            SurfaceProblem::Size { nx, ny } => {
                write!(f, "{nx} × {ny} points (1 to {MAX_NODES} allowed)")
            }
            SurfaceProblem::NotAscending => write!(f, "grid lines not in ascending order"),
            SurfaceProblem::Missing { x, y } => write!(f, "no height at [{x:.3} {y:.3}]"),
            SurfaceProblem::Duplicate { x, y } => write!(f, "two heights at [{x:.3} {y:.3}]"),
            SurfaceProblem::Malformed { text } => write!(f, "unreadable record: {text}"),
        }
    }
}

/// Heights `z[j * nx + i]` at the grid points (`xs[i]`, `ys[j]`), measured against the
/// nominal top `top`.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    xs: Vec<f64>,
    ys: Vec<f64>,
    z: Vec<f64>,
    top: f64,
}

fn sane(v: f64) -> bool {
    v.is_finite() && v.abs() <= MAX_MAGNITUDE
}

impl HeightMap {
    /// A map from its columns, rows and row-major heights; `Err` unless every number is
    /// sane, the lines strictly ascend and the counts agree.
    pub fn new(xs: Vec<f64>, ys: Vec<f64>, z: Vec<f64>, top: f64) -> Result<Self, SurfaceProblem> {
        let (nx, ny) = (xs.len(), ys.len());
        if nx == 0 || ny == 0 || nx.saturating_mul(ny) > MAX_NODES || z.len() != nx * ny {
            return Err(SurfaceProblem::Size { nx, ny });
        }
        if let Some(v) = xs
            .iter()
            .chain(&ys)
            .chain(&z)
            .chain([&top])
            .find(|v| !sane(**v))
        {
            return Err(SurfaceProblem::BadNumber {
                text: v.to_string(),
            });
        }
        let ascending = |v: &[f64]| v.windows(2).all(|w| w[1] > w[0]);
        if !ascending(&xs) || !ascending(&ys) {
            return Err(SurfaceProblem::NotAscending);
        }
        Ok(HeightMap { xs, ys, z, top })
    }

    /// A map from measured points `(x, y, height)` in any order: the distinct X and Y
    /// values (closer than `tol` count as one) must form a full grid, each point once.
    pub fn from_points(
        points: &[(f64, f64, f64)],
        top: f64,
        tol: f64,
    ) -> Result<Self, SurfaceProblem> {
        if points.is_empty() || points.len() > MAX_NODES {
            return Err(SurfaceProblem::Size {
                nx: points.len(),
                ny: 1,
            });
        }
        if let Some(v) = points
            .iter()
            .flat_map(|p| [p.0, p.1, p.2])
            .find(|v| !sane(*v))
        {
            return Err(SurfaceProblem::BadNumber {
                text: v.to_string(),
            });
        }
        let lines = |coord: &dyn Fn(&(f64, f64, f64)) -> f64| {
            let mut v: Vec<f64> = points.iter().map(coord).collect();
            v.sort_by(f64::total_cmp);
            v.dedup_by(|b, a| (*b - *a).abs() <= tol);
            v
        };
        let (xs, ys) = (lines(&|p| p.0), lines(&|p| p.1));
        if xs.len().saturating_mul(ys.len()) > MAX_NODES {
            return Err(SurfaceProblem::Size {
                nx: xs.len(),
                ny: ys.len(),
            });
        }
        let index = |v: &[f64], c: f64| v.iter().position(|l| (l - c).abs() <= tol);
        let mut z = vec![None; xs.len() * ys.len()];
        for &(x, y, h) in points {
            // every point is on a line: the lines were made from the points
            let (Some(i), Some(j)) = (index(&xs, x), index(&ys, y)) else {
                return Err(SurfaceProblem::Missing { x, y });
            };
            let slot = &mut z[j * xs.len() + i];
            if slot.is_some() {
                return Err(SurfaceProblem::Duplicate { x: xs[i], y: ys[j] });
            }
            *slot = Some(h);
        }
        if let Some(k) = z.iter().position(Option::is_none) {
            let (i, j) = (k % xs.len(), k / xs.len());
            return Err(SurfaceProblem::Missing { x: xs[i], y: ys[j] });
        }
        let z = z.into_iter().flatten().collect();
        HeightMap::new(xs, ys, z, top)
    }

    pub fn xs(&self) -> &[f64] {
        &self.xs
    }
    pub fn ys(&self) -> &[f64] {
        &self.ys
    }
    /// The nominal top the heights were measured against.
    pub fn top(&self) -> f64 {
        self.top
    }
    /// The measured height at grid point (i, j).
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.z[j * self.xs.len() + i]
    }
    /// The highest measured point.
    pub fn max_height(&self) -> f64 {
        self.z.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }
    /// The lowest measured point.
    pub fn min_height(&self) -> f64 {
        self.z.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// Whether (x, y) lies on the map (within [`EDGE`]).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let inside = |v: &[f64], c: f64| c >= v[0] - EDGE && c <= v[v.len() - 1] + EDGE;
        inside(&self.xs, x) && inside(&self.ys, y)
    }

    /// The interval of `lines` that holds `c` (clamped onto the edges) and the position of
    /// `c` in it (0..=1); a single line is an interval of width 0.
    fn locate(lines: &[f64], c: f64) -> (usize, f64) {
        if lines.len() == 1 {
            return (0, 0.0);
        }
        let c = c.clamp(lines[0], lines[lines.len() - 1]);
        let k = lines[1..lines.len() - 1].partition_point(|l| *l <= c);
        let (a, b) = (lines[k], lines[k + 1]);
        (k, ((c - a) / (b - a)).clamp(0.0, 1.0))
    }

    /// The cell (i, j) whose lower-left grid point is (`xs[i]`, `ys[j]`) holding (x, y);
    /// on a grid line, the cell above or right of it (the last cell at the far edge).
    pub fn cell(&self, x: f64, y: f64) -> (usize, usize) {
        (Self::locate(&self.xs, x).0, Self::locate(&self.ys, y).0)
    }

    /// The surface height at (x, y) by bilinear interpolation of the cell's four corners;
    /// `None` off the map (never an extrapolation).
    pub fn height(&self, x: f64, y: f64) -> Option<f64> {
        if !self.contains(x, y) {
            return None;
        }
        let (i, u) = Self::locate(&self.xs, x);
        let (j, v) = Self::locate(&self.ys, y);
        let i1 = (i + 1).min(self.xs.len() - 1);
        let j1 = (j + 1).min(self.ys.len() - 1);
        let (z00, z10) = (self.at(i, j), self.at(i1, j));
        let (z01, z11) = (self.at(i, j1), self.at(i1, j1));
        let bottom = z00 + (z10 - z00) * u;
        let top = z01 + (z11 - z01) * u;
        Some(bottom + (top - bottom) * v)
    }

    /// How far the surface at (x, y) lies above the nominal top; `None` off the map.
    pub fn offset(&self, x: f64, y: f64) -> Option<f64> {
        self.height(x, y).map(|h| h - self.top)
    }

    /// The record of this map as comment lines (without line ends), each within 255
    /// characters.
    pub fn comment_lines(&self) -> Vec<String> {
        let f3 = |v: f64| format!("{v:.3}");
        let mut out = vec![format!(
            "({SURFACE_WORD} T={} NX={} NY={})",
            f3(self.top),
            self.xs.len(),
            self.ys.len()
        )];
        let list = |out: &mut Vec<String>, head: &dyn Fn(usize) -> String, v: &[f64]| {
            for (c, chunk) in v.chunks(LINE_VALUES).enumerate() {
                let values: Vec<String> = chunk.iter().map(|x| f3(*x)).collect();
                out.push(format!("({} {})", head(c * LINE_VALUES), values.join(" ")));
            }
        };
        list(&mut out, &|i| format!("{SURFACE_WORD}-X I={i}"), &self.xs);
        list(&mut out, &|j| format!("{SURFACE_WORD}-Y J={j}"), &self.ys);
        let nx = self.xs.len();
        for j in 0..self.ys.len() {
            let row = &self.z[j * nx..(j + 1) * nx];
            list(&mut out, &|i| format!("{SURFACE_WORD}-Z J={j} I={i}"), row);
        }
        out
    }

    /// The map recorded in a program's comments (lines numbered from 1): `None` when there
    /// is no record, else the map or the first problem with its line.
    pub fn read_comments<'a>(
        lines: impl Iterator<Item = &'a str>,
    ) -> Option<Result<HeightMap, (usize, SurfaceProblem)>> {
        let mut rec = Record::default();
        for (n, line) in lines.enumerate() {
            let Some(at) = line.find(SURFACE_WORD) else {
                continue;
            };
            // only inside a parenthesised comment
            if !line[..at].ends_with('(') {
                continue;
            }
            let body = line[at..].split(')').next().unwrap_or("");
            if let Err(p) = rec.take(body) {
                return Some(Err((n + 1, p)));
            }
            rec.last_line = n + 1;
        }
        rec.finish()
    }
}

/// A record being read: the header's values and the lists as they come.
#[derive(Default)]
struct Record {
    header: Option<(f64, usize, usize)>,
    xs: Vec<Option<f64>>,
    ys: Vec<Option<f64>>,
    z: Vec<Option<f64>>,
    last_line: usize,
}

impl Record {
    fn take(&mut self, body: &str) -> Result<(), SurfaceProblem> {
        let bad = || SurfaceProblem::Malformed {
            text: body.chars().take(60).collect(),
        };
        let mut words = body.split_whitespace();
        let kind = words.next().ok_or_else(bad)?;
        let mut key = |name: &str| -> Result<&str, SurfaceProblem> {
            let w = words.next().ok_or_else(bad)?;
            w.strip_prefix(name)
                .and_then(|v| v.strip_prefix('='))
                .ok_or_else(bad)
        };
        let count = |v: &str| v.parse::<usize>().map_err(|_| bad());
        let number = |v: &str| -> Result<f64, SurfaceProblem> {
            match v.parse::<f64>() {
                Ok(x) if sane(x) => Ok(x),
                _ => Err(SurfaceProblem::BadNumber {
                    text: v.chars().take(40).collect(),
                }),
            }
        };
        match kind {
            SURFACE_WORD => {
                if self.header.is_some() {
                    return Err(bad());
                }
                let top = number(key("T")?)?;
                let (nx, ny) = (count(key("NX")?)?, count(key("NY")?)?);
                if nx == 0 || ny == 0 || nx.saturating_mul(ny) > MAX_NODES {
                    return Err(SurfaceProblem::Size { nx, ny });
                }
                self.header = Some((top, nx, ny));
                self.xs = vec![None; nx];
                self.ys = vec![None; ny];
                self.z = vec![None; nx * ny];
            }
            _ => {
                let (_, nx, ny) = self.header.ok_or_else(bad)?;
                let (slots, offset) = match kind.strip_prefix(SURFACE_WORD) {
                    Some("-X") => (&mut self.xs, count(key("I")?)?),
                    Some("-Y") => (&mut self.ys, count(key("J")?)?),
                    Some("-Z") => {
                        let j = count(key("J")?)?;
                        let i = count(key("I")?)?;
                        if j >= ny || i >= nx {
                            return Err(bad());
                        }
                        (&mut self.z, j * nx + i)
                    }
                    _ => return Err(bad()),
                };
                let row_end = match kind {
                    k if k.ends_with("-Z") => (offset / nx + 1) * nx,
                    _ => slots.len(),
                };
                for (k, w) in words.enumerate() {
                    let at = offset + k;
                    if at >= row_end || slots[at].is_some() {
                        return Err(bad());
                    }
                    slots[at] = Some(number(w)?);
                }
            }
        }
        Ok(())
    }

    fn finish(self) -> Option<Result<HeightMap, (usize, SurfaceProblem)>> {
        let (top, _, _) = self.header?;
        let at = self.last_line;
        let all = |v: Vec<Option<f64>>| v.into_iter().collect::<Option<Vec<f64>>>();
        let incomplete = || SurfaceProblem::Malformed {
            text: "values missing".to_string(),
        };
        let (Some(xs), Some(ys), Some(z)) = (all(self.xs), all(self.ys), all(self.z)) else {
            return Some(Err((at, incomplete())));
        };
        Some(HeightMap::new(xs, ys, z, top).map_err(|p| (at, p)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn twist() -> HeightMap {
        // z = 3 + 0.01·x + 0.02·y + 0.001·x·y on a 3 × 2 grid with a short last column
        let xs = vec![0.0, 10.0, 15.0];
        let ys = vec![-5.0, 5.0];
        let f = |x: f64, y: f64| 3.0 + 0.01 * x + 0.02 * y + 0.001 * x * y;
        let z = ys
            .iter()
            .flat_map(|&y| xs.iter().map(move |&x| f(x, y)))
            .collect();
        HeightMap::new(xs, ys, z, 3.0).unwrap()
    }

    #[test]
    fn bilinear_is_exact_for_a_bilinear_surface_and_refuses_outside() {
        let m = twist();
        let f = |x: f64, y: f64| 3.0 + 0.01 * x + 0.02 * y + 0.001 * x * y;
        for &(x, y) in &[
            (0.0, -5.0),
            (3.3, 1.7),
            (10.0, 0.0),
            (14.9, 4.9),
            (15.0, 5.0),
        ] {
            assert!((m.height(x, y).unwrap() - f(x, y)).abs() < 1e-12, "{x} {y}");
            assert!((m.offset(x, y).unwrap() - (f(x, y) - 3.0)).abs() < 1e-12);
        }
        // on the edge within EDGE, never beyond
        assert!(m.height(-0.001, 0.0).is_some());
        assert!(m.height(-0.01, 0.0).is_none());
        assert!(m.height(7.0, 5.01).is_none());
        assert!(m.height(f64::NAN, 0.0).is_none());
        assert_eq!(m.cell(10.0, 0.0), (1, 0));
        assert_eq!(m.cell(15.0, 5.0), (1, 0));
    }

    #[test]
    fn a_single_row_interpolates_along_it() {
        let m = HeightMap::new(vec![0.0, 10.0], vec![2.0], vec![1.0, 2.0], 1.0).unwrap();
        assert!((m.height(2.5, 2.0).unwrap() - 1.25).abs() < 1e-12);
        assert!(m.height(2.5, 2.1).is_none());
    }

    #[test]
    fn the_record_reads_back_and_stays_within_255_characters() {
        let m = twist();
        let lines = m.comment_lines();
        assert_eq!(lines[0], "(MILLPATH-SURFACE T=3.000 NX=3 NY=2)");
        let back = HeightMap::read_comments(lines.iter().map(String::as_str))
            .unwrap()
            .unwrap();
        assert_eq!(back.xs(), m.xs());
        for j in 0..2 {
            for i in 0..3 {
                assert!((back.at(i, j) - m.at(i, j)).abs() <= 0.0005);
            }
        }
        // a big map: chunked lines, all read back
        let (nx, ny) = (100, 40);
        let xs: Vec<f64> = (0..nx).map(|i| -999_000.0 + i as f64).collect();
        let ys: Vec<f64> = (0..ny).map(|j| j as f64 * 2.5).collect();
        let z: Vec<f64> = (0..nx * ny).map(|k| -999_999.123 + k as f64).collect();
        let big = HeightMap::new(xs, ys, z, -999_999.0).unwrap();
        let lines = big.comment_lines();
        assert!(
            lines.iter().all(|l| l.len() <= 255),
            "{}",
            lines.iter().map(|l| l.len()).max().unwrap()
        );
        let back = HeightMap::read_comments(lines.iter().map(String::as_str))
            .unwrap()
            .unwrap();
        assert_eq!(back, big);
        // no record at all
        assert!(HeightMap::read_comments(["G00 X1", "(MILLPATH-STOCK T=1)"].into_iter()).is_none());
    }

    #[test]
    fn broken_records_are_problems_with_their_line() {
        let good = twist().comment_lines();
        let read = |lines: &[String]| HeightMap::read_comments(lines.iter().map(String::as_str));
        // a line missing
        let mut cut = good.clone();
        cut.remove(4);
        assert!(matches!(
            read(&cut),
            Some(Err((_, SurfaceProblem::Malformed { .. })))
        ));
        // a value that is no number
        let nan = good
            .iter()
            .map(|l| l.replace("3.250", "NaN"))
            .collect::<Vec<_>>();
        assert!(
            matches!(read(&nan), Some(Err((5, SurfaceProblem::BadNumber { .. })))),
            "{:?}",
            read(&nan)
        );
        // too many values in a row, a row beyond NY, a huge header
        let mut extra = good.clone();
        extra[4] = extra[4].replace(')', " 1.0)");
        assert!(read(&extra).unwrap().is_err());
        let mut beyond = good.clone();
        beyond.push("(MILLPATH-SURFACE-Z J=2 I=0 1 1 1)".into());
        assert!(read(&beyond).unwrap().is_err());
        let huge = vec!["(MILLPATH-SURFACE T=1 NX=100000 NY=100000)".to_string()];
        assert!(matches!(
            read(&huge),
            Some(Err((1, SurfaceProblem::Size { .. })))
        ));
        // values before the header
        let mut early = good.clone();
        early.swap(0, 1);
        assert!(read(&early).unwrap().is_err());
    }

    #[test]
    fn points_in_any_order_make_the_grid_or_name_the_gap() {
        let pts = [
            (10.0, 0.0, 1.0),
            (0.0, 0.0, 0.5),
            (0.0004, 8.0, 0.7),
            (10.0, 8.0, 1.2),
        ];
        let m = HeightMap::from_points(&pts, 0.0, 0.01).unwrap();
        assert_eq!(m.xs(), &[0.0, 10.0]);
        assert_eq!((m.at(0, 1), m.at(1, 1)), (0.7, 1.2));
        let gap = HeightMap::from_points(&pts[..3], 0.0, 0.01).unwrap_err();
        assert_eq!(gap, SurfaceProblem::Missing { x: 10.0, y: 8.0 });
        let mut twice = pts.to_vec();
        twice.push((10.0, 8.001, 1.3));
        assert_eq!(
            HeightMap::from_points(&twice, 0.0, 0.01).unwrap_err(),
            SurfaceProblem::Duplicate { x: 10.0, y: 8.0 }
        );
        let nan = [(0.0, 0.0, f64::NAN)];
        assert!(matches!(
            HeightMap::from_points(&nan, 0.0, 0.01),
            Err(SurfaceProblem::BadNumber { .. })
        ));
    }
}
