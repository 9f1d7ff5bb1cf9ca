//! The group-code reader: bytes → text → (code, value, line) pairs → sections → [`Drawing`].
//!
//! The file is turned into text once ([`String::from_utf8_lossy`]: borrowed when the file is
//! valid UTF-8, which every ASCII file is). The pairs borrow their values from it; only the
//! values that end up in the [`Drawing`] are copied. Those strings are decoded with the file's
//! code page from their own bytes, value by value: the code page is only known after the
//! header, and decoding a value on its own is what fixes the behaviour at the edges (byte
//! order marks at the start of a value, multi-byte sequences cut by the end of a line).

use crate::decode::{decode_unicode_escapes_into, encoding_for, FileText};
use crate::{Drawing, DxfError, DxfErrorKind, Entity, EntityKind, MText, Point3, Text};
use encoding_rs::Encoding;

pub(crate) struct Pair<'a> {
    pub(crate) code: i32,
    /// The value line (end of line removed), a part of the file's text.
    pub(crate) value: &'a str,
    /// 1-based line of the group code.
    pub(crate) line: usize,
}

/// The lines of a text without their line ends (`\n` and the `\r`s before it), as
/// `text.as_bytes().split(|&b| b == b'\n')` gives them.
struct Lines<'a> {
    text: &'a str,
    /// Start of the next line; past the end of `text` after the last line.
    pos: usize,
}

impl<'a> Lines<'a> {
    /// What follows the current line (empty after the last one).
    fn rest(&self) -> &'a str {
        self.text.get(self.pos..).unwrap_or("")
    }
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

impl<'a> Iterator for Lines<'a> {
    type Item = &'a str;

    fn next(&mut self) -> Option<&'a str> {
        let b = self.text.as_bytes();
        let start = self.pos;
        if start > b.len() {
            return None;
        }
        let mut end = find_newline(b, start);
        self.pos = end + 1;
        while end > start && b[end - 1] == b'\r' {
            end -= 1;
        }
        Some(&self.text[start..end])
    }
}

/// `s.trim()`, quicker for ASCII ends.
fn trim(s: &str) -> &str {
    // the ASCII characters of `char::is_whitespace` (note `\x0B`, unlike `u8::is_ascii_whitespace`)
    let ws = |c: u8| matches!(c, b' ' | b'\t' | b'\n' | b'\x0B' | b'\x0C' | b'\r');
    let b = s.as_bytes();
    let mut i = 0;
    while i < b.len() && ws(b[i]) {
        i += 1;
    }
    let mut j = b.len();
    while j > i && ws(b[j - 1]) {
        j -= 1;
    }
    if i < j && (b[i] >= 0x80 || b[j - 1] >= 0x80) {
        // other Unicode white space may follow
        return s.trim();
    }
    &s[i..j]
}

/// The usual group code lines (`  0`, ` 10`, `100`): spaces, at most nine digits, spaces.
/// `None` for anything else, which then goes the general way.
fn plain_group_code(s: &str) -> Option<i32> {
    let b = s.as_bytes();
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

fn split_pairs(text: &str) -> Result<Vec<Pair<'_>>, DxfError> {
    let mut lines = Lines { text, pos: 0 };
    // a pair takes about ten bytes of a file
    let mut pairs = Vec::with_capacity(text.len() / 8);
    let mut line_no = 0usize;
    while let Some(code_line) = lines.next() {
        line_no += 1;
        let code = match plain_group_code(code_line) {
            Some(code) => code,
            None => {
                let code_trim = trim(code_line);
                if code_trim.is_empty() {
                    // trailing empty lines at the end of the file are harmless
                    if lines.rest().bytes().all(|b| b.is_ascii_whitespace()) {
                        break;
                    }
                    return Err(DxfError {
                        line: line_no,
                        kind: DxfErrorKind::BadGroupCode(String::new()),
                    });
                }
                code_trim.parse().map_err(|_| DxfError {
                    line: line_no,
                    kind: DxfErrorKind::BadGroupCode(code_trim.chars().take(40).collect()),
                })?
            }
        };
        let Some(value) = lines.next() else {
            return Err(DxfError {
                line: line_no,
                kind: DxfErrorKind::Truncated,
            });
        };
        pairs.push(Pair {
            code,
            value,
            line: line_no,
        });
        line_no += 1;
    }
    Ok(pairs)
}

