//! The group-code tokenizer: the file's bytes → (code, value, line) pairs, one pass, no copy.
//!
//! Values stay bytes of the file; the few helpers here turn them into text exactly as if the
//! whole file had been decoded with [`String::from_utf8_lossy`] first (an invalid sequence
//! never spans a line end, so a line decoded on its own is the same line of the decoded file).

use crate::{DxfError, DxfErrorKind};
use std::borrow::Cow;

/// One group: its code and its value line (end of line removed), a part of the file.
#[derive(Clone, Copy)]
pub(crate) struct Pair<'a> {
    pub(crate) code: i32,
    pub(crate) value: &'a [u8],
    /// 1-based line of the group code.
    pub(crate) line: usize,
}

/// The pairs of a file, as `bytes.split(|&b| b == b'\n')` lines taken two by two.
pub(crate) struct Tokens<'a> {
    bytes: &'a [u8],
    /// Start of the next line; past the end of `bytes` after the last line.
    pos: usize,
    /// Lines taken so far.
    line: usize,
}

/// The index of the first `\n` at or after `from`, or the length. Lines are short (`  0`,
/// `LINE`, `1.5`): eight bytes at a time, one well-predicted branch for most lines, is
/// quicker here than a byte loop or `memchr`'s set-up.
fn find_newline(b: &[u8], from: usize) -> usize {
    const ONES: u64 = 0x0101_0101_0101_0101;
    let mut i = from;
    while let Some(&word) = b.get(i..).and_then(|rest| rest.first_chunk::<8>()) {
        // the lowest zero byte of `x` is the first `\n` (bytes above it may be flagged too)
        let x = u64::from_le_bytes(word) ^ (ONES * u64::from(b'\n'));
        let zero = x.wrapping_sub(ONES) & !x & (ONES << 7);
        if zero != 0 {
            return i + (zero.trailing_zeros() / 8) as usize;
        }
        i += 8;
    }
    while i < b.len() && b[i] != b'\n' {
        i += 1;
    }
    i
}

/// A usual group code line (as [`plain_group_code`] takes them) that starts at `at` and
/// ends with `\r`s and a `\n`: its code and the start of the next line. Read in one go, as
/// this is where a reader spends its time.
#[inline]
fn plain_code_line(b: &[u8], at: usize) -> Option<(i32, usize)> {
    let mut i = at;
    while b.get(i) == Some(&b' ') {
        i += 1;
    }
    let digits = i;
    let mut v = 0i32;
    while let Some(&c) = b.get(i).filter(|c| c.is_ascii_digit()) {
        if i - digits == 9 {
            return None;
        }
        v = v * 10 + (c - b'0') as i32;
        i += 1;
    }
    if i == digits {
        return None;
    }
    while b.get(i) == Some(&b' ') {
        i += 1;
    }
    while b.get(i) == Some(&b'\r') {
        i += 1;
    }
    (b.get(i) == Some(&b'\n')).then_some((v, i + 1))
}

/// The usual group code lines (`  0`, ` 10`, `100`): spaces, at most nine digits, spaces.
/// `None` for anything else, which then goes the general way.
fn plain_group_code(b: &[u8]) -> Option<i32> {
    let mut i = 0;
    while i < b.len() && b[i] == b' ' {
        i += 1;
    }
    let digits = i;
    let mut v = 0i32;
    while i < b.len() && b[i].is_ascii_digit() && i - digits < 9 {
        v = v * 10 + (b[i] - b'0') as i32;
        i += 1;
    }
    (i > digits && b[i..].iter().all(|&c| c == b' ')).then_some(v)
}

impl<'a> Tokens<'a> {
    pub(crate) fn new(bytes: &'a [u8]) -> Self {
        Tokens {
            bytes,
            pos: 0,
            line: 0,
        }
    }

    /// The next line without its line end (`\n` and the `\r`s before it).
    fn next_line(&mut self) -> Option<&'a [u8]> {
        let b = self.bytes;
        let start = self.pos;
        if start > b.len() {
            return None;
        }
        let end = find_newline(b, start);
        self.pos = end + 1;
        self.line += 1;
        let mut line = &b[start..end];
        while let [rest @ .., b'\r'] = line {
            line = rest;
        }
        Some(line)
    }

    /// The next pair; `Ok(None)` at the end (trailing blank lines are harmless).
    #[inline]
    pub(crate) fn next_pair(&mut self) -> Result<Option<Pair<'a>>, DxfError> {
        let b = self.bytes;
        if let Some((code, value_start)) = plain_code_line(b, self.pos) {
            // the value line: `value_start` is at most the length, so there is one
            let end = find_newline(b, value_start);
            self.pos = end + 1;
            self.line += 2;
            let mut value = &b[value_start..end];
            while let [rest @ .., b'\r'] = value {
                value = rest;
            }
            return Ok(Some(Pair {
                code,
                value,
                line: self.line - 1,
            }));
        }
        self.general_pair()
    }

    /// [`Tokens::next_pair`] for any code line (white space, signs, blank lines, the end).
    #[cold]
    fn general_pair(&mut self) -> Result<Option<Pair<'a>>, DxfError> {
        let Some(code_line) = self.next_line() else {
            return Ok(None);
        };
        let line = self.line;
        let code = match plain_group_code(code_line) {
            Some(code) => code,
            None => {
                let text = String::from_utf8_lossy(code_line);
                let code = text.trim();
                if code.is_empty() {
                    let rest = self.bytes.get(self.pos..).unwrap_or_default();
                    if rest.iter().all(u8::is_ascii_whitespace) {
                        self.pos = self.bytes.len() + 1;
                        return Ok(None);
                    }
                    return Err(DxfError {
                        line,
                        kind: DxfErrorKind::BadGroupCode(String::new()),
                    });
                }
                code.parse().map_err(|_| DxfError {
                    line,
                    kind: DxfErrorKind::BadGroupCode(code.chars().take(40).collect()),
                })?
            }
        };
        let Some(value) = self.next_line() else {
            return Err(DxfError {
                line,
                kind: DxfErrorKind::Truncated,
            });
        };
        Ok(Some(Pair { code, value, line }))
    }
}

