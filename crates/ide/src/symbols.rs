//! Document and workspace symbols.

use crate::common::*;
use crate::{workspace_files, Analysis, Workspace};
use millpath_core::Session;

#[derive(Debug, Clone, PartialEq)]
pub struct Symbol {
    pub name: String,
    pub detail: String,
    /// `true` for paths, `false` for elements.
    pub is_path: bool,
    pub start: usize,
    pub end: usize,
    /// The name within `start..end` (the path's name, the element's kind and geometry).
    pub name_start: usize,
    pub name_end: usize,
    pub children: Vec<Symbol>,
}

pub fn document_symbols(a: &Analysis) -> Vec<Symbol> {
    a.ast
        .paths()
        .map(|p| Symbol {
            name: p.name.value.clone(),
            detail: format!("{} elements", p.elements().count()),
            is_path: true,
            start: p.span.start,
            end: p.span.end,
            name_start: p.name.span.start,
            name_end: p.name.span.end,
            children: p
                .elements()
                .map(|e| Symbol {
                    name: format!(
                        "{} {}",
                        e.kind.value.words(),
                        millpath_syntax::format::geometry(&e.geometry.value)
                    ),
                    detail: e
                        .params
                        .iter()
                        .map(|p| p.value.as_str())
                        .collect::<Vec<_>>()
                        .join(" "),
                    is_path: false,
                    start: e.span.start,
                    end: e.span.end,
                    name_start: e.kind.span.start,
                    name_end: e.geometry.span.end,
                    children: Vec::new(),
                })
                .collect(),
        })
        .collect()
}

/// Paths of every workspace file whose name contains `query` (case-insensitive).
pub fn workspace_symbols(ws: &Workspace, query: &str) -> Vec<(String, Location)> {
    let q = query.to_lowercase();
    let mut out = Vec::new();
    for f in workspace_files(ws) {
        let fs = ws.fs();
        let Ok(mut session) = Session::new(ws.settings_for(&f).settings, &fs) else {
            continue;
        };
        for name in session.load_file(&f) {
            if name.to_lowercase().contains(&q) {
                if let Some(raw) = session.raw_path(&name) {
                    out.push((name, location_of(ws, &raw)));
                }
            }
        }
    }
    out
}
