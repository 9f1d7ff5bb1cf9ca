//! Programs adjusted to a measured surface (adjust-z): `G01 Z0.921(==0.800+0.794*[#51-2.000]+…)`.
//!
//! Such a program cuts at heights that follow the measured surface, not the drawn ones, so
//! its stock comment (nominal T and BOTTOM) does not describe it directly. The checker moves
//! every adjusted line back to the drawing's frame: its Z minus the surface offset its own
//! expression gives with the measured heights (`(MILLPATH-PROBES #51=2.100 …)`, written by
//! adjust-z), minus nominal. A correct line lands on its drawn height; a line cut deeper
//! than the measured surface minus the depth lands below the drawn depth and is reported
//! as such. A Z that is not its expression's value is reported as well. Lines without an
//! expression (safe heights) are moved down by the largest measured rise, so a rapid is
//! judged as if the surface were that high everywhere (the surface between the probes is a
//! weighted mean of theirs). Without measured values only the nominal heights are known:
//! each adjusted line is checked at its drawn height, with a warning.
//!
//! Programs adjusted by adjust-z: `(==expr)` lines moved back to the drawing's frame with the
//! measured heights of `(MILLPATH-PROBES …)` (a Z that is not its expression's value is an error),
//! other Z lowered by the largest measured rise; its own small evaluator (verify stays independent
//! of core).

use crate::finding::{AdjustedProblem, FindingKind};
use std::collections::HashMap;

/// The word of adjust-z's comment with the measured heights.
pub const PROBES_WORD: &str = "MILLPATH-PROBES";

/// A written Z may differ from its expression's value by the rounding to 3 decimals.
const ROUNDING: f64 = 0.0015;
/// Deepest nesting of brackets and unary minus.
const MAX_DEPTH: usize = 64;

/// What the whole program says about its adjustment.
#[derive(Debug, Default)]
pub struct Surface {
    /// Measured heights by probe name (`#51`).
    measured: HashMap<String, f64>,
    /// Some line carries `(==…)`.
    pub adjusted: bool,
    /// Nominal heights seen in probe terms `[#n-TH]`.
    nominal: HashMap<String, f64>,
}

impl Surface {
    /// Reads the measured heights and the nominal heights of every probe; `Err` for a value
    /// in a `MILLPATH-PROBES` comment that is no sane number.
    pub fn scan<'a>(lines: impl Iterator<Item = &'a str>) -> (Surface, Vec<(usize, FindingKind)>) {
        let mut s = Surface::default();
        let mut problems = Vec::new();
        for (i, line) in lines.enumerate() {
            for comment in comments(line) {
                if let Some(expr) = comment.strip_prefix("==") {
                    s.adjusted = true;
                    for (name, th) in probe_terms(expr) {
                        s.nominal.entry(name).or_insert(th);
                    }
                } else if let Some(at) = comment.find(PROBES_WORD) {
                    let words = &comment[at + PROBES_WORD.len()..];
                    for w in words.split_whitespace() {
                        let value = w.split_once('=').and_then(|(name, v)| {
                            let ok = name.len() > 1
                                && name.starts_with('#')
                                && name[1..].bytes().all(|b| b.is_ascii_digit());
                            let v = v
                                .parse::<f64>()
                                .ok()
                                .filter(|v| v.is_finite() && v.abs() <= crate::MAX_MAGNITUDE);
                            ok.then_some((name, v?))
                        });
                        match value {
                            Some((name, v)) => {
                                s.measured.insert(name.to_string(), v);
                            }
                            None => problems.push((
                                i + 1,
                                FindingKind::Adjusted(AdjustedProblem::BadValue {
                                    text: w.chars().take(40).collect(),
                                }),
                            )),
                        }
                    }
                }
            }
        }
        (s, problems)
    }

    /// Measured heights were given.
    pub fn has_values(&self) -> bool {
        !self.measured.is_empty()
    }

    /// How far lines without an expression are moved down: the largest measured rise.
    pub fn max_rise(&self) -> f64 {
        self.measured
            .iter()
            .filter_map(|(name, m)| self.nominal.get(name).map(|th| m - th))
            .fold(0.0, f64::max)
    }

    /// The drawing-frame height of an adjusted line with written height `z` and probe
    /// expression `expr`, or the problem that keeps it from being known.
    pub fn nominal_z(&self, z: f64, expr: &str) -> Result<f64, AdjustedProblem> {
        let terms = probe_terms(expr);
        let nominal: HashMap<String, f64> = terms.iter().cloned().collect();
        let at_nominal = eval(expr, &nominal).ok_or(AdjustedProblem::Unreadable)?;
        if !self.has_values() {
            return Ok(at_nominal);
        }
        if let Some((name, _)) = terms.iter().find(|(n, _)| !self.measured.contains_key(n)) {
            return Err(AdjustedProblem::NoValue { name: name.clone() });
        }
        let expected = eval(expr, &self.measured).ok_or(AdjustedProblem::Unreadable)?;
        if (z - expected).abs() > ROUNDING {
            return Err(AdjustedProblem::ZMismatch { z, expected });
        }
        Ok(z - (expected - at_nominal))
    }
}

