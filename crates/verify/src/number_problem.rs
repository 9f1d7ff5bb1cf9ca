//! Why a number in a program is not acceptable: shared by the G-code reader's findings
//! (`finding.rs`) and the `.NCC` reader's (`ncc_problem.rs`), below both.

/// Why a number is not acceptable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NumberProblem {
    /// NaN or infinite.
    NonFinite,
    /// |value| > 1e6.
    Absurd,
    /// `1e3`: not G-code (controllers read it differently or reject it).
    Exponent,
}
