//! Go to definition and find references of subpath names.

use crate::common::*;
use crate::{file_ref, workspace_files, Analysis, Pos, Workspace};
use millpath_core::diag::Origin;
use millpath_core::front::drawing::DrawnObject;

/// A path name in the document: a `>NAME` parameter or the name of a `path NAME` header.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct NameAt {
    pub name: String,
    /// The token in the text (the whole `>NAME` parameter, or the header's name).
    pub start: usize,
    pub end: usize,
    pub is_header: bool,
}

/// The path name at an offset: `>NAME` parameters and `path NAME` headers.
pub(crate) fn name_token_at(a: &Analysis, offset: usize) -> Option<NameAt> {
    if let Some((_, el)) = element_at(a, offset) {
        let p = el
            .params
            .iter()
            .find(|p| p.span.start <= offset && offset <= p.span.end && p.value.starts_with('>'))?;
        return Some(NameAt {
            name: p.value[1..].to_string(),
            start: p.span.start,
            end: p.span.end,
            is_header: false,
        });
    }
    a.ast
        .paths()
        .find(|p| p.name.span.start <= offset && offset <= p.name.span.end)
        .map(|p| NameAt {
            name: p.name.value.clone(),
            start: p.name.span.start,
            end: p.name.span.end,
            is_header: true,
        })
}

pub(crate) fn name_at(a: &Analysis, offset: usize) -> Option<String> {
    name_token_at(a, offset).map(|n| n.name)
}

/// Go to definition of a subpath name.
pub fn definition(a: &Analysis, ws: &Workspace, offset: usize) -> Vec<Location> {
    let Some(name) = name_at(a, offset) else {
        return Vec::new();
    };
    lookup(ws, &a.path, &name)
        .map(|raw| vec![location_of(ws, &raw)])
        .unwrap_or_default()
}

/// Every embedding of a path name in the workspace (text and DXF files).
pub fn references(a: &Analysis, ws: &Workspace, offset: usize) -> Vec<Location> {
    let Some(name) = name_at(a, offset) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for f in workspace_files(ws) {
        let objects = objects_of_file(ws, &f);
        for o in objects {
            let Some(t) = &o.text else { continue };
            if t.raw('>') != Some(name.as_str()) {
                continue;
            }
            match &t.origin {
                Origin::Span { start, end, .. } => {
                    let text = ws.text(&f).unwrap_or_default();
                    let idx = ws.line_index(&text);
                    out.push(Location {
                        path: f.clone(),
                        start: idx.pos(*start as usize),
                        end: idx.pos(*end as usize),
                    });
                }
                Origin::Entity(e) => {
                    let line = e.line.saturating_sub(1) as u32;
                    out.push(Location {
                        path: f.clone(),
                        start: Pos { line, col: 0 },
                        end: Pos { line, col: 0 },
                    });
                }
                _ => {}
            }
        }
    }
    out
}

/// The drawn objects of a workspace file (a text buffer or file, a DXF drawing on disk);
/// empty when it does not load.
pub(crate) fn objects_of_file(ws: &Workspace, f: &std::path::Path) -> Vec<DrawnObject> {
    let fref = file_ref(f);
    if millpath_core::load::fs::is_text_file(f) {
        let Some(text) = ws.text(f) else {
            return Vec::new();
        };
        let mut d = millpath_core::Diags::default();
        return millpath_core::front::text::text_objects(&text, &fref, &mut d)
            .map(|t| t.objects)
            .unwrap_or_default();
    }
    let Ok(bytes) = millpath_core::load::fs::FileSystem::read(&millpath_core::OsFileSystem, f)
    else {
        return Vec::new();
    };
    let Ok(dxf) = millpath_dxf::read_dxf(&bytes) else {
        return Vec::new();
    };
    let s = ws.settings_for(f).settings;
    let Ok(p) = millpath_core::load::names::Patterns::shared(&s.path_pattern, &s.file_pattern)
    else {
        return Vec::new();
    };
    let opts = millpath_core::front::options::FrontOptions {
        layer_pattern: &p.path_full,
        path_pattern: &p.path_cs,
        pattern_text: &p.path_text,
        input: s.input,
        debug: None,
    };
    let mut d = millpath_core::Diags::default();
    millpath_core::front::dxf::dxf_objects(&dxf, &fref, &opts, &mut d)
        .map(|x| x.0)
        .unwrap_or_default()
}
