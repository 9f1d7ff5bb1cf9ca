//! A text as the merge sees it: paths keyed by name, elements keyed by identity, each with
//! the fields a side may change on its own (kind, geometry, parameters, comments).
//!
//! An element's identity: `start` and `end` are one per path (their position is a field,
//! so moving the start on one side and changing its parameters on the other merge); other
//! markers and circles by kind class and position; lines and arcs by their geometry (a line
//! by its two end points, either way round). A repeated identity counts its occurrences.

use millpath_syntax::ast::{Element, File, Geometry, Item, Kind, PathItem};
use millpath_syntax::format;
use millpath_syntax::lexer::{quote_if_needed, quote_param};

/// Identity of a path or an element within its parent, with the occurrence of a repeat.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Key {
    pub class: String,
    pub at: String,
    pub nth: usize,
}

/// One element line and the comment lines above it, as canonical text pieces.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    pub lead: Vec<String>,
    pub kind: String,
    pub geometry: String,
    pub params: String,
    pub comment: String,
}

impl Line {
    fn of(e: &Element, lead: Vec<String>) -> Line {
        Line {
            lead,
            kind: e.kind.value.words(),
            geometry: format::geometry(&e.geometry.value),
            params: e
                .params
                .iter()
                .map(|p| quote_param(&p.value))
                .collect::<Vec<_>>()
                .join(" "),
            comment: e
                .comment
                .as_ref()
                .map(|c| c.value.trim_end().to_string())
                .unwrap_or_default(),
        }
    }

    /// The element line, indented, without its lead comments (as `fmt` writes it).
    pub fn element_line(&self) -> String {
        let mut s = format!("  {} {}", self.kind, self.geometry);
        for part in [&self.params, &self.comment] {
            if !part.is_empty() {
                s.push_str("  ");
                s.push_str(part);
            }
        }
        s
    }

    /// The lead comments and the element line, each line ending in `\n`.
    pub fn render(&self, out: &mut String) {
        for c in &self.lead {
            out.push_str("  ");
            out.push_str(c);
            out.push('\n');
        }
        out.push_str(&self.element_line());
        out.push('\n');
    }
}

/// One `path NAME { … }` block.
#[derive(Debug, Clone, PartialEq)]
pub struct PathDoc {
    /// Comment lines above the block.
    pub lead: Vec<String>,
    pub name: String,
    /// The comment after `{`.
    pub comment: String,
    pub elements: Vec<(Key, Line)>,
    /// Comment lines after the last element.
    pub tail: Vec<String>,
    /// The comment after the closing `}`.
    pub close: String,
}

impl PathDoc {
    pub fn head(&self) -> String {
        head(&self.name, &self.comment)
    }

    /// The whole block, comment lines above it included.
    pub fn render(&self, out: &mut String) {
        for c in &self.lead {
            out.push_str(c);
            out.push('\n');
        }
        out.push_str(&self.head());
        out.push('\n');
        for (_, l) in &self.elements {
            l.render(out);
        }
        for c in &self.tail {
            out.push_str("  ");
            out.push_str(c);
            out.push('\n');
        }
        out.push_str(&close(&self.close));
        out.push('\n');
    }
}

/// `}` with the comment after it.
pub fn close(comment: &str) -> String {
    if comment.is_empty() {
        "}".into()
    } else {
        format!("}}  {comment}")
    }
}

/// `path NAME {` with the comment after it.
pub fn head(name: &str, comment: &str) -> String {
    let mut s = format!("path {} {{", quote_if_needed(name));
    if !comment.is_empty() {
        s.push_str("  ");
        s.push_str(comment);
    }
    s
}

/// A whole text: its paths in order and the comment lines after the last one.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Doc {
    pub paths: Vec<(Key, PathDoc)>,
    pub tail: Vec<String>,
}

/// The identity class and position of an element (see the module doc).
fn identity(kind: &Kind, g: &Geometry) -> (String, String) {
    let class = match kind {
        Kind::Start => return ("start".into(), String::new()),
        Kind::End => return ("end".into(), String::new()),
        Kind::Turn => "turn",
        Kind::Probe | Kind::NoProbe => "probe",
        _ => match g {
            Geometry::Point(_) => "point",
            Geometry::Circle { .. } => "circle",
            Geometry::Line(..) | Geometry::Arc { .. } => "segment",
        },
    };
    let at = match g {
        Geometry::Line(a, b) => {
            let (a, b) = (format::point(*a), format::point(*b));
            if a <= b {
                format!("{a} {b}")
            } else {
                format!("{b} {a}")
            }
        }
        g => format::geometry(g),
    };
    (class.into(), at)
}

/// Numbers repeated identities: the first is 0, the next 1, …
fn numbered<T>(items: Vec<((String, String), T)>) -> Vec<(Key, T)> {
    let mut seen = std::collections::HashMap::<(String, String), usize>::new();
    items
        .into_iter()
        .map(|((class, at), v)| {
            let n = seen.entry((class.clone(), at.clone())).or_default();
            let key = Key { class, at, nth: *n };
            *n += 1;
            (key, v)
        })
        .collect()
}

/// The merge's view of a parsed text (a text with syntax errors is refused before).
pub fn doc_of(file: &File) -> Doc {
    let mut paths = Vec::new();
    let mut lead: Vec<String> = Vec::new();
    for item in &file.items {
        match item {
            Item::Comment(c) => lead.push(c.value.trim_end().to_string()),
            Item::Path(p) => {
                let mut elements = Vec::new();
                let mut el_lead = Vec::new();
                for pi in &p.items {
                    match pi {
                        PathItem::Comment(c) => el_lead.push(c.value.trim_end().to_string()),
                        PathItem::Element(e) => {
                            let id = identity(&e.kind.value, &e.geometry.value);
                            elements.push((id, Line::of(e, std::mem::take(&mut el_lead))));
                        }
                        PathItem::Blank | PathItem::Error(_) => {}
                    }
                }
                let doc = PathDoc {
                    lead: std::mem::take(&mut lead),
                    name: p.name.value.clone(),
                    comment: p
                        .comment
                        .as_ref()
                        .map(|c| c.value.trim_end().to_string())
                        .unwrap_or_default(),
                    elements: numbered(elements),
                    tail: el_lead,
                    close: p
                        .close_comment
                        .as_ref()
                        .map(|c| c.value.trim_end().to_string())
                        .unwrap_or_default(),
                };
                paths.push(((String::from("path"), p.name.value.clone()), doc));
            }
            Item::Blank | Item::Error(_) => {}
        }
    }
    Doc {
        paths: numbered(paths),
        tail: lead,
    }
}
