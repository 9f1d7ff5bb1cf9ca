//! adjust-z: `_Clean.gcode` + measured `_Z.txt` → `_Milling.gcode` (reference-output.md §15).
//!
//! Beyond the reference, adjust-z refuses anything that could make a dangerous program
//! (docs/differences.md): every number must be finite and within ±[`LIMIT`]; the nominal
//! height of each probe comes from `_Clean.gcode` (the `w*[#n-TH]` terms), and `_Z.txt` must
//! agree with it and hold exactly the probes used there; `_Clean.gcode` must be a complete
//! program; lines and expression nesting are bounded. [`adjust`] is the one entry point.

use crate::args;
use crate::diag::{Diagnostic, Diags, Msg, Origin};
use crate::geom::f3;
use crate::params::{parse_number_checked, NumberError};
use regex::Regex;
use std::collections::HashMap;
use std::ops::Range;
use std::sync::OnceLock;

/// Largest absolute value of any number adjust-z reads or writes (mm).
pub const LIMIT: f64 = 1e6;
/// Longest line of `_Clean.gcode` or `_Z.txt`, in bytes.
pub const MAX_LINE: usize = 10_000;
/// Deepest nesting of `(`, `[` and unary `-` in a probe expression.
pub const MAX_DEPTH: usize = 64;

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

/// The limit option as the user spelled it: `/m` (reference command line) or `--max`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MaxOption {
    Slash,
    Long,
}

impl MaxOption {
    pub fn name(self) -> &'static str {
        match self {
            MaxOption::Slash => "/m",
            MaxOption::Long => "--max",
        }
    }
}

/// `None` when `max` is a usable limit (finite, > 0, ≤ [`LIMIT`]), else the option error.
pub fn check_max(max: f64, text: &str, opt: MaxOption) -> Option<Diagnostic> {
    if max.is_finite() && max > 0.0 && max <= LIMIT {
        None
    } else {
        Some(Diagnostic::error(
            Msg::MaxInvalid,
            Origin::Options,
            args![opt.name(), text],
        ))
    }
}

fn line_origin(file: &str, line: usize) -> Origin {
    Origin::FileLine {
        file: file.to_string(),
        line,
    }
}

/// A number of `_Z.txt`: `Err(message)` unless finite and within ±[`LIMIT`].
fn sane_number(text: &str) -> Result<f64, Msg> {
    match parse_number_checked(text) {
        Ok(v) if v.abs() <= LIMIT => Ok(v),
        Ok(_) | Err(NumberError::OutOfRange) => Err(Msg::ZOutOfRange),
        Err(_) => Err(Msg::ZNotNumber),
    }
}

/// One measured line of `_Z.txt`: `(comment/T=<t>) #<n>=<value>`.
#[derive(Debug, Clone, PartialEq)]
pub struct ZLine {
    /// 1-based line number.
    pub line: usize,
    /// `#51`.
    pub name: String,
    pub t: f64,
    pub t_text: String,
    pub value: f64,
    pub value_text: String,
}

/// Splits a `_Z.txt` line into T text, name and value text; `None` if it is not of the form
/// `(…/T=t) #digits=value` (blanks allowed around `#`, the digits and `=`).
fn split_z_line(line: &str) -> Option<(&str, &str, &str)> {
    let line = line.trim();
    let rest = line.strip_prefix('(')?;
    // the comment cannot contain `)`: AsComment writes it as `]`
    let close = rest.find(')')?;
    let comment = &rest[..close];
    let t_text = comment[comment.rfind("/T=")? + 3..].trim();
    let rest = rest[close + 1..]
        .trim_start()
        .strip_prefix('#')?
        .trim_start();
    let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    if digits == 0 {
        return None;
    }
    let (name, rest) = rest.split_at(digits);
    let value = rest.trim_start().strip_prefix('=')?.trim();
    if value.is_empty() {
        return None;
    }
    Some((t_text, name, value))
}

