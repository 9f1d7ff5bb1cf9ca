//! The group-code tokenizer: the file's bytes → (code, value, line) pairs, one pass, no copy.
//!
//! Values stay bytes of the file; the few helpers here turn them into text exactly as if the
//! whole file had been decoded with [`String::from_utf8_lossy`] first (an invalid sequence
//! never spans a line end, so a line decoded on its own is the same line of the decoded file).
//!
//! The group-code tokenizer over the file's bytes (no decoded copy of the file): (code, value
//! bytes, line) pairs, each pair cut from two line ends of `lines.rs` with the usual three-wide
//! code read in place (`quick_pair`: `  0` and `  0\r`, both line ends found by `quick_two`), every
//! other pair by `next_pair`, every other code line the general way; value helpers that read as the
//! lossy UTF-8 text of the file would (`raw_str`, names, numbers with exact fast paths for plain
//! decimals and integers).

use crate::lines::LineEnds;
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
#[derive(Clone, Copy)]
pub(crate) struct Tokens<'a> {
    /// The line ends, and the file's bytes (held once: the copies the section loops make
    /// then need fewer registers).
    ends: LineEnds<'a>,
    /// Start of the next line; past the end of `bytes` after the last line.
    pos: usize,
    /// Lines taken so far.
    line: usize,
}

/// The usual group code lines (`  0`, ` 10`, `100`): spaces, at most nine digits, spaces.
/// `None` for anything else, which then goes the general way.
#[inline(always)]
fn plain_group_code(b: &[u8]) -> Option<i32> {
    three_wide_code(b).or_else(|| plain_group_code_any_width(b))
}

/// [`plain_group_code`] of the lines most codes are written as: `  0`, ` 10`, `100`.
#[inline(always)]
fn three_wide_code(b: &[u8]) -> Option<i32> {
    if let [x, y, z] = *b {
        let digit = |c: u8| c.wrapping_sub(b'0');
        let (x, y, z) = (digit(x), digit(y), digit(z));
        const SPACE: u8 = b' '.wrapping_sub(b'0');
        if z < 10 {
            match (x, y) {
                (SPACE, SPACE) => return Some(i32::from(z)),
                (SPACE, 0..=9) => return Some(i32::from(y) * 10 + i32::from(z)),
                (0..=9, 0..=9) => {
                    return Some(i32::from(x) * 100 + i32::from(y) * 10 + i32::from(z))
                }
                _ => {}
            }
        }
    }
    None
}

/// [`three_wide_code`] of a line that ends with one `\r` (CR LF files).
#[inline(never)]
fn crlf_code(b: &[u8]) -> Option<i32> {
    match *b {
        [x, y, z, b'\r'] => three_wide_code(&[x, y, z]),
        _ => None,
    }
}

#[inline(never)]
fn plain_group_code_any_width(b: &[u8]) -> Option<i32> {
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
    if i == digits {
        return None;
    }
    while i < b.len() && b[i] == b' ' {
        i += 1;
    }
    (i == b.len()).then_some(v)
}

/// A line without the `\r`s before its end.
#[inline(always)]
fn without_cr(line: &[u8]) -> &[u8] {
    match line {
        [rest @ .., b'\r'] => {
            let mut line = rest;
            while let [rest @ .., b'\r'] = line {
                line = rest;
            }
            line
        }
        _ => line,
    }
}

impl<'a> Tokens<'a> {
    /// The line of the last pair taken (0 before the first).
    pub(crate) fn last_pair_line(&self) -> usize {
        self.line.saturating_sub(1)
    }

    /// Where the next pair starts (a byte offset into the file).
    pub(crate) fn pos(&self) -> usize {
        self.pos
    }

    pub(crate) fn new(bytes: &'a [u8]) -> Self {
        Tokens {
            ends: LineEnds::new(bytes),
            pos: 0,
            line: 0,
        }
    }

