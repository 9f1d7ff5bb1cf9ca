//! The height map of the toolpath view as plain data: the grid, its heights and each point's
//! colour, so the page only draws. A path with `[heightmap]` being edited shows its probe
//! points at the nominal top (not measured yet); a measured surface (`render --surface`)
//! shows its heights, coloured from the lowest to the highest with a legend.
//!
//! The height map of the toolpath view as data: a `[heightmap]` grid at T, or a measured surface
//! (`with_surface`) with each point's colour (blue → teal → yellow) and the legend; cells in the
//! SVG top view.

use serde_json::{json, Value};

/// The colour ramp of measured heights, low → high (blue, teal, yellow): unlike the depth
/// ramp of the cuts, so the surface is not read as a depth.
const RAMP: [(f64, [f64; 3]); 3] = [
    (0.0, [48.0, 64.0, 200.0]),
    (0.5, [32.0, 170.0, 140.0]),
    (1.0, [245.0, 205.0, 40.0]),
];
/// The probe points of a grid not measured yet.
const GRID_COLOUR: &str = "#8a8f98";

/// The ramp's colour at `t` in 0..=1 as `#rrggbb`.
pub fn ramp(t: f64) -> String {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.5
    };
    let k = usize::from(t > RAMP[1].0);
    let ((t0, a), (t1, b)) = (RAMP[k], RAMP[k + 1]);
    let u = (t - t0) / (t1 - t0);
    let c: Vec<String> = (0..3)
        .map(|i| format!("{:02x}", (a[i] + (b[i] - a[i]) * u).round() as u8))
        .collect();
    format!("#{}", c.concat())
}

fn r3(v: f64) -> f64 {
    let r = (v * 1000.0).round() / 1000.0;
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

/// The view's `heightmap` entry: columns `xs`, rows `ys`, heights `z` row by row (`None`:
/// not measured, every point at the nominal `top`).
pub fn heightmap_json(xs: &[f64], ys: &[f64], z: Option<&[f64]>, top: f64) -> Value {
    let nx = xs.len();
    let height = |i: usize, j: usize| z.and_then(|z| z.get(j * nx + i).copied()).unwrap_or(top);
    let all = || (0..ys.len()).flat_map(|j| (0..nx).map(move |i| height(i, j)));
    let (min, max) = all().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| {
        (lo.min(h), hi.max(h))
    });
    let colour = |h: f64| match z {
        None => GRID_COLOUR.to_string(),
        Some(_) if max > min => ramp((h - min) / (max - min)),
        Some(_) => ramp(0.5),
    };
    let rows = |f: &dyn Fn(f64) -> Value| -> Vec<Value> {
        (0..ys.len())
            .map(|j| Value::Array((0..nx).map(|i| f(height(i, j))).collect()))
            .collect()
    };
    json!({
        "measured": z.is_some(),
        "top": r3(top),
        "xs": xs.iter().map(|v| r3(*v)).collect::<Vec<_>>(),
        "ys": ys.iter().map(|v| r3(*v)).collect::<Vec<_>>(),
        "z": rows(&|h| json!(r3(h))),
        "colours": rows(&|h| json!(colour(h))),
        "legend": {
            "min": r3(if min.is_finite() { min } else { top }),
            "max": r3(if max.is_finite() { max } else { top }),
            "ramp": [ramp(0.0), ramp(0.5), ramp(1.0)],
        },
    })
}

/// Puts a measured surface into the toolpath data (`render --surface`), in place of the
/// probe grid; the XY bounds grow to hold it.
pub fn with_surface(data: &mut Value, map: &millpath_verify::HeightMap) {
    let z: Vec<f64> = (0..map.ys().len())
        .flat_map(|j| (0..map.xs().len()).map(move |i| map.at(i, j)))
        .collect();
    let hm = heightmap_json(map.xs(), map.ys(), Some(&z), map.top());
    grow_bounds(data, &hm);
    data["heightmap"] = hm;
}