/// Reads the measured values of a `_Z.txt` file. Every line must be blank or of the form
/// `(comment/T=t) #n=value` with finite numbers within ±[`LIMIT`]; errors name file and line.
pub fn parse_z_file(text: &str, file: &str, diags: &mut Diags) -> Vec<ZLine> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut out: Vec<ZLine> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let origin = line_origin(file, i + 1);
        if line.len() > MAX_LINE {
            diags.error(Msg::LineTooLong, origin, args![MAX_LINE]);
            continue;
        }
        if line.trim().is_empty() {
            continue;
        }
        let Some((t_text, digits, value_text)) = split_z_line(line) else {
            diags.error(Msg::ZLineFormat, origin, vec![]);
            continue;
        };
        let name = format!("#{digits}");
        let (t, value) = match (sane_number(t_text), sane_number(value_text)) {
            (Ok(t), Ok(v)) => (t, v),
            (Err(msg), _) => {
                diags.error(msg, origin, args![t_text, name]);
                continue;
            }
            (_, Err(msg)) => {
                diags.error(msg, origin, args![value_text, name]);
                continue;
            }
        };
        if out.iter().any(|z| z.name == name) {
            diags.error(Msg::ZDuplicate, origin, args![name]);
            continue;
        }
        out.push(ZLine {
            line: i + 1,
            name,
            t,
            t_text: t_text.to_string(),
            value,
            value_text: value_text.to_string(),
        });
    }
    out
}

fn z_regex() -> &'static Regex {
    static RE: OnceLock<Regex> = OnceLock::new();
    RE.get_or_init(|| {
        Regex::new(r"[0-9.-]+\(=([0-9.-]+([\]\[)(+*/\-]|#[0-9]+|[0-9.-]+)*)\)")
            .expect("static regex")
    })
}

/// A probe as `_Clean.gcode` uses it: its nominal height and the first line naming it.
#[derive(Debug, Clone, PartialEq)]
pub struct Probe {
    pub name: String,
    pub th: f64,
    /// 1-based line of the first use.
    pub line: usize,
}

/// A probe expression found in a line of `_Clean.gcode`.
#[derive(Debug, Clone)]
struct Found {
    /// 0-based line index.
    index: usize,
    /// The matched text (`0.800(=…)`), replaced by the value.
    whole: Range<usize>,
    /// The expression (regex group 1).
    expr: String,
}

/// The probe expressions of `_Clean.gcode` and the probes they name, in order of first use.
#[derive(Debug, Default)]
pub struct CleanProgram {
    pub probes: Vec<Probe>,
    found: Vec<Found>,
}

/// Is this `_Clean.gcode` line a comment (trace comment or a move commented out by `; `)?
fn is_comment(line: &str) -> bool {
    let t = line.trim_start();
    t.starts_with('(') || t.starts_with(';')
}

/// Does `text` contain `(=` that is not `(==`?
fn has_expression_mark(text: &str) -> bool {
    text.match_indices("(=")
        .any(|(i, _)| text.as_bytes().get(i + 2) != Some(&b'='))
}

/// Checks that `clean` is a complete program: first line `%`, a line `M30`, last line `%`.
fn check_complete(clean: &str, file: &str, diags: &mut Diags) {
    let lines: Vec<&str> = clean.lines().collect();
    let last = lines.iter().rposition(|l| !l.trim().is_empty());
    let bad_line = match last {
        None => Some(1),
        Some(_) if lines[0].trim() != "%" => Some(1),
        Some(last) if lines[last].trim() != "%" || last == 0 => Some(last + 1),
        Some(last) if !lines[1..last].iter().any(|l| l.trim() == "M30") => Some(last + 1),
        Some(_) => None,
    };
    if let Some(line) = bad_line {
        diags.error(
            Msg::ZIncompleteProgram,
            line_origin(file, line),
            args![file],
        );
    }
}

