//! Shared helpers of the features: edits, locations, finding elements and paths.
//!
//! Shared helpers: `TextEdit`, `Location`, the element/path at an offset, subpath lookup.

use crate::{Analysis, Pos, Workspace};
use millpath_core::diag::Origin;
use millpath_core::front::drawing::{RawPath, RawSegment};
use millpath_core::{Lang, Session};
use millpath_syntax::{Element, Kind, PathBlock};
use std::path::{Path, PathBuf};

/// A replacement of the byte range `start..end` of the document.
#[derive(Debug, Clone, PartialEq)]
pub struct TextEdit {
    pub start: usize,
    pub end: usize,
    pub text: String,
}

/// A place in some file: positions are 0-based lines and UTF-16 columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Location {
    pub path: PathBuf,
    pub start: Pos,
    pub end: Pos,
}

pub(crate) fn de(a: &Analysis) -> bool {
    a.settings.settings.lang == Lang::De
}

/// The path block and element at a byte offset.
pub fn element_at(a: &Analysis, offset: usize) -> Option<(&PathBlock, &Element)> {
    a.ast.paths().find_map(|p| {
        p.elements()
            .find(|e| e.span.start <= offset && offset <= e.span.end)
            .map(|e| (p, e))
    })
}

pub(crate) fn object_index(a: &Analysis, el: &Element) -> Option<usize> {
    a.object_at(el.span.start)
}

pub(crate) fn raw_path<'a>(a: &'a Analysis, name: &str) -> Option<&'a RawPath> {
    a.paths.iter().find(|p| p.name == name).map(|p| &**p)
}

pub(crate) fn segment_of<'a>(
    a: &'a Analysis,
    el: &Element,
) -> Option<(&'a RawPath, Option<&'a RawSegment>)> {
    let i = object_index(a, el)?;
    let path = raw_path(a, &a.objects[i].path)?;
    Some((path, path.segments.iter().find(|s| s.object == i)))
}

pub(crate) fn lookup(ws: &Workspace, from: &Path, name: &str) -> Option<std::sync::Arc<RawPath>> {
    let fs = ws.fs();
    let settings = ws.settings_for(from).settings;
    let mut session = Session::new(settings, &fs).ok()?;
    session.load_file(from);
    session.lookup(name, from)
}

/// Where a path is defined: the name in its `path NAME` header in a text file, the start
/// marker's entity line in a drawing.
pub(crate) fn location_of(ws: &Workspace, raw: &RawPath) -> Location {
    if millpath_core::load::fs::is_text_file(&raw.file.path) {
        if let Some(text) = ws.text(&raw.file.path) {
            let (ast, _) = millpath_syntax::parse(&text);
            let name = ast
                .paths()
                .find(|p| p.name.value == raw.name)
                .map(|p| p.name.span.clone());
            if let Some(span) = name {
                let idx = ws.line_index(&text);
                return Location {
                    path: raw.file.path.clone(),
                    start: idx.pos(span.start),
                    end: idx.pos(span.end),
                };
            }
        }
    }
    let origin = raw.start_origin();
    match origin {
        Origin::Span {
            file, start, end, ..
        } => {
            let text = ws.text(&file.path).unwrap_or_default();
            let idx = ws.line_index(&text);
            Location {
                path: file.path.clone(),
                start: idx.pos(start as usize),
                end: idx.pos(end as usize),
            }
        }
        Origin::Entity(e) => {
            let line = e.line.saturating_sub(1) as u32;
            Location {
                path: e.file.path.clone(),
                start: Pos { line, col: 0 },
                end: Pos { line, col: 0 },
            }
        }
        o => {
            let path = o.file().map(|f| f.path.clone()).unwrap_or_default();
            Location {
                path,
                start: Pos { line: 0, col: 0 },
                end: Pos { line: 0, col: 0 },
            }
        }
    }
}

pub(crate) fn start_element<'a>(a: &'a Analysis, path_name: &str) -> Option<&'a Element> {
    a.ast
        .paths()
        .filter(|p| p.name.value == path_name)
        .flat_map(|p| p.elements())
        .find(|e| matches!(e.kind.value, Kind::Start))
}

pub(crate) fn path_at(a: &Analysis, offset: usize) -> Option<&PathBlock> {
    a.ast
        .paths()
        .find(|p| p.span.start <= offset && offset <= p.span.end)
}

/// A span without the line break (and blanks) its syntax node ends with.
pub(crate) fn trimmed(a: &Analysis, span: &std::ops::Range<usize>) -> (usize, usize) {
    let end = span.end.min(a.src.len());
    let start = span.start.min(end);
    (start, start + a.src[start..end].trim_end().len())
}
