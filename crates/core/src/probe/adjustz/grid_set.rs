//! The measured surface of a height-map set: the `_Z.txt` of `[heightmap]` names every grid
//! point with its XY (`([x y]/T=t) #1000=h`), so its filled-in values are the map.

use super::bounds::{line_origin, MaxOption};
use super::zfile::ZLine;
use crate::args;
use crate::diag::{Diags, Msg};
use crate::geom::F3;
use millpath_verify::surface::{HeightMap, SurfaceProblem, MAX_NODES};

/// Grid coordinates are written with three decimals: closer values are one line.
const SAME_LINE: f64 = 1e-6;

/// The `[x y]` at the start of a `_Z.txt` line's comment.
fn point_of(line: &str) -> Option<(f64, f64)> {
    let inner = line.trim().strip_prefix("([")?;
    let (xy, _) = inner.split_once(']')?;
    let mut it = xy.split_whitespace().map(|v| v.parse::<f64>().ok());
    let (x, y) = (it.next()??, it.next()??);
    (it.next().is_none() && x.is_finite() && y.is_finite()).then_some((x, y))
}

/// The height map of a filled-in grid `_Z.txt` (`lines` as [`super::parse_z_file`] read
/// them from `text`): every point once, one nominal top, each measured value within `max`
/// of it. Measured values are taken to 0.001 mm, as the adjusted program records them.
/// `None` after errors, each at its line.
pub fn surface(
    text: &str,
    file: &str,
    lines: &[ZLine],
    max: f64,
    opt: MaxOption,
    diags: &mut Diags,
) -> Option<HeightMap> {
    let before = diags.error_count();
    if lines.len() > MAX_NODES {
        let at = line_origin(file, lines[MAX_NODES].line);
        diags.error(Msg::SurfaceGridSize, at, args![lines.len(), MAX_NODES]);
        return None;
    }
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let raw: Vec<&str> = text.lines().collect();
    let first = lines.first()?;
    let mut points = Vec::with_capacity(lines.len());
    for zl in lines {
        let origin = line_origin(file, zl.line);
        let Some((x, y)) = raw.get(zl.line - 1).and_then(|l| point_of(l)) else {
            diags.error(Msg::ZLineFormat, origin, vec![]);
            continue;
        };
        if (zl.t - first.t).abs() > 1e-9 {
            let args = args![zl.t_text, zl.name, F3(first.t), file, first.line];
            diags.error(Msg::ZNominalMismatch, origin, args);
            continue;
        }
        if (zl.value - zl.t).abs() > max {
            let msg = match opt {
                MaxOption::Slash => Msg::ZTooFar,
                MaxOption::Long => Msg::ZTooFarMax,
            };
            diags.error(msg, origin, args![zl.value_text, zl.name, F3(zl.t), max]);
            continue;
        }
        points.push((x, y, (zl.value * 1000.0).round() / 1000.0));
    }
    if diags.error_count() > before {
        return None;
    }
    match HeightMap::from_points(&points, first.t, SAME_LINE) {
        Ok(map) => Some(map),
        Err(p) => {
            let at = line_origin(file, first.line);
            let (msg, args) = match p {
                SurfaceProblem::Missing { x, y } => (Msg::SurfacePointMissing, args![F3(x), F3(y)]),
                SurfaceProblem::Duplicate { x, y } => (Msg::SurfacePointTwice, args![F3(x), F3(y)]),
                // the values were checked above: only the grid's size is left
                _ => (Msg::SurfaceGridSize, args![points.len(), MAX_NODES]),
            };
            diags.error(msg, at, args);
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::parse_z_file;
    use super::*;

    fn read(z: &str, max: f64) -> (Option<HeightMap>, Vec<Msg>) {
        let mut d = Diags::default();
        let lines = parse_z_file(z, "z", &mut d);
        if d.has_errors() {
            return (None, d.list.iter().map(|x| x.msg).collect());
        }
        let map = surface(z, "z", &lines, max, MaxOption::Long, &mut d);
        (map, d.list.iter().map(|x| x.msg).collect())
    }

    const GRID: &str = "([0.000 0.000]/T=3.000) #1000=3.1\n([10.000 0.000]/T=3.000) #1001=3,2\n([10.000 5.000]/T=3.000) #1002=3.0004\n([0.000 5.000]/T=3.000) #1003=2.9\n";

    #[test]
    fn a_filled_grid_is_the_map() {
        let (map, msgs) = read(GRID, 1.0);
        assert!(msgs.is_empty(), "{msgs:?}");
        let map = map.unwrap();
        assert_eq!(
            (map.xs(), map.ys(), map.top()),
            (&[0.0, 10.0][..], &[0.0, 5.0][..], 3.0)
        );
        assert_eq!(
            (map.at(0, 0), map.at(1, 0), map.at(1, 1), map.at(0, 1)),
            (3.1, 3.2, 3.0, 2.9)
        );
    }

    #[test]
    fn gaps_doubles_limits_and_mixed_tops_are_refused() {
        let missing = GRID.replace("([10.000 5.000]/T=3.000) #1002=3.0004\n", "");
        assert_eq!(read(&missing, 1.0).1, [Msg::SurfacePointMissing]);
        let twice = GRID.replace("[10.000 5.000]", "[10.000 0.000]");
        assert_eq!(read(&twice, 1.0).1, [Msg::SurfacePointTwice]);
        assert_eq!(read(GRID, 0.15).1, [Msg::ZTooFarMax]);
        let top = GRID.replace("[0.000 5.000]/T=3.000", "[0.000 5.000]/T=2.000");
        assert_eq!(read(&top, 1.0).1, [Msg::ZNominalMismatch]);
        let nan = GRID.replace("#1003=2.9", "#1003=NaN");
        assert_eq!(read(&nan, 1.0).1, [Msg::ZNotNumber]);
        let no_xy = GRID.replace("([0.000 5.000]", "(5.000");
        assert_eq!(read(&no_xy, 1.0).1, [Msg::ZLineFormat]);
    }
}
