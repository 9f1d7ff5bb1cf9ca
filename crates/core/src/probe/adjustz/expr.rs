//! Probe expressions of `_Clean.gcode` (reference-output.md §15.4): syntax, probe terms
//! `[#n-TH]` and their value with the measured heights.

use super::bounds::LIMIT;
use super::bounds::MAX_DEPTH;
use crate::args;
use crate::diag::Msg;
use regex::Regex;
use std::collections::HashMap;
use std::sync::OnceLock;

/// Evaluates a probe expression (`0.800+0.794*[#51-2.000]`) to a finite height within
/// ±[`LIMIT`].
pub fn eval(expr: &str, vars: &HashMap<String, f64>) -> Result<f64, (Msg, Vec<String>)> {
    let mut p = Parser::new(expr, Some(vars));
    let v = p.run()?;
    if v.is_finite() && v.abs() <= LIMIT {
        Ok(v)
    } else {
        Err((Msg::ExprResultRange, args![shown(expr)]))
    }
}

/// An expression or number as shown in a message: at most 200 characters, then `…`.
pub(super) fn shown(text: &str) -> String {
    match text.char_indices().nth(200) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.to_string(),
    }
}

type ExprResult = Result<f64, (Msg, Vec<String>)>;

/// LL(1) parser and evaluator of §15.4. Without variables (`vars: None`) it only checks the
/// syntax and collects the probe terms `[#n-TH]`.
pub(super) struct Parser<'a> {
    s: &'a [u8],
    i: usize,
    expr: &'a str,
    vars: Option<&'a HashMap<String, f64>>,
    depth: usize,
    /// Every variable with its position.
    uses: Vec<(usize, String)>,
    /// Probe terms `[#n-TH]`: name and TH.
    pub(super) refs: Vec<(String, f64)>,
    /// Positions of the variables inside probe terms.
    ref_positions: Vec<usize>,
}

fn probe_term_regex() -> &'static Regex {
    static RE: OnceLock<Regex> = OnceLock::new();
    RE.get_or_init(|| Regex::new(r"^#[0-9]+-(-?[0-9.]+)$").expect("static regex"))
}

