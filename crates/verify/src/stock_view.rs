//! The stock as the toolpath view draws it: the same height field as the stock checks
//! (`stock.rs`, cells lowered exactly to the lowest tool tip over the part of a move whose
//! footprint covers their centre), exported as data: the heights after the program, and every
//! lowering of a cell in program order (its move's line, the cell, the new height), so that a
//! viewer can cut the stock move by move during playback without computing anything.
//!
//! The stock for a viewer (`Options::view`): the same height field on a grid of the checks' cell
//! (or asked for; coarsened to a cell budget), heights after the program and every lowering in
//! program order (thinned to the last per cell beyond a budget).

use crate::machine::{Move, MoveKind};
use crate::stock::{visit_arc, visit_line, GridGeom};

/// What the view asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewRequest {
    /// Cell edge (mm); `None`: the stock checks' cell (O/8 where the area allows).
    pub cell: Option<f64>,
    /// At most this many cells: a finer cell is coarsened until the grid fits.
    pub max_cells: usize,
    /// At most this many recorded lowerings; beyond, each cell keeps only its last one.
    pub max_events: usize,
}

impl Default for ViewRequest {
    fn default() -> Self {
        ViewRequest {
            cell: None,
            max_cells: 1_000_000,
            max_events: 4_000_000,
        }
    }
}

/// The stock's height field after the program, and how it got there.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StockView {
    /// Lower left corner of the grid; cell (i, j) has its centre at
    /// (x0 + (i + ½)·cell, y0 + (j + ½)·cell) and index j·nx + i.
    pub x0: f64,
    pub y0: f64,
    pub cell: f64,
    pub nx: usize,
    pub ny: usize,
    pub top: f64,
    /// Heights after the program.
    pub heights: Vec<f32>,
    /// Lowerings in program order: the 1-based G-code line of the move, the cell, its new
    /// height.
    pub events: Vec<(u32, u32, f32)>,
    /// Only the last lowering of each cell was kept (the event budget was exceeded).
    pub events_thinned: bool,
    /// The cell was made coarser than asked to stay within the cell budget.
    pub coarsened: bool,
}