/// Reads `_Clean.gcode`: completeness, every probe expression (syntax, numbers, nesting) and
/// the nominal height of each probe from its `w*[#n-TH]` terms. Errors name file and line.
pub fn read_clean(clean: &str, file: &str, diags: &mut Diags) -> CleanProgram {
    check_complete(clean, file, diags);
    let mut prog = CleanProgram::default();
    for (index, line) in clean.lines().enumerate() {
        let origin = || line_origin(file, index + 1);
        if line.len() > MAX_LINE {
            diags.error(Msg::LineTooLong, origin(), args![MAX_LINE]);
            continue;
        }
        let found = z_regex().captures(line).map(|c| {
            let whole = c.get(0).map_or(0..0, |m| m.range());
            let expr = c.get(1).map_or("", |m| m.as_str()).to_string();
            (whole, expr)
        });
        if !is_comment(line) {
            if line.contains("(==") {
                diags.error(Msg::ZAlreadyAdjusted, origin(), args![file]);
                continue;
            }
            // every expression must be the one the rewriting replaces; another one would
            // stay in the output as an uncorrected Z
            let rest = match &found {
                Some((whole, _)) => format!("{}{}", &line[..whole.start], &line[whole.end..]),
                None => line.to_string(),
            };
            if has_expression_mark(&rest) {
                diags.error(
                    Msg::ZUnreadableExpression,
                    origin(),
                    args![shown(line.trim())],
                );
                continue;
            }
        }
        let Some((whole, expr)) = found else {
            continue;
        };
        let mut p = Parser::new(&expr, None);
        if let Err((msg, a)) = p.run() {
            diags.error(msg, origin(), a);
            continue;
        }
        if let Some(name) = p.bare_variable() {
            diags.error(Msg::ZProbeTermForm, origin(), args![name, shown(&expr)]);
            continue;
        }
        for (name, th) in p.refs {
            match prog.probes.iter().find(|q| q.name == name) {
                Some(q) if (q.th - th).abs() > 1e-9 => diags.error(
                    Msg::ZProbeHeightsDiffer,
                    origin(),
                    args![name, f3(th), f3(q.th), q.line],
                ),
                Some(_) => {}
                None => prog.probes.push(Probe {
                    name,
                    th,
                    line: index + 1,
                }),
            }
        }
        prog.found.push(Found { index, whole, expr });
    }
    prog
}

/// Matches the measured values against the probes of `_Clean.gcode`: each probe needs exactly
/// one line whose T is its nominal height and whose value is within `max` of it.
pub fn measured_values(
    prog: &CleanProgram,
    clean_file: &str,
    z: &[ZLine],
    z_file: &str,
    max: f64,
    opt: MaxOption,
    diags: &mut Diags,
) -> HashMap<String, f64> {
    let mut vars = HashMap::new();
    for zl in z {
        let origin = line_origin(z_file, zl.line);
        let Some(p) = prog.probes.iter().find(|p| p.name == zl.name) else {
            diags.error(Msg::ZUnknownProbe, origin, args![zl.name, clean_file]);
            continue;
        };
        if (zl.t - p.th).abs() > 1e-9 {
            diags.error(
                Msg::ZNominalMismatch,
                origin,
                args![zl.t_text, zl.name, f3(p.th), clean_file, p.line],
            );
            continue;
        }
        if (zl.value - p.th).abs() > max {
            let msg = match opt {
                MaxOption::Slash => Msg::ZTooFar,
                MaxOption::Long => Msg::ZTooFarMax,
            };
            diags.error(msg, origin, args![zl.value_text, zl.name, f3(p.th), max]);
            continue;
        }
        vars.insert(zl.name.clone(), zl.value);
    }
    for p in &prog.probes {
        if !z.iter().any(|zl| zl.name == p.name) {
            diags.error(
                Msg::ZProbeMissing,
                line_origin(clean_file, p.line),
                args![p.name, f3(p.th), z_file],
            );
        }
    }
    vars
}

