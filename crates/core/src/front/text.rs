//! The text front-end: a `.mpath` file → drawn objects, the same as the DXF front-end
//! produces, so that everything after it is shared.
//!
//! `.mpath` → drawn objects (syntax errors as diagnostics with line:column, worded per language by
//! `syntax_diagnostic`).

use crate::args;
use crate::diag::{arg_per_lang, Diagnostic, Diags, FileRef, Msg, Origin};
use crate::front::drawing::{takes_text, DrawnObject, Shape};
use crate::geom::{normalize_angle, Geom, P2};
use crate::params::ParamText;
use millpath_syntax::error::or_list;
use millpath_syntax::{parse, ErrorKind, Expected, Found, Geometry, Kind, Span, SyntaxError};
use std::cell::Cell;
use std::sync::Arc;

/// 1-based line and column of a byte offset.
pub fn line_col(src: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(src.len());
    let before = &src[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before
        .rfind('\n')
        .map_or(before.chars().count(), |p| before[p + 1..].chars().count())
        + 1;
    (line, col)
}

/// Line starts of a text, for many offset → line:column look-ups.
pub struct Lines<'a> {
    src: &'a str,
    starts: Vec<usize>,
    /// The line of the last answer: offsets mostly come in text order, one line or two on.
    last: Cell<usize>,
}

impl<'a> Lines<'a> {
    pub fn new(src: &'a str) -> Lines<'a> {
        let mut starts = vec![0];
        starts.extend(src.match_indices('\n').map(|(i, _)| i + 1));
        Lines {
            src,
            starts,
            last: Cell::new(1),
        }
    }
    /// The 1-based line holding a byte offset (≤ the text's length).
    fn line_of(&self, offset: usize) -> usize {
        let holds = |line: usize| {
            self.starts.get(line - 1).is_some_and(|&s| s <= offset)
                && self.starts.get(line).is_none_or(|&next| offset < next)
        };
        let last = self.last.get();
        let line = [last, last + 1, last + 2]
            .into_iter()
            .find(|&l| holds(l))
            .unwrap_or_else(|| self.starts.partition_point(|&s| s <= offset));
        self.last.set(line);
        line
    }
    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.src.len());
        let line = self.line_of(offset);
        let start = self.starts[line - 1];
        let mut end = offset;
        while !self.src.is_char_boundary(end) {
            end -= 1;
        }
        (line, self.src[start..end].chars().count() + 1)
    }
    pub fn origin(&self, file: &Arc<FileRef>, span: &Span) -> Origin {
        let (line, col) = self.line_col(span.start);
        span_of(file, span, line, col)
    }
}

pub fn span_origin(src: &str, file: &Arc<FileRef>, span: &Span) -> Origin {
    let (line, col) = line_col(src, span.start);
    span_of(file, span, line, col)
}

/// An origin's 32-bit positions (a file is at most 1 GiB; an editor's larger buffer ends at
/// the last position).
pub(crate) fn span_of(file: &Arc<FileRef>, span: &Span, line: usize, col: usize) -> Origin {
    let at = |v: usize| u32::try_from(v).unwrap_or(u32::MAX);
    Origin::Span {
        file: file.clone(),
        start: at(span.start),
        end: at(span.end),
        line: at(line),
        col: at(col),
    }
}

