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
mod error;
pub mod explode;
mod extra;
mod lines;
mod reader;
mod record;
pub mod splice;
mod tokens;
pub mod units;
pub mod writer;

pub use decode::decode_unicode_escapes;
pub use entity::{Entity, EntityKind, MText, Point3, Text};
pub use error::{DxfError, DxfErrorKind};
pub use extra::{Block, Extra, ExtraKind, Insert, Polyline, Vertex};
pub use reader::read_dxf;

use std::collections::BTreeMap;

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
