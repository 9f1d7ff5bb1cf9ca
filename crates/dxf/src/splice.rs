//! Writing entities into an existing drawing: the entities a caller chooses are taken out
//! of the ENTITIES section, new ones are added at its end, and every other byte of the file
//! stays as it was (its line ends, code page, tables, blocks, objects and header values).
//!
//! It knows layers and entities, not paths: which entities go is the caller's predicate.
//! New entities get handles from `$HANDSEED` (raised past them) where the file uses handles,
//! the model space block record as owner where the version has owners, and the LAYER and
//! LTYPE table entries they need.
//!
//! Writing entities into an existing drawing (`text2dxf --into`): `scan` (after `read_dxf`
//! validated the file) finds the header's `$ACADVER`/`$DWGCODEPAGE`/`$HANDSEED`, the LAYER and
//! LTYPE tables, the model space record, the blocks and the ENTITIES records (VERTEX/SEQEND/ATTRIB
//! with their entity) as byte ranges; `splice` drops the records a caller's predicate chooses, adds
//! new LINE/ARC/CIRCLE/MTEXT (TEXT before R13) at the section's end with handles from `$HANDSEED`
//! (raised), owners from R2000, subclasses from R13, the file's line ends and code page, and the
//! missing LAYER/LTYPE entries; every other byte stays.

use crate::decode::{decode_value_into, encoding_for};
use crate::tokens::{raw_name, Tokens};
use crate::writer::{linetype_pattern, num};
use crate::DxfError;
use encoding_rs::Encoding;
use std::ops::Range;

/// One model-space or paper-space entity of the ENTITIES section, with the VERTEX, SEQEND
/// and ATTRIB records that follow it (they go and stay with it).
#[derive(Debug, Clone)]
pub struct Record {
    /// Entity type (`LINE`, `DIMENSION`, …).
    pub kind: String,
    /// Layer (group 8), `0` when absent.
    pub layer: String,
    /// Handle (group 5), empty when the file has none.
    pub handle: String,
    /// In paper space (group 67 = 1).
    pub paper: bool,
    /// 1-based line of its `0` group.
    pub line: usize,
    bytes: Range<usize>,
}

/// A new entity: what it is, on which layer, with which own line type.
#[derive(Debug, Clone, PartialEq)]
pub struct NewEntity {
    pub layer: String,
    /// Own line type (group 6); `None` = ByLayer.
    pub linetype: Option<String>,
    pub shape: NewShape,
}

#[derive(Debug, Clone, PartialEq)]
pub enum NewShape {
    Line {
        a: (f64, f64),
        b: (f64, f64),
    },
    Circle {
        c: (f64, f64),
        r: f64,
    },
    /// Counter-clockwise from `a0` to `a1` degrees.
    Arc {
        c: (f64, f64),
        r: f64,
        a0: f64,
        a1: f64,
    },
    /// A text centred on `at`: MTEXT where the version has it (R13 on), TEXT before.
    Text {
        at: (f64, f64),
        height: f64,
        value: String,
    },
}

/// A symbol table (LAYER or LTYPE) of the file.
#[derive(Debug, Default, Clone)]
struct Table {
    handle: Option<String>,
    /// The value of the table's group 70 (its entry count), as written.
    count: Option<Range<usize>>,
    /// Where its `0 ENDTAB` starts: new entries go there.
    end: usize,
    /// Entry names with where each name's value is written.
    names: Vec<(String, Range<usize>)>,
}

/// The parts of a DXF file that splicing needs; nothing else of the file is interpreted.
#[derive(Debug)]
pub struct Target<'a> {
    bytes: &'a [u8],
    eol: &'static str,
    version: String,
    enc: &'static Encoding,
    handseed: Option<Range<usize>>,
    header_end: Option<usize>,
    uses_handles: bool,
    max_handle: u64,
    layers: Option<Table>,
    ltypes: Option<Table>,
    model_space: Option<String>,
    blocks: Vec<String>,
    entities: Vec<Record>,
    /// Where the ENTITIES section's `0 ENDSEC` starts.
    entities_end: Option<usize>,
    eof: Option<usize>,
}

