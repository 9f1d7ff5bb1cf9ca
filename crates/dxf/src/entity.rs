//! One entity record of the ENTITIES section or a block: the group codes of LINE, ARC,
//! CIRCLE, TEXT and MTEXT and the entity they make; records split at their `0` groups, and
//! kept values decoded once the code page is known (`Ctx`).

use crate::decode::decode_value_into;
use crate::tokens::{int, num, raw_str, Pair};
use crate::{DxfError, Entity, EntityKind, MText, Point3, Text};
use encoding_rs::Encoding;

#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Kind {
    Line,
    Arc,
    Circle,
    Text,
    MText,
}

/// The entity being read: its groups so far (string groups: the last one counts).
pub(crate) struct EntityRecord<'a> {
    kind: Kind,
    line: usize,
    handle: Option<&'a [u8]>,
    pub(crate) layer: Option<&'a [u8]>,
    pub(crate) linetype: Option<&'a [u8]>,
    pub(crate) text_1: Option<&'a [u8]>,
    /// MTEXT groups 1 and 3 in file order.
    pub(crate) pieces: Vec<&'a [u8]>,
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
    pub(crate) paper_space: bool,
}

impl<'a> EntityRecord<'a> {
    /// A new record in place of this one, its pieces buffer kept.
    pub(crate) fn reset(&mut self, kind: Kind, line: usize) {
        let pieces = std::mem::take(&mut self.pieces);
        *self = EntityRecord::new(kind, line, pieces);
    }

    pub(crate) fn new(kind: Kind, line: usize, mut pieces: Vec<&'a [u8]>) -> Self {
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

    #[inline(always)]
    pub(crate) fn group(&mut self, p: &Pair<'a>) -> Result<(), DxfError> {
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
    pub(crate) fn entity(&self) -> Entity {
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
            handle: self.handle.map_or_else(String::new, handle_text),
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

/// [`raw_str`] of a handle, owned: the usual one (hex digits) has nothing to trim or decode.
fn handle_text(h: &[u8]) -> String {
    if h.iter().all(u8::is_ascii_graphic) {
        if let Ok(s) = std::str::from_utf8(h) {
            return s.to_owned();
        }
    }
    raw_str(h).into_owned()
}

/// Decoding of kept values for `extra.rs` and `blocks.rs`.
pub(crate) struct Ctx {
    pub(crate) enc: &'static Encoding,
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
