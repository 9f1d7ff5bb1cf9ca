//! Streaming reader for the part of DXF that path drawings use.
//!
//! It knows nothing about milling paths: it returns the header values, the LAYER and LTYPE
//! tables and the model-space LINE, ARC, CIRCLE, TEXT and MTEXT entities, each with the line
//! number where it starts, so that every later message can point into the file. Every other
//! entity is counted and skipped, as the reference tool does. Malformed input gives a
//! [`DxfError`] with a line number; the reader never panics.

mod blocks;
mod decode;
mod entity;
pub mod explode;
mod extra;
mod lines;
mod reader;
pub mod splice;
mod tokens;
pub mod units;
pub mod writer;

pub use decode::decode_unicode_escapes;
pub use extra::{Block, Extra, ExtraKind, Insert, Polyline, Vertex};
pub use reader::read_dxf;

use std::collections::BTreeMap;
use std::fmt;

/// A 3-D point as read from group codes 10/20/30 (or 11/21/31, 210/220/230).
pub type Point3 = [f64; 3];

/// Everything the path compiler needs from one DXF file.
#[derive(Debug, Clone, Default)]
pub struct Drawing {
    /// `$ACADVER`, e.g. `AC1015`; empty when the header has none.
    pub version: String,
    /// `$DWGCODEPAGE` as written, e.g. `ANSI_1252`.
    pub codepage: String,
    /// `$TEXTSIZE`, the default text height (2.5 when absent).
    pub text_size: f64,
    /// Layer name → layer line type name (as written in the LAYER table, group 6).
    pub layers: BTreeMap<String, String>,
    /// Line type names of the LTYPE table, in table order.
    pub linetypes: Vec<String>,
    /// Model-space entities of the supported kinds, in file order.
    pub entities: Vec<Entity>,
    /// Number of model-space entities of other kinds (ignored).
    pub ignored_entities: usize,
    /// `$INSUNITS` (0 = unitless, 1 = inches, 4 = millimetres, …), `None` when absent.
    pub insunits: Option<i32>,
    /// Model-space geometry the reference ignores (polylines, block references, ellipses,
    /// splines), in file order: read for the extended input mode and its warnings.
    pub extra: Vec<Extra>,
    /// The BLOCKS section: block name → its base point and entities (model and paper space
    /// blocks left out).
    pub blocks: BTreeMap<String, Block>,
    /// Malformed polylines, inserts and block contents: dropped here (the reference ignores
    /// these entities, so they must not cost it the file); an error in the extended mode.
    pub extra_errors: Vec<DxfError>,
}

/// One supported entity with its common properties.
#[derive(Debug, Clone, PartialEq)]
pub struct Entity {
    /// 1-based line number of the `0` group code that starts the entity.
    pub line: usize,
    /// Handle (group 5), empty when the file has none (R12 may omit it).
    pub handle: String,
    /// Layer name (group 8), `0` when absent.
    pub layer: String,
    /// Own line type name (group 6), `None` when absent (= ByLayer).
    pub linetype: Option<String>,
    /// Line type scale (group 48), 1 when absent.
    pub linetype_scale: f64,
    /// Extrusion direction (210/220/230), +Z when absent.
    pub extrusion: Point3,
    pub kind: EntityKind,
}

#[derive(Debug, Clone, PartialEq)]
pub enum EntityKind {
    Line {
        start: Point3,
        end: Point3,
    },
    Circle {
        center: Point3,
        radius: f64,
    },
    Arc {
        center: Point3,
        radius: f64,
        start_angle: f64,
        end_angle: f64,
    },
    Text(Text),
    MText(MText),
}

impl EntityKind {
    /// The DXF entity type name (`LINE`, `CIRCLE`, …).
    pub fn code_name(&self) -> &'static str {
        match self {
            EntityKind::Line { .. } => "LINE",
            EntityKind::Circle { .. } => "CIRCLE",
            EntityKind::Arc { .. } => "ARC",
            EntityKind::Text(_) => "TEXT",
            EntityKind::MText(_) => "MTEXT",
        }
    }
}

/// A TEXT entity (single-line text).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Text {
    /// Group 1, after `\U+XXXX` decoding.
    pub value: String,
    /// First alignment point (10/20/30).
    pub first: Point3,
    /// Second alignment point (11/21/31), if present.
    pub second: Option<Point3>,
    /// Height (40).
    pub height: f64,
    /// Rotation in degrees (50).
    pub rotation: f64,
    /// Text generation flags (71): 2 = backwards, 4 = upside down.
    pub generation: i32,
    /// Horizontal justification (72).
    pub halign: i32,
    /// Vertical justification (73).
    pub valign: i32,
}