/// The XY bounds of `data` widened to the map's (the Z bounds stay the cuts': they scale the
/// depth colours).
pub fn grow_bounds(data: &mut Value, hm: &Value) {
    let num = |v: &Value| v.as_f64().unwrap_or(0.0);
    let first_last = |key: &str| {
        let a = hm[key].as_array().cloned().unwrap_or_default();
        (a.first().map(num), a.last().map(num))
    };
    let ((Some(x0), Some(x1)), (Some(y0), Some(y1))) = (first_last("xs"), first_last("ys")) else {
        return;
    };
    let b = &mut data["bounds"];
    let mut set = |key: &str, v: f64, lower: bool| {
        let old = b[key].as_f64().unwrap_or(v);
        b[key] = json!(if lower { old.min(v) } else { old.max(v) });
    };
    set("minX", x0, true);
    set("maxX", x1, false);
    set("minY", y0, true);
    set("maxY", y1, false);
}

/// The map in the SVG top view, under the moves: measured cells filled with the colour of
/// their mean height, probe points of a grid not measured as small circles.
pub fn svg(hm: &Value, stroke: f64) -> String {
    use std::fmt::Write;
    let num = |v: &Value| v.as_f64().unwrap_or(0.0);
    let list = |key: &str| -> Vec<f64> {
        hm[key]
            .as_array()
            .map(|a| a.iter().map(num).collect())
            .unwrap_or_default()
    };
    let (xs, ys) = (list("xs"), list("ys"));
    let mut s = String::new();
    if hm["measured"].as_bool() != Some(true) {
        for y in &ys {
            for x in &xs {
                let _ = writeln!(
                    s,
                    r#"<circle cx="{x}" cy="{y}" r="{}" fill="{GRID_COLOUR}"/>"#,
                    stroke * 2.0
                );
            }
        }
        return s;
    }
    let (lo, hi) = (num(&hm["legend"]["min"]), num(&hm["legend"]["max"]));
    let z = |i: usize, j: usize| num(&hm["z"][j][i]);
    for j in 0..ys.len().saturating_sub(1) {
        for i in 0..xs.len().saturating_sub(1) {
            let mean = (z(i, j) + z(i + 1, j) + z(i, j + 1) + z(i + 1, j + 1)) / 4.0;
            let t = if hi > lo {
                (mean - lo) / (hi - lo)
            } else {
                0.5
            };
            let _ = writeln!(
                s,
                r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{}" fill-opacity="0.45"/>"#,
                xs[i],
                ys[j],
                xs[i + 1] - xs[i],
                ys[j + 1] - ys[j],
                ramp(t)
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_follow_the_heights() {
        assert_eq!(ramp(0.0), "#3040c8");
        assert_eq!(ramp(1.0), "#f5cd28");
        assert_eq!(ramp(f64::NAN), ramp(0.5));
        let z = [3.0, 3.1, 3.2, 3.3];
        let v = heightmap_json(&[0.0, 10.0], &[0.0, 5.0], Some(&z), 3.0);
        assert_eq!(v["colours"][0][0], "#3040c8");
        assert_eq!(v["colours"][1][1], "#f5cd28");
        assert_eq!(v["z"][1][0], 3.2);
        assert_eq!(v["legend"]["max"], 3.3);
        // a flat map: one colour; a grid not measured: the grid's grey at T
        let flat = heightmap_json(&[0.0, 10.0], &[0.0], Some(&[1.0, 1.0]), 1.0);
        assert_eq!(flat["colours"][0][0], flat["colours"][0][1]);
        let grid = heightmap_json(&[0.0, 10.0], &[0.0], None, 2.5);
        assert_eq!(grid["measured"], false);
        assert_eq!(grid["z"][0][1], 2.5);
        assert_eq!(grid["colours"][0][0], GRID_COLOUR);
    }
}
