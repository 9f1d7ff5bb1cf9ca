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
use crate::extra::ExtraReader;
use crate::tokens::{int, is, num, raw_name, raw_str, Pair, Tokens};
use crate::{Drawing, DxfError, DxfErrorKind, Entity, EntityKind, MText, Point3, Text};
use encoding_rs::Encoding;

/// What a section's contents are read as.
#[derive(Clone, Copy, PartialEq)]
enum Body {
    Header,
    Tables,
    Entities,
    Blocks,
    Other,
}

/// Where the pass is in the file's structure.
#[derive(Clone, Copy)]
enum State {
    Outside,
    /// Right after `0`/`SECTION`: this pair names the section (when its code is 2).
    Name,
    In(Body),
    /// After `0`/`EOF` outside a section, or after a structure error: only the pairs are
    /// still checked.
    Done,
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

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Line,
    Arc,
    Circle,
    Text,
    MText,
}

/// The entity being read: its groups so far (string groups: the last one counts).
struct EntityRecord<'a> {
    kind: Kind,
    line: usize,
    handle: Option<&'a [u8]>,
    layer: Option<&'a [u8]>,
    linetype: Option<&'a [u8]>,
    text_1: Option<&'a [u8]>,
    /// MTEXT groups 1 and 3 in file order.
    pieces: Vec<&'a [u8]>,
    linetype_scale: f64,
    extrusion: Point3,
    p10: Point3,
    p11: Point3,
    has11: bool,
    r40: f64,
    a50: Option<f64>,
    a51: f64,
    i71: Option<i32>,
    i72: i32,
    i73: i32,
    paper_space: bool,
}

impl<'a> EntityRecord<'a> {
    fn new(kind: Kind, line: usize, mut pieces: Vec<&'a [u8]>) -> Self {
        pieces.clear();
        EntityRecord {
            kind,
            line,
            handle: None,
            layer: None,
            linetype: None,
            text_1: None,
            pieces,
            linetype_scale: 1.0,
            extrusion: [0.0, 0.0, 1.0],
            p10: [0.0; 3],
            p11: [0.0; 3],
            has11: false,
            r40: 0.0,
            a50: None,
            a51: 0.0,
            i71: None,
            i72: 0,
            i73: 0,
            paper_space: false,
        }
    }

    fn group(&mut self, p: &Pair<'a>) -> Result<(), DxfError> {
        match p.code {
            5 => self.handle = Some(p.value),
            8 => self.layer = Some(p.value),
            6 => self.linetype = Some(p.value),
            48 => self.linetype_scale = num(p)?,
            67 => self.paper_space = int(p)? == 1,
            10 => self.p10[0] = num(p)?,
            20 => self.p10[1] = num(p)?,
            30 => self.p10[2] = num(p)?,
            11 => {
                self.has11 = true;
                self.p11[0] = num(p)?
            }
            21 => self.p11[1] = num(p)?,
            31 => self.p11[2] = num(p)?,
            210 => self.extrusion[0] = num(p)?,
            220 => self.extrusion[1] = num(p)?,
            230 => self.extrusion[2] = num(p)?,
            40 => self.r40 = num(p)?,
            50 => self.a50 = Some(num(p)?),
            51 => self.a51 = num(p)?,
            71 => self.i71 = Some(int(p)?),
            72 => self.i72 = int(p)?,
            73 => self.i73 = int(p)?,
            1 | 3 if self.kind == Kind::MText => self.pieces.push(p.value),
            1 if self.kind == Kind::Text => self.text_1 = Some(p.value),
            _ => {}
        }
        Ok(())
    }

    /// The entity, its strings still empty (they are [`Kept`]).
    fn entity(&self) -> Entity {
        let kind = match self.kind {
            Kind::Line => EntityKind::Line {
                start: self.p10,
                end: self.p11,
            },
            Kind::Circle => EntityKind::Circle {
                center: self.p10,
                radius: self.r40,
            },
            Kind::Arc => EntityKind::Arc {
                center: self.p10,
                radius: self.r40,
                start_angle: self.a50.unwrap_or(0.0),
                end_angle: self.a51,
            },
            Kind::Text => EntityKind::Text(Text {
                value: String::new(),
                first: self.p10,
                second: self.has11.then_some(self.p11),
                height: self.r40,
                rotation: self.a50.unwrap_or(0.0),
                generation: self.i71.unwrap_or(0),
                halign: self.i72,
                valign: self.i73,
            }),
            Kind::MText => EntityKind::MText(MText {
                value: String::new(),
                insert: self.p10,
                height: self.r40,
                attachment: self.i71.unwrap_or(1),
                rotation: self.a50,
                direction: self.has11.then_some(self.p11),
            }),
        };
        Entity {
            line: self.line,
            handle: self
                .handle
                .map_or_else(String::new, |h| raw_str(h).into_owned()),
            layer: if self.layer.is_some() {
                String::new()
            } else {
                "0".to_string()
            },
            linetype: self.linetype.map(|_| String::new()),
            linetype_scale: self.linetype_scale,
            extrusion: self.extrusion,
            kind,
        }
    }
}