/// Replaces every probe expression by its value (`Z0.921(==…)`). Errors name the line.
fn rewrite_program(
    clean: &str,
    file: &str,
    prog: &CleanProgram,
    vars: &HashMap<String, f64>,
    diags: &mut Diags,
) -> String {
    let mut out = String::with_capacity(clean.len() + clean.len() / 8);
    let mut found = prog.found.iter().peekable();
    for (i, line) in clean.lines().enumerate() {
        match found.next_if(|f| f.index == i) {
            Some(f) => match eval(&f.expr, vars) {
                Ok(v) => {
                    out.push_str(&line[..f.whole.start]);
                    out.push_str(&format!("{}(=={})", f3(v), f.expr));
                    out.push_str(&line[f.whole.end..]);
                }
                Err((msg, a)) => {
                    diags.error(msg, line_origin(file, i + 1), a);
                    out.push_str(line);
                }
            },
            None => out.push_str(line),
        }
        out.push('\n');
    }
    out
}

/// The whole of adjust-z for one part: `_Milling.gcode`'s content, or `None` after errors
/// (each naming its file and line). Nothing is produced unless every check passes.
pub fn adjust(
    clean: &str,
    clean_file: &str,
    z: &str,
    z_file: &str,
    max: f64,
    opt: MaxOption,
    diags: &mut Diags,
) -> Option<String> {
    let before = diags.error_count();
    if let Some(d) = check_max(max, &max.to_string(), opt) {
        diags.push(d);
        return None;
    }
    let lines = parse_z_file(z, z_file, diags);
    let prog = read_clean(clean, clean_file, diags);
    if diags.error_count() > before {
        return None;
    }
    let vars = measured_values(&prog, clean_file, &lines, z_file, max, opt, diags);
    if diags.error_count() > before {
        return None;
    }
    let milling = rewrite_program(clean, clean_file, &prog, &vars, diags);
    (diags.error_count() == before).then_some(milling)
}

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
fn shown(text: &str) -> String {
    match text.char_indices().nth(200) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.to_string(),
    }
}

type ExprResult = Result<f64, (Msg, Vec<String>)>;

/// LL(1) parser and evaluator of §15.4. Without variables (`vars: None`) it only checks the
/// syntax and collects the probe terms `[#n-TH]`.
struct Parser<'a> {
    s: &'a [u8],
    i: usize,
    expr: &'a str,
    vars: Option<&'a HashMap<String, f64>>,
    depth: usize,
    /// Every variable with its position.
    uses: Vec<(usize, String)>,
    /// Probe terms `[#n-TH]`: name and TH.
    refs: Vec<(String, f64)>,
    /// Positions of the variables inside probe terms.
    ref_positions: Vec<usize>,
}

fn probe_term_regex() -> &'static Regex {
    static RE: OnceLock<Regex> = OnceLock::new();
    RE.get_or_init(|| Regex::new(r"^#[0-9]+-(-?[0-9.]+)$").expect("static regex"))
}