/// A syntax error as a diagnostic whose words follow the message language.
pub fn syntax_diagnostic(e: SyntaxError, origin: Origin) -> Diagnostic {
    let (msg, args) = match e.kind {
        ErrorKind::UnexpectedChar(c) => (Msg::SyntaxUnexpectedChar, args![c]),
        ErrorKind::NotANumber(w) => (Msg::SyntaxNotANumber, args![w]),
        ErrorKind::NotPrefixedNumber { word, prefix } => {
            (Msg::SyntaxNotPrefixed, args![word, prefix])
        }
        ErrorKind::MissingBrace => (Msg::SyntaxMissingBrace, vec![]),
        ErrorKind::UnknownKind {
            word,
            suggestion: Some(s),
        } => (Msg::SyntaxKindDidYouMean, args![word, s]),
        ErrorKind::DidYouMean {
            word,
            suggestion: s,
        } => (Msg::SyntaxDidYouMean, args![word, s]),
        ErrorKind::UnknownKind {
            word,
            suggestion: None,
        } => (Msg::SyntaxUnknownKind, args![word]),
        ErrorKind::DecimalComma { written, fixed } => {
            (Msg::SyntaxDecimalComma, args![written, fixed])
        }
        ErrorKind::Expected { expected, found } => {
            let en: Vec<String> = expected.iter().map(Expected::english).collect();
            let de: Vec<String> = expected.iter().map(expected_de).collect();
            let found_de = match &found {
                Found::Text(t) => format!("`{t}`"),
                Found::EndOfLine => "das Zeilenende".into(),
                Found::EndOfInput => "das Dateiende".into(),
            };
            (
                Msg::SyntaxExpected,
                vec![
                    arg_per_lang(&or_list(&en, "or"), &or_list(&de, "oder")),
                    arg_per_lang(&found.english(), &found_de),
                ],
            )
        }
    };
    Diagnostic::error(msg, origin, args)
}

fn expected_de(e: &Expected) -> String {
    match e {
        Expected::Text(t) => format!("`{t}`"),
        Expected::Number => "eine Zahl".into(),
        Expected::Point => "ein Punkt `(x, y)`".into(),
        Expected::PathName => "ein Pfadname".into(),
        Expected::LineType => "ein Linientyp".into(),
        Expected::EndOfLine => "das Zeilenende".into(),
    }
}

fn p2(p: millpath_syntax::Point) -> P2 {
    P2::new(p.x, p.y)
}

/// Parses a text file into drawn objects. Syntax errors are reported and the rest is used;
/// `Err` aborts the file like the DXF front-end does (e.g. a parameter given twice).
pub fn text_objects(
    src: &str,
    file: &Arc<FileRef>,
    diags: &mut Diags,
) -> Result<TextDrawing, Diagnostic> {
    let (ast, errors) = parse(src);
    objects_of(&ast, errors, src, file, diags)
}

/// Drawn objects of an already parsed text (editors parse once and use the tree twice).
pub fn objects_of(
    ast: &millpath_syntax::File,
    errors: Vec<millpath_syntax::SyntaxError>,
    src: &str,
    file: &Arc<FileRef>,
    diags: &mut Diags,
) -> Result<TextDrawing, Diagnostic> {
    let lines = Lines::new(src);
    for e in errors {
        let origin = lines.origin(file, &e.span);
        diags.push(syntax_diagnostic(e, origin));
    }
    let mut out = Vec::with_capacity(ast.paths().map(|p| p.items.len()).sum());
    let mut names = ElementNames::default();
    let mut declared = Vec::new();
    for path in ast.paths() {
        // one look-up a path, not one an element
        let path_name = names.shared.get(&path.name.value);
        for el in path.elements() {
            let object = element_object(
                el,
                &path_name,
                &mut names,
                &|s| lines.origin(file, s),
                diags,
            )?;
            if let Some(drill) = declared_drill(el) {
                declared.push((out.len(), drill));
            }
            out.push(object);
        }
    }
    Ok(TextDrawing {
        objects: out,
        declared,
    })
}

/// The shared names of a text's objects; its handful of line types found by a comparison
/// or two instead of a hash.
#[derive(Default)]
pub(crate) struct ElementNames {
    pub(crate) shared: crate::front::drawing::SharedNames,
    linetypes: Vec<Arc<str>>,
}

impl ElementNames {
    fn linetype(&mut self, kind: &Kind) -> Arc<str> {
        let name = kind.linetype();
        if let Some(a) = self.linetypes.iter().find(|a| ***a == *name) {
            return a.clone();
        }
        let a = self.shared.get(name);
        // a hostile text's thousands of raw line types are hashed, not searched
        if self.linetypes.len() < 16 {
            self.linetypes.push(a.clone());
        }
        a
    }
}