#[derive(Clone, Copy, PartialEq)]
enum Section {
    None,
    Header,
    Tables,
    Blocks,
    Entities,
    Other,
}

/// A table record being read (an entry of a symbol table).
struct TableEntry {
    kind: String,
    name: Option<(String, Range<usize>)>,
    handle: Option<String>,
}

fn span_of(bytes: &[u8], value: &[u8]) -> Option<Range<usize>> {
    let off = (value.as_ptr() as usize).checked_sub(bytes.as_ptr() as usize)?;
    (off + value.len() <= bytes.len()).then_some(off..off + value.len())
}

fn text(v: &[u8]) -> String {
    String::from_utf8_lossy(&raw_name(v)).into_owned()
}

/// Reads the structure of `bytes`. The whole file is first read by [`crate::read_dxf`], so
/// anything that reader refuses (cut pairs, bad codes or numbers, open sections) is refused
/// here with the same located error.
pub fn scan(bytes: &[u8]) -> Result<Target<'_>, DxfError> {
    crate::read_dxf(bytes)?;
    let eol = match bytes.iter().position(|&b| b == b'\n') {
        Some(i) if i > 0 && bytes[i - 1] == b'\r' => "\r\n",
        _ => "\n",
    };
    let mut t = Target {
        bytes,
        eol,
        version: String::new(),
        enc: encoding_rs::WINDOWS_1252,
        handseed: None,
        header_end: None,
        uses_handles: false,
        max_handle: 0,
        layers: None,
        ltypes: None,
        model_space: None,
        blocks: Vec::new(),
        entities: Vec::new(),
        entities_end: None,
        eof: None,
    };
    let mut codepage = String::new();
    let mut raw_layers: Vec<Option<Range<usize>>> = Vec::new();
    let mut block_spans: Vec<Range<usize>> = Vec::new();
    let mut tokens = Tokens::new(bytes);
    let mut sec = Section::None;
    let mut section_name_next = false;
    let mut var: Option<String> = None;
    // tables: the open table (name, data), whether its header is being read, the open entry
    let mut table: Option<(String, Table)> = None;
    let mut table_header = false;
    let mut entry: Option<TableEntry> = None;
    let mut block_header = false;
    // entities: the open record is main (not a follower)
    let mut main_open = false;
    loop {
        let start = tokens.pos().min(bytes.len());
        let Some(p) = tokens.next_pair()? else {
            break;
        };
        if p.code == 0 {
            if let Some(last) = t.entities.last_mut() {
                if sec == Section::Entities && last.bytes.end == usize::MAX {
                    last.bytes.end = start;
                }
            }
            if let (Some(e), Some(tab)) = (entry.take(), table.as_mut()) {
                finish_entry(bytes, e, tab, &mut t.model_space);
            }
            let name = raw_name(p.value);
            match &*name {
                b"SECTION" => {
                    section_name_next = true;
                    continue;
                }
                b"ENDSEC" => {
                    match sec {
                        Section::Header => t.header_end = Some(start),
                        Section::Entities => t.entities_end = Some(start),
                        _ => {}
                    }
                    sec = Section::None;
                    continue;
                }
                b"EOF" => {
                    t.eof = Some(start);
                    break;
                }
                _ => {}
            }
            match sec {
                Section::Tables => match &*name {
                    b"TABLE" => {
                        table = Some((String::new(), Table::default()));
                        table_header = true;
                    }
                    b"ENDTAB" => {
                        if let Some((n, mut tab)) = table.take() {
                            tab.end = start;
                            match n.as_str() {
                                "LAYER" => t.layers = Some(tab),
                                "LTYPE" => t.ltypes = Some(tab),
                                _ => {}
                            }
                        }
                        table_header = false;
                    }
                    kind => {
                        table_header = false;
                        entry = Some(TableEntry {
                            kind: String::from_utf8_lossy(kind).into_owned(),
                            name: None,
                            handle: None,
                        });
                    }
                },
                Section::Blocks => block_header = &*name == b"BLOCK",
                Section::Entities => {
                    let kind = text(p.value);
                    let follower = matches!(kind.as_str(), "VERTEX" | "SEQEND" | "ATTRIB");
                    match t.entities.last_mut() {
                        // it goes and stays with the entity before it
                        Some(last) if follower => {
                            last.bytes.end = usize::MAX;
                            main_open = false;
                        }
                        _ => {
                            t.entities.push(Record {
                                kind,
                                layer: String::new(),
                                handle: String::new(),
                                paper: false,
                                line: p.line,
                                bytes: start..usize::MAX,
                            });
                            raw_layers.push(None);
                            main_open = true;
                        }
                    }
                }
                _ => {}
            }
            continue;
        }
        if section_name_next {
            section_name_next = false;
            if p.code == 2 {
                sec = match &*raw_name(p.value) {
                    b"HEADER" => Section::Header,
                    b"TABLES" => Section::Tables,
                    b"BLOCKS" => Section::Blocks,
                    b"ENTITIES" => Section::Entities,
                    _ => Section::Other,
                };
                continue;
            }
        }
        if sec == Section::Header {
            if p.code == 9 {
                var = Some(text(p.value));
            } else if let Some(v) = var.take() {
                match v.as_str() {
                    "$ACADVER" => t.version = text(p.value),
                    "$DWGCODEPAGE" => codepage = text(p.value),
                    "$HANDSEED" => t.handseed = span_of(bytes, p.value),
                    _ => {}
                }
            }
            continue;
        }
        if p.code == 5 || p.code == 105 {
            let h = text(p.value);
            if let Ok(v) = u64::from_str_radix(&h, 16) {
                t.uses_handles = true;
                t.max_handle = t.max_handle.max(v);
            }
            if table_header {
                if let Some((_, tab)) = table.as_mut() {
                    tab.handle.get_or_insert(h.clone());
                }
            }
            if let Some(e) = entry.as_mut() {
                e.handle.get_or_insert(h.clone());
            }
            if sec == Section::Entities && main_open {
                if let Some(last) = t.entities.last_mut() {
                    if last.handle.is_empty() {
                        last.handle = h;
                    }
                }
            }
            continue;
        }
        match (sec, p.code) {
            (Section::Tables, 2) => {
                if table_header {
                    if let Some((n, _)) = table.as_mut() {
                        if n.is_empty() {
                            *n = text(p.value);
                        }
                    }
                } else if let Some(e) = entry.as_mut() {
                    if e.name.is_none() {
                        e.name = span_of(bytes, p.value).map(|s| (String::new(), s));
                    }
                }
            }
            (Section::Tables, 70) if table_header => {
                if let Some((_, tab)) = table.as_mut() {
                    tab.count
                        .get_or_insert_with(|| span_of(bytes, p.value).unwrap_or(0..0));
                }
            }
            (Section::Blocks, 2) if block_header => {
                block_header = false;
                block_spans.extend(span_of(bytes, p.value));
            }
            (Section::Entities, 8) if main_open => {
                if let Some(l) = raw_layers.last_mut() {
                    l.get_or_insert_with(|| span_of(bytes, p.value).unwrap_or(0..0));
                }
            }
            (Section::Entities, 67) if main_open => {
                if let Some(last) = t.entities.last_mut() {
                    last.paper = text(p.value) == "1";
                }
            }
            _ => {}
        }
    }
    if let Some(last) = t.entities.last_mut() {
        if last.bytes.end == usize::MAX {
            last.bytes.end = t.entities_end.unwrap_or(bytes.len());
        }
    }
    t.enc = encoding_for(&t.version, &codepage);
    let decode = |r: &Range<usize>| {
        let mut s = String::new();
        let raw = bytes.get(r.clone()).unwrap_or_default();
        decode_value_into(t.enc, &raw_name(raw), &mut s);
        s
    };
    for (rec, raw) in t.entities.iter_mut().zip(&raw_layers) {
        rec.layer = raw.as_ref().map_or_else(|| "0".to_string(), &decode);
    }
    for tab in [t.layers.as_mut(), t.ltypes.as_mut()].into_iter().flatten() {
        for (name, span) in tab.names.iter_mut() {
            *name = decode(span);
        }
    }
    t.blocks = block_spans.iter().map(decode).collect();
    Ok(t)
}