/// An MTEXT entity (paragraph text, still with its formatting codes).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MText {
    /// Groups 3 and 1 concatenated in file order, after `\U+XXXX` decoding.
    pub value: String,
    /// Insertion point (10/20/30).
    pub insert: Point3,
    /// Nominal height (40).
    pub height: f64,
    /// Attachment point (71), 1 (top left) when absent.
    pub attachment: i32,
    /// Rotation in degrees (50), if present.
    pub rotation: Option<f64>,
    /// X axis direction (11/21/31), if present.
    pub direction: Option<Point3>,
}

/// A file that cannot be read as DXF, with the line where reading stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct DxfError {
    /// 1-based line number (0 when the problem is not tied to a line).
    pub line: usize,
    pub kind: DxfErrorKind,
}

#[derive(Debug, Clone, PartialEq)]
pub enum DxfErrorKind {
    /// The file ends in the middle of a group (code without value).
    Truncated,
    /// A group code line that is not an integer.
    BadGroupCode(String),
    /// A numeric value that does not parse.
    BadNumber { code: i32, value: String },
    /// Binary DXF is not supported.
    Binary,
    /// No `EOF` / missing sections: not a DXF file at all.
    NotDxf,
    /// UTF-16 text (a byte-order mark): a DXF file is ASCII or UTF-8.
    Utf16 { big_endian: bool },
}

impl fmt::Display for DxfError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            DxfErrorKind::Truncated => {
                write!(f, "line {}: file ends in the middle of a group", self.line)
            }
            DxfErrorKind::BadGroupCode(s) => {
                write!(
                    f,
                    "line {}: '{}' is not a group code",
                    self.line,
                    excerpt(s)
                )
            }
            DxfErrorKind::BadNumber { code, value } => {
                write!(
                    f,
                    "line {}: value '{}' of group {} is not a number",
                    self.line,
                    excerpt(value),
                    code
                )
            }
            DxfErrorKind::Binary => {
                write!(f, "binary DXF files are not supported; export as ASCII DXF")
            }
            DxfErrorKind::Utf16 { big_endian } => {
                let which = if *big_endian { "BE" } else { "LE" };
                write!(
                    f,
                    "the file is UTF-16 {which} text, a DXF must be ASCII or UTF-8 (PowerShell 5's `>` writes UTF-16: write with -o FILE instead)"
                )
            }
            DxfErrorKind::NotDxf => {
                write!(f, "line {}: not a DXF file (no SECTION found)", self.line)
            }
        }
    }
}

impl std::error::Error for DxfError {}

impl DxfError {
    /// The German wording of [`Display`](fmt::Display)'s text, for German reports.
    pub fn german(&self) -> String {
        let line = self.line;
        match &self.kind {
            DxfErrorKind::Truncated => {
                format!("Zeile {line}: die Datei endet mitten in einer Gruppe")
            }
            DxfErrorKind::BadGroupCode(s) => {
                format!("Zeile {line}: '{}' ist kein Gruppencode", excerpt(s))
            }
            DxfErrorKind::BadNumber { code, value } => format!(
                "Zeile {line}: Wert '{}' der Gruppe {code} ist keine Zahl",
                excerpt(value)
            ),
            DxfErrorKind::Binary => {
                "binäre DXF-Dateien werden nicht unterstützt; als ASCII-DXF exportieren".into()
            }
            DxfErrorKind::Utf16 { big_endian } => {
                let which = if *big_endian { "BE" } else { "LE" };
                format!("die Datei ist UTF-16-{which}-Text, eine DXF muss ASCII oder UTF-8 sein (PowerShell 5 schreibt mit `>` UTF-16: stattdessen mit -o DATEI schreiben)")
            }
            DxfErrorKind::NotDxf => {
                format!("Zeile {line}: keine DXF-Datei (kein SECTION gefunden)")
            }
        }
    }
}

/// At most 40 characters of a line, control characters escaped (`\0`, `\u{7f}`): a binary
/// file given as DXF shows a short readable excerpt, never raw bytes.
fn excerpt(s: &str) -> String {
    const MAX: usize = 40;
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i == MAX {
            out.push('…');
            break;
        }
        match c {
            '\0' => out.push_str("\\0"),
            c if c.is_control() => out.extend(c.escape_default()),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_reading_error_has_its_german_wording() {
        let kinds = [
            DxfErrorKind::Truncated,
            DxfErrorKind::BadGroupCode("layer".into()),
            DxfErrorKind::BadNumber {
                code: 10,
                value: "1,5".into(),
            },
            DxfErrorKind::Binary,
            DxfErrorKind::NotDxf,
            DxfErrorKind::Utf16 { big_endian: false },
        ];
        for kind in kinds {
            let e = DxfError { line: 3, kind };
            let (en, de) = (e.to_string(), e.german());
            assert_ne!(en, de);
            for word in ["line ", " not ", " is ", "file "] {
                assert!(!de.contains(word), "{de}");
            }
        }
    }
}