/// For a circle written as `drill`/`helix`: whether it said drill.
pub(crate) fn declared_drill(el: &millpath_syntax::Element) -> Option<bool> {
    match el.kind.value {
        Kind::Drill(_) => Some(true),
        Kind::Helix(_) => Some(false),
        _ => None,
    }
}

/// The drawn object of one element of the path `path_name`; `origin` locates a span of it.
/// What it reads: the element, the path's name and where the element is (line, column).
pub(crate) fn element_object(
    el: &millpath_syntax::Element,
    path_name: &Arc<str>,
    names: &mut ElementNames,
    origin_of: &dyn Fn(&Span) -> Origin,
    diags: &mut Diags,
) -> Result<DrawnObject, Diagnostic> {
    // the element without its trailing comment: what a diagnostic points at
    let end = el
        .params
        .last()
        .map_or(el.geometry.span.end, |p| p.span.end);
    let origin = origin_of(&(el.span.start..end.max(el.geometry.span.end)));
    let linetype = names.linetype(&el.kind.value);
    let shape = match el.geometry.value {
        Geometry::Point(p) => Shape::Circle {
            c: p2(p),
            r: el.kind.value.marker_diameter().unwrap_or(1.0) / 2.0,
        },
        Geometry::Circle { c, d } => Shape::Circle {
            c: p2(c),
            r: d / 2.0,
        },
        Geometry::Line(a, b) => Shape::Path(Geom::Line { a: p2(a), b: p2(b) }),
        Geometry::Arc { c, r, a0, a1 } => Shape::Path(Geom::Arc {
            c: p2(c),
            r,
            a0: normalize_angle(a0),
            a1: normalize_angle(a1),
            ccw: true,
        }),
    };
    if let Shape::Circle { r, .. } | Shape::Path(Geom::Arc { r, .. }) = shape {
        if r <= 0.0 {
            return Err(Diagnostic::error(Msg::BadRadius, origin, args![r]));
        }
    }
    let text = if el.params.is_empty() {
        None
    } else if !takes_text(&linetype, &shape) {
        // the DXF of this text could not attach it: refused, never silently dropped
        let span = el.params[0].span.start..el.params[el.params.len() - 1].span.end;
        let joined: Vec<&str> = el.params.iter().map(|p| p.value.as_str()).collect();
        diags.error(
            Msg::NoTextHere,
            origin_of(&span),
            args![el.kind.value.words(), joined.join(" ")],
        );
        None
    } else {
        let span = el.params[0].span.start..el.params[el.params.len() - 1].span.end;
        let joined: Vec<&str> = el.params.iter().map(|p| p.value.as_str()).collect();
        Some(Box::new(ParamText::parse(
            &joined.join(" "),
            origin_of(&span),
        )?))
    };
    Ok(DrawnObject {
        path: path_name.clone(),
        linetype,
        shape,
        text,
        origin,
    })
}

/// The drawn objects of a text file, and for circles written as `drill`/`helix` which of the
/// two the author said (index into `objects`, `true` = drill).
#[derive(Debug, Clone, Default)]
pub struct TextDrawing {
    pub objects: Vec<DrawnObject>,
    pub declared: Vec<(usize, bool)>,
}

