//! The checks that can only start once the whole program was read (the tool and bottom a
//! `(MILLPATH-STOCK …)` comment may give, the grid the program's extent decides): the
//! clamps, the depth below the bottom and the stock model, one move at a time. The checker
//! that keeps its moves runs them over its list; the lean one (`reread.rs`) over the moves
//! of a second reading, so both give the same findings in the same order.
//!
//! The end checks as per-move steps shared by both: `ClampCheck` (stops past the findings limit),
//! `below_bottom`, `Extent` and `StockRun` (grid ≤ 4 M cells, cell O/8 … O/2, the work budget).

use crate::machine::{Move, MoveKind, Raw};
use crate::stock::{GridGeom, Stock};
use crate::{
    clamps, Clamp, FindingKind, Limits, Options, Report, Severity, StockInfo, StockSkip,
    MAX_CLAMPS, XY_TOLERANCE,
};

/// The keep-out boxes against every move, one finding per move and box it touches; stops
/// after the move that takes the findings past the limit.
pub(crate) struct ClampCheck {
    radius: f64,
    /// Findings before this check's (they count towards the limit).
    base: usize,
    max_findings: usize,
    done: bool,
}

/// The boxes checked (at most [`MAX_CLAMPS`]).
pub(crate) fn clamps_of(options: &Options) -> &[Clamp] {
    &options.clamps[..options.clamps.len().min(MAX_CLAMPS)]
}

impl ClampCheck {
    /// `None` without boxes. `base`: findings before `out`'s that count towards the limit;
    /// a missing tool is said in `out` (the boxes are then judged with the tool's axis).
    pub(crate) fn new(
        options: &Options,
        tool: Option<f64>,
        base: usize,
        out: &mut Vec<Raw>,
    ) -> Option<ClampCheck> {
        if clamps_of(options).is_empty() {
            return None;
        }
        if tool.is_none() {
            out.push(Raw {
                line: None,
                kind: FindingKind::ClampsWithoutTool,
                severity: Severity::Warning,
            });
        }
        Some(ClampCheck {
            radius: tool.unwrap_or(0.0) / 2.0,
            base,
            max_findings: options.limits.max_findings,
            done: false,
        })
    }

    /// One move (machine coordinates: before a height map's frame).
    pub(crate) fn step(&mut self, mv: &Move, clamps: &[Clamp], out: &mut Vec<Raw>) {
        if self.done {
            return;
        }
        for c in clamps {
            if clamps::hit(mv, self.radius, std::slice::from_ref(c)).is_some() {
                out.push(Raw {
                    line: Some(mv.line),
                    kind: FindingKind::ClampHit {
                        name: c.name.clone(),
                        min: c.min,
                        max: c.max,
                        radius: self.radius,
                    },
                    severity: Severity::Error,
                });
            }
        }
        if self.base + out.len() > self.max_findings {
            self.done = true;
        }
    }
}

/// A cut below the deepest drawn depth: its ends (or, on a height map, its lowest point
/// inside, `low_inside`, judged with `inside_tol`) more than `ztol` below `bottom`.
pub(crate) fn below_bottom(
    mv: &Move,
    bottom: f64,
    (ztol, inside_tol): (f64, f64),
    low_inside: Option<f64>,
) -> Option<Raw> {
    if mv.kind != MoveKind::Cut {
        return None;
    }
    let ends = mv.from[2].min(mv.to[2]);
    let below_ends = ends < bottom - ztol;
    let below_inside = low_inside.is_some_and(|z| z < bottom - inside_tol);
    if !(below_ends || below_inside) {
        return None;
    }
    let z = match low_inside {
        Some(z) if below_inside => z.min(ends),
        _ => ends,
    };
    Some(Raw {
        line: Some(mv.line),
        kind: FindingKind::BelowBottom { z, bottom },
        severity: Severity::Error,
    })
}

/// The XY extent of every known position and arc of the moves: the stock model's grid.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Extent(Option<(f64, f64, f64, f64)>);

impl Extent {
    fn add(&mut self, x: f64, y: f64) {
        if x.is_finite() && y.is_finite() {
            self.0 = Some(match self.0 {
                None => (x, y, x, y),
                Some(b) => (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y)),
            });
        }
    }

    pub(crate) fn add_move(&mut self, mv: &Move) {
        self.add(mv.from[0], mv.from[1]);
        self.add(mv.to[0], mv.to[1]);
        if let Some(a) = &mv.arc {
            let b = a.bbox();
            self.add(b.0, b.1);
            self.add(b.2, b.3);
        }
    }
}

