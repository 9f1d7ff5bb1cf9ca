//! The DXF structure, in one pass over the pairs of [`Tokens`]: sections, records, the header
//! variables, the LAYER and LTYPE tables and the model-space entities → [`Drawing`].
//!
//! The strings kept in the drawing are decoded with the file's code page, which is only known
//! once every header has been read: the pass notes them as bytes of the file ([`Kept`]) and
//! decodes them at the end, value by value (that fixes the behaviour at the edges: a byte
//! order mark starting a value, a multi-byte sequence cut by the end of a line).
//!
//! The errors are the ones of a reader that looks at the whole file before its contents: a
//! bad group code or a cut pair anywhere first, then an unterminated section, then a file
//! without sections, then the first bad header number, then the first bad entity number.
//!
//! The geometry the reference ignores (polylines, inserts, curves: `extra.rs`) and the BLOCKS
//! section (`blocks.rs`) are kept as pairs and read at the end, when the code page is known;
//! their errors never cost the file (`Drawing::extra_errors`).

use crate::decode::{decode_value_into, encoding_for};
use crate::entity::{records, Ctx, EntityRecord, Kind};
use crate::extra::ExtraReader;
use crate::tokens::{int, num, raw_name, raw_str, Pair, Tokens};
use crate::{Drawing, DxfError, DxfErrorKind, EntityKind, MText, Text};
use std::collections::BTreeMap;

/// What a section's contents are read as.
#[derive(Clone, Copy, PartialEq)]
enum Body {
    Header,
    Tables,
    Entities,
    Blocks,
    Other,
}

