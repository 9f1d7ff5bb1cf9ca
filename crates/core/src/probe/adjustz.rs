//! adjust-z: `_Clean.gcode` + measured `_Z.txt` → `_Milling.gcode` (reference-output.md §15).

use crate::args;
use crate::diag::{Diagnostic, Diags, Msg, Origin};
use crate::geom::f3;
use crate::params::parse_number;
use regex::Regex;
use std::collections::HashMap;
use std::sync::OnceLock;

/// The file argument reduced to its base: `.dxf`, `_Clean.gcode`, `_Z.txt` or `.gcode` removed.
pub fn base_path(arg: &str) -> String {
    let lower = arg.to_ascii_lowercase();
    for suffix in [".dxf", "_clean.gcode", "_z.txt", ".gcode", ".mpath"] {
        if lower.ends_with(suffix) {
            return arg[..arg.len() - suffix.len()].to_string();
        }
    }
    arg.to_string()
}

/// Reads the measured values of a `_Z.txt` file. Errors name the file and line.
pub fn parse_z_file(text: &str, file: &str, max: f64, diags: &mut Diags) -> HashMap<String, f64> {
    let mut vars = HashMap::new();
    for (i, line) in text.lines().enumerate() {
        let origin = Origin::FileLine {
            file: file.to_string(),
            line: i + 1,
        };
        if line.trim().is_empty() {
            continue;
        }
        let parts: Vec<&str> = line
            .split(['#', '='])
            .filter(|p| !p.is_empty())
            .map(str::trim)
            .collect();
        if parts.len() < 4 {
            diags.error(Msg::ZLineFormat, origin, vec![]);
            continue;
        }
        let t_text = parts[1].trim_end_matches([')', ' ']);
        let name = format!("#{}", parts[2]);
        let value_text = parts[3];
        let (Some(t), Some(v)) = (parse_number(t_text), parse_number(value_text)) else {
            let bad = if parse_number(value_text).is_none() {
                value_text
            } else {
                t_text
            };
            diags.error(Msg::ZNotNumber, origin, args![bad, name]);
            continue;
        };
        if (v - t).abs() > max {
            diags.error(Msg::ZTooFar, origin, args![t_text, name, value_text, max]);
            continue;
        }
        if vars.insert(name.clone(), v).is_some() {
            diags.error(Msg::ZDuplicate, origin, args![name]);
        }
    }
    vars
}

fn z_regex() -> &'static Regex {
    static RE: OnceLock<Regex> = OnceLock::new();
    RE.get_or_init(|| {
        Regex::new(r"[0-9.-]+\(=([0-9.-]+([\]\[)(+*/\-]|#[0-9]+|[0-9.-]+)*)\)")
            .expect("static regex")
    })
}

/// Replaces every probe expression by its value (`Z0.921(==…)`). Errors name the line.
pub fn rewrite(clean: &str, file: &str, vars: &HashMap<String, f64>, diags: &mut Diags) -> String {
    let mut out = String::with_capacity(clean.len() + clean.len() / 8);
    for (i, line) in clean.lines().enumerate() {
        match z_regex().captures(line) {
            Some(c) => {
                let whole = c.get(0).map_or(0..0, |m| m.range());
                let expr = c.get(1).map_or("", |m| m.as_str());
                match eval(expr, vars) {
                    Ok(v) => {
                        out.push_str(&line[..whole.start]);
                        out.push_str(&format!("{}(=={expr})", f3(v)));
                        out.push_str(&line[whole.end..]);
                    }
                    Err((msg, a)) => {
                        diags.push(Diagnostic::error(
                            msg,
                            Origin::FileLine {
                                file: file.to_string(),
                                line: i + 1,
                            },
                            a,
                        ));
                        out.push_str(line);
                    }
                }
            }
            None => out.push_str(line),
        }
        out.push('\n');
    }
    out
}

