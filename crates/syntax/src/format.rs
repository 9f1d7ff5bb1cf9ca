//! The canonical formatter: the only writer of MillPath text.

use crate::ast::*;
use crate::lexer::{quote_if_needed, quote_param};

use std::fmt::Write;

/// A number in its shortest exact decimal form (`-0` keeps its sign: it can show in G-code).
pub fn num(v: f64) -> String {
    format!("{v}")
}

pub fn point(p: Point) -> String {
    let mut s = String::new();
    write_point(&mut s, p);
    s
}

pub fn geometry(g: &Geometry) -> String {
    let mut s = String::new();
    write_geometry(&mut s, g);
    s
}

/// One element line without indentation.
pub fn element(e: &Element) -> String {
    let mut s = String::new();
    write_element(&mut s, e);
    s
}

// The writers below append to one line (a file's formatting makes no string per number).
// Writing into a `String` cannot fail.

fn write_point(out: &mut String, p: Point) {
    let _ = write!(out, "({}, {})", p.x, p.y);
}

fn write_geometry(out: &mut String, g: &Geometry) {
    match g {
        Geometry::Point(p) => write_point(out, *p),
        Geometry::Line(a, b) => {
            write_point(out, *a);
            out.push_str(" -> ");
            write_point(out, *b);
        }
        Geometry::Arc { c, r, a0, a1 } => {
            out.push_str("arc ");
            write_point(out, *c);
            let _ = write!(out, " r{r} from {a0} to {a1}");
        }
        Geometry::Circle { c, d } => {
            write_point(out, *c);
            let _ = write!(out, " d{d}");
        }
    }
}

fn write_element(out: &mut String, e: &Element) {
    out.push_str(&e.kind.value.words());
    out.push(' ');
    write_geometry(out, &e.geometry.value);
    for (i, p) in e.params.iter().enumerate() {
        out.push_str(if i == 0 { "  " } else { " " });
        out.push_str(&quote_param(&p.value));
    }
    if let Some(c) = &e.comment {
        out.push_str("  ");
        out.push_str(c.value.trim_end());
    }
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
                        PathItem::Element(e) => {
                            let mut line = String::from("  ");
                            write_element(&mut line, e);
                            out.push(line);
                        }
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