    /// The next pair; `Ok(None)` at the end (trailing blank lines are harmless). Inlined
    /// into each loop over the pairs: the reader spends most of its time here.
    #[inline(always)]
    pub(crate) fn next_pair(&mut self) -> Result<Option<Pair<'a>>, DxfError> {
        let Some((code_end, value_end)) = self.ends.next_two() else {
            // the last line, without a line end
            return self.pair_by_lines();
        };
        let b = self.ends.bytes();
        // every line is taken in order, so `pos` ≤ `code_end` < `value_end` ≤ the length
        // (the value line may be the last one, without a line end)
        let code_line = &b[self.pos..code_end];
        let value = without_cr(&b[code_end + 1..value_end]);
        let line = self.line + 1;
        self.line += 2;
        self.pos = value_end + 1;
        // a three wide code line has no `\r` to strip when it is a code
        let code = match three_wide_code(code_line) {
            Some(code) => code,
            None => match plain_group_code(without_cr(code_line)) {
                Some(code) => code,
                None => match self.general_code(without_cr(code_line), line, code_end + 1)? {
                    Some(code) => code,
                    None => return Ok(None),
                },
            },
        };
        Ok(Some(Pair { code, value, line }))
    }

    /// The next pair when it is the usual kind (a three wide code, both line ends found by
    /// [`LineEnds::quick_two`]); `None`, nothing taken, when [`Tokens::next_pair`] must take
    /// it. The section loops call it on a copy of the tokens, which then lives in registers.
    #[inline(always)]
    pub(crate) fn quick_pair(&mut self) -> Option<Pair<'a>> {
        let mut ends = self.ends;
        let (code_end, value_end) = ends.quick_two()?;
        let b = self.ends.bytes();
        let code_line = &b[self.pos..code_end];
        let code = match three_wide_code(code_line) {
            Some(code) => code,
            None => crlf_code(code_line)?,
        };
        let value = without_cr(&b[code_end + 1..value_end]);
        let line = self.line + 1;
        self.ends = ends;
        self.line += 2;
        self.pos = value_end + 1;
        Some(Pair { code, value, line })
    }

    /// [`Tokens::next_pair`] line by line, at the end of the file.
    #[inline(never)]
    fn pair_by_lines(&mut self) -> Result<Option<Pair<'a>>, DxfError> {
        let Some(code_line) = self.next_line() else {
            return Ok(None);
        };
        let line = self.line;
        let code = match plain_group_code(code_line) {
            Some(code) => code,
            None => match self.general_code(code_line, line, self.pos)? {
                Some(code) => code,
                None => return Ok(None),
            },
        };
        let Some(value) = self.next_line() else {
            return Err(DxfError {
                line,
                kind: DxfErrorKind::Truncated,
            });
        };
        Ok(Some(Pair { code, value, line }))
    }

    /// The next line without its line end (`\n` and the `\r`s before it).
    #[inline(always)]
    fn next_line(&mut self) -> Option<&'a [u8]> {
        let start = self.pos;
        if start > self.ends.bytes().len() {
            return None;
        }
        // every line is taken here or in `next_pair`, in order: the next line end is this
        // line's
        let end = self.ends.next_end();
        self.pos = end + 1;
        self.line += 1;
        Some(without_cr(
            self.ends.bytes().get(start..end).unwrap_or_default(),
        ))
    }

    /// The code of any other code line (white space, signs, leading zeros) at `line`;
    /// `None` for blank lines up to the end (`rest`: where the next line starts).
    #[cold]
    fn general_code(
        &mut self,
        code_line: &[u8],
        line: usize,
        rest: usize,
    ) -> Result<Option<i32>, DxfError> {
        let text = String::from_utf8_lossy(code_line);
        let code = text.trim();
        if code.is_empty() {
            let rest = self.ends.bytes().get(rest..).unwrap_or_default();
            if rest.iter().all(u8::is_ascii_whitespace) {
                // the end: the line ends of those blank lines are not lines of pairs
                self.pos = self.ends.bytes().len() + 1;
                self.ends.exhaust();
                return Ok(None);
            }
            return Err(DxfError {
                line,
                kind: DxfErrorKind::BadGroupCode(String::new()),
            });
        }
        code.parse().map(Some).map_err(|_| DxfError {
            line,
            kind: DxfErrorKind::BadGroupCode(code.chars().take(40).collect()),
        })
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
            // borrowed exactly when ASCII: quicker than `from_utf8` on short values
            if let Cow::Borrowed(s) = encoding_rs::mem::decode_latin1(t) {
                return Cow::Borrowed(s);
            }
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
#[inline(always)]
pub(crate) fn raw_name(v: &[u8]) -> Cow<'_, [u8]> {
    // the usual name: no white space (all of it is at most b' ') and ASCII at both ends
    match (v.first(), v.last()) {
        (Some(&a), Some(&z)) if (b'!'..0x80).contains(&a) && (b'!'..0x80).contains(&z) => {
            Cow::Borrowed(v)
        }
        _ => raw_name_trimmed(v),
    }
}

fn raw_name_trimmed(v: &[u8]) -> Cow<'_, [u8]> {
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
#[inline(always)]
fn plain_decimal(v: &[u8]) -> Option<f64> {
    const POW10: [f64; 16] = [
        1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
    ];
    // white space is at most b' ': most values have none to trim
    let v = match (v.first(), v.last()) {
        (Some(&a), Some(&z)) if a > b' ' && z > b' ' => v,
        _ => v.trim_ascii(),
    };
    let (neg, body) = match v {
        [b'-', rest @ ..] => (true, rest),
        _ => (false, v),
    };
    // fifteen digits and a point at most
    if body.len() > 16 {
        return None;
    }
    let digit = |c: u8| c.wrapping_sub(b'0');
    let (mut m, mut i) = (0u64, 0);
    while let Some(&c) = body.get(i).filter(|&&c| digit(c) < 10) {
        m = m * 10 + u64::from(digit(c));
        i += 1;
    }
    if i == 0 {
        return None;
    }
    let mut frac = 0;
    if i < body.len() {
        // a point, then at least one digit
        if body[i] != b'.' || i + 1 == body.len() {
            return None;
        }
        for &c in &body[i + 1..] {
            if digit(c) >= 10 {
                return None;
            }
            m = m * 10 + u64::from(digit(c));
        }
        frac = body.len() - i - 1;
    }
    if i + frac > 15 {
        return None;
    }
    let x = m as f64 / POW10[frac];
    Some(if neg { -x } else { x })
}