/// The texts of a line's parenthesised comments.
fn comments(line: &str) -> impl Iterator<Item = &str> {
    line.split('(')
        .skip(1)
        .filter_map(|c| c.split_once(')').map(|(t, _)| t))
}

/// The probe terms `[#n-TH]` of an expression: name and nominal height.
fn probe_terms(expr: &str) -> Vec<(String, f64)> {
    expr.split('[')
        .skip(1)
        .filter_map(|t| {
            let inner = t.split_once(']')?.0;
            let rest = inner.strip_prefix('#')?;
            let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
            let th = rest[digits..].strip_prefix('-')?.parse::<f64>().ok()?;
            (digits > 0 && th.is_finite()).then(|| (format!("#{}", &rest[..digits]), th))
        })
        .collect()
}

/// Evaluates `+ - * / ( ) [ ]`, numbers and `#n` with `vars`; `None` when it cannot.
fn eval(expr: &str, vars: &HashMap<String, f64>) -> Option<f64> {
    let mut p = Eval {
        s: expr.as_bytes(),
        i: 0,
        vars,
        depth: 0,
    };
    let v = p.sum()?;
    (p.i == p.s.len() && v.is_finite()).then_some(v)
}

struct Eval<'a> {
    s: &'a [u8],
    i: usize,
    vars: &'a HashMap<String, f64>,
    depth: usize,
}

impl Eval<'_> {
    fn peek(&self) -> Option<u8> {
        self.s.get(self.i).copied()
    }
    fn sum(&mut self) -> Option<f64> {
        let mut v = self.product()?;
        while let Some(c @ (b'+' | b'-')) = self.peek() {
            self.i += 1;
            let r = self.product()?;
            v = if c == b'+' { v + r } else { v - r };
        }
        Some(v)
    }
    fn product(&mut self) -> Option<f64> {
        let mut v = self.factor()?;
        while let Some(c @ (b'*' | b'/')) = self.peek() {
            self.i += 1;
            let r = self.factor()?;
            v = if c == b'*' { v * r } else { v / r };
        }
        v.is_finite().then_some(v)
    }
    fn factor(&mut self) -> Option<f64> {
        self.depth += 1;
        let v = if self.depth > MAX_DEPTH {
            None
        } else {
            self.factor_inner()
        };
        self.depth -= 1;
        v
    }
    fn factor_inner(&mut self) -> Option<f64> {
        let start = self.i;
        match self.peek()? {
            b'-' => {
                self.i += 1;
                Some(-self.factor()?)
            }
            open @ (b'(' | b'[') => {
                self.i += 1;
                let v = self.sum()?;
                let close = if open == b'(' { b')' } else { b']' };
                (self.peek()? == close).then_some(())?;
                self.i += 1;
                Some(v)
            }
            b'#' => {
                self.i += 1;
                while self.peek().is_some_and(|c| c.is_ascii_digit()) {
                    self.i += 1;
                }
                let name = std::str::from_utf8(&self.s[start..self.i]).ok()?;
                self.vars.get(name).copied()
            }
            c if c.is_ascii_digit() || c == b'.' => {
                while self.peek().is_some_and(|c| c.is_ascii_digit() || c == b'.') {
                    self.i += 1;
                }
                let text = std::str::from_utf8(&self.s[start..self.i]).ok()?;
                text.parse::<f64>()
                    .ok()
                    .filter(|v| v.abs() <= crate::MAX_MAGNITUDE)
            }
            _ => None,
        }
    }
}