fn finish_entry(
    bytes: &[u8],
    e: TableEntry,
    tab: &mut (String, Table),
    model_space: &mut Option<String>,
) {
    let Some((_, span)) = e.name else {
        return;
    };
    match tab.0.as_str() {
        "LAYER" | "LTYPE" if e.kind == tab.0 => tab.1.names.push((String::new(), span)),
        // the model space's block record: the owner of model-space entities (R2000 on)
        "BLOCK_RECORD" if model_space.is_none() => {
            let name = raw_name(bytes.get(span).unwrap_or_default());
            if name.eq_ignore_ascii_case(b"*Model_Space") {
                *model_space = e.handle;
            }
        }
        _ => {}
    }
}

impl<'a> Target<'a> {
    /// The entities of the ENTITIES section in file order.
    pub fn entities(&self) -> &[Record] {
        &self.entities
    }

    /// The bytes of one entity as the file holds them (its `0` group up to the next one).
    pub fn bytes_of(&self, r: &Record) -> &'a [u8] {
        &self.bytes[r.bytes.clone()]
    }

    /// The layer names of the LAYER table.
    pub fn layer_names(&self) -> Vec<&str> {
        self.layers
            .iter()
            .flat_map(|t| t.names.iter().map(|(n, _)| n.as_str()))
            .collect()
    }

    /// The block names of the BLOCKS section (the model and paper space blocks included).
    pub fn block_names(&self) -> &[String] {
        &self.blocks
    }

    /// `$ACADVER` (empty when absent: an R12-style file).
    pub fn version(&self) -> &str {
        &self.version
    }

    fn version_number(&self) -> u32 {
        self.version
            .strip_prefix("AC")
            .and_then(|v| v.parse().ok())
            .unwrap_or(1009)
    }

    /// The file with the entities `remove` chooses taken out and `new` added at the end of
    /// the ENTITIES section (a new section before `EOF` when it has none).
    pub fn splice(&self, remove: &dyn Fn(&Record) -> bool, new: &[NewEntity]) -> Vec<u8> {
        let v = self.version_number();
        let out = Writer {
            eol: self.eol,
            enc: self.enc,
            subclasses: v >= 1012,
            handles: self.uses_handles || v >= 1012,
            owner: if v >= 1015 {
                self.model_space.clone()
            } else {
                None
            },
            lineweight: v >= 1015,
        };
        let seed = self
            .handseed
            .as_ref()
            .and_then(|s| self.bytes.get(s.clone()))
            .and_then(|b| u64::from_str_radix(text(b).trim(), 16).ok())
            .unwrap_or(0);
        let mut next = seed.max(self.max_handle.saturating_add(1)).max(1);
        let mut edits: Vec<(Range<usize>, Vec<u8>)> = Vec::new();

        // line types: added, or respelled where the table has another case (readers that
        // compare names exactly take the table's spelling)
        let mut linetypes: Vec<&str> = Vec::new();
        for e in new {
            if let Some(lt) = e.linetype.as_deref() {
                let by = lt.eq_ignore_ascii_case("bylayer") || lt.eq_ignore_ascii_case("byblock");
                if !by && !linetypes.iter().any(|l| l.eq_ignore_ascii_case(lt)) {
                    linetypes.push(lt);
                }
            }
        }
        if !linetypes
            .iter()
            .any(|l| l.eq_ignore_ascii_case("continuous"))
        {
            linetypes.push("CONTINUOUS");
        }
        if let Some(tab) = &self.ltypes {
            let mut added = Vec::new();
            for lt in &linetypes {
                match tab.names.iter().find(|(n, _)| n.eq_ignore_ascii_case(lt)) {
                    Some((n, _)) if n == lt => {}
                    Some((_, span)) => edits.push((span.clone(), out.encode(lt))),
                    None => added.push(out.ltype(lt, &mut next, tab.handle.as_deref())),
                }
            }
            self.add_entries(tab, added, &mut edits);
        }
        if let Some(tab) = &self.layers {
            let mut added = Vec::new();
            let mut seen: Vec<&str> = Vec::new();
            for e in new {
                let l = e.layer.as_str();
                let known = tab.names.iter().any(|(n, _)| n.eq_ignore_ascii_case(l))
                    || seen.iter().any(|s| s.eq_ignore_ascii_case(l));
                if !known {
                    seen.push(l);
                    added.push(out.layer(l, &mut next, tab.handle.as_deref()));
                }
            }
            self.add_entries(tab, added, &mut edits);
        }
        for r in self.entities.iter().filter(|r| remove(r)) {
            edits.push((r.bytes.clone(), Vec::new()));
        }
        let mut body = Vec::new();
        for e in new {
            body.extend(out.entity(e, &mut next));
        }
        match self.entities_end {
            Some(at) => edits.push((at..at, body)),
            None => {
                let mut sec = out.pairs(&[(0, "SECTION"), (2, "ENTITIES")]);
                sec.extend(body);
                sec.extend(out.pairs(&[(0, "ENDSEC")]));
                let at = self.eof.unwrap_or(self.bytes.len());
                edits.push((at..at, sec));
            }
        }
        if out.handles {
            let hex = format!("{next:X}");
            match (&self.handseed, self.header_end) {
                (Some(span), _) => edits.push((span.clone(), hex.into_bytes())),
                (None, Some(at)) => {
                    edits.push((at..at, out.pairs(&[(9, "$HANDSEED"), (5, &hex)])));
                }
                (None, None) => {}
            }
        }
        apply(self.bytes, edits)
    }

    fn add_entries(
        &self,
        tab: &Table,
        added: Vec<Vec<u8>>,
        edits: &mut Vec<(Range<usize>, Vec<u8>)>,
    ) {
        if added.is_empty() {
            return;
        }
        if let Some(span) = &tab.count {
            let old = self.bytes.get(span.clone()).unwrap_or_default();
            if let Ok(n) = text(old).parse::<i64>() {
                let width = old.len();
                let new = format!("{:>width$}", n.saturating_add(added.len() as i64));
                edits.push((span.clone(), new.into_bytes()));
            }
        }
        edits.push((tab.end..tab.end, added.concat()));
    }
}