#[inline(always)]
pub(crate) fn num(p: &Pair) -> Result<f64, DxfError> {
    match plain_decimal(p.value) {
        Some(x) => Ok(x),
        None => any_num(p),
    }
}

#[inline(never)]
fn any_num(p: &Pair) -> Result<f64, DxfError> {
    let s = raw_str(p.value);
    s.parse::<f64>().map_err(|_| bad_number(p, &s))
}

/// Plain integers (`-12`: a sign, at most nine digits) as `str::parse::<i32>` reads them.
#[inline(always)]
fn plain_int(v: &[u8]) -> Option<i32> {
    // integers are often written right-aligned (`     7`)
    let v = v.trim_ascii();
    let (neg, body) = match v {
        [b'-', rest @ ..] => (true, rest),
        _ => (false, v),
    };
    if body.is_empty() || body.len() > 9 {
        return None;
    }
    let mut x = 0i32;
    for &c in body {
        let d = c.wrapping_sub(b'0');
        if d >= 10 {
            return None;
        }
        x = x * 10 + i32::from(d);
    }
    Some(if neg { -x } else { x })
}

pub(crate) fn int(p: &Pair) -> Result<i32, DxfError> {
    if let Some(x) = plain_int(p.value) {
        return Ok(x);
    }
    let s = raw_str(p.value);
    s.parse::<i32>()
        .or_else(|_| s.parse::<f64>().map(|f| f as i32))
        .map_err(|_| bad_number(p, &s))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_decimals_read_as_str_parse_reads_them() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let alphabet = b"0123456789.-+e \x0b";
        for i in 0..400_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let mut r = seed;
            let len = (seed % 19) as usize;
            let s: Vec<u8> = (0..len)
                .map(|_| {
                    r = r
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    // mostly digits
                    let k = (r >> 33) as usize;
                    if i % 2 == 0 || k & 3 != 0 {
                        b'0' + (k % 10) as u8
                    } else {
                        alphabet[k % alphabet.len()]
                    }
                })
                .collect();
            let text = std::str::from_utf8(&s).unwrap();
            let std = text.trim().parse::<f64>().ok();
            if let Some(x) = plain_decimal(&s) {
                assert_eq!(Some(x.to_bits()), std.map(f64::to_bits), "{text:?}");
            }
        }
        for t in [
            "0.1",
            "-0",
            "-0.0",
            "123456789012345",
            "0.00000000000001",
            "9.99999999999999",
        ] {
            assert_eq!(
                plain_decimal(t.as_bytes()).map(f64::to_bits),
                t.parse::<f64>().ok().map(f64::to_bits)
            );
        }
        for t in [
            "1.",
            ".5",
            "1234567890123456",
            "0.000000000000001",
            "1e5",
            "+1",
            "1.2.3",
            "-",
            "",
        ] {
            assert_eq!(plain_decimal(t.as_bytes()), None, "{t}");
        }
    }

    #[test]
    fn plain_ints_read_as_str_parse_reads_them() {
        for t in [
            "0",
            "-0",
            "7",
            "-12",
            "999999999",
            "-999999999",
            "1000000000",
            "+5",
            " 5",
            "5 ",
            "\t-3\r",
            "",
            "-",
            "--1",
            "1.0",
            "1e3",
            "12a",
            "\u{a0}3",
        ] {
            if let Some(x) = plain_int(t.as_bytes()) {
                assert_eq!(Ok(x), t.trim().parse::<i32>(), "{t:?}");
            }
        }
        assert_eq!(plain_int(b"1000000000"), None);
        assert_eq!(plain_int(b"     5 "), Some(5));
        assert_eq!(plain_int(b"\x0b5"), None);
    }

    /// The pairs and `raw_str` of every value match the lossy decoding of the whole file.
    #[test]
    fn values_match_the_lossy_text_of_the_file() {
        let pieces: &[&[u8]] = &[
            b"ab",
            b"\n",
            b"\r\n",
            b"\r",
            b"\xfc",
            b"\xc3\xbc",
            b"\xc3",
            b"\xe2\x82",
            b"\xe2\x82\xac",
            b"\xc2\xa0",
            b"\xe2\x80\x83",
            b"\x0b",
            b" ",
            b"\t",
            b"1",
        ];
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..50_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let mut r = seed;
            let mut bytes = Vec::new();
            for _ in 0..(seed % 12) {
                r = r
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                bytes.extend_from_slice(pieces[(r >> 33) as usize % pieces.len()]);
            }
            let text = String::from_utf8_lossy(&bytes);
            let lines: Vec<&str> = text.split('\n').map(|l| l.trim_end_matches('\r')).collect();
            let mut tokens = Tokens::new(&bytes);
            let mut n = 0;
            while let Ok(Some(p)) = tokens.next_pair() {
                assert_eq!(p.line, n + 1);
                assert_eq!(raw_str(p.value), lines[n + 1].trim(), "{bytes:?}");
                n += 2;
            }
        }
    }
}
