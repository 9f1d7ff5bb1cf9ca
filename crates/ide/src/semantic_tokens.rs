//! Semantic tokens for highlighting.

use crate::Analysis;
use millpath_syntax::{Item, PathItem};

/// Semantic token types, in the order of the legend.
pub const TOKEN_TYPES: &[&str] = &[
    "keyword", "number", "property", "string", "comment", "type", "operator",
];

#[derive(Debug, Clone, PartialEq)]
pub struct SemToken {
    pub start: usize,
    pub end: usize,
    pub kind: u32,
}

pub fn semantic_tokens(a: &Analysis) -> Vec<SemToken> {
    let mut out = Vec::new();
    let push = |out: &mut Vec<SemToken>, start: usize, end: usize, kind: u32| {
        if end > start {
            out.push(SemToken { start, end, kind });
        }
    };
    for item in &a.ast.items {
        match item {
            Item::Comment(c) => push(&mut out, c.span.start, c.span.end, 4),
            Item::Path(p) => {
                push(&mut out, p.span.start, p.span.start + 4, 0);
                push(&mut out, p.name.span.start, p.name.span.end, 5);
                if let Some(c) = &p.comment {
                    push(&mut out, c.span.start, c.span.end, 4);
                }
                for pi in &p.items {
                    match pi {
                        PathItem::Comment(c) => push(&mut out, c.span.start, c.span.end, 4),
                        PathItem::Element(e) => {
                            push(&mut out, e.kind.span.start, e.kind.span.end, 0);
                            // numbers of the geometry
                            let g = &a.src[e.geometry.span.clone()];
                            let mut i = 0;
                            let bytes = g.as_bytes();
                            while i < bytes.len() {
                                let c = bytes[i] as char;
                                if c.is_ascii_digit()
                                    || ((c == '-' || c == '.')
                                        && i + 1 < bytes.len()
                                        && (bytes[i + 1] as char).is_ascii_digit())
                                {
                                    let s = i;
                                    while i < bytes.len()
                                        && ((bytes[i] as char).is_ascii_digit()
                                            || matches!(bytes[i], b'.' | b'-' | b'e' | b'E' | b'+'))
                                    {
                                        i += 1;
                                    }
                                    push(
                                        &mut out,
                                        e.geometry.span.start + s,
                                        e.geometry.span.start + i,
                                        1,
                                    );
                                } else if g[i..].starts_with("->") {
                                    push(
                                        &mut out,
                                        e.geometry.span.start + i,
                                        e.geometry.span.start + i + 2,
                                        6,
                                    );
                                    i += 2;
                                } else {
                                    i += 1;
                                }
                            }
                            for p in &e.params {
                                let k = p.value.chars().next().map_or(1, char::len_utf8);
                                push(&mut out, p.span.start, p.span.start + k, 2);
                                push(&mut out, p.span.start + k, p.span.end, 3);
                            }
                            if let Some(c) = &e.comment {
                                push(&mut out, c.span.start, c.span.end, 4);
                            }
                        }
                        _ => {}
                    }
                }
            }
            _ => {}
        }
    }
    out.sort_by_key(|t| t.start);
    out
}
