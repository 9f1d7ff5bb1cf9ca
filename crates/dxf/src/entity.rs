//! The entities a path drawing is made of, as read: LINE, ARC, CIRCLE, TEXT and MTEXT with
//! their common properties.

/// A 3-D point as read from group codes 10/20/30 (or 11/21/31, 210/220/230).
pub type Point3 = [f64; 3];

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