pub(crate) struct Ctx<'t> {
    enc: &'static Encoding,
    src: &'t FileText<'t>,
}

impl Ctx<'_> {
    /// A kept string value: decoded with the file's code page, then `\U+XXXX` escapes.
    pub(crate) fn text(&self, p: &Pair) -> String {
        let mut out = String::new();
        self.push_text(p, &mut out);
        out
    }

    fn push_text(&self, p: &Pair, out: &mut String) {
        let (s, _, _) = self.enc.decode(self.src.raw(p.value));
        decode_unicode_escapes_into(&s, out);
    }
}

/// The value as written, without surrounding white space.
pub(crate) fn raw_str<'a>(p: &Pair<'a>) -> &'a str {
    trim(p.value)
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

pub(crate) fn num(p: &Pair) -> Result<f64, DxfError> {
    let s = raw_str(p);
    s.parse::<f64>().map_err(|_| bad_number(p, s))
}

pub(crate) fn int(p: &Pair) -> Result<i32, DxfError> {
    let s = raw_str(p);
    s.parse::<i32>()
        .or_else(|_| s.parse::<f64>().map(|f| f as i32))
        .map_err(|_| bad_number(p, s))
}

/// Structure markers (`0`/`SECTION`, …) are compared without ASCII white space only.
fn is(p: &Pair, code: i32, value: &str) -> bool {
    p.code == code && p.value.trim_ascii() == value
}

/// Reads a DXF file (ASCII, R12 to current versions).
pub fn read_dxf(bytes: &[u8]) -> Result<Drawing, DxfError> {
    if bytes.starts_with(b"AutoCAD Binary DXF") {
        return Err(DxfError {
            line: 0,
            kind: DxfErrorKind::Binary,
        });
    }
    // The one decoding of the whole file; borrowed unless it has invalid UTF-8.
    let src = FileText::new(bytes);
    let pairs = split_pairs(&src.text)?;
    // Sections: (name, first pair index after the name, index of ENDSEC).
    let mut sections: Vec<(&str, usize, usize)> = Vec::new();
    let mut i = 0;
    while i < pairs.len() {
        if is(&pairs[i], 0, "SECTION") {
            let name = pairs
                .get(i + 1)
                .filter(|p| p.code == 2)
                .map(raw_str)
                .unwrap_or_default();
            let start = i + 2;
            let mut j = start;
            while j < pairs.len() && !is(&pairs[j], 0, "ENDSEC") {
                if is(&pairs[j], 0, "SECTION") || is(&pairs[j], 0, "EOF") {
                    break;
                }
                j += 1;
            }
            if j >= pairs.len() || !is(&pairs[j], 0, "ENDSEC") {
                let line = pairs.get(j).or(pairs.last()).map_or(0, |p| p.line);
                return Err(DxfError {
                    line,
                    kind: DxfErrorKind::Truncated,
                });
            }
            sections.push((name, start, j));
            i = j + 1;
        } else if is(&pairs[i], 0, "EOF") {
            break;
        } else {
            i += 1;
        }
    }
    if sections.is_empty() {
        return Err(DxfError {
            line: pairs.first().map_or(1, |p| p.line),
            kind: DxfErrorKind::NotDxf,
        });
    }

    let mut drawing = Drawing {
        text_size: 2.5,
        ..Default::default()
    };
    // Header first: it decides the string decoding.
    for (name, s, e) in &sections {
        if *name == "HEADER" {
            read_header(&pairs[*s..*e], &mut drawing)?;
        }
    }
    let ctx = Ctx {
        enc: encoding_for(&drawing.version, &drawing.codepage),
        src: &src,
    };
    for (name, s, e) in &sections {
        match *name {
            "TABLES" => read_tables(&ctx, &pairs[*s..*e], &mut drawing),
            "ENTITIES" => read_entities(&ctx, &pairs[*s..*e], &mut drawing)?,
            "BLOCKS" => crate::blocks::read_blocks(&ctx, &pairs[*s..*e], &mut drawing),
            _ => {}
        }
    }
    Ok(drawing)
}