/// The edits applied in file order (they never overlap: each is one pair's value, one
/// record, or an insertion point).
fn apply(bytes: &[u8], mut edits: Vec<(Range<usize>, Vec<u8>)>) -> Vec<u8> {
    edits.sort_by_key(|(r, _)| (r.start, r.end));
    let mut out = Vec::with_capacity(bytes.len() + edits.iter().map(|e| e.1.len()).sum::<usize>());
    let mut at = 0;
    for (r, new) in edits {
        let start = r.start.clamp(at, bytes.len());
        out.extend_from_slice(&bytes[at..start]);
        out.extend_from_slice(&new);
        at = r.end.clamp(start, bytes.len());
    }
    out.extend_from_slice(&bytes[at..]);
    out
}

/// Writes pairs as the target file writes them.
struct Writer {
    eol: &'static str,
    enc: &'static Encoding,
    subclasses: bool,
    handles: bool,
    owner: Option<String>,
    lineweight: bool,
}

impl Writer {
    /// A value in the file's encoding; characters its code page lacks as `\U+XXXX`.
    fn encode(&self, s: &str) -> Vec<u8> {
        if self.enc == encoding_rs::UTF_8 {
            return s.as_bytes().to_vec();
        }
        let mut out = Vec::new();
        let mut buf = [0u8; 4];
        for c in s.chars() {
            if c.is_ascii() {
                out.push(c as u8);
                continue;
            }
            let (b, _, bad) = self.enc.encode(c.encode_utf8(&mut buf));
            if bad {
                out.extend(format!("\\U+{:04X}", u32::from(c)).bytes());
            } else {
                out.extend_from_slice(&b);
            }
        }
        out
    }

