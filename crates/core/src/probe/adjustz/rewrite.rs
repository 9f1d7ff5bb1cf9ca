//! Reading `_Clean.gcode` and rewriting its probe expressions with the measured values.
//!
//! Reading `_Clean.gcode` (completeness, with or without `%`), matching the measured values,
//! rewriting; `(MILLPATH-PROBES …)` for verify in our own sets.

use super::bounds::{line_origin, MaxOption, MAX_LINE};
use super::expr::{eval, shown, Parser};
use super::zfile::ZLine;
use crate::args;
use crate::diag::{Diags, Msg};
use crate::geom::f3;
use regex::Regex;
use std::collections::HashMap;
use std::ops::Range;
use std::sync::OnceLock;

pub(super) fn z_regex() -> &'static Regex {
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
pub(super) fn has_expression_mark(text: &str) -> bool {
    text.match_indices("(=")
        .any(|(i, _)| text.as_bytes().get(i + 2) != Some(&b'='))
}

/// Checks that `clean` is a complete program: first line `%`, a line `M30`, last line `%`;
/// or, in the grbl dialect (no `%`), a last line `M30`.
fn check_complete(clean: &str, file: &str, diags: &mut Diags) {
    // a post's line numbers (`N10 M30`) are not part of what is checked
    let lines: Vec<&str> = clean.lines().map(without_line_number).collect();
    let last = lines.iter().rposition(|l| !l.trim().is_empty());
    let percent = lines.first().is_some_and(|l| l.trim() == "%");
    let bad_line = match last {
        None => Some(1),
        Some(last) if !percent && lines[last].trim() == "M30" && last > 0 => None,
        Some(_) if !percent => Some(1),
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

/// A line without its line number word (`N10 M30` → `M30`).
fn without_line_number(line: &str) -> &str {
    let t = line.trim_start();
    let digits = t
        .strip_prefix('N')
        .map(|r| r.len() - r.trim_start_matches(|c: char| c.is_ascii_digit()).len());
    match digits {
        Some(n) if n > 0 && t[1 + n..].starts_with([' ', '\t']) => &t[1 + n..],
        _ => line,
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
pub(super) fn rewrite_program(
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

/// The word before the measured values in an adjusted program's comment, for `verify`.
pub const PROBES_WORD: &str = "MILLPATH-PROBES";

/// Probes per `(MILLPATH-PROBES …)` line: short lines for controllers with a line limit.
const PROBES_PER_LINE: usize = 8;

/// Writes the measured values into the adjusted program, so that `verify` can check depths
/// below the measured surface: `(MILLPATH-PROBES #51=3.200 #52=2.900)` lines after the
/// `(MILLPATH-STOCK …)` comment; in the reference dialect, which has no such comment and no
/// line to spare, the same words at the end of the banner comment (line 2).
pub(super) fn record_measured(
    milling: &str,
    prog: &CleanProgram,
    vars: &HashMap<String, f64>,
) -> String {
    let words: Vec<String> = prog
        .probes
        .iter()
        .filter_map(|p| vars.get(&p.name).map(|v| format!("{}={}", p.name, f3(*v))))
        .collect();
    if words.is_empty() {
        return milling.to_string();
    }
    let banner = crate::digest::banner_index(milling);
    let stock = milling
        .lines()
        .position(|l| l.trim_start().starts_with("(MILLPATH-STOCK"));
    let mut out = String::with_capacity(milling.len() + words.len() * 16 + 64);
    for (i, line) in milling.lines().enumerate() {
        match (stock, line.trim_end().strip_suffix(')')) {
            (None, Some(open)) if i == banner && !open.contains(PROBES_WORD) => {
                out.push_str(&format!("{open} {PROBES_WORD} {})", words.join(" ")));
            }
            _ => out.push_str(line),
        }
        out.push('\n');
        if stock == Some(i) {
            for chunk in words.chunks(PROBES_PER_LINE) {
                out.push_str(&format!("({PROBES_WORD} {})\n", chunk.join(" ")));
            }
        }
    }
    out
}
