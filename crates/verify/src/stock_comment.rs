//! The structured comment our compiler writes for the stock and the tool,
//! `(MILLPATH-STOCK T=… O=… BOTTOM=…)`, and its reading.

use crate::{StockCommentProblem, MAX_MAGNITUDE};

/// The data the stock checks need; from options or a `(MILLPATH-STOCK …)` comment.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StockParams {
    /// Material top T, mm.
    pub top: Option<f64>,
    /// Tool diameter O, mm.
    pub tool: Option<f64>,
    /// The deepest drawn depth, mm.
    pub bottom: Option<f64>,
}

/// The structured comment our compiler writes:
/// `(MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300)` (BOTTOM only when known).
pub fn stock_comment(top: f64, tool: f64, bottom: Option<f64>) -> String {
    match bottom {
        Some(b) => format!("(MILLPATH-STOCK T={top:.3} O={tool:.3} BOTTOM={b:.3})"),
        None => format!("(MILLPATH-STOCK T={top:.3} O={tool:.3})"),
    }
}

/// Reads the text of a comment (without parentheses). `None`: not a stock comment. Keys are
/// T, O and BOTTOM; unknown keys are ignored (for later additions).
pub fn parse_stock_comment(text: &str) -> Option<Result<StockParams, StockCommentProblem>> {
    let rest = text.trim().strip_prefix("MILLPATH-STOCK")?;
    if !rest.is_empty() && !rest.starts_with(char::is_whitespace) {
        return None;
    }
    let mut p = StockParams::default();
    for tok in rest.split_whitespace() {
        let (key, value) = tok.split_once('=').unwrap_or((tok, ""));
        let key = key.to_ascii_uppercase();
        let plain = !value.is_empty()
            && value
                .chars()
                .all(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+'));
        let v = value
            .parse::<f64>()
            .ok()
            .filter(|v| plain && v.is_finite() && v.abs() <= MAX_MAGNITUDE);
        let slot = match key.as_str() {
            "T" => &mut p.top,
            "O" => &mut p.tool,
            "BOTTOM" => &mut p.bottom,
            _ => continue,
        };
        match v {
            Some(v) if key != "O" || v > 0.0 => *slot = Some(v),
            _ => {
                return Some(Err(StockCommentProblem::BadValue {
                    key,
                    text: value.to_string(),
                }))
            }
        }
    }
    Some(Ok(p))
}