fn read_header(pairs: &[Pair], d: &mut Drawing) -> Result<(), DxfError> {
    let mut var = "";
    for p in pairs {
        match p.code {
            9 => var = raw_str(p),
            1 if var == "$ACADVER" => d.version = raw_str(p).to_string(),
            3 if var == "$DWGCODEPAGE" => d.codepage = raw_str(p).to_string(),
            40 if var == "$TEXTSIZE" => d.text_size = num(p)?,
            // ignored by the reference: a malformed value must not cost it the file
            70 if var == "$INSUNITS" => d.insunits = int(p).ok(),
            _ => {}
        }
    }
    Ok(())
}

/// Splits a section body into records, each starting at a `0` group.
pub(crate) fn records<'p, 'a>(pairs: &'p [Pair<'a>]) -> impl Iterator<Item = &'p [Pair<'a>]> {
    let mut i = 0;
    std::iter::from_fn(move || {
        while i < pairs.len() && pairs[i].code != 0 {
            i += 1;
        }
        if i >= pairs.len() {
            return None;
        }
        let start = i;
        i += 1;
        while i < pairs.len() && pairs[i].code != 0 {
            i += 1;
        }
        Some(&pairs[start..i])
    })
}

fn read_tables(ctx: &Ctx, pairs: &[Pair], d: &mut Drawing) {
    for rec in records(pairs) {
        match raw_str(&rec[0]) {
            "LTYPE" => {
                if let Some(p) = rec.iter().find(|p| p.code == 2) {
                    d.linetypes.push(ctx.text(p));
                }
            }
            "LAYER" => {
                let name = rec.iter().find(|p| p.code == 2).map(|p| ctx.text(p));
                let lt = rec.iter().find(|p| p.code == 6).map(|p| ctx.text(p));
                if let Some(name) = name {
                    d.layers
                        .insert(name, lt.unwrap_or_else(|| "Continuous".to_string()));
                }
            }
            _ => {}
        }
    }
}

fn read_entities(ctx: &Ctx, pairs: &[Pair], d: &mut Drawing) -> Result<(), DxfError> {
    let mut extra = crate::extra::ExtraReader::default();
    for rec in records(pairs) {
        let kind = raw_str(&rec[0]);
        // polylines, inserts, ellipses, splines: kept for the extended mode, ignored here
        if extra.take(ctx, kind, rec, &mut d.extra, &mut d.extra_errors) {
            d.ignored_entities += usize::from(!matches!(kind, "VERTEX" | "SEQEND" | "ATTRIB"));
            continue;
        }
        if !matches!(kind, "LINE" | "ARC" | "CIRCLE" | "TEXT" | "MTEXT") {
            if !matches!(kind, "VERTEX" | "SEQEND" | "ATTRIB") {
                d.ignored_entities += 1;
            }
            continue;
        }
        if let Some(e) = read_entity(ctx, kind, rec)? {
            d.entities.push(e);
        }
    }
    extra.finish(&mut d.extra);
    Ok(())
}

fn set(pt: &mut Point3, axis: usize, p: &Pair) -> Result<(), DxfError> {
    pt[axis] = num(p)?;
    Ok(())
}