/// Builds the view's stock over `moves` (cutting moves only, as the checks cut them).
pub fn stock_view(
    moves: &[Move],
    top: f64,
    tool: f64,
    default_cell: Option<f64>,
    req: &ViewRequest,
) -> Option<StockView> {
    let r = tool / 2.0;
    let mut bb: Option<(f64, f64, f64, f64)> = None;
    for mv in moves.iter().filter(|m| m.kind == MoveKind::Cut) {
        let mut add = |x: f64, y: f64| {
            if x.is_finite() && y.is_finite() {
                bb = Some(match bb {
                    None => (x, y, x, y),
                    Some(b) => (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y)),
                });
            }
        };
        add(mv.from[0], mv.from[1]);
        add(mv.to[0], mv.to[1]);
        if let Some(a) = &mv.arc {
            let b = a.bbox();
            add(b.0, b.1);
            add(b.2, b.3);
        }
    }
    let (bx0, by0, bx1, by1) = bb?;
    // a margin of one tool diameter of uncut stock around the cuts
    let (w, h) = (bx1 - bx0 + 4.0 * r, by1 - by0 + 4.0 * r);
    let wanted = req
        .cell
        .or(default_cell)
        .filter(|c| c.is_finite() && *c > 0.0)
        .unwrap_or(tool / 8.0);
    let max_cells = req.max_cells.max(1) as f64;
    let cells = |c: f64| (w / c).ceil().max(1.0) * (h / c).ceil().max(1.0);
    let mut cell = wanted.max((w * h / max_cells).sqrt() * 0.999);
    for _ in 0..1000 {
        if cells(cell) <= max_cells {
            break;
        }
        cell *= 1.02;
    }
    if cells(cell) > max_cells {
        return None;
    }
    let geom = GridGeom {
        x0: bx0 - 2.0 * r,
        y0: by0 - 2.0 * r,
        cell,
        nx: (w / cell).ceil().max(1.0) as usize,
        ny: (h / cell).ceil().max(1.0) as usize,
    };
    let mut heights = vec![top; geom.nx * geom.ny];
    let mut events: Vec<(u32, u32, f32)> = Vec::new();
    let mut thinned = false;
    for mv in moves {
        if mv.kind != MoveKind::Cut || mv.from[2].min(mv.to[2]) >= top {
            continue;
        }
        if mv.from.iter().chain(mv.to.iter()).any(|v| !v.is_finite()) {
            continue;
        }
        let line = u32::try_from(mv.line).unwrap_or(u32::MAX);
        let mut lower = |k: usize, z: f64, _: f64, _: f64| {
            if z < heights[k] {
                heights[k] = z;
                if !thinned {
                    events.push((line, k as u32, z as f32));
                }
            }
        };
        match &mv.arc {
            Some(a) => visit_arc(&geom, a, mv.from[2], mv.to[2], r, &mut lower),
            None => visit_line(&geom, mv.from, mv.to, r, &mut lower),
        };
        if !thinned && events.len() > req.max_events {
            thinned = true;
            events = Vec::new();
        }
    }
    if thinned {
        // one lowering per cell, at the last move that lowered it, in program order
        let mut last: Vec<Option<(u32, f32)>> = vec![None; heights.len()];
        for mv in moves {
            if mv.kind != MoveKind::Cut || mv.from[2].min(mv.to[2]) >= top {
                continue;
            }
            if mv.from.iter().chain(mv.to.iter()).any(|v| !v.is_finite()) {
                continue;
            }
            let line = u32::try_from(mv.line).unwrap_or(u32::MAX);
            let mut note = |k: usize, z: f64, _: f64, _: f64| {
                if (z - heights[k]).abs() < 1e-12 {
                    last[k] = Some((line, z as f32));
                }
            };
            match &mv.arc {
                Some(a) => visit_arc(&geom, a, mv.from[2], mv.to[2], r, &mut note),
                None => visit_line(&geom, mv.from, mv.to, r, &mut note),
            };
        }
        events = last
            .iter()
            .enumerate()
            .filter_map(|(k, e)| e.map(|(l, z)| (l, k as u32, z)))
            .collect();
        events.sort_by_key(|e| e.0);
    }
    Some(StockView {
        x0: geom.x0,
        y0: geom.y0,
        cell,
        nx: geom.nx,
        ny: geom.ny,
        top,
        heights: heights.iter().map(|&z| z as f32).collect(),
        events,
        events_thinned: thinned,
        coarsened: cell > wanted * 1.0001,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cut(line: usize, from: [f64; 3], to: [f64; 3]) -> Move {
        Move {
            line,
            kind: MoveKind::Cut,
            from,
            to,
            arc: None,
        }
    }

    #[test]
    fn two_slots_in_order_and_the_lowest_point() {
        let moves = [
            cut(1, [0.0, 0.0, 3.0], [0.0, 0.0, -1.0]),
            cut(2, [0.0, 0.0, -1.0], [10.0, 0.0, -1.0]),
            cut(3, [0.0, 10.0, 3.0], [10.0, 10.0, -2.0]),
        ];
        let v = stock_view(&moves, 3.0, 2.0, None, &ViewRequest::default()).unwrap();
        assert_eq!(v.cell, 0.25);
        let lowest = v.heights.iter().cloned().fold(f32::INFINITY, f32::min);
        assert_eq!(lowest, -2.0);
        assert!(v.events.windows(2).all(|w| w[0].0 <= w[1].0));
        // replaying the events gives the final heights
        let mut h = vec![3.0f32; v.nx * v.ny];
        for &(_, k, z) in &v.events {
            h[k as usize] = z;
        }
        assert_eq!(h, v.heights);
        // a small budget coarsens the cell; a tiny event budget keeps one per cell
        let small = ViewRequest {
            max_cells: 500,
            max_events: 10,
            ..ViewRequest::default()
        };
        let c = stock_view(&moves, 3.0, 2.0, None, &small).unwrap();
        assert!(c.coarsened && c.events_thinned && c.nx * c.ny <= 500);
        let mut h = vec![3.0f32; c.nx * c.ny];
        for &(_, k, z) in &c.events {
            h[k as usize] = z;
        }
        assert_eq!(h, c.heights);
    }
}