/// Everything the pass gathers.
struct Reader<'a> {
    d: Drawing,
    kept: Vec<Kept<'a>>,
    header_var: HeaderVar,
    table: TableRecord,
    table_name: Option<&'a [u8]>,
    table_linetype: Option<&'a [u8]>,
    entity: Option<EntityRecord<'a>>,
    /// The MTEXT pieces buffer, reused from entity to entity.
    spare_pieces: Vec<&'a [u8]>,
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
}

/// Reads a DXF file (ASCII, R12 to current versions).
pub fn read_dxf(bytes: &[u8]) -> Result<Drawing, DxfError> {
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
        entity: None,
        spare_pieces: Vec::new(),
        sections: 0,
        structure_error: None,
        header_error: None,
        entity_error: None,
        extra_pairs: Vec::new(),
        block_pairs: Vec::new(),
        in_extra: false,
    };
    let mut tokens = Tokens::new(bytes);
    let mut state = State::Outside;
    let mut last_line = 0;
    while let Some(p) = tokens.next_pair()? {
        last_line = p.line;
        state = match state {
            State::Outside if is(&p, 0, "SECTION") => State::Name,
            State::Outside if is(&p, 0, "EOF") => State::Done,
            State::Outside | State::Done => state,
            State::Name => {
                let body = match (p.code, &*raw_name(p.value)) {
                    (2, b"HEADER") => Body::Header,
                    (2, b"TABLES") => Body::Tables,
                    (2, b"ENTITIES") => Body::Entities,
                    (2, b"BLOCKS") => Body::Blocks,
                    _ => Body::Other,
                };
                r.begin();
                State::In(body)
            }
            State::In(body) if p.code == 0 => {
                let marker = p.value.trim_ascii();
                if marker == b"ENDSEC" {
                    r.end(body);
                    State::Outside
                } else if marker == b"SECTION" || marker == b"EOF" {
                    r.structure_error = Some(DxfError {
                        line: p.line,
                        kind: DxfErrorKind::Truncated,
                    });
                    State::Done
                } else {
                    r.group(body, &p);
                    state
                }
            }
            State::In(body) => {
                r.group(body, &p);
                state
            }
        };
    }
    if let State::Name | State::In(_) = state {
        r.structure_error = Some(DxfError {
            line: last_line,
            kind: DxfErrorKind::Truncated,
        });
    }
    r.finish()
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
            Body::Entities => self.end_entity(),
            Body::Header | Body::Blocks | Body::Other => {}
        }
    }

    fn group(&mut self, body: Body, p: &Pair<'a>) {
        match body {
            Body::Header => self.header_group(p),
            Body::Tables => self.table_group(p),
            Body::Entities => self.entity_group(p),
            Body::Blocks => self.block_pairs.push(*p),
            Body::Other => {}
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

    fn entity_group(&mut self, p: &Pair<'a>) {
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
            let pieces = std::mem::take(&mut self.spare_pieces);
            self.entity = Some(EntityRecord::new(kind, p.line, pieces));
            return;
        }
        if self.in_extra {
            self.extra_pairs.push(*p);
            return;
        }
        if let Some(e) = &mut self.entity {
            if let Err(err) = e.group(p) {
                self.entity_error = Some(err);
                self.entity = None;
            }
        }
    }

    fn end_entity(&mut self) {
        let Some(mut e) = self.entity.take() else {
            return;
        };
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
        self.spare_pieces = e.pieces;
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
        for k in self.kept {
            match k {
                Kept::Linetype(name) => d.linetypes.push(decode(name)),
                Kept::Layer { name, linetype } => {
                    let lt = linetype.map_or_else(|| "Continuous".to_string(), decode);
                    d.layers.insert(decode(name), lt);
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

/// Decoding of kept values for `extra.rs` and `blocks.rs`.
pub(crate) struct Ctx {
    enc: &'static Encoding,
}

impl Ctx {
    /// A kept string value: decoded with the file's code page, then `\U+XXXX` escapes.
    pub(crate) fn text(&self, p: &Pair) -> String {
        self.decode(p.value)
    }

    fn decode(&self, raw: &[u8]) -> String {
        let mut s = String::new();
        decode_value_into(self.enc, raw, &mut s);
        s
    }
}

/// Splits pairs into records, each starting at a `0` group.
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

/// One LINE/ARC/CIRCLE/TEXT/MTEXT record (of a block) with its strings decoded; `None` for
/// paper space and other kinds.
pub(crate) fn read_entity(ctx: &Ctx, kind: &str, rec: &[Pair]) -> Result<Option<Entity>, DxfError> {
    let kind = match kind {
        "LINE" => Kind::Line,
        "ARC" => Kind::Arc,
        "CIRCLE" => Kind::Circle,
        "TEXT" => Kind::Text,
        "MTEXT" => Kind::MText,
        _ => return Ok(None),
    };
    let mut r = EntityRecord::new(kind, rec[0].line, Vec::new());
    for p in &rec[1..] {
        r.group(p)?;
    }
    if r.paper_space {
        return Ok(None);
    }
    let mut e = r.entity();
    if let Some(layer) = r.layer {
        e.layer = ctx.decode(layer);
    }
    e.linetype = r.linetype.map(|lt| ctx.decode(lt));
    if let EntityKind::Text(Text { value, .. }) | EntityKind::MText(MText { value, .. }) =
        &mut e.kind
    {
        for raw in r.text_1.iter().chain(&r.pieces) {
            decode_value_into(ctx.enc, raw, value);
        }
    }
    Ok(Some(e))
}
