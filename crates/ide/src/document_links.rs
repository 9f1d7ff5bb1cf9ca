//! Document links: each `>NAME` opens the file that defines the subpath.

use crate::common::*;
use crate::{Analysis, Workspace};
use std::collections::HashMap;
use std::path::PathBuf;

#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// The name after `>` (byte offsets).
    pub start: usize,
    pub end: usize,
    pub target: PathBuf,
    /// Line (0-based) of the definition in the target.
    pub line: u32,
}

/// Every `>NAME` of the document whose subpath is found (the same search as the compiler's).
pub fn document_links(a: &Analysis, ws: &Workspace) -> Vec<Link> {
    let mut found: HashMap<String, Option<Location>> = HashMap::new();
    let mut out = Vec::new();
    for p in a.ast.paths() {
        for el in p.elements() {
            for prm in &el.params {
                let Some(name) = prm.value.strip_prefix('>') else {
                    continue;
                };
                let target = found
                    .entry(name.to_string())
                    .or_insert_with(|| lookup(ws, &a.path, name).map(|r| location_of(ws, &r)));
                if let Some(t) = target {
                    let plain = a.src.get(prm.span.clone()) == Some(prm.value.as_str());
                    out.push(Link {
                        start: if plain {
                            prm.span.start + 1
                        } else {
                            prm.span.start
                        },
                        end: prm.span.end,
                        target: t.path.clone(),
                        line: t.start.line,
                    });
                }
            }
        }
    }
    out
}