/// Evaluates a probe expression (`0.800+0.794*[#51-2.000]`).
pub fn eval(expr: &str, vars: &HashMap<String, f64>) -> Result<f64, (Msg, Vec<String>)> {
    let mut p = Parser {
        s: expr.as_bytes(),
        i: 0,
        expr,
        vars,
    };
    let v = p.expr()?;
    if p.i < p.s.len() && p.s[p.i] != b'=' {
        return Err((Msg::ExprEndExpected, args![p.i, expr]));
    }
    Ok(v)
}

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
    expr: &'a str,
    vars: &'a HashMap<String, f64>,
}

impl Parser<'_> {
    fn peek(&self) -> Option<u8> {
        self.s.get(self.i).copied()
    }
    fn expr(&mut self) -> Result<f64, (Msg, Vec<String>)> {
        let mut v = self.term()?;
        while let Some(c @ (b'+' | b'-')) = self.peek() {
            self.i += 1;
            let r = self.term()?;
            v = if c == b'+' { v + r } else { v - r };
        }
        Ok(v)
    }
    fn term(&mut self) -> Result<f64, (Msg, Vec<String>)> {
        let mut v = self.factor()?;
        while let Some(c @ (b'*' | b'/')) = self.peek() {
            self.i += 1;
            let r = self.factor()?;
            v = if c == b'*' { v * r } else { v / r };
        }
        Ok(v)
    }
    fn factor(&mut self) -> Result<f64, (Msg, Vec<String>)> {
        let start = self.i;
        match self.peek() {
            Some(b'#') => {
                self.i += 1;
                while self.peek().is_some_and(|c| c.is_ascii_digit()) {
                    self.i += 1;
                }
                let name = &self.expr[start..self.i];
                self.vars
                    .get(name)
                    .copied()
                    .ok_or_else(|| (Msg::ZUnknownVariable, args![name, self.expr]))
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
                    return Err((msg, args![self.i, self.expr]));
                }
                self.i += 1;
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
                text.parse::<f64>()
                    .map_err(|_| (Msg::ExprBadNumber, args![text, start, self.expr]))
            }
            Some(c) => Err((Msg::ExprUnexpected, args![c as char, self.i, self.expr])),
            None => Err((Msg::ExprUnexpected, args!["<end>", self.i, self.expr])),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
    }

    #[test]
    fn rewrites_lines_once() {
        let mut d = Diags::default();
        let clean = "G00 Z5.000\nG01 Z0.800(=0.800+0.794*[#51-2.000]+0.206*[#52-2.000])\n";
        let out = rewrite(clean, "x_Clean.gcode", &vars(), &mut d);
        assert_eq!(
            out,
            "G00 Z5.000\nG01 Z0.921(==0.800+0.794*[#51-2.000]+0.206*[#52-2.000])\n"
        );
        assert_eq!(rewrite(&out, "x", &vars(), &mut d), out);
        assert!(!d.has_errors());
    }

    #[test]
    fn z_file_lines() {
        let mut d = Diags::default();
        let v = parse_z_file(
            "([57.358 242.020]/T=2.000) #51=2,1\n\n([1.000 2.000]/L:a/T=2.000) #52=2.2\n",
            "z",
            1.0,
            &mut d,
        );
        assert!(!d.has_errors());
        assert_eq!(v.get("#51"), Some(&2.1));
        let mut d = Diags::default();
        parse_z_file("([57.358 242.020]/T=2.000) #51=\n([0 0]/T=2.000) #52=x\n([0 0]/T=2.000) #53=5\n([0 0]/T=2.000) #53=2\n([0 0]/T=2.000) #53=2\n", "z", 1.0, &mut d);
        let msgs: Vec<Msg> = d.list.iter().map(|x| x.msg).collect();
        assert_eq!(
            msgs,
            vec![
                Msg::ZLineFormat,
                Msg::ZNotNumber,
                Msg::ZTooFar,
                Msg::ZDuplicate
            ]
        );
        assert_eq!(d.list[0].origin.context(), "z:1");
    }

    #[test]
    fn base_paths() {
        assert_eq!(base_path("a/8999.19P.dxf"), "a/8999.19P");
        assert_eq!(base_path("8999.19P_Clean.gcode"), "8999.19P");
        assert_eq!(base_path("8999.19P_Z.txt"), "8999.19P");
        assert_eq!(base_path("x.GCODE"), "x");
        assert_eq!(base_path("x"), "x");
    }
}
