//! Reading and validating a post file. Every value is read with its span
//! (`toml::Spanned`), so each error names the file, line, column and key; a syntax or type
//! error is located by toml's own span.

use crate::error::{ErrorKind, PostError};
use crate::event::Event;
use crate::number::{Decimals, NumberFormat, MAX_DECIMALS};
use crate::template::Template;
use crate::*;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::ops::Range;
use toml::Spanned;

type S<T> = Spanned<T>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Raw {
    post: S<RawHeader>,
    format: Option<S<RawFormat>>,
    line_numbers: Option<S<RawLineNumbers>>,
    comments: Option<S<RawComments>>,
    capabilities: Option<S<RawCaps>>,
    templates: S<BTreeMap<S<String>, S<String>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHeader {
    name: S<String>,
    description: Option<S<String>>,
    family: S<String>,
    extension: Option<S<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawNumber {
    decimals: Option<S<toml::Value>>,
    decimal_separator: Option<S<String>>,
    trailing_zeros: Option<bool>,
    leading_zero: Option<bool>,
    plus_sign: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFormat {
    decimals: Option<S<toml::Value>>,
    decimal_separator: Option<S<String>>,
    trailing_zeros: Option<bool>,
    leading_zero: Option<bool>,
    plus_sign: Option<bool>,
    words: Option<BTreeMap<S<String>, S<RawNumber>>>,
    modal: Option<Vec<S<String>>>,
    line_end: Option<S<String>>,
    max_line_length: Option<S<toml::Value>>,
    percent: Option<bool>,
    arcs: Option<S<String>>,
    chord_tolerance: Option<S<toml::Value>>,
    max_arc_radius: Option<S<toml::Value>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLineNumbers {
    enabled: Option<bool>,
    letter: Option<S<String>>,
    start: Option<S<toml::Value>>,
    step: Option<S<toml::Value>>,
    width: Option<S<toml::Value>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawComments {
    style: Option<S<String>>,
    reserved: Option<S<String>>,
    ascii: Option<bool>,
    active_words: Option<Vec<S<String>>>,
    line_break: Option<S<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCaps {
    probing: Option<S<String>>,
    probe_log: Option<bool>,
    spindle: Option<bool>,
    dwell: Option<bool>,
}

/// Where errors are located: the file's name and text.
struct Src<'a> {
    file: &'a str,
    text: &'a str,
}

impl Src<'_> {
    fn at(&self, offset: usize, key: &str, kind: ErrorKind) -> PostError {
        let offset = offset.min(self.text.len());
        let before = &self.text[..offset];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = self.text[line_start..offset].chars().count() + 1;
        PostError {
            file: self.file.to_string(),
            line,
            column,
            key: key.to_string(),
            kind,
        }
    }
    fn span(&self, span: Range<usize>, key: &str, kind: ErrorKind) -> PostError {
        self.at(span.start, key, kind)
    }
    /// The dotted key of the line at `offset`: the table header above it and the key before
    /// its `=` (for toml's own errors, which give a span but no key).
    fn key_at(&self, offset: usize) -> String {
        let offset = offset.min(self.text.len());
        let line_start = self.text[..offset].rfind('\n').map_or(0, |i| i + 1);
        let line = self.text[line_start..].lines().next().unwrap_or("");
        let key = line
            .split_once('=')
            .map(|(k, _)| k.trim().trim_matches('"').to_string())
            .unwrap_or_default();
        let table = self.text[..line_start]
            .lines()
            .rev()
            .find_map(|l| {
                let l = l.trim();
                (l.starts_with('[') && l.ends_with(']'))
                    .then(|| l.trim_matches(|c| c == '[' || c == ']').trim().to_string())
            })
            .unwrap_or_default();
        match (table.is_empty(), key.is_empty()) {
            (_, true) if line.trim_start().starts_with('[') => line
                .trim()
                .trim_matches(|c| c == '[' || c == ']')
                .trim()
                .to_string(),
            (true, _) => key,
            (false, true) => table,
            (false, false) => format!("{table}.{key}"),
        }
    }
}

/// Loads a post from its text; `file` names it in the errors (`builtin:NAME` or a path).
pub fn load(file: &str, text: &str) -> Result<Post, PostError> {
    let src = Src { file, text };
    if text.len() > MAX_POST_FILE {
        return Err(src.at(0, "", ErrorKind::TooLarge(text.len())));
    }
    let raw: Raw = toml::from_str(text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        let key = if e.span().is_some() {
            src.key_at(offset)
        } else {
            String::new()
        };
        let mut err = src.at(
            offset,
            &key,
            ErrorKind::Syntax(e.message().trim().to_string()),
        );
        if e.span().is_none() {
            err.line = 0;
        }
        err
    })?;
    build(&src, raw)
}

fn bad(src: &Src, span: Range<usize>, key: &str, what: &'static str) -> PostError {
    src.span(span, key, ErrorKind::BadValue(what))
}

fn build(src: &Src, raw: Raw) -> Result<Post, PostError> {
    let header = raw.post.into_inner();
    let name = header.name.get_ref().clone();
    if name.is_empty()
        || name.len() > 64
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
    {
        return Err(bad(
            src,
            header.name.span(),
            "post.name",
            "a name of letters, digits, `-` and `_`",
        ));
    }
    let family = match header.family.get_ref().as_str() {
        "rs274" => Family::Rs274,
        "grbl" => Family::Grbl,
        "marlin" => Family::Marlin,
        "xcam" => Family::Xcam,
        _ => {
            return Err(bad(
                src,
                header.family.span(),
                "post.family",
                "\"rs274\", \"grbl\", \"marlin\" or \"xcam\"",
            ))
        }
    };
    let extension = match &header.extension {
        Some(e) => {
            let v = e.get_ref();
            if v.is_empty() || v.len() > 8 || !v.chars().all(|c| c.is_ascii_alphanumeric()) {
                return Err(bad(
                    src,
                    e.span(),
                    "post.extension",
                    "a file extension of letters and digits",
                ));
            }
            v.clone()
        }
        None => "gcode".into(),
    };
    let format = format(src, raw.format.map(|f| f.into_inner()))?;
    let line_numbers = match raw.line_numbers.map(|l| l.into_inner()) {
        None => None,
        Some(l) if l.enabled == Some(false) => None,
        Some(l) => Some(line_numbers(src, l)?),
    };
    let comments = comments(src, raw.comments.map(|c| c.into_inner()))?;
    let capabilities = capabilities(src, raw.capabilities.map(|c| c.into_inner()))?;
    let templates_span = raw.templates.span();
    let mut templates = BTreeMap::new();
    for (key, value) in raw.templates.into_inner() {
        let dotted = format!("templates.{}", key.get_ref());
        let Some(event) = Event::from_key(key.get_ref()) else {
            return Err(src.span(
                key.span(),
                &dotted,
                ErrorKind::UnknownTemplate(key.get_ref().clone()),
            ));
        };
        let t = Template::parse(event, value.get_ref()).map_err(|(offset, e)| {
            let at = template_offset(src.text, value.span(), offset);
            src.at(at, &dotted, ErrorKind::Template(e))
        })?;
        templates.insert(event, t);
    }
    if let Some(e) = Event::ALL
        .into_iter()
        .find(|e| e.required() && !templates.contains_key(e))
    {
        return Err(src.span(
            templates_span,
            "templates",
            ErrorKind::MissingTemplate(e.key()),
        ));
    }
    Ok(Post {
        name,
        description: header
            .description
            .map(|d| d.into_inner())
            .unwrap_or_default(),
        family,
        extension,
        format,
        line_numbers,
        comments,
        capabilities,
        templates,
        source: src.text.to_string(),
        origin: src.file.to_string(),
    })
}

/// Where byte `offset` of a template's text is in the file: after the string's opening
/// quotes (and the line break TOML drops after `"""`); escapes before it may shift it a
/// little, the line stays right for templates written on their own lines.
fn template_offset(text: &str, span: Range<usize>, offset: usize) -> usize {
    let raw = &text[span.clone()];
    let mut start = span.start;
    for q in ["\"\"\"", "'''", "\"", "'"] {
        if raw.starts_with(q) {
            start += q.len();
            if q.len() == 3 {
                if text[start..].starts_with("\r\n") {
                    start += 2;
                } else if text[start..].starts_with('\n') {
                    start += 1;
                }
            }
            break;
        }
    }
    (start + offset).min(span.end.saturating_sub(1).max(span.start))
}

fn decimals(src: &Src, v: &S<toml::Value>, key: &str) -> Result<Decimals, PostError> {
    match v.get_ref() {
        toml::Value::Integer(n) if (0..=MAX_DECIMALS as i64).contains(n) => {
            Ok(Decimals::Fixed(*n as u8))
        }
        toml::Value::String(s) if s == "shortest" => Ok(Decimals::Shortest),
        other => {
            // a hostile value (1e300) is shown short
            let mut shown = other.to_string();
            if shown.chars().count() > 24 {
                shown = shown.chars().take(20).collect::<String>() + "…";
            }
            Err(src.span(v.span(), key, ErrorKind::BadDecimals(shown)))
        }
    }
}

fn separator(src: &Src, v: &S<String>, key: &str) -> Result<char, PostError> {
    let mut chars = v.get_ref().chars();
    match (chars.next(), chars.next()) {
        (Some(c), None) if !c.is_ascii_digit() && !"+- \t".contains(c) && !c.is_control() => Ok(c),
        _ => Err(bad(
            src,
            v.span(),
            key,
            "one character, not a digit, sign or blank",
        )),
    }
}

/// A number of a table: `lo..=hi`.
fn in_range(
    src: &Src,
    v: &S<toml::Value>,
    key: &str,
    lo: f64,
    hi: f64,
    what: &'static str,
) -> Result<f64, PostError> {
    let x = match v.get_ref() {
        toml::Value::Integer(n) => *n as f64,
        toml::Value::Float(f) => *f,
        _ => f64::NAN,
    };
    if x.is_finite() && x >= lo && x <= hi {
        Ok(x)
    } else {
        Err(bad(src, v.span(), key, what))
    }
}

/// A whole number `lo..=hi`.
fn whole(
    src: &Src,
    v: &S<toml::Value>,
    key: &str,
    lo: i64,
    hi: i64,
    what: &'static str,
) -> Result<i64, PostError> {
    match v.get_ref() {
        toml::Value::Integer(n) if (lo..=hi).contains(n) => Ok(*n),
        _ => Err(bad(src, v.span(), key, what)),
    }
}

/// The number keys of `[format]` or of one word in `[format.words]`.
struct NumberKeys<'a> {
    decimals: Option<&'a S<toml::Value>>,
    separator: Option<&'a S<String>>,
    trailing_zeros: Option<bool>,
    leading_zero: Option<bool>,
    plus_sign: Option<bool>,
}

fn number_format(
    src: &Src,
    base: NumberFormat,
    prefix: &str,
    keys: NumberKeys,
) -> Result<NumberFormat, PostError> {
    let NumberKeys {
        decimals: decimals_v,
        separator: sep,
        trailing_zeros,
        leading_zero,
        plus_sign,
    } = keys;
    Ok(NumberFormat {
        decimals: match decimals_v {
            Some(d) => decimals(src, d, &format!("{prefix}decimals"))?,
            None => base.decimals,
        },
        separator: match sep {
            Some(s) => separator(src, s, &format!("{prefix}decimal_separator"))?,
            None => base.separator,
        },
        trailing_zeros: trailing_zeros.unwrap_or(base.trailing_zeros),
        leading_zero: leading_zero.unwrap_or(base.leading_zero),
        plus_sign: plus_sign.unwrap_or(base.plus_sign),
    })
}

fn format(src: &Src, raw: Option<RawFormat>) -> Result<Format, PostError> {
    let Some(f) = raw else {
        return Ok(Format {
            number: NumberFormat::default(),
            words: BTreeMap::new(),
            modal: Vec::new(),
            line_end: LineEnd::Lf,
            max_line_length: None,
            percent: true,
            arcs: ArcMode::Ij,
            chord_tolerance: 0.01,
            max_arc_radius: None,
        });
    };
    let number = number_format(
        src,
        NumberFormat::default(),
        "format.",
        NumberKeys {
            decimals: f.decimals.as_ref(),
            separator: f.decimal_separator.as_ref(),
            trailing_zeros: f.trailing_zeros,
            leading_zero: f.leading_zero,
            plus_sign: f.plus_sign,
        },
    )?;
    let mut words = BTreeMap::new();
    for (k, v) in f.words.iter().flatten() {
        let key = format!("format.words.{}", k.get_ref());
        let letter = single_letter(k.get_ref())
            .ok_or_else(|| bad(src, k.span(), &key, "a single letter A–Z"))?;
        let w = v.get_ref();
        let nf = number_format(
            src,
            number,
            &format!("{key}."),
            NumberKeys {
                decimals: w.decimals.as_ref(),
                separator: w.decimal_separator.as_ref(),
                trailing_zeros: w.trailing_zeros,
                leading_zero: w.leading_zero,
                plus_sign: w.plus_sign,
            },
        )?;
        words.insert(letter, nf);
    }
    let mut modal = Vec::new();
    for m in f.modal.iter().flatten() {
        let v = m.get_ref();
        let ok = v == "motion" || single_letter(v).is_some_and(|c| !"GNIJKR".contains(c));
        if !ok {
            return Err(bad(
                src,
                m.span(),
                "format.modal",
                "a word letter (A–Z) or \"motion\"",
            ));
        }
        modal.push(v.to_ascii_uppercase().replace("MOTION", "motion"));
    }
    let line_end = match f
        .line_end
        .as_ref()
        .map(|l| (l.get_ref().as_str(), l.span()))
    {
        None | Some(("lf", _)) => LineEnd::Lf,
        Some(("crlf", _)) => LineEnd::CrLf,
        Some((_, span)) => return Err(bad(src, span, "format.line_end", "\"lf\" or \"crlf\"")),
    };
    let max_line_length = match &f.max_line_length {
        None => None,
        Some(v) => Some(whole(
            src,
            v,
            "format.max_line_length",
            40,
            100_000,
            "a line length from 40 to 100000",
        )? as usize),
    };
    let arcs = match f.arcs.as_ref().map(|a| (a.get_ref().as_str(), a.span())) {
        None | Some(("ij", _)) => ArcMode::Ij,
        Some(("r", _)) => ArcMode::R,
        Some(("lines", _)) => ArcMode::Lines,
        Some((_, span)) => return Err(bad(src, span, "format.arcs", "\"ij\", \"r\" or \"lines\"")),
    };
    let chord_tolerance = match &f.chord_tolerance {
        None => 0.01,
        Some(v) => in_range(
            src,
            v,
            "format.chord_tolerance",
            0.0001,
            1.0,
            "a chord tolerance from 0.0001 to 1 mm",
        )?,
    };
    let max_arc_radius = match &f.max_arc_radius {
        None => None,
        Some(v) => {
            let r = in_range(
                src,
                v,
                "format.max_arc_radius",
                f64::MIN_POSITIVE,
                100_000.0,
                "a radius above 0 and at most 100000 mm",
            )?;
            Some(r)
        }
    };
    Ok(Format {
        number,
        words,
        modal,
        line_end,
        max_line_length,
        percent: f.percent.unwrap_or(true),
        arcs,
        chord_tolerance,
        max_arc_radius,
    })
}

fn single_letter(s: &str) -> Option<char> {
    let mut c = s.chars();
    match (c.next(), c.next()) {
        (Some(l), None) if l.is_ascii_alphabetic() => Some(l.to_ascii_uppercase()),
        _ => None,
    }
}

fn line_numbers(src: &Src, l: RawLineNumbers) -> Result<LineNumbers, PostError> {
    let letter = match &l.letter {
        None => 'N',
        Some(s) => single_letter(s.get_ref())
            .ok_or_else(|| bad(src, s.span(), "line_numbers.letter", "a single letter A–Z"))?,
    };
    let get = |v: &Option<S<toml::Value>>, key: &str, lo, hi, what, default| match v {
        None => Ok(default),
        Some(v) => whole(src, v, key, lo, hi, what),
    };
    Ok(LineNumbers {
        letter,
        start: get(
            &l.start,
            "line_numbers.start",
            0,
            1_000_000,
            "a whole number from 0 to 1000000",
            10,
        )? as u64,
        step: get(
            &l.step,
            "line_numbers.step",
            1,
            1000,
            "a step from 1 to 1000",
            10,
        )? as u64,
        width: get(
            &l.width,
            "line_numbers.width",
            0,
            9,
            "a width from 0 to 9",
            0,
        )? as usize,
    })
}

fn comments(src: &Src, raw: Option<RawComments>) -> Result<CommentRules, PostError> {
    let Some(c) = raw else {
        return Ok(CommentRules {
            style: CommentStyle::Parens,
            reserved: String::new(),
            ascii: false,
            active_words: Vec::new(),
            line_break: String::new(),
        });
    };
    let style = match c.style.as_ref().map(|s| (s.get_ref().as_str(), s.span())) {
        None | Some(("parens", _)) => CommentStyle::Parens,
        Some(("semicolon", _)) => CommentStyle::Semicolon,
        Some((_, span)) => {
            return Err(bad(
                src,
                span,
                "comments.style",
                "\"parens\" or \"semicolon\"",
            ))
        }
    };
    let reserved = match &c.reserved {
        None => String::new(),
        Some(r) => {
            let v = r.get_ref();
            if v.len() > 32 || !v.chars().all(|ch| ch.is_ascii_graphic()) {
                return Err(bad(
                    src,
                    r.span(),
                    "comments.reserved",
                    "printable ASCII characters",
                ));
            }
            v.clone()
        }
    };
    let mut active_words = Vec::new();
    for w in c.active_words.iter().flatten() {
        let v = w.get_ref();
        if v.is_empty() || v.len() > 32 || !v.chars().all(|ch| ch.is_ascii_alphabetic()) {
            return Err(bad(
                src,
                w.span(),
                "comments.active_words",
                "a word of letters",
            ));
        }
        active_words.push(v.clone());
    }
    let line_break = match &c.line_break {
        None => String::new(),
        Some(l) => {
            let v = l.get_ref();
            if v.is_empty() || v.len() > 16 || !v.chars().all(|ch| ch.is_ascii_graphic()) {
                return Err(bad(
                    src,
                    l.span(),
                    "comments.line_break",
                    "1 to 16 printable ASCII characters",
                ));
            }
            v.clone()
        }
    };
    Ok(CommentRules {
        style,
        reserved,
        ascii: c.ascii.unwrap_or(false),
        active_words,
        line_break,
    })
}

fn capabilities(src: &Src, raw: Option<RawCaps>) -> Result<Capabilities, PostError> {
    let c = raw.unwrap_or(RawCaps {
        probing: None,
        probe_log: None,
        spindle: None,
        dwell: None,
    });
    let probing = match c.probing.as_ref().map(|p| (p.get_ref().as_str(), p.span())) {
        None | Some(("none", _)) => Probing::None,
        Some(("G38.2", _)) => Probing::G38_2,
        Some(("G38.3", _)) => Probing::G38_3,
        Some(("G31", _)) => Probing::G31,
        Some((_, span)) => {
            return Err(bad(
                src,
                span,
                "capabilities.probing",
                "\"none\", \"G38.2\", \"G38.3\" or \"G31\"",
            ))
        }
    };
    Ok(Capabilities {
        probing,
        probe_log: c.probe_log.unwrap_or(false),
        spindle: c.spindle.unwrap_or(false),
        dwell: c.dwell.unwrap_or(false),
    })
}
