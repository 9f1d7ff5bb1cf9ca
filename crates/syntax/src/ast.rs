//! The syntax tree: lossless for everything meaningful (comments and blank lines included),
//! with byte spans for every part.

use std::ops::Range;

pub type Span = Range<usize>;

#[derive(Debug, Clone, PartialEq)]
pub struct Spanned<T> {
    pub value: T,
    pub span: Span,
}

impl<T> Spanned<T> {
    pub fn new(value: T, span: Span) -> Self {
        Spanned { value, span }
    }
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct File {
    pub items: Vec<Item>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Item {
    Blank,
    Comment(Spanned<String>),
    Path(PathBlock),
    /// A line that could not be parsed (an error was reported).
    Error(Span),
}

#[derive(Debug, Clone, PartialEq)]
pub struct PathBlock {
    pub name: Spanned<String>,
    /// Comment after `{`.
    pub comment: Option<Spanned<String>>,
    pub items: Vec<PathItem>,
    /// Comment after the closing `}`.
    pub close_comment: Option<Spanned<String>>,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub enum PathItem {
    Blank,
    Comment(Spanned<String>),
    Element(Element),
    Error(Span),
}

/// How a circle's tool works: plain (CONTINUOUS), `mark` (DIVIDE), `bars` (BORDER).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Style {
    Mill,
    Mark,
    Bars,
}

#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Kind {
    /// Markers (PHANTOM circles, DOT for the ignored probe).
    Start,
    End,
    Turn,
    Probe,
    NoProbe,
    /// Lines and arcs.
    Mill,
    Mark,
    Bars,
    Sub,
    Sweep,
    /// HIDDEN: a sweep that carries no parameters.
    Move,
    /// DOT: a skipped subpath embedding, travelled as a sweep.
    Skip,
    /// Circles: drill (Ø = O) and helix (Ø > O).
    Drill(Style),
    Helix(Style),
    /// Any other line type, kept as it is.
    Raw(String),
}

impl Kind {
    /// Every kind an element line can start with (all but `raw`), in the order the manual
    /// lists them.
    pub const ALL: [Kind; 18] = [
        Kind::Start,
        Kind::End,
        Kind::Turn,
        Kind::Probe,
        Kind::NoProbe,
        Kind::Mill,
        Kind::Mark,
        Kind::Bars,
        Kind::Sub,
        Kind::Sweep,
        Kind::Move,
        Kind::Skip,
        Kind::Drill(Style::Mill),
        Kind::Helix(Style::Mill),
        Kind::Drill(Style::Mark),
        Kind::Helix(Style::Mark),
        Kind::Drill(Style::Bars),
        Kind::Helix(Style::Bars),
    ];

    /// The DXF line type the kind stands for.
    pub fn linetype(&self) -> &str {
        match self {
            Kind::Start | Kind::End | Kind::Turn | Kind::Probe => "PHANTOM",
            Kind::NoProbe | Kind::Skip => "DOT",
            Kind::Mill | Kind::Drill(Style::Mill) | Kind::Helix(Style::Mill) => "CONTINUOUS",
            Kind::Mark | Kind::Drill(Style::Mark) | Kind::Helix(Style::Mark) => "DIVIDE",
            Kind::Bars | Kind::Drill(Style::Bars) | Kind::Helix(Style::Bars) => "BORDER",
            Kind::Sub => "DASHDOT",
            Kind::Sweep => "DASHED",
            Kind::Move => "HIDDEN",
            Kind::Raw(lt) => lt,
        }
    }

    /// The marker diameter of marker kinds.
    pub fn marker_diameter(&self) -> Option<f64> {
        match self {
            Kind::Start => Some(1.0),
            Kind::End => Some(2.0),
            Kind::Turn => Some(1.5),
            Kind::Probe | Kind::NoProbe => Some(6.0),
            _ => None,
        }
    }

    /// The words that start an element of this kind.
    pub fn words(&self) -> String {
        match self {
            Kind::Start => "start".into(),
            Kind::End => "end".into(),
            Kind::Turn => "turn".into(),
            Kind::Probe => "probe".into(),
            Kind::NoProbe => "noprobe".into(),
            Kind::Mill => "mill".into(),
            Kind::Mark => "mark".into(),
            Kind::Bars => "bars".into(),
            Kind::Sub => "sub".into(),
            Kind::Sweep => "sweep".into(),
            Kind::Move => "move".into(),
            Kind::Skip => "skip".into(),
            Kind::Drill(s) | Kind::Helix(s) => {
                let base = if matches!(self, Kind::Drill(_)) {
                    "drill"
                } else {
                    "helix"
                };
                match s {
                    Style::Mill => base.into(),
                    Style::Mark => format!("mark {base}"),
                    Style::Bars => format!("bars {base}"),
                }
            }
            Kind::Raw(lt) => format!("raw {}", crate::lexer::quote_if_needed(lt)),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    pub x: f64,
    pub y: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Geometry {
    /// `(x, y)`: markers.
    Point(Point),
    /// `(x1, y1) -> (x2, y2)`
    Line(Point, Point),
    /// `arc (cx, cy) r10 from 270 to 360`: counter-clockwise, angles in degrees as drawn.
    Arc { c: Point, r: f64, a0: f64, a1: f64 },
    /// `(cx, cy) d2`
    Circle { c: Point, d: f64 },
}

impl Geometry {
    /// The arc from `a` to `b` around `c` (`ccw` or clockwise) in the exact form: centre,
    /// radius (|a − c|) and the angles of `a` and `b`, counter-clockwise as DXF stores arcs.
    pub fn arc_through(a: Point, b: Point, c: Point, ccw: bool) -> Geometry {
        let angle = |p: Point| {
            let d = (p.y - c.y).atan2(p.x - c.x).to_degrees();
            if d < 0.0 {
                d + 360.0
            } else {
                d
            }
        };
        let r = (a.x - c.x).hypot(a.y - c.y);
        let (from, to) = if ccw { (a, b) } else { (b, a) };
        Geometry::Arc {
            c,
            r,
            a0: angle(from),
            a1: angle(to),
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Element {
    pub kind: Spanned<Kind>,
    pub geometry: Spanned<Geometry>,
    /// Parameter tokens exactly as in the drawing (`T2`, `B-0,3`, `>8998.2P`, `:B1`).
    pub params: Vec<Spanned<String>>,
    /// Boxed: most lines have none, and a file can have millions of lines.
    pub comment: Option<Box<Spanned<String>>>,
    /// The whole line.
    pub span: Span,
}

impl File {
    pub fn paths(&self) -> impl Iterator<Item = &PathBlock> {
        self.items.iter().filter_map(|i| match i {
            Item::Path(p) => Some(p),
            _ => None,
        })
    }
}

impl PathBlock {
    pub fn elements(&self) -> impl Iterator<Item = &Element> {
        self.items.iter().filter_map(|i| match i {
            PathItem::Element(e) => Some(e),
            _ => None,
        })
    }
}
