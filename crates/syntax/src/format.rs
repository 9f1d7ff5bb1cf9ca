//! The canonical formatter: the only writer of MillPath text.

use crate::ast::*;
use crate::lexer::{quote_if_needed, quote_param};

/// A number in its shortest exact decimal form (`-0` keeps its sign: it can show in G-code).
pub fn num(v: f64) -> String {
    format!("{v}")
}

pub fn point(p: Point) -> String {
    format!("({}, {})", num(p.x), num(p.y))
}

pub fn geometry(g: &Geometry) -> String {
    match g {
        Geometry::Point(p) => point(*p),
        Geometry::Line(a, b) => format!("{} -> {}", point(*a), point(*b)),
        Geometry::Arc { c, r, a0, a1 } => format!(
            "arc {} r{} from {} to {}",
            point(*c),
            num(*r),
            num(*a0),
            num(*a1)
        ),
        Geometry::Circle { c, d } => format!("{} d{}", point(*c), num(*d)),
    }
}

/// One element line without indentation.
pub fn element(e: &Element) -> String {
    let mut s = format!("{} {}", e.kind.value.words(), geometry(&e.geometry.value));
    if !e.params.is_empty() {
        s.push_str("  ");
        s.push_str(
            &e.params
                .iter()
                .map(|p| quote_param(&p.value))
                .collect::<Vec<_>>()
                .join(" "),
        );
    }
    if let Some(c) = &e.comment {
        s.push_str("  ");
        s.push_str(c.value.trim_end());
    }
    s
}

/// Formats a file. Lines that did not parse are kept as they are (taken from `src`).
pub fn format(file: &File, src: &str) -> String {
    let mut out = Vec::<String>::new();
    let push_blank = |out: &mut Vec<String>| {
        if out
            .last()
            .is_some_and(|l| !l.is_empty() && !l.ends_with('{'))
        {
            out.push(String::new());
        }
    };
    for item in &file.items {
        match item {
            Item::Blank => push_blank(&mut out),
            Item::Comment(c) => out.push(c.value.trim_end().to_string()),
            Item::Error(span) => {
                out.push(src.get(span.clone()).unwrap_or("").trim_end().to_string())
            }
            Item::Path(p) => {
                let mut head = format!("path {} {{", quote_if_needed(&p.name.value));
                if let Some(c) = &p.comment {
                    head.push_str("  ");
                    head.push_str(c.value.trim_end());
                }
                out.push(head);
                for pi in &p.items {
                    match pi {
                        PathItem::Blank => push_blank(&mut out),
                        PathItem::Comment(c) => out.push(format!("  {}", c.value.trim_end())),
                        PathItem::Element(e) => out.push(format!("  {}", element(e))),
                        PathItem::Error(span) => {
                            out.push(format!("  {}", src.get(span.clone()).unwrap_or("").trim()))
                        }
                    }
                }
                while out.last().is_some_and(String::is_empty) {
                    out.pop();
                }
                match &p.close_comment {
                    Some(c) => out.push(format!("}}  {}", c.value.trim_end())),
                    None => out.push("}".into()),
                }
            }
        }
    }
    while out.last().is_some_and(String::is_empty) {
        out.pop();
    }
    let mut s = out.join("\n");
    s.push('\n');
    s
}
