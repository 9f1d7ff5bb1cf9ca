//! Rename of a path name across the workspace: every `path NAME` header and every `>NAME`
//! in the text files (open buffers over the disk). Drawings are never edited, so a name that
//! a DXF file defines or embeds is refused rather than left inconsistent.
//!
//! Rename of a path name: every `path NAME` and `>NAME` in the workspace's text files (buffers over
//! the disk); refuses invalid names (the `/n` pattern), names in use, a file whose name no longer
//! covers the path (reference-input.md §3.2) and names a DXF file defines or embeds (naming the
//! drawings); prepareRename.

use crate::common::*;
use crate::navigation::{name_token_at, objects_of_file};
use crate::{workspace_files, Analysis, Workspace};
use millpath_core::load::fs::is_text_file;
use millpath_core::load::names::Patterns;
use millpath_syntax::lexer::{quote_if_needed, quote_param};
use std::path::{Path, PathBuf};

/// One replacement in some file of the workspace.
#[derive(Debug, Clone, PartialEq)]
pub struct FileEdit {
    pub location: Location,
    pub text: String,
}

/// The name under the cursor that can be renamed: its byte range (without the `>`) and the
/// name itself.
pub fn prepare_rename(a: &Analysis, offset: usize) -> Option<(usize, usize, String)> {
    let n = name_token_at(a, offset)?;
    let token = &a.src[n.start..n.end.min(a.src.len())];
    // a plain `>NAME`: the name without its key; a quoted one as a whole
    let start = if !n.is_header && token.starts_with('>') {
        n.start + 1
    } else {
        n.start
    };
    Some((start, n.end, n.name))
}

/// The edits renaming the path name at `offset` to `new_name` in every text file of the
/// workspace, or why it cannot be done (in the document's language).
pub fn rename(
    a: &Analysis,
    ws: &Workspace,
    offset: usize,
    new_name: &str,
) -> Result<Vec<FileEdit>, String> {
    let german = de(a);
    let Some(n) = name_token_at(a, offset) else {
        return Err(if german {
            "hier steht kein Pfadname".into()
        } else {
            "there is no path name here".into()
        });
    };
    let old = n.name.as_str();
    let new = new_name.trim();
    if new == old {
        return Ok(Vec::new());
    }
    let settings = &a.settings.settings;
    let patterns = Patterns::shared(&settings.path_pattern, &settings.file_pattern)
        .map_err(|(_, p, e)| format!("{p}: {e}"))?;
    if !patterns.path_full.is_match(new) || new.contains(['\n', '\r']) {
        return Err(if german {
            format!(
                "`{new}` ist kein gültiger Pfadname: er muss zum Muster für Pfadnamen {} passen (z. B. 1234.1A)",
                settings.path_pattern
            )
        } else {
            format!(
                "`{new}` is not a valid path name: it must match the path-name pattern {} (e.g. 1234.1A)",
                settings.path_pattern
            )
        });
    }
    let mut drawings = Vec::new();
    let mut edits = Vec::new();
    // reasons to refuse, the most important first: a name in use, drawings, file names
    let (mut exists, mut lost) = (None, None);
    for f in workspace_files(ws) {
        if !is_text_file(&f) {
            let objects = objects_of_file(ws, &f);
            let uses = objects
                .iter()
                .any(|o| &*o.path == old || o.text.as_ref().and_then(|t| t.raw('>')) == Some(old));
            if objects.iter().any(|o| &*o.path == new) && exists.is_none() {
                exists = Some(in_use(new, &f, german));
            }
            if uses {
                drawings.push(f);
            }
            continue;
        }
        let Some(text) = ws.text(&f) else { continue };
        let (ast, _) = millpath_syntax::parse(&text);
        let idx = ws.line_index(&text);
        let mut edit = |start: usize, end: usize, text: String| {
            edits.push(FileEdit {
                location: Location {
                    path: f.clone(),
                    start: idx.pos(start),
                    end: idx.pos(end),
                },
                text,
            })
        };
        for p in ast.paths() {
            if p.name.value == new && exists.is_none() {
                exists = Some(in_use(new, &f, german));
            }
            if p.name.value == old {
                if lost.is_none() {
                    lost = lost_by_file_name(&patterns, &f, old, new, german);
                }
                edit(p.name.span.start, p.name.span.end, quote_if_needed(new));
            }
            for el in p.elements() {
                for prm in &el.params {
                    if prm.value.strip_prefix('>') == Some(old) {
                        edit(
                            prm.span.start,
                            prm.span.end,
                            quote_param(&format!(">{new}")),
                        );
                    }
                }
            }
        }
    }
    if let Some(e) = exists {
        return Err(e);
    }
    if !drawings.is_empty() {
        let list = drawings
            .iter()
            .map(|d| d.display().to_string())
            .collect::<Vec<_>>()
            .join(", ");
        return Err(if german {
            format!("{old} wird nicht umbenannt: die DXF-Datei(en) {list} definieren oder verwenden den Namen, und Zeichnungen werden nicht bearbeitet; zuerst dort umbenennen")
        } else {
            format!("{old} is not renamed: the DXF file(s) {list} define or embed the name, and drawings are not edited; rename it there first")
        });
    }
    match lost {
        Some(e) => Err(e),
        None => Ok(edits),
    }
}

fn in_use(new: &str, file: &Path, german: bool) -> String {
    if german {
        format!("in {} gibt es schon einen Pfad {new}", file.display())
    } else {
        format!("a path named {new} already exists in {}", file.display())
    }
}

/// A file found by its name for `old` that its name no longer covers under `new` (the
/// subpath search looks at file names, RI §3.2).
fn lost_by_file_name(
    patterns: &Patterns,
    file: &Path,
    old: &str,
    new: &str,
    german: bool,
) -> Option<String> {
    let stem = file.file_stem()?.to_string_lossy().into_owned();
    if !patterns.file_contains(&stem, old) || patterns.file_contains(&stem, new) {
        return None;
    }
    let name = PathBuf::from(file.file_name()?);
    Some(if german {
        format!("Teilpfade werden über den Dateinamen gefunden, und {} passt nicht zu {new}: einen passenden Namen wählen oder die Datei umbenennen", name.display())
    } else {
        format!("subpaths are found by their file name, and {} does not cover {new}: choose a name it covers or rename the file", name.display())
    })
}