impl TextDrawing {
    /// A warning where the declared kind is not what the path's O makes of the circle.
    pub fn check_declared_kinds(
        &self,
        paths: &[crate::front::drawing::RawPath],
        diags: &mut Diags,
    ) {
        for (i, drill) in &self.declared {
            let o = &self.objects[*i];
            let Shape::Circle { r, .. } = o.shape else {
                continue;
            };
            let Some(path_o) = paths
                .iter()
                .find(|p| *p.name == *o.path)
                .and_then(|p| p.start_text.as_ref())
                .and_then(|t| t.raw('O'))
                .and_then(crate::params::parse_number)
            else {
                continue;
            };
            let is_drill = crate::geom::near(r, path_o / 2.0);
            if is_drill != *drill && r >= path_o / 2.0 {
                let (said, is) = if *drill {
                    ("drill", "helix")
                } else {
                    ("helix", "drill")
                };
                diags.push(Diagnostic::warning(
                    Msg::KindMismatch,
                    o.origin.clone(),
                    args![said, crate::params::fmt_num(path_o), is],
                ));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn objects_from_text() {
        let src = "path 1000.1P {\n  start (0, 0)  O2 T1 :Bx,y\n  mill arc (0, 0) r5 from -90 to 90\n  drill (1, 2) d2\n  raw CENTER (0, 0) -> (1, 1)\n}\n";
        let file = FileRef::new("a.mpath".into());
        let mut d = Diags::default();
        let objs = text_objects(src, &file, &mut d).unwrap().objects;
        assert!(d.list.is_empty());
        assert_eq!(objs.len(), 4);
        assert_eq!(&*objs[0].linetype, "PHANTOM");
        assert_eq!(
            objs[0].shape,
            Shape::Circle {
                c: P2::new(0.0, 0.0),
                r: 0.5
            }
        );
        assert_eq!(objs[0].text.as_ref().unwrap().tokens, ["O2", "T1", ":Bx,y"]);
        assert_eq!(
            objs[1].shape,
            Shape::Path(Geom::Arc {
                c: P2::new(0.0, 0.0),
                r: 5.0,
                a0: 270.0,
                a1: 90.0,
                ccw: true
            })
        );
        assert_eq!(
            objs[2].shape,
            Shape::Circle {
                c: P2::new(1.0, 2.0),
                r: 1.0
            }
        );
        assert_eq!(&*objs[3].linetype, "CENTER");
        assert_eq!(objs[1].origin.context(), "a.mpath:3:3");
    }

    #[test]
    fn syntax_errors_and_aborts() {
        let file = FileRef::new("a.mpath".into());
        let mut d = Diags::default();
        let objs = text_objects(
            "path X {\n  mill (0, 0) ->\n  end (1, 1)\n}\n",
            &file,
            &mut d,
        )
        .unwrap();
        assert_eq!(objs.objects.len(), 1);
        assert_eq!(d.list[0].msg, Msg::SyntaxExpected);
        assert_eq!(d.list[0].origin.context(), "a.mpath:2:17");
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "Expected a point `(x, y)`, found the end of the line"
        );
        assert_eq!(
            d.list[0].message(crate::Lang::De),
            "Erwartet: ein Punkt `(x, y)`; gefunden: das Zeilenende"
        );
        let e = text_objects("path X {\n  start (0, 0)  B1 B2\n}\n", &file, &mut d).unwrap_err();
        assert_eq!(e.msg, Msg::DuplicateParameter);
        assert_eq!(line_col("ab\ncd", 4), (2, 2));
        let l = Lines::new("ab\nüd\n");
        assert_eq!(l.line_col(5), (2, 2));
        assert_eq!(l.line_col(0), (1, 1));
        assert_eq!(l.line_col(7), (3, 1));
    }

    /// The remembered line is only a guess: any order of offsets gives the plain answers.
    #[test]
    fn lines_in_any_order() {
        let src = "a\n\nbc\nüü\n\n\nlast";
        let plain = |o: usize| line_col(src, o);
        let l = Lines::new(src);
        let forward: Vec<usize> = (0..=src.len() + 2).collect();
        let mut order = forward.clone();
        order.extend(forward.iter().rev());
        order.extend(forward.iter().map(|o| (o * 7) % (src.len() + 3)));
        for o in order
            .into_iter()
            .filter(|&o| o > src.len() || src.is_char_boundary(o))
        {
            assert_eq!(l.line_col(o), plain(o.min(src.len())), "offset {o}");
        }
    }
}