    fn pairs(&self, pairs: &[(i32, &str)]) -> Vec<u8> {
        let mut out = Vec::new();
        for (code, v) in pairs {
            out.extend(format!("{code:>3}{}", self.eol).bytes());
            out.extend(self.encode(v));
            out.extend(self.eol.bytes());
        }
        out
    }

    /// `0 KIND`, its handle and owner where the file has them.
    fn head(&self, kind: &str, next: &mut u64, owner: Option<&str>) -> Vec<(i32, String)> {
        let mut p = vec![(0, kind.to_string())];
        if self.handles {
            p.push((5, format!("{:X}", *next)));
            *next = next.saturating_add(1);
            if self.subclasses {
                p.push((330, owner.unwrap_or("0").to_string()));
            }
        }
        p
    }

    fn finish(&self, p: Vec<(i32, String)>) -> Vec<u8> {
        let refs: Vec<(i32, &str)> = p
            .iter()
            .filter(|(c, _)| self.subclasses || *c != 100)
            .map(|(c, v)| (*c, v.as_str()))
            .collect();
        self.pairs(&refs)
    }

    fn ltype(&self, name: &str, next: &mut u64, table: Option<&str>) -> Vec<u8> {
        let mut p = self.head("LTYPE", next, table);
        let (desc, pattern) = linetype_pattern(name);
        p.push((100, "AcDbSymbolTableRecord".into()));
        p.push((100, "AcDbLinetypeTableRecord".into()));
        p.push((2, name.into()));
        p.push((70, "0".into()));
        p.push((3, desc.into()));
        p.push((72, "65".into()));
        p.push((73, pattern.len().to_string()));
        p.push((40, num(pattern.iter().map(|x| x.abs()).sum::<f64>())));
        for d in pattern {
            p.push((49, num(d)));
            if self.subclasses {
                p.push((74, "0".into()));
            }
        }
        self.finish(p)
    }