impl<'a> Parser<'a> {
    fn new(expr: &'a str, vars: Option<&'a HashMap<String, f64>>) -> Parser<'a> {
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
    fn run(&mut self) -> ExprResult {
        let v = self.expr()?;
        if self.i < self.s.len() && self.s[self.i] != b'=' {
            return Err((Msg::ExprEndExpected, args![self.i, shown(self.expr)]));
        }
        Ok(v)
    }
    /// The first variable that is not part of a probe term.
    fn bare_variable(&self) -> Option<&str> {
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

    fn vars() -> HashMap<String, f64> {
        HashMap::from([("#51".to_string(), 2.1), ("#52".to_string(), 2.2)])
    }

    const CLEAN: &str =
        "%\nG00 Z5.000\nG01 Z0.800(=0.800+0.794*[#51-2.000]+0.206*[#52-2.000])\nM30\n%\n";
    const Z: &str = "([57.358 242.020]/T=2.000) #51=2,1\n\n([1.000 2.000]/L:a/T=2.000) #52=2.2\n";

    fn run(clean: &str, z: &str, max: f64) -> (Option<String>, Vec<Msg>, Diags) {
        let mut d = Diags::default();
        let out = adjust(clean, "c", z, "z", max, MaxOption::Slash, &mut d);
        let msgs = d.list.iter().map(|x| x.msg).collect();
        (out, msgs, d)
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

    #[test]
    fn adjusts_good_input_unchanged() {
        let (out, msgs, _) = run(CLEAN, Z, 1.0);
        assert!(msgs.is_empty(), "{msgs:?}");
        assert_eq!(
            out.unwrap(),
            "%\nG00 Z5.000\nG01 Z0.921(==0.800+0.794*[#51-2.000]+0.206*[#52-2.000])\nM30\n%\n"
        );
    }

    #[test]
    fn non_finite_or_insane_numbers_are_refused() {
        for bad in [
            "NaN",
            "inf",
            "Infinity",
            "-Infinity",
            "1e999",
            "2e6",
            "-1000001",
        ] {
            let z = Z.replace("#51=2,1", &format!("#51={bad}"));
            let (out, msgs, d) = run(CLEAN, &z, 1e6);
            assert!(out.is_none(), "{bad}");
            assert!(
                msgs == [Msg::ZNotNumber] || msgs == [Msg::ZOutOfRange],
                "{bad}: {msgs:?}"
            );
            assert_eq!(d.list[0].origin.context(), "z:1");
            let z = Z.replace("T=2.000) #51", &format!("T={bad}) #51"));
            assert!(run(CLEAN, &z, 1e6).0.is_none(), "T={bad}");
        }
        let (_, _, d) = run(CLEAN, &Z.replace("#51=2,1", "#51=NaN"), 1.0);
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "Value 'NaN' for #51 is not a valid number"
        );
        let (_, msgs, _) = run(CLEAN, &Z.replace("#51=2,1", "#51=2e6"), 1.0);
        assert_eq!(msgs, [Msg::ZOutOfRange]);
    }

    #[test]
    fn max_must_be_finite_and_positive() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0, -1.0, 2e6] {
            let (out, msgs, _) = run(CLEAN, Z, bad);
            assert!(out.is_none(), "{bad}");
            assert_eq!(msgs, [Msg::MaxInvalid], "{bad}");
        }
        let d = check_max(f64::NAN, "NaN", MaxOption::Long).unwrap();
        assert_eq!(
            d.message(crate::Lang::En),
            "--max value NaN must be a finite number > 0 and at most 1000000"
        );
        assert!(check_max(0.5, "0.5", MaxOption::Slash).is_none());
    }

    #[test]
    fn nominal_height_comes_from_clean_gcode() {
        // editing T in _Z.txt does not move the limit: the T must match _Clean.gcode
        let z = Z.replace("T=2.000) #51=2,1", "T=-50) #51=-50");
        let (out, msgs, d) = run(CLEAN, &z, 0.5);
        assert!(out.is_none());
        assert_eq!(msgs, [Msg::ZNominalMismatch]);
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "T=-50 for #51 differs from its nominal height 2.000 in c:3"
        );
        assert_eq!(d.list[0].origin.context(), "z:1");
        // the limit is measured from the nominal height of _Clean.gcode
        let z = Z.replace("#51=2,1", "#51=2.6");
        assert_eq!(run(CLEAN, &z, 0.5).1, [Msg::ZTooFar]);
        // T written differently but equal is fine
        let z = Z.replace("T=2.000) #51", "T=2) #51");
        assert!(run(CLEAN, &z, 0.5).0.is_some());
        // a probe of _Clean.gcode without a value
        let (out, msgs, d) = run(CLEAN, "([0 0]/T=2.000) #51=2\n", 0.5);
        assert!(out.is_none());
        assert_eq!(msgs, [Msg::ZProbeMissing]);
        assert_eq!(d.list[0].origin.context(), "c:3");
        // one probe with two nominal heights in _Clean.gcode
        let clean = CLEAN.replace("M30", "G01 Z1.000(=1.000+1.000*[#51-3.000])\nM30");
        assert_eq!(run(&clean, Z, 0.5).1, [Msg::ZProbeHeightsDiffer]);
        // a probe variable outside a [#n-TH] term
        let clean = CLEAN.replace("M30", "G01 Z1.000(=1.000+#51)\nM30");
        assert_eq!(run(&clean, Z, 0.5).1, [Msg::ZProbeTermForm]);
    }

    #[test]
    fn negative_nominal_heights() {
        let clean = "%\nG01 Z-1.000(=-1.000+1.000*[#51--1.500])\nM30\n%\n";
        let (out, msgs, _) = run(clean, "([0 0]/T=-1.500) #51=-1,4\n", 0.5);
        assert!(msgs.is_empty(), "{msgs:?}");
        assert_eq!(
            out.unwrap(),
            "%\nG01 Z-0.900(==-1.000+1.000*[#51--1.500])\nM30\n%\n"
        );
    }

    #[test]
    fn incomplete_programs_are_refused() {
        for (clean, line) in [
            ("", 1),
            ("\n\n", 1),
            ("G00 Z5.000\nM30\n%\n", 1),
            ("%\nG00 Z5.000\nM30\n", 3),
            ("%\nG00 Z5.000\n%\n", 3),
            ("%\nG01 Z0.800(=0.800+0.794*[#51-2.000]+0.206*[#52-2.0", 2),
            ("%\n", 1),
        ] {
            let (out, msgs, d) = run(clean, "", 0.5);
            assert!(out.is_none(), "{clean:?}");
            assert!(
                msgs.contains(&Msg::ZIncompleteProgram),
                "{clean:?}: {msgs:?}"
            );
            let d = d
                .list
                .iter()
                .find(|d| d.msg == Msg::ZIncompleteProgram)
                .unwrap();
            assert_eq!(d.origin.context(), format!("c:{line}"), "{clean:?}");
        }
        // trailing blank lines and CR LF are fine
        let crlf = CLEAN.replace('\n', "\r\n") + "\r\n";
        assert!(run(&crlf, Z, 1.0).0.is_some());
    }

    #[test]
    fn z_lines_must_have_the_form() {
        for line in [
            "2.1=9",
            "([0 0]/T=2.000) #51",
            "([0 0]/T=2.000) 51=2.1",
            "([0 0]/T=2.000) #=2.1",
            "([0 0]/T=2.000) #5a=2.1",
            "([0 0]/T=2.000) #51=",
            "([0 0]) #51=2.1",
            "[0 0]/T=2.000 #51=2.1",
            "#51=2.1",
            "([0 0]/T=2.000 #51=2.1",
        ] {
            let z = format!("{}\n{line}\n", Z.lines().next().unwrap());
            let mut d = Diags::default();
            parse_z_file(&z, "z", &mut d);
            assert_eq!(
                d.list.iter().map(|x| x.msg).collect::<Vec<_>>(),
                [Msg::ZLineFormat],
                "{line}"
            );
            assert_eq!(d.list[0].origin.context(), "z:2", "{line}");
        }
        // a second `=` is not a number
        let mut d = Diags::default();
        parse_z_file("([0 0]/T=2.000) #51=2.1=9\n", "z", &mut d);
        assert_eq!(d.list[0].msg, Msg::ZNotNumber);
        assert_eq!(d.list[0].args, args!["2.1=9", "#51"]);
        // blanks, a label with `#` and `=`, CR LF and a byte-order mark are fine
        let mut d = Diags::default();
        let v = parse_z_file(
            "\u{feff}([1 2]/L:a#b=c/T=2.000)  # 51 = 2,1 \r\n \r\n",
            "z",
            &mut d,
        );
        assert!(d.list.is_empty(), "{:?}", d.list);
        assert_eq!((v[0].name.as_str(), v[0].t, v[0].value), ("#51", 2.0, 2.1));
        // too long
        let mut d = Diags::default();
        parse_z_file(&"x".repeat(MAX_LINE + 1), "z", &mut d);
        assert_eq!(d.list[0].msg, Msg::LineTooLong);
    }

    #[test]
    fn unknown_probes_in_z_file_are_errors() {
        let z = format!("{Z}([0 0]/T=2.000) #99=2\n");
        let (out, msgs, d) = run(CLEAN, &z, 1.0);
        assert!(out.is_none());
        assert_eq!(msgs, [Msg::ZUnknownProbe]);
        assert_eq!(d.list[0].origin.context(), "z:4");
    }

    #[test]
    fn too_far_names_the_measured_value_first() {
        let z = Z.replace("#51=2,1", "#51=9,9");
        let (_, _, d) = run(CLEAN, &z, 0.5);
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "Value 9,9 for #51 differs from 2.000 by more than /m=0.5"
        );
        let mut d = Diags::default();
        adjust(CLEAN, "c", &z, "z", 0.5, MaxOption::Long, &mut d);
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "Value 9,9 for #51 differs from 2.000 by more than --max=0.5"
        );
        assert_eq!(
            d.list[0].message(crate::Lang::De),
            "Wert 9,9 für #51 weicht von 2.000 um mehr als --max=0.5 ab"
        );
    }

    #[test]
    fn clean_lines_the_rewriting_cannot_handle_are_refused() {
        // a second expression on a line would stay uncorrected
        let clean = CLEAN.replace(
            "M30",
            "G01 X1.000(=1.000+1.000*[#51-2.000]) Z0.800(=0.800+1.000*[#51-2.000])\nM30",
        );
        assert_eq!(run(&clean, Z, 1.0).1, [Msg::ZUnreadableExpression]);
        let clean = CLEAN.replace("M30", "G01 Z0.800(=0.800 + 1.000*[#51-2.000])\nM30");
        assert_eq!(run(&clean, Z, 1.0).1, [Msg::ZUnreadableExpression]);
        // an already adjusted line carries an old measurement
        let clean = CLEAN.replace("M30", "G01 Z0.900(==0.800+1.000*[#51-2.000])\nM30");
        assert_eq!(run(&clean, Z, 1.0).1, [Msg::ZAlreadyAdjusted]);
        // a long line
        let clean = CLEAN.replace("M30", &format!("({})\nM30", "x".repeat(MAX_LINE)));
        assert_eq!(run(&clean, Z, 1.0).1, [Msg::LineTooLong]);
        // comments may say anything
        let clean = CLEAN.replace("M30", "  (a (=b (==c)\n; G00 Z1(=x\nM30");
        assert!(run(&clean, Z, 1.0).0.is_some());
        // expression errors name the line
        let clean = CLEAN.replace("[#52-2.000])", "[#52-2.000)");
        let (_, msgs, d) = run(&clean, Z, 1.0);
        assert_eq!(msgs, [Msg::ExprBracketExpected]);
        assert_eq!(d.list[0].origin.context(), "c:3");
    }

    #[test]
    fn duplicates_and_missing_values() {
        let mut d = Diags::default();
        parse_z_file(
            "([57.358 242.020]/T=2.000) #51=\n([0 0]/T=2.000) #52=x\n([0 0]/T=2.000) #53=2\n([0 0]/T=2.000) #53=2\n",
            "z",
            &mut d,
        );
        let msgs: Vec<Msg> = d.list.iter().map(|x| x.msg).collect();
        assert_eq!(
            msgs,
            vec![Msg::ZLineFormat, Msg::ZNotNumber, Msg::ZDuplicate]
        );
        assert_eq!(d.list[0].origin.context(), "z:1");
    }

    #[test]
    fn rewrites_lines_once() {
        let (out, _, _) = run(CLEAN, Z, 1.0);
        let out = out.unwrap();
        // the adjusted program no longer matches: nothing is left to rewrite
        assert!(!has_expression_mark(&out));
        assert!(z_regex().captures(&out).is_none());
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