/// The value as text without surrounding white space (`str::trim` of the decoded line):
/// borrowed from the file for the usual ASCII values.
pub(crate) fn raw_str(v: &[u8]) -> Cow<'_, str> {
    // the ASCII characters of `char::is_whitespace` (note `\x0B`, unlike `u8::is_ascii_whitespace`)
    let ws = |c: &u8| matches!(c, b' ' | b'\t' | b'\n' | b'\x0B' | b'\x0C' | b'\r');
    let start = v.iter().position(|c| !ws(c)).unwrap_or(v.len());
    let end = v.iter().rposition(|c| !ws(c)).map_or(start, |i| i + 1);
    let t = &v[start..end];
    match (t.first(), t.last()) {
        (None, _) => return Cow::Borrowed(""),
        // other Unicode white space may be at the ends, or invalid UTF-8 in the middle
        (Some(&a), Some(&z)) if a < 0x80 && z < 0x80 => {
            if let Ok(s) = std::str::from_utf8(t) {
                return Cow::Borrowed(s);
            }
        }
        _ => {}
    }
    match String::from_utf8_lossy(v) {
        Cow::Borrowed(s) => Cow::Borrowed(s.trim()),
        Cow::Owned(s) => Cow::Owned(s.trim().to_string()),
    }
}

/// [`raw_str`] as bytes, to compare with ASCII names (`LINE`, `$ACADVER`): borrowed from the
/// file unless non-ASCII bytes end it (other Unicode white space may be trimmed there).
pub(crate) fn raw_name(v: &[u8]) -> Cow<'_, [u8]> {
    let ws = |c: &u8| matches!(c, b' ' | b'\t' | b'\n' | b'\x0B' | b'\x0C' | b'\r');
    let start = v.iter().position(|c| !ws(c)).unwrap_or(v.len());
    let end = v.iter().rposition(|c| !ws(c)).map_or(start, |i| i + 1);
    let t = &v[start..end];
    match (t.first(), t.last()) {
        (Some(&a), Some(&z)) if a >= 0x80 || z >= 0x80 => {
            Cow::Owned(raw_str(v).into_owned().into_bytes())
        }
        // invalid UTF-8 inside: not an ASCII name either way
        _ => Cow::Borrowed(t),
    }
}

/// Structure markers (`0`/`SECTION`, …) are compared without ASCII white space only.
pub(crate) fn is(p: &Pair, code: i32, value: &str) -> bool {
    p.code == code && p.value.trim_ascii() == value.as_bytes()
}

fn bad_number(p: &Pair, s: &str) -> DxfError {
    DxfError {
        line: p.line + 1,
        kind: DxfErrorKind::BadNumber {
            code: p.code,
            value: s.chars().take(40).collect(),
        },
    }
}

/// Plain decimals (`-12.375`: a sign, at most 15 digits with a point between two of them) as
/// `str::parse` reads them: the digits and the power of ten are both exact doubles, so the one
/// division rounds once, correctly (Clinger's fast path). `None` for anything else.
fn plain_decimal(v: &[u8]) -> Option<f64> {
    const POW10: [f64; 16] = [
        1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
    ];
    let v = v.trim_ascii();
    let (neg, body) = match v {
        [b'-', rest @ ..] => (true, rest),
        _ => (false, v),
    };
    let (mut m, mut digits, mut point) = (0u64, 0usize, None);
    for &c in body {
        match c {
            b'0'..=b'9' if digits < 15 => {
                m = m * 10 + u64::from(c - b'0');
                digits += 1;
            }
            b'.' if point.is_none() && digits > 0 => point = Some(digits),
            _ => return None,
        }
    }
    let frac = digits - point.unwrap_or(digits);
    if digits == 0 || point == Some(digits) {
        return None;
    }
    let x = m as f64 / POW10[frac];
    Some(if neg { -x } else { x })
}

pub(crate) fn num(p: &Pair) -> Result<f64, DxfError> {
    if let Some(x) = plain_decimal(p.value) {
        return Ok(x);
    }
    let s = raw_str(p.value);
    s.parse::<f64>().map_err(|_| bad_number(p, &s))
}

pub(crate) fn int(p: &Pair) -> Result<i32, DxfError> {
    let s = raw_str(p.value);
    s.parse::<i32>()
        .or_else(|_| s.parse::<f64>().map(|f| f as i32))
        .map_err(|_| bad_number(p, &s))
}
