//! The cut part for the toolpath view: the independent checker's stock model of the written
//! program (`millpath_verify::StockView`) as JSON with binary arrays in base64 (little
//! endian): the heights after the program, and the lowerings grouped by G-code line so the
//! page can cut the stock move by move during playback. The page computes nothing.
//!
//! The cut part of the view: `verify`'s stock model of the written program (`StockView`) as JSON,
//! base64 little-endian arrays (heights after the program; lowerings grouped by G-code line: lines,
//! counts, cells, z); ≤ 2 M cells, ≤ 2 M lowerings; `cut_svg` for `render --cut` (row runs in 24
//! depth levels).

use base64::Engine;
use millpath_core::emit::Controller;
use millpath_core::machine::Reading;
use millpath_verify::{verify, Options, ViewRequest};
use serde_json::{json, Value};

/// Cells of the view's grid at most (a finer cell is coarsened, the legend says so).
pub const MAX_CELLS: usize = 2_000_000;
/// Lowerings at most; beyond, each cell keeps only its last one.
pub const MAX_EVENTS: usize = 2_000_000;

fn b64<T: Copy>(values: &[T], bytes: impl Fn(T) -> [u8; 4]) -> String {
    let mut raw = Vec::with_capacity(values.len() * 4);
    for &v in values {
        raw.extend_from_slice(&bytes(v));
    }
    base64::engine::general_purpose::STANDARD.encode(raw)
}

/// The cut part of `program` with tool diameter `tool` from material top `top`; `cell`: the
/// resolution asked for (mm; `None`: the checker's, O/8 where the area allows). The program
/// is read as the second opinion reads what `controller`'s post writes: by the post's family
/// (a custom post of the grbl family is read as grbl), not by the dialect's name.
pub fn cut_json(
    program: &str,
    controller: &Controller,
    top: f64,
    tool: f64,
    cell: Option<f64>,
) -> Option<Value> {
    // a family the checker cannot read was refused with the settings: no cut part
    let reading = Reading::of(controller.dialect, &controller.post).ok()?;
    let report = verify(
        program,
        &Options {
            dialect: reading.dialect,
            arcs_as_lines: reading.arcs_as_lines,
            top: Some(top),
            tool: Some(tool),
            skip_stock: true,
            view: Some(ViewRequest {
                cell,
                max_cells: MAX_CELLS,
                max_events: MAX_EVENTS,
            }),
            ..Options::default()
        },
    );
    let v = report.view?;
    // lowerings grouped by line: the distinct lines in order, how many each, cells, heights
    let (mut lines, mut counts): (Vec<u32>, Vec<u32>) = (Vec::new(), Vec::new());
    for &(line, _, _) in &v.events {
        if lines.last() == Some(&line) {
            if let Some(c) = counts.last_mut() {
                *c += 1;
            }
        } else {
            lines.push(line);
            counts.push(1);
        }
    }
    let cells: Vec<u32> = v.events.iter().map(|e| e.1).collect();
    let zs: Vec<f32> = v.events.iter().map(|e| e.2).collect();
    let lowest = v.heights.iter().cloned().fold(f32::INFINITY, f32::min);
    Some(json!({
        "x0": v.x0, "y0": v.y0, "cell": v.cell, "nx": v.nx, "ny": v.ny, "top": v.top,
        "lowest": if lowest.is_finite() { f64::from(lowest) } else { v.top },
        "coarsened": v.coarsened,
        "thinned": v.events_thinned,
        "heights": b64(&v.heights, f32::to_le_bytes),
        "lines": b64(&lines, u32::to_le_bytes),
        "counts": b64(&counts, u32::to_le_bytes),
        "cells": b64(&cells, u32::to_le_bytes),
        "z": b64(&zs, f32::to_le_bytes),
    }))
}

/// The float32 values of a base64 field of the cut part.
fn floats(v: &Value) -> Vec<f32> {
    let raw = v
        .as_str()
        .and_then(|s| base64::engine::general_purpose::STANDARD.decode(s).ok())
        .unwrap_or_default();
    raw.chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// Depth levels of the SVG's cut part (cells of one level are one path).
const LEVELS: usize = 24;

/// The cut part as SVG paths for the top view (in the drawing's coordinates, Y up like the
/// moves): uncut stock in one colour, cut cells in depth colours from the top (light blue)
/// to the lowest cut (red), in [`LEVELS`] steps, each level's cells joined in row runs.
pub fn cut_svg(cut: &Value) -> String {
    use std::fmt::Write;
    let f = |k: &str| cut[k].as_f64().unwrap_or(0.0);
    let (x0, y0, cell, top, lowest) = (f("x0"), f("y0"), f("cell"), f("top"), f("lowest"));
    let (nx, ny) = (f("nx") as usize, f("ny") as usize);
    let heights = floats(&cut["heights"]);
    if heights.len() != nx * ny || nx == 0 || cell.is_nan() || cell <= 0.0 {
        return String::new();
    }
    let span = top - lowest;
    let level = |z: f32| -> Option<usize> {
        let d = top - f64::from(z);
        if d <= 1e-6 || span <= 0.0 {
            return None;
        }
        Some((((d / span) * LEVELS as f64).ceil() as usize).clamp(1, LEVELS) - 1)
    };
    let mut paths = vec![String::new(); LEVELS];
    for j in 0..ny {
        let y = y0 + j as f64 * cell;
        let mut i = 0;
        while i < nx {
            let l = level(heights[j * nx + i]);
            let start = i;
            while i < nx && level(heights[j * nx + i]) == l {
                i += 1;
            }
            if let Some(l) = l {
                let x = x0 + start as f64 * cell;
                let w = (i - start) as f64 * cell;
                let _ = write!(paths[l], "M{x:.3} {y:.3}h{w:.3}v{cell:.3}h{:.3}z", -w);
            }
        }
    }
    let mut s = String::new();
    let _ = writeln!(
        s,
        r##"<rect x="{x0:.3}" y="{y0:.3}" width="{:.3}" height="{:.3}" fill="#e8dcc4" stroke="none"/>"##,
        nx as f64 * cell,
        ny as f64 * cell
    );
    for (l, d) in paths.iter().enumerate().filter(|(_, d)| !d.is_empty()) {
        let t = (l as f64 + 1.0) / LEVELS as f64;
        let _ = writeln!(
            s,
            r#"<path d="{d}" fill="hsl({:.0},55%,{:.0}%)" stroke="none"/>"#,
            200.0 - 200.0 * t,
            78.0 - 18.0 * t
        );
    }
    s
}