/// A string of the drawing, still the file's bytes.
enum Kept<'a> {
    Linetype(&'a [u8]),
    Layer {
        name: &'a [u8],
        linetype: Option<&'a [u8]>,
    },
    EntityLayer(usize, &'a [u8]),
    EntityLinetype(usize, &'a [u8]),
    /// A TEXT's group 1 or one of an MTEXT's groups 1 and 3 (appended in file order).
    EntityText(usize, &'a [u8]),
}

/// The header variables we read.
#[derive(Clone, Copy, PartialEq)]
enum HeaderVar {
    AcadVer,
    CodePage,
    TextSize,
    InsUnits,
    Other,
}

/// The record (a `0` group and the groups up to the next `0`) being read in a table.
#[derive(Clone, Copy, PartialEq)]
enum TableRecord {
    Skip,
    Ltype,
    Layer,
}

/// Everything the pass gathers.
struct Reader<'a> {
    d: Drawing,
    kept: Vec<Kept<'a>>,
    header_var: HeaderVar,
    table: TableRecord,
    table_name: Option<&'a [u8]>,
    table_linetype: Option<&'a [u8]>,
    /// The entity being read when `entity_open`: one record reused from entity to entity
    /// (it is large, and its MTEXT pieces buffer is kept).
    entity: EntityRecord<'a>,
    entity_open: bool,
    sections: usize,
    structure_error: Option<DxfError>,
    header_error: Option<DxfError>,
    entity_error: Option<DxfError>,
    /// The ENTITIES records of other kinds, in file order; of the five kinds above only the
    /// `0` group (it ends a pending POLYLINE).
    extra_pairs: Vec<Pair<'a>>,
    /// The BLOCKS section.
    block_pairs: Vec<Pair<'a>>,
    /// Whether the ENTITIES record being read goes to `extra_pairs`.
    in_extra: bool,
    /// Where the ENTITIES groups other than `0` go, from the three fields above: one test
    /// per group instead of three.
    route: Route,
}

/// See [`Reader::route`].
#[derive(Clone, Copy, PartialEq)]
enum Route {
    Entity,
    Extra,
    Nowhere,
}

/// Reads a DXF file (ASCII, R12 to current versions).
pub fn read_dxf(bytes: &[u8]) -> Result<Drawing, DxfError> {
    // a UTF-8 byte-order mark (an editor's save) is no part of the first group code;
    // UTF-16 (PowerShell 5's `>`) would need the code page before reading: refused by name
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    if let Some(big_endian) = match bytes {
        [0xFF, 0xFE, ..] => Some(false),
        [0xFE, 0xFF, ..] => Some(true),
        _ => None,
    } {
        return Err(DxfError {
            line: 0,
            kind: DxfErrorKind::Utf16 { big_endian },
        });
    }
    if bytes.starts_with(b"AutoCAD Binary DXF") {
        return Err(DxfError {
            line: 0,
            kind: DxfErrorKind::Binary,
        });
    }
    let mut r = Reader {
        d: Drawing {
            text_size: 2.5,
            ..Default::default()
        },
        kept: Vec::new(),
        header_var: HeaderVar::Other,
        table: TableRecord::Skip,
        table_name: None,
        table_linetype: None,
        entity: EntityRecord::new(Kind::Line, 0, Vec::new()),
        entity_open: false,
        sections: 0,
        structure_error: None,
        header_error: None,
        entity_error: None,
        extra_pairs: Vec::new(),
        block_pairs: Vec::new(),
        in_extra: false,
        route: Route::Nowhere,
    };
    let mut tokens = Tokens::new(bytes);
    // the line of the last pair read: where a file that ends inside a section is cut
    let mut last_line = 0;
    let mut open_section = false;
    while let Some(p) = tokens.next_pair()? {
        last_line = p.line;
        if p.code != 0 {
            continue;
        }
        match p.value.trim_ascii() {
            b"SECTION" => {}
            b"EOF" => break,
            _ => continue,
        }
        // this pair names the section (when its code is 2)
        let Some(p) = tokens.next_pair()? else {
            open_section = true;
            break;
        };
        last_line = p.line;
        let body = match (p.code, &*raw_name(p.value)) {
            (2, b"HEADER") => Body::Header,
            (2, b"TABLES") => Body::Tables,
            (2, b"ENTITIES") => Body::Entities,
            (2, b"BLOCKS") => Body::Blocks,
            _ => Body::Other,
        };
        r.begin();
        // one loop per kind of section, each with its reading inlined
        let end = match body {
            Body::Header => section(&mut tokens, &mut last_line, |p| r.header_group(p))?,
            Body::Tables => section(&mut tokens, &mut last_line, |p| r.table_group(p))?,
            Body::Entities => section(&mut tokens, &mut last_line, |p| r.entity_group(p))?,
            Body::Blocks => section(&mut tokens, &mut last_line, |p| r.block_pairs.push(*p))?,
            Body::Other => section(&mut tokens, &mut last_line, |_| {})?,
        };
        match end {
            SectionEnd::EndSec => r.end(body),
            SectionEnd::Marker(line) => {
                r.structure_error = Some(DxfError {
                    line,
                    kind: DxfErrorKind::Truncated,
                });
                break;
            }
            SectionEnd::FileEnd => {
                open_section = true;
                break;
            }
        }
    }
    // after `0`/`EOF` or a structure error: only the pairs are still checked
    while tokens.next_pair()?.is_some() {}
    if open_section {
        r.structure_error = Some(DxfError {
            line: last_line,
            kind: DxfErrorKind::Truncated,
        });
    }
    r.finish()
}

/// How the pairs of a section ended.
enum SectionEnd {
    /// `0`/`ENDSEC`.
    EndSec,
    /// `0`/`SECTION` or `0`/`EOF` inside the section (its line): a structure error.
    Marker(usize),
    /// The end of the file.
    FileEnd,
}

/// The pairs of a section up to its end, each given to `group` (`0` groups too, but not
/// the one that ends the section). Not inlined: each loop gets the registers to itself.
#[inline(never)]
fn section<'a>(
    tokens: &mut Tokens<'a>,
    last_line: &mut usize,
    mut group: impl FnMut(&Pair<'a>),
) -> Result<SectionEnd, DxfError> {
    // a local copy the usual pairs are taken from (kept in registers); the others are taken
    // by `next_pair` from `tokens`
    let mut t = *tokens;
    let end = loop {
        let p = match t.quick_pair() {
            Some(p) => p,
            None => {
                // every pair taken leaves the line after its value line as the last one
                // taken: before this try, the last pair's line is the one before
                let before = t.last_pair_line();
                *tokens = t;
                let p = tokens.next_pair()?;
                t = *tokens;
                match p {
                    Some(p) => p,
                    None => {
                        *last_line = before;
                        break SectionEnd::FileEnd;
                    }
                }
            }
        };
        if p.code == 0 {
            match trimmed_name(p.value) {
                b"ENDSEC" => {
                    *last_line = p.line;
                    break SectionEnd::EndSec;
                }
                b"SECTION" | b"EOF" => {
                    *last_line = p.line;
                    break SectionEnd::Marker(p.line);
                }
                _ => {}
            }
        }
        group(&p);
    };
    *tokens = t;
    Ok(end)
}

/// `trim_ascii` of a value, without its calls for the usual values (nothing to trim).
#[inline(always)]
fn trimmed_name(v: &[u8]) -> &[u8] {
    match (v.first(), v.last()) {
        (Some(&a), Some(&z)) if a > b' ' && z > b' ' => v,
        _ => v.trim_ascii(),
    }
}

impl<'a> Reader<'a> {
    fn begin(&mut self) {
        self.header_var = HeaderVar::Other;
        self.table = TableRecord::Skip;
    }

    fn end(&mut self, body: Body) {
        self.sections += 1;
        match body {
            Body::Tables => self.end_table_record(),
            Body::Entities => {
                self.end_entity();
                if self.route == Route::Entity {
                    self.route = Route::Nowhere;
                }
            }
            Body::Header | Body::Blocks | Body::Other => {}
        }
    }

    fn header_group(&mut self, p: &Pair<'a>) {
        match (p.code, self.header_var) {
            (9, _) => {
                self.header_var = match &*raw_name(p.value) {
                    b"$ACADVER" => HeaderVar::AcadVer,
                    b"$DWGCODEPAGE" => HeaderVar::CodePage,
                    b"$TEXTSIZE" => HeaderVar::TextSize,
                    b"$INSUNITS" => HeaderVar::InsUnits,
                    _ => HeaderVar::Other,
                }
            }
            (1, HeaderVar::AcadVer) => self.d.version = raw_str(p.value).into_owned(),
            (3, HeaderVar::CodePage) => self.d.codepage = raw_str(p.value).into_owned(),
            (40, HeaderVar::TextSize) => match num(p) {
                Ok(v) => self.d.text_size = v,
                Err(e) => {
                    self.header_error.get_or_insert(e);
                }
            },
            // ignored by the reference: a malformed value must not cost it the file
            (70, HeaderVar::InsUnits) => self.d.insunits = int(p).ok(),
            _ => {}
        }
    }

    fn table_group(&mut self, p: &Pair<'a>) {
        if p.code == 0 {
            self.end_table_record();
            self.table = match &*raw_name(p.value) {
                b"LTYPE" => TableRecord::Ltype,
                b"LAYER" => TableRecord::Layer,
                _ => TableRecord::Skip,
            };
            return;
        }
        // the first name and line type of a record count
        match (self.table, p.code) {
            (TableRecord::Ltype | TableRecord::Layer, 2) if self.table_name.is_none() => {
                self.table_name = Some(p.value)
            }
            (TableRecord::Layer, 6) if self.table_linetype.is_none() => {
                self.table_linetype = Some(p.value)
            }
            _ => {}
        }
    }

    fn end_table_record(&mut self) {
        let (name, linetype) = (self.table_name.take(), self.table_linetype.take());
        match (self.table, name) {
            (TableRecord::Ltype, Some(name)) => self.kept.push(Kept::Linetype(name)),
            (TableRecord::Layer, Some(name)) => self.kept.push(Kept::Layer { name, linetype }),
            _ => {}
        }
        self.table = TableRecord::Skip;
    }

    #[inline(always)]
    fn entity_group(&mut self, p: &Pair<'a>) {
        if p.code != 0 {
            match self.route {
                Route::Entity => {
                    if let Err(err) = self.entity.group(p) {
                        self.entity_error = Some(err);
                        self.entity_open = false;
                        self.route = Route::Nowhere;
                    }
                }
                Route::Extra => self.extra_pairs.push(*p),
                Route::Nowhere => {}
            }
            return;
        }
        self.entity_record(p);
        self.route = match (self.entity_error.is_some(), self.in_extra, self.entity_open) {
            (true, _, _) => Route::Nowhere,
            (false, true, _) => Route::Extra,
            (false, false, true) => Route::Entity,
            (false, false, false) => Route::Nowhere,
        };
    }

    /// A `0` group of the ENTITIES section.
    fn entity_record(&mut self, p: &Pair<'a>) {
        if self.entity_error.is_some() {
            return; // the file's answer is that error (or an earlier one)
        }
        if p.code == 0 {
            self.end_entity();
            let name = raw_name(p.value);
            let kind = match &*name {
                b"LINE" => Some(Kind::Line),
                b"ARC" => Some(Kind::Arc),
                b"CIRCLE" => Some(Kind::Circle),
                b"TEXT" => Some(Kind::Text),
                b"MTEXT" => Some(Kind::MText),
                _ => None,
            };
            self.in_extra = kind.is_none();
            // a boundary for a pending POLYLINE, once per run of the five kinds
            let after_extra = self.extra_pairs.last().is_some_and(|last| {
                !matches!(
                    &*raw_name(last.value),
                    b"LINE" | b"ARC" | b"CIRCLE" | b"TEXT" | b"MTEXT"
                ) || last.code != 0
            });
            if self.in_extra || after_extra {
                self.extra_pairs.push(*p);
            }
            let Some(kind) = kind else {
                if !matches!(&*name, b"VERTEX" | b"SEQEND" | b"ATTRIB") {
                    self.d.ignored_entities += 1;
                }
                return;
            };
            self.entity.reset(kind, p.line);
            self.entity_open = true;
        }
    }

    fn end_entity(&mut self) {
        if !std::mem::take(&mut self.entity_open) {
            return;
        }
        let e = &mut self.entity;
        if !e.paper_space {
            let i = self.d.entities.len();
            self.d.entities.push(e.entity());
            if let Some(layer) = e.layer {
                self.kept.push(Kept::EntityLayer(i, layer));
            }
            if let Some(lt) = e.linetype {
                self.kept.push(Kept::EntityLinetype(i, lt));
            }
            if let Some(t) = e.text_1 {
                self.kept.push(Kept::EntityText(i, t));
            }
            self.kept
                .extend(e.pieces.drain(..).map(|t| Kept::EntityText(i, t)));
        }
    }

    /// The drawing, its strings decoded with the code page of the header; or the file's error.
    fn finish(mut self) -> Result<Drawing, DxfError> {
        if let Some(e) = self.structure_error {
            return Err(e);
        }
        if self.sections == 0 {
            return Err(DxfError {
                line: 1,
                kind: DxfErrorKind::NotDxf,
            });
        }
        if let Some(e) = self.header_error.or(self.entity_error) {
            return Err(e);
        }
        let d = &mut self.d;
        let enc = encoding_for(&d.version, &d.codepage);
        let decode = |raw: &[u8]| {
            let mut s = String::new();
            decode_value_into(enc, raw, &mut s);
            s
        };
        // consecutive entities mostly share their layer: decoded once
        let mut last_layer: Option<(&[u8], String)> = None;
        // built in one go at the end: `from_iter` sorts stably and keeps the last of equal
        // names, as inserting them one by one would
        let mut layers = Vec::new();
        let mut last_layer_linetype: Option<(&[u8], String)> = None;
        for k in self.kept {
            match k {
                Kept::Linetype(name) => d.linetypes.push(decode(name)),
                Kept::Layer { name, linetype } => {
                    // most layers share a few line types: decoded once per run
                    let lt = match (linetype, &last_layer_linetype) {
                        (None, _) => "Continuous".to_string(),
                        (Some(raw), Some((r, s))) if *r == raw => s.clone(),
                        (Some(raw), _) => {
                            let s = decode(raw);
                            last_layer_linetype = Some((raw, s.clone()));
                            s
                        }
                    };
                    layers.push((decode(name), lt));
                }
                Kept::EntityLayer(i, raw) => {
                    let layer = match &last_layer {
                        Some((r, s)) if *r == raw => s.clone(),
                        _ => {
                            let s = decode(raw);
                            last_layer = Some((raw, s.clone()));
                            s
                        }
                    };
                    if let Some(e) = d.entities.get_mut(i) {
                        e.layer = layer;
                    }
                }
                Kept::EntityLinetype(i, raw) => {
                    if let Some(e) = d.entities.get_mut(i) {
                        e.linetype = Some(decode(raw));
                    }
                }
                Kept::EntityText(i, raw) => match d.entities.get_mut(i).map(|e| &mut e.kind) {
                    Some(EntityKind::Text(Text { value, .. }))
                    | Some(EntityKind::MText(MText { value, .. })) => {
                        decode_value_into(enc, raw, value)
                    }
                    _ => {}
                },
            }
        }
        d.layers = layer_map(layers);
        // the geometry the reference ignores, and the blocks, now that the code page is known
        let ctx = Ctx { enc };
        let mut extra = ExtraReader::default();
        for rec in records(&self.extra_pairs) {
            let kind = raw_str(rec[0].value);
            extra.take(&ctx, &kind, rec, &mut d.extra, &mut d.extra_errors);
        }
        extra.finish(&mut d.extra);
        crate::blocks::read_blocks(&ctx, &self.block_pairs, d);
        Ok(self.d)
    }
}

/// The LAYER table as a map, the last of equal names kept (as inserting them one by one
/// would). Sorted once by an index and the names' first eight bytes, which mostly decide;
/// `from_iter` then finds the order made and only drops the duplicates.
fn layer_map(layers: Vec<(String, String)>) -> BTreeMap<String, String> {
    let prefix = |name: &str| {
        let b = name.as_bytes();
        (0..8).fold(0u64, |p, k| {
            p << 8 | u64::from(b.get(k).copied().unwrap_or(0))
        })
    };
    let mut order: Vec<(u64, usize)> = layers
        .iter()
        .enumerate()
        .map(|(i, (name, _))| (prefix(name), i))
        .collect();
    order.sort_unstable_by(|a, b| {
        a.0.cmp(&b.0)
            .then_with(|| layers[a.1].0.cmp(&layers[b.1].0))
            .then(a.1.cmp(&b.1))
    });
    let mut slots: Vec<Option<(String, String)>> = layers.into_iter().map(Some).collect();
    order
        .iter()
        .filter_map(|&(_, i)| slots.get_mut(i).and_then(Option::take))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Entity;

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
    fn the_layer_map_keeps_the_last_of_equal_names_as_inserting_does() {
        let names = [
            "P1",
            "P1 ",
            "1234_1P~A",
            "1234_1P~B",
            "1234_1P",
            "",
            "Ä",
            "a",
            "1234_1P~A",
        ];
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..2_000 {
            let mut layers = Vec::new();
            let mut inserted = BTreeMap::new();
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            for k in 0..(seed % 40) {
                let name = names[(seed >> (k % 50)) as usize % names.len()].to_string();
                let lt = format!("LT{k}");
                inserted.insert(name.clone(), lt.clone());
                layers.push((name, lt));
            }
            assert_eq!(layer_map(layers), inserted);
        }
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