/// Moves the Z of a line of an adjusted program to the drawing's frame.
pub(crate) fn to_drawing_frame(
    b: &mut crate::parse::Block,
    surface: &Surface,
    rise: f64,
) -> Result<(), AdjustedProblem> {
    let Some(z) = b.words.iter_mut().find(|w| w.letter == 'Z') else {
        return Ok(());
    };
    match b.comments.iter().find_map(|c| c.strip_prefix("==")) {
        Some(expr) => {
            z.value = surface.nominal_z(z.value, expr)?;
        }
        None => z.value -= rise,
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const EXPR: &str = "0.800+0.794*[#51-2.000]+0.206*[#52-2.000]";

    fn surface(program: &str) -> Surface {
        let (s, problems) = Surface::scan(program.lines());
        assert!(problems.is_empty(), "{problems:?}");
        s
    }

    #[test]
    fn expressions_evaluate_and_name_their_probes() {
        let vars = HashMap::from([("#51".to_string(), 2.1), ("#52".to_string(), 2.2)]);
        assert!((eval(EXPR, &vars).unwrap() - 0.9206).abs() < 1e-9);
        assert_eq!(
            probe_terms(EXPR),
            [("#51".to_string(), 2.0), ("#52".to_string(), 2.0)]
        );
        assert_eq!(probe_terms("1+[#7--1.5]"), [("#7".to_string(), -1.5)]);
        for bad in [
            "1+",
            "(1",
            "[1",
            "1)",
            "#9",
            "1/0",
            "",
            "a",
            &"(".repeat(100),
        ] {
            assert_eq!(eval(bad, &vars), None, "{bad}");
        }
    }

    #[test]
    fn adjusted_lines_move_back_to_the_drawing() {
        let s = surface(&format!(
            "(x MILLPATH-PROBES #51=2.100 #52=2.200)\nG01 Z0.921(=={EXPR})\n"
        ));
        assert!(s.adjusted && s.has_values());
        assert!((s.nominal_z(0.921, EXPR).unwrap() - 0.800).abs() < 0.001);
        assert!((s.max_rise() - 0.2).abs() < 1e-9);
        // a Z that is not the expression's value
        match s.nominal_z(0.421, EXPR) {
            Err(AdjustedProblem::ZMismatch { z, expected }) => {
                assert_eq!(z, 0.421);
                assert!((expected - 0.9206).abs() < 1e-9);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(
            s.nominal_z(0.9, "0.8+1.0*[#53-2.000]"),
            Err(AdjustedProblem::NoValue { name: "#53".into() })
        );
        assert_eq!(s.nominal_z(0.9, "0.8+"), Err(AdjustedProblem::Unreadable));
        // a deeper constant moves the drawn height down with it
        let deeper = EXPR.replacen("0.800", "0.300", 1);
        assert!((s.nominal_z(0.421, &deeper).unwrap() - 0.300).abs() < 0.001);
    }

    #[test]
    fn without_values_the_nominal_height_is_taken() {
        let s = surface(&format!("G01 Z0.921(=={EXPR})\n"));
        assert!(s.adjusted && !s.has_values());
        assert_eq!(s.nominal_z(0.921, EXPR), Ok(0.8));
        assert_eq!(s.max_rise(), 0.0);
    }

    #[test]
    fn bad_measured_values_are_findings() {
        let (_, problems) = Surface::scan(["(MILLPATH-PROBES #51=NaN 52=1 #53=2.0)"].into_iter());
        assert_eq!(problems.len(), 2);
    }
}