impl<'a> Parser<'a> {
    pub(super) fn new(expr: &'a str, vars: Option<&'a HashMap<String, f64>>) -> Parser<'a> {
        Parser {
            s: expr.as_bytes(),
            i: 0,
            expr,
            vars,
            depth: 0,
            uses: Vec::new(),
            refs: Vec::new(),
            ref_positions: Vec::new(),
        }
    }
    pub(super) fn run(&mut self) -> ExprResult {
        let v = self.expr()?;
        if self.i < self.s.len() && self.s[self.i] != b'=' {
            return Err((Msg::ExprEndExpected, args![self.i, shown(self.expr)]));
        }
        Ok(v)
    }
    /// The first variable that is not part of a probe term.
    pub(super) fn bare_variable(&self) -> Option<&str> {
        self.uses
            .iter()
            .find(|(pos, _)| !self.ref_positions.contains(pos))
            .map(|(_, name)| name.as_str())
    }
    fn peek(&self) -> Option<u8> {
        self.s.get(self.i).copied()
    }
    /// With variables, every intermediate result must be finite (`1/(1/0)` is refused).
    fn checked(&self, v: f64) -> ExprResult {
        if self.vars.is_some() && !v.is_finite() {
            return Err((Msg::ExprResultRange, args![shown(self.expr)]));
        }
        Ok(v)
    }
    fn expr(&mut self) -> ExprResult {
        let mut v = self.term()?;
        while let Some(c @ (b'+' | b'-')) = self.peek() {
            self.i += 1;
            let r = self.term()?;
            v = self.checked(if c == b'+' { v + r } else { v - r })?;
        }
        Ok(v)
    }
    fn term(&mut self) -> ExprResult {
        let mut v = self.factor()?;
        while let Some(c @ (b'*' | b'/')) = self.peek() {
            self.i += 1;
            let r = self.factor()?;
            v = self.checked(if c == b'*' { v * r } else { v / r })?;
        }
        Ok(v)
    }
    fn factor(&mut self) -> ExprResult {
        self.depth += 1;
        let v = if self.depth > MAX_DEPTH {
            Err((Msg::ExprTooDeep, args![MAX_DEPTH, self.i, shown(self.expr)]))
        } else {
            self.factor_inner()
        };
        self.depth -= 1;
        v
    }
    fn factor_inner(&mut self) -> ExprResult {
        let start = self.i;
        match self.peek() {
            Some(b'#') => {
                self.i += 1;
                while self.peek().is_some_and(|c| c.is_ascii_digit()) {
                    self.i += 1;
                }
                let name = &self.expr[start..self.i];
                self.uses.push((start, name.to_string()));
                match self.vars {
                    None => Ok(0.0),
                    Some(vars) => vars.get(name).copied().ok_or_else(|| {
                        (Msg::ZUnknownVariable, args![shown(name), shown(self.expr)])
                    }),
                }
            }
            Some(open @ (b'(' | b'[')) => {
                self.i += 1;
                let v = self.expr()?;
                let close = if open == b'(' { b')' } else { b']' };
                if self.peek() != Some(close) {
                    let msg = if open == b'(' {
                        Msg::ExprParenExpected
                    } else {
                        Msg::ExprBracketExpected
                    };
                    return Err((msg, args![self.i, shown(self.expr)]));
                }
                self.i += 1;
                if open == b'[' {
                    self.probe_term(start + 1, self.i - 1);
                }
                Ok(v)
            }
            Some(b'-') => {
                self.i += 1;
                Ok(-self.factor()?)
            }
            Some(c) if c.is_ascii_digit() || c == b'.' => {
                while self.peek().is_some_and(|c| c.is_ascii_digit() || c == b'.') {
                    self.i += 1;
                }
                let text = &self.expr[start..self.i];
                match text.parse::<f64>() {
                    Ok(v) if v.is_finite() && v.abs() <= LIMIT => Ok(v),
                    Ok(_) => Err((
                        Msg::ExprNumberRange,
                        args![shown(text), start, shown(self.expr)],
                    )),
                    Err(_) => Err((
                        Msg::ExprBadNumber,
                        args![shown(text), start, shown(self.expr)],
                    )),
                }
            }
            Some(c) => Err((
                Msg::ExprUnexpected,
                args![c as char, self.i, shown(self.expr)],
            )),
            None => Err((
                Msg::ExprUnexpected,
                args!["<end>", self.i, shown(self.expr)],
            )),
        }
    }
    /// Records `[#n-TH]` (the text between the brackets at `from..to`) as a probe term.
    fn probe_term(&mut self, from: usize, to: usize) {
        let inner = &self.expr[from..to];
        let Some(c) = probe_term_regex().captures(inner) else {
            return;
        };
        // the number was checked by the parser
        let Some(th) = c.get(1).and_then(|m| m.as_str().parse::<f64>().ok()) else {
            return;
        };
        let name_len = inner.find('-').unwrap_or(inner.len());
        self.refs.push((inner[..name_len].to_string(), th));
        self.ref_positions.push(from);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::f3;

    fn vars() -> HashMap<String, f64> {
        HashMap::from([("#51".to_string(), 2.1), ("#52".to_string(), 2.2)])
    }

    #[test]
    fn evaluates_probe_expressions() {
        let v = eval("0.800+0.794*[#51-2.000]+0.206*[#52-2.000]", &vars()).unwrap();
        assert_eq!(f3(v), "0.921");
        assert_eq!(eval("-(1+2)*2", &vars()).unwrap(), -6.0);
        assert_eq!(eval("1/4", &vars()).unwrap(), 0.25);
    }

    #[test]
    fn expression_errors_have_columns() {
        assert_eq!(eval("1+", &vars()).unwrap_err().0, Msg::ExprUnexpected);
        assert_eq!(
            eval("(1+2", &vars()).unwrap_err(),
            (Msg::ExprParenExpected, args![4, "(1+2"])
        );
        assert_eq!(eval("[1", &vars()).unwrap_err().0, Msg::ExprBracketExpected);
        assert_eq!(
            eval("1)", &vars()).unwrap_err(),
            (Msg::ExprEndExpected, args![1, "1)"])
        );
        assert_eq!(eval("#99", &vars()).unwrap_err().0, Msg::ZUnknownVariable);
        assert_eq!(eval("1..2", &vars()).unwrap_err().0, Msg::ExprBadNumber);
        assert_eq!(eval(".", &vars()).unwrap_err().0, Msg::ExprBadNumber);
    }

    #[test]
    fn expressions_are_finite_sane_and_shallow() {
        let huge = format!("1{}", "0".repeat(400));
        assert_eq!(eval(&huge, &vars()).unwrap_err().0, Msg::ExprNumberRange);
        assert_eq!(
            eval("2000000", &vars()).unwrap_err().0,
            Msg::ExprNumberRange
        );
        assert_eq!(eval("1/0", &vars()).unwrap_err().0, Msg::ExprResultRange);
        assert_eq!(
            eval("1/(1/0)", &vars()).unwrap_err().0,
            Msg::ExprResultRange
        );
        assert_eq!(
            eval("1000000*2", &vars()).unwrap_err().0,
            Msg::ExprResultRange
        );
        // 100,000 `(` or `-` must not overflow the stack
        let deep = "(".repeat(100_000);
        assert_eq!(eval(&deep, &vars()).unwrap_err().0, Msg::ExprTooDeep);
        let minus = format!("{}1", "-".repeat(100_000));
        assert_eq!(eval(&minus, &vars()).unwrap_err().0, Msg::ExprTooDeep);
        let ok = format!(
            "{}1{}",
            "(".repeat(MAX_DEPTH - 1),
            ")".repeat(MAX_DEPTH - 1)
        );
        assert_eq!(eval(&ok, &vars()).unwrap(), 1.0);
        // a long flat chain is evaluated in a loop, not by recursion
        let chain = format!("1{}", "+1".repeat(4000));
        assert_eq!(eval(&chain, &vars()).unwrap(), 4001.0);
    }
}