pub(crate) fn read_entity(ctx: &Ctx, kind: &str, rec: &[Pair]) -> Result<Option<Entity>, DxfError> {
    // String groups: the last one counts; copied once at the end.
    let mut handle: Option<&Pair> = None;
    let mut layer: Option<&Pair> = None;
    let mut linetype: Option<&Pair> = None;
    let mut text_1: Option<&Pair> = None;
    let mut linetype_scale = 1.0;
    let mut extrusion = [0.0, 0.0, 1.0];
    let mut p10 = [0.0; 3];
    let mut p11 = [0.0; 3];
    let mut has11 = false;
    let mut r40 = 0.0;
    let mut a50: Option<f64> = None;
    let mut a51 = 0.0;
    let (mut i71, mut i72, mut i73): (Option<i32>, i32, i32) = (None, 0, 0);
    let mut text = String::new();
    let mut paper_space = false;
    for p in &rec[1..] {
        match p.code {
            5 => handle = Some(p),
            8 => layer = Some(p),
            6 => linetype = Some(p),
            48 => linetype_scale = num(p)?,
            67 => paper_space = int(p)? == 1,
            10 => set(&mut p10, 0, p)?,
            20 => set(&mut p10, 1, p)?,
            30 => set(&mut p10, 2, p)?,
            11 => {
                has11 = true;
                set(&mut p11, 0, p)?
            }
            21 => set(&mut p11, 1, p)?,
            31 => set(&mut p11, 2, p)?,
            210 => set(&mut extrusion, 0, p)?,
            220 => set(&mut extrusion, 1, p)?,
            230 => set(&mut extrusion, 2, p)?,
            40 => r40 = num(p)?,
            50 => a50 = Some(num(p)?),
            51 => a51 = num(p)?,
            71 => i71 = Some(int(p)?),
            72 => i72 = int(p)?,
            73 => i73 = int(p)?,
            1 | 3 if kind == "MTEXT" => ctx.push_text(p, &mut text),
            1 if kind == "TEXT" => text_1 = Some(p),
            _ => {}
        }
    }
    if paper_space {
        return Ok(None);
    }
    if let Some(p) = text_1 {
        text = ctx.text(p);
    }
    let kind = match kind {
        "LINE" => EntityKind::Line {
            start: p10,
            end: p11,
        },
        "CIRCLE" => EntityKind::Circle {
            center: p10,
            radius: r40,
        },
        "ARC" => EntityKind::Arc {
            center: p10,
            radius: r40,
            start_angle: a50.unwrap_or(0.0),
            end_angle: a51,
        },
        "TEXT" => EntityKind::Text(Text {
            value: text,
            first: p10,
            second: has11.then_some(p11),
            height: r40,
            rotation: a50.unwrap_or(0.0),
            generation: i71.unwrap_or(0),
            halign: i72,
            valign: i73,
        }),
        _ => EntityKind::MText(MText {
            value: text,
            insert: p10,
            height: r40,
            attachment: i71.unwrap_or(1),
            rotation: a50,
            direction: has11.then_some(p11),
        }),
    };
    Ok(Some(Entity {
        line: rec[0].line,
        handle: handle.map_or_else(String::new, |p| raw_str(p).to_string()),
        layer: layer.map_or_else(|| "0".to_string(), |p| ctx.text(p)),
        linetype: linetype.map(|p| ctx.text(p)),
        linetype_scale,
        extrusion,
        kind,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dxf(body: &str) -> String {
        format!(
            "  0\nSECTION\n  2\nHEADER\n  9\n$ACADVER\n  1\nAC1015\n  9\n$DWGCODEPAGE\n  3\nANSI_1252\n  0\nENDSEC\n  0\nSECTION\n  2\nTABLES\n  0\nTABLE\n  2\nLAYER\n  0\nLAYER\n  2\nP1\n  6\nDASHED\n  0\nENDTAB\n  0\nENDSEC\n  0\nSECTION\n  2\nENTITIES\n{body}  0\nENDSEC\n  0\nEOF\n"
        )
    }

    #[test]
    fn reads_entities_with_line_numbers() {
        let src = dxf("  0\nLINE\n  5\nA1\n  8\nP1\n 10\n1.5\n 20\n2\n 30\n0\n 11\n3\n 21\n4\n 31\n0\n  0\nPOINT\n  8\nP1\n  0\nMTEXT\n  8\nP1\n  3\nAB\n  1\nC\\PD\n 71\n7\n");
        let d = read_dxf(src.as_bytes()).unwrap();
        assert_eq!(d.version, "AC1015");
        assert_eq!(d.layers.get("P1").map(String::as_str), Some("DASHED"));
        assert_eq!(d.entities.len(), 2);
        assert_eq!(d.ignored_entities, 1);
        let e = &d.entities[0];
        assert_eq!(e.handle, "A1");
        assert_eq!(
            e.kind,
            EntityKind::Line {
                start: [1.5, 2.0, 0.0],
                end: [3.0, 4.0, 0.0]
            }
        );
        assert_eq!(src.lines().nth(e.line - 1).unwrap().trim(), "0");
        assert_eq!(src.lines().nth(e.line).unwrap(), "LINE");
        match &d.entities[1].kind {
            EntityKind::MText(m) => {
                assert_eq!(m.value, "ABC\\PD");
                assert_eq!(m.attachment, 7);
            }
            k => panic!("unexpected {k:?}"),
        }
    }

    #[test]
    fn code_page_1252_is_decoded() {
        let mut bytes = dxf("  0\nTEXT\n  8\nP1\n  1\nGr\u{1}n\n").into_bytes();
        let pos = bytes.iter().position(|&b| b == 1).unwrap();
        bytes[pos] = 0xFC; // ü in windows-1252
        let d = read_dxf(&bytes).unwrap();
        match &d.entities[0].kind {
            EntityKind::Text(t) => assert_eq!(t.value, "Grün"),
            k => panic!("unexpected {k:?}"),
        }
    }

    #[test]
    fn truncated_and_malformed_files_report_lines() {
        let src = dxf("  0\nLINE\n  8\nP1\n 10\n1.5\n");
        let cut = &src[..src.find(" 10\n1.5").unwrap() + 4];
        let err = read_dxf(cut.as_bytes()).unwrap_err();
        assert_eq!(err.kind, DxfErrorKind::Truncated);
        assert!(err.line > 20);
        let bad = dxf("  0\nLINE\n  8\nP1\n 10\nabc\n");
        let err = read_dxf(bad.as_bytes()).unwrap_err();
        assert!(
            matches!(err.kind, DxfErrorKind::BadNumber { code: 10, .. }),
            "{err:?}"
        );
        assert_eq!(bad.lines().nth(err.line - 1), Some("abc"));
        let err = read_dxf(b"hello\nworld\n").unwrap_err();
        assert!(matches!(err.kind, DxfErrorKind::BadGroupCode(_)));
        assert!(read_dxf(b"").is_err());
        assert_eq!(
            read_dxf(b"AutoCAD Binary DXF\r\n\x1a\0").unwrap_err().kind,
            DxfErrorKind::Binary
        );
    }

    #[test]
    fn r12_files_without_handles_or_subclasses() {
        let src = "  0\nSECTION\n  2\nHEADER\n  9\n$ACADVER\n  1\nAC1009\n  0\nENDSEC\n  0\nSECTION\n  2\nTABLES\n  0\nTABLE\n  2\nLAYER\n  0\nLAYER\n  2\n1000_1P\n 70\n0\n 62\n7\n  6\nCONTINUOUS\n  0\nENDTAB\n  0\nENDSEC\n  0\nSECTION\n  2\nBLOCKS\n  0\nBLOCK\n  8\n0\n  0\nLINE\n  8\n1000_1P\n 10\n5\n 20\n5\n 11\n6\n 21\n6\n  0\nENDBLK\n  0\nENDSEC\n  0\nSECTION\n  2\nENTITIES\n  0\nCIRCLE\n  8\n1000_1P\n  6\nPHANTOM\n 10\n1.0\n 20\n2.0\n 30\n0.0\n 40\n0.5\n  0\nARC\n  8\n1000_1P\n 10\n0\n 20\n0\n 40\n3\n 50\n0\n 51\n90\n  0\nENDSEC\n  0\nEOF\n";
        let d = read_dxf(src.as_bytes()).unwrap();
        assert_eq!(d.version, "AC1009");
        // entities of blocks are not model space
        assert_eq!(d.entities.len(), 2);
        assert_eq!(d.entities[0].handle, "");
        assert_eq!(
            d.entities[0].kind,
            EntityKind::Circle {
                center: [1.0, 2.0, 0.0],
                radius: 0.5
            }
        );
        assert_eq!(
            d.entities[1].kind,
            EntityKind::Arc {
                center: [0.0, 0.0, 0.0],
                radius: 3.0,
                start_angle: 0.0,
                end_angle: 90.0
            }
        );
    }

    fn dxf_bytes(ver: &str, cp: &[u8], layer: &[u8], body: &[u8]) -> Vec<u8> {
        let mut v = format!(
            "  0\nSECTION\n  2\nHEADER\n  9\n$ACADVER\n  1\n{ver}\n  9\n$DWGCODEPAGE\n  3\n"
        )
        .into_bytes();
        v.extend_from_slice(cp);
        v.extend_from_slice(
            b"\n  0\nENDSEC\n  0\nSECTION\n  2\nTABLES\n  0\nTABLE\n  2\nLAYER\n  0\nLAYER\n  2\n",
        );
        v.extend_from_slice(layer);
        v.extend_from_slice(
            b"\n  6\nDASHED\n  0\nENDTAB\n  0\nENDSEC\n  0\nSECTION\n  2\nENTITIES\n",
        );
        v.extend_from_slice(body);
        v.extend_from_slice(b"  0\nENDSEC\n  0\nEOF\n");
        v
    }

    fn one_entity(bytes: &[u8]) -> (Drawing, Entity) {
        let d = read_dxf(bytes).unwrap();
        assert_eq!(d.entities.len(), 1);
        let e = d.entities[0].clone();
        (d, e)
    }

    /// Corners of the text handling, as the first (allocating) reader had them.
    #[test]
    fn invalid_utf8_white_space_and_byte_order_marks() {
        // windows-1252 bytes: decoded in kept strings, U+FFFD in raw ones (handles)
        let (d, e) = one_entity(&dxf_bytes(
            "AC1015",
            b"ANSI_1252",
            b"SCHL\xdcSSEL",
            b"  0\nTEXT\n  5\nA\xfc\n  8\nSCHL\xdcSSEL\n  1\nGr\xfcn \\U+00E4x\n",
        ));
        assert_eq!(
            d.layers.get("SCHLÜSSEL").map(String::as_str),
            Some("DASHED")
        );
        assert_eq!(
            (e.handle.as_str(), e.layer.as_str()),
            ("A\u{FFFD}", "SCHLÜSSEL")
        );
        match e.kind {
            EntityKind::Text(t) => assert_eq!(t.value, "Grün äx"),
            k => panic!("unexpected {k:?}"),
        }
        // a number with an invalid byte
        let err = read_dxf(&dxf_bytes(
            "AC1015",
            b"ANSI_1252",
            b"P1",
            b"  0\nLINE\n  8\nP1\n 10\n 1.\xfc5 \n",
        ))
        .unwrap_err();
        assert_eq!(
            err.to_string(),
            "line 42: value '1.\u{FFFD}5' of group 10 is not a number"
        );
        // Unicode white space around codes and raw values, not around decoded strings;
        // codes with a sign, leading zeros or more than nine digits
        let (d, e) = one_entity(&dxf_bytes(
            "AC1024",
            b"ANSI_1252",
            b"\xc2\xa0P1",
            b"  0\nLINE\n  5\n\xc2\xa0A1\xe2\x80\x83\n\xc2\xa0 8\n\xc2\xa0P1\n+10\n1\n\x0b20\n2\n0000000011\n3\n",
        ));
        assert!(d.layers.contains_key("\u{a0}P1"));
        assert_eq!((e.handle.as_str(), e.layer.as_str()), ("A1", "\u{a0}P1"));
        assert_eq!(
            e.kind,
            EntityKind::Line {
                start: [1.0, 2.0, 0.0],
                end: [3.0, 0.0, 0.0]
            }
        );
        // a UTF-8 byte order mark starting a decoded string is dropped (encoding_rs)
        let d = read_dxf(&dxf_bytes(
            "AC1024",
            b"ANSI_1252",
            b"\xef\xbb\xbfP1",
            b"  0\nCIRCLE\n  8\n\xef\xbb\xbfP1\n 40\n\xc2\xa02.5\xc2\xa0\n",
        ))
        .unwrap();
        assert!(d.layers.contains_key("P1"));
        assert_eq!(d.entities[0].layer, "P1");
        // windows-1251, an escape split over MTEXT groups stays as it is
        let (d, e) = one_entity(&dxf_bytes(
            "AC1015",
            b"ANSI_1251",
            b"\xcf1",
            b"  0\nMTEXT\n  8\n\xcf1\n  3\n\xe0\\U+00\n  1\nE4\xe0b\n 71\n2.7\n",
        ));
        assert!(d.layers.contains_key("П1"));
        match e.kind {
            EntityKind::MText(m) => {
                assert_eq!(m.value, "а\\U+00E4аb");
                assert_eq!(m.attachment, 2);
            }
            k => panic!("unexpected {k:?}"),
        }
        // CR LF and extra CRs; integers from floats
        let (_, e) = one_entity(&dxf_bytes(
            "AC1015",
            b"ANSI_1252",
            b"P1",
            b"  0\r\nARC\r\n  8\r\nP1\r\r\n 40\r\n1e1\r\n 50\r\n-0\r\n 51\r\ninf\r\n",
        ));
        assert_eq!(e.layer, "P1");
        assert!(
            matches!(e.kind, EntityKind::Arc { radius: 10.0, end_angle, .. } if end_angle.is_infinite())
        );
        let (_, e) = one_entity(&dxf_bytes(
            "AC1015",
            b"ANSI_1252",
            b"P1",
            b"  0\nTEXT\n 71\n 4.9 \n 72\n-3e9\n 73\nnan\n",
        ));
        match e.kind {
            EntityKind::Text(t) => assert_eq!((t.generation, t.halign, t.valign), (4, i32::MIN, 0)),
            k => panic!("unexpected {k:?}"),
        }
    }

    #[test]
    fn group_code_lines_and_trailing_lines() {
        let with = |body: &[u8], tail: &[u8]| {
            let mut v = dxf_bytes("AC1015", b"ANSI_1252", b"P1", body);
            v.extend_from_slice(tail);
            read_dxf(&v)
        };
        let err = |r: Result<Drawing, DxfError>| r.unwrap_err().to_string();
        assert!(with(b"", b"\n \t\r\n\x0c\n").is_ok());
        // vertical tab: white space to `str::trim`, not to the trailing-lines check
        assert_eq!(
            err(with(b"", b"\n\x0b\n")),
            "line 41: '' is not a group code"
        );
        assert_eq!(
            err(with(b"  0\nLINE\n\xc2\xa0\n5\n", b"")),
            "line 39: '' is not a group code"
        );
        assert_eq!(
            err(with(b"  0\nLINE\n1\xfc0\n5\n", b"")),
            "line 39: '1\u{FFFD}0' is not a group code"
        );
        assert_eq!(
            err(with(b"1234567890\nx\n  0\nLINE\n99999999999\nx\n", b"")),
            "line 41: '99999999999' is not a group code"
        );
        assert_eq!(
            err(read_dxf(
                b"  0\nSECTION\n  2\nENTITIES\n  0\nLINE\n  0\nSECTION\n"
            )),
            "line 7: file ends in the middle of a group"
        );
        assert_eq!(
            err(read_dxf(b"  0\nSECTION\n  2\nENTITIES\n  0")),
            "line 5: file ends in the middle of a group"
        );
        assert_eq!(
            err(read_dxf(b"  0\nEOF\n")),
            "line 1: not a DXF file (no SECTION found)"
        );
    }

    #[test]
    fn paper_space_entities_are_skipped() {
        let d =
            read_dxf(dxf("  0\nLINE\n  8\nP1\n 67\n1\n  0\nCIRCLE\n  8\nP1\n 40\n2\n").as_bytes())
                .unwrap();
        assert_eq!(d.entities.len(), 1);
        assert_eq!(d.entities[0].kind.code_name(), "CIRCLE");
    }
}
