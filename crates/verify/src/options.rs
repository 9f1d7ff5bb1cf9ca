//! What a program is checked against (stock, clamps, dialect, the view asked for) and the
//! bounds on the work done for it; the tolerances of the stock checks.

use crate::{Clamp, Dialect, ViewRequest};

/// Bounds on the work done for one program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    pub max_lines: usize,
    pub max_line_len: usize,
    pub max_cells: usize,
    /// Cell visits of the stock model.
    pub max_work: u64,
    pub max_findings: usize,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            max_lines: 1_000_000,
            max_line_len: 4096,
            max_cells: 4_000_000,
            max_work: 100_000_000,
            max_findings: 10_000,
        }
    }
}

/// What to check against. `top`/`tool`/`bottom` override a `(MILLPATH-STOCK …)` comment.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Options {
    /// The family whose reading rules apply ([`Dialect::rules`]).
    pub dialect: Dialect,
    /// The post writes arcs as lines: a G02/G03 in its program is a finding.
    pub arcs_as_lines: bool,
    pub top: Option<f64>,
    pub tool: Option<f64>,
    pub bottom: Option<f64>,
    pub limits: Limits,
    /// Keep-out boxes in machine coordinates: every move is checked against them.
    pub clamps: Vec<Clamp>,
    /// Leave the stock model out (a quick check of the clamps and the program's words).
    pub skip_stock: bool,
    /// Export the stock's height field for a viewer ([`Report::view`]).
    pub view: Option<ViewRequest>,
}

/// How far (mm) the tool tip may be below the stock before a rapid counts as a collision.
pub const Z_TOLERANCE: f64 = 0.001;
/// Extra tolerance (mm) on the footprint radius of rapids, besides one grid cell.
pub const XY_TOLERANCE: f64 = 0.01;
