//! Call hierarchy over subpath embedding: a path "calls" the subpaths its elements embed
//! (`>NAME`), in text files and DXF drawings alike.
//!
//! Call hierarchy over subpath embedding: the path named at an offset (header or `>NAME`) where it
//! is defined, the paths embedding it in every workspace file (text and DXF) with the embeddings'
//! ranges, the subpaths it embeds.

use crate::common::{location_of, lookup, Location};
use crate::navigation::{name_token_at, objects_of_file};
use crate::{workspace_files, Analysis, Pos, Workspace};
use millpath_core::diag::Origin;
use std::collections::BTreeMap;
use std::path::Path;

/// A path as a node of the hierarchy: its name and where it is defined (the header's name,
/// a drawing's start marker line).
#[derive(Debug, Clone, PartialEq)]
pub struct CallItem {
    pub name: String,
    pub at: Location,
}

/// A caller or callee with the places of the embeddings (always in the caller's file).
#[derive(Debug, Clone, PartialEq)]
pub struct Call {
    pub item: CallItem,
    pub ranges: Vec<(Pos, Pos)>,
}

/// The path named at `offset` (a `path NAME` header or a `>NAME` embedding), where it is
/// defined; `None` when no path of that name is found.
pub fn prepare_call_hierarchy(a: &Analysis, ws: &Workspace, offset: usize) -> Option<CallItem> {
    let n = name_token_at(a, offset)?;
    let raw = lookup(ws, &a.path, &n.name)?;
    Some(CallItem {
        name: n.name,
        at: location_of(ws, &raw),
    })
}

/// Every path of the workspace (text files and drawings) that embeds `name`, with the
/// ranges of its embeddings.
pub fn incoming_calls(ws: &Workspace, name: &str) -> Vec<Call> {
    let mut out = Vec::new();
    for f in workspace_files(ws) {
        let mut by_caller: BTreeMap<String, Vec<(Pos, Pos)>> = BTreeMap::new();
        for o in objects_of_file(ws, &f) {
            let Some(t) = &o.text else { continue };
            if t.raw('>') != Some(name) {
                continue;
            }
            if let Some(r) = range_of(ws, &f, &t.origin) {
                by_caller.entry(o.path.to_string()).or_default().push(r);
            }
        }
        for (caller, ranges) in by_caller {
            let at = definition_in(ws, &f, &caller).unwrap_or(Location {
                path: f.clone(),
                start: ranges[0].0,
                end: ranges[0].1,
            });
            out.push(Call {
                item: CallItem { name: caller, at },
                ranges,
            });
        }
    }
    out
}

/// The subpaths `item` embeds, each with the ranges of its embeddings in `item`'s file;
/// names no search finds are left out.
pub fn outgoing_calls(ws: &Workspace, item: &CallItem) -> Vec<Call> {
    let file = &item.at.path;
    let mut by_callee: BTreeMap<String, Vec<(Pos, Pos)>> = BTreeMap::new();
    for o in objects_of_file(ws, file) {
        if *o.path != *item.name {
            continue;
        }
        let Some(t) = &o.text else { continue };
        let Some(callee) = t.raw('>') else { continue };
        if let Some(r) = range_of(ws, file, &t.origin) {
            by_callee.entry(callee.to_string()).or_default().push(r);
        }
    }
    by_callee
        .into_iter()
        .filter_map(|(callee, ranges)| {
            let raw = lookup(ws, file, &callee)?;
            Some(Call {
                item: CallItem {
                    name: callee,
                    at: location_of(ws, &raw),
                },
                ranges,
            })
        })
        .collect()
}

/// Where `name` is defined when `file` defines it.
fn definition_in(ws: &Workspace, file: &Path, name: &str) -> Option<Location> {
    let raw = lookup(ws, file, name)?;
    let at = location_of(ws, &raw);
    (at.path == file).then_some(at)
}

/// The range of a parameter text: its span in a text file, its entity's line in a drawing.
fn range_of(ws: &Workspace, file: &Path, origin: &Origin) -> Option<(Pos, Pos)> {
    match origin {
        Origin::Span { start, end, .. } => {
            let text = ws.text(file)?;
            let idx = ws.line_index(&text);
            Some((idx.pos(*start as usize), idx.pos(*end as usize)))
        }
        Origin::Entity(e) => {
            let p = Pos {
                line: e.line.saturating_sub(1) as u32,
                col: 0,
            };
            Some((p, p))
        }
        _ => None,
    }
}
