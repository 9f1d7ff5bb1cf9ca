//! What a check of a program found: its findings, the stock model's grid and the view.

use crate::{Finding, HeightMap, Severity, StockParams, StockView};

/// The grid the stock model used.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StockInfo {
    pub top: f64,
    pub tool_diameter: f64,
    /// Cell edge, mm.
    pub cell: f64,
    pub nx: usize,
    pub ny: usize,
    /// Lower left corner of the grid.
    pub x0: f64,
    pub y0: f64,
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct Report {
    /// Sorted by line (findings about the whole program first).
    pub findings: Vec<Finding>,
    /// ∫ (T − height) over the grid, mm³; 0 when the stock model did not run.
    pub removed_volume_mm3: f64,
    /// The grid, when the stock model ran.
    pub stock: Option<StockInfo>,
    /// The values used (options over the program's comment).
    pub params: StockParams,
    /// Lines read.
    pub lines: usize,
    /// Moves executed (G00/G01/G02/G03/G38.x with known start or end).
    pub moves: usize,
    /// The measured surface the moves were judged against (given, or the program's
    /// `(MILLPATH-SURFACE …)` record).
    pub surface: Option<HeightMap>,
    /// The stock after the program and its lowerings, when [`Options::view`] asked for it.
    pub view: Option<StockView>,
}

impl Report {
    pub fn count(&self, severity: Severity) -> usize {
        self.findings
            .iter()
            .filter(|f| f.severity == severity)
            .count()
    }
    pub fn has_errors(&self) -> bool {
        self.findings.iter().any(|f| f.severity == Severity::Error)
    }
}