    fn layer(&self, name: &str, next: &mut u64, table: Option<&str>) -> Vec<u8> {
        let mut p = self.head("LAYER", next, table);
        p.push((100, "AcDbSymbolTableRecord".into()));
        p.push((100, "AcDbLayerTableRecord".into()));
        p.push((2, name.into()));
        p.push((70, "0".into()));
        p.push((62, "7".into()));
        p.push((6, "CONTINUOUS".into()));
        if self.lineweight {
            p.push((370, "-3".into()));
        }
        self.finish(p)
    }

    fn entity(&self, e: &NewEntity, next: &mut u64) -> Vec<u8> {
        let kind = match &e.shape {
            NewShape::Line { .. } => "LINE",
            NewShape::Circle { .. } => "CIRCLE",
            NewShape::Arc { .. } => "ARC",
            NewShape::Text { .. } if self.subclasses => "MTEXT",
            NewShape::Text { .. } => "TEXT",
        };
        let mut p = self.head(kind, next, self.owner.as_deref());
        p.push((100, "AcDbEntity".into()));
        p.push((8, e.layer.clone()));
        if let Some(lt) = &e.linetype {
            p.push((6, lt.clone()));
        }
        let xy = |p: &mut Vec<(i32, String)>, code: i32, (x, y): (f64, f64)| {
            p.push((code, num(x)));
            p.push((code + 10, num(y)));
            p.push((code + 20, "0.0".into()));
        };
        match &e.shape {
            NewShape::Line { a, b } => {
                p.push((100, "AcDbLine".into()));
                xy(&mut p, 10, *a);
                xy(&mut p, 11, *b);
            }
            NewShape::Circle { c, r } => {
                p.push((100, "AcDbCircle".into()));
                xy(&mut p, 10, *c);
                p.push((40, num(*r)));
            }
            NewShape::Arc { c, r, a0, a1 } => {
                p.push((100, "AcDbCircle".into()));
                xy(&mut p, 10, *c);
                p.push((40, num(*r)));
                p.push((100, "AcDbArc".into()));
                p.push((50, num(*a0)));
                p.push((51, num(*a1)));
            }
            NewShape::Text { at, height, value } if self.subclasses => {
                p.push((100, "AcDbMText".into()));
                xy(&mut p, 10, *at);
                p.push((40, num(*height)));
                p.push((71, "5".into()));
                p.push((72, "1".into()));
                let v = value
                    .replace('\\', "\\\\")
                    .replace('{', "\\{")
                    .replace('}', "\\}");
                p.push((1, v));
            }
            NewShape::Text { at, height, value } => {
                xy(&mut p, 10, *at);
                p.push((40, num(*height)));
                p.push((1, value.clone()));
                p.push((72, "1".into()));
                xy(&mut p, 11, *at);
                p.push((73, "2".into()));
            }
        }
        self.finish(p)
    }
}