/// The stock model, move by move: rapids checked against it, cuts lowering it.
pub(crate) struct StockRun {
    stock: Stock,
    top: f64,
    tool: f64,
    /// How far below the stock a tool tip may pass.
    ztol: f64,
    r_check: f64,
    work: u64,
    max_work: u64,
    /// The work limit was reached: later moves are not modelled.
    stopped: bool,
}

impl StockRun {
    /// The grid over `extent` (cell O/8 when the area allows, up to O/2). `None` without
    /// any known position, or when the area needs too coarse a grid (said in `findings`).
    pub(crate) fn new(
        extent: &Extent,
        (top, tool, ztol): (f64, f64, f64),
        limits: &Limits,
        findings: &mut Vec<Raw>,
    ) -> Option<StockRun> {
        let r = tool / 2.0;
        let (bx0, by0, bx1, by1) = extent.0?;
        let (w, h) = (bx1 - bx0 + 2.0 * r, by1 - by0 + 2.0 * r);
        let cells = |c: f64| ((w / c).ceil() + 4.0) * ((h / c).ceil() + 4.0);
        let max_cells = limits.max_cells.max(1) as f64;
        // O/8 when the area allows (finer volumes, a tighter rapid tolerance), up to O/2
        let mut cell = (tool / 8.0).max((w * h / max_cells).sqrt());
        for _ in 0..1000 {
            if cells(cell) <= max_cells {
                break;
            }
            cell *= 1.05;
        }
        if !(cell <= tool / 2.0 && cells(cell) <= max_cells) {
            findings.push(Raw {
                line: None,
                kind: FindingKind::StockSkipped(StockSkip::AreaTooLarge { cell }),
                severity: Severity::Warning,
            });
            return None;
        }
        let geom = GridGeom {
            x0: bx0 - r - 2.0 * cell,
            y0: by0 - r - 2.0 * cell,
            cell,
            nx: (w / cell).ceil() as usize + 4,
            ny: (h / cell).ceil() as usize + 4,
        };
        Some(StockRun {
            stock: Stock::new(geom, top),
            top,
            tool,
            ztol,
            r_check: (r - cell - XY_TOLERANCE).max(0.0),
            work: 0,
            max_work: limits.max_work,
            stopped: false,
        })
    }

    /// One move, in program order.
    pub(crate) fn step(&mut self, mv: &Move, findings: &mut Vec<Raw>) {
        if self.stopped {
            return;
        }
        if self.work > self.max_work {
            findings.push(Raw {
                line: None,
                kind: FindingKind::StockSkipped(StockSkip::WorkLimit { line: mv.line }),
                severity: Severity::Warning,
            });
            self.stopped = true;
            return;
        }
        let (top, ztol, r) = (self.top, self.ztol, self.tool / 2.0);
        let stock = &mut self.stock;
        let (from, to) = (mv.from, mv.to);
        match mv.kind {
            MoveKind::Probe => {}
            MoveKind::Rapid => {
                if to.iter().any(|v| v.is_nan()) {
                    return;
                }
                let xy_moves = (to[0] - from[0]).hypot(to[1] - from[1]) > 1e-9;
                let (a, b) = if from.iter().any(|v| v.is_nan()) {
                    // from an unknown place: at least the destination must be free
                    (to, to)
                } else if xy_moves || to[2] < from[2] {
                    (from, to)
                } else {
                    return;
                };
                if a[2].min(b[2]) >= top - ztol {
                    return;
                }
                let (hit, w) = stock.intrusion(a, b, self.r_check);
                self.work += w;
                if let Some((depth, x, y)) = hit.filter(|h| h.0 > ztol) {
                    findings.push(Raw {
                        line: Some(mv.line),
                        kind: FindingKind::RapidIntoMaterial { depth, x, y },
                        severity: Severity::Error,
                    });
                    // the model goes on as if the tool had cut its way (no cascades)
                    self.work += stock.cut_line(a, b, r);
                }
            }
            MoveKind::Cut => {
                if from[2].min(to[2]) >= top {
                    return;
                }
                self.work += match &mv.arc {
                    Some(arc) => stock.cut_arc(arc, from[2], to[2], r),
                    None => stock.cut_line(from, to, r),
                };
            }
        }
    }

    /// The removed volume and the grid into the report.
    pub(crate) fn finish(self, report: &mut Report) {
        let geom = self.stock.geom;
        report.removed_volume_mm3 = self.stock.removed_volume();
        report.stock = Some(StockInfo {
            top: self.top,
            tool_diameter: self.tool,
            cell: geom.cell,
            nx: geom.nx,
            ny: geom.ny,
            x0: geom.x0,
            y0: geom.y0,
        });
    }
}
