//! Conversions between LSP types and the plain data of `millpath-ide`: URIs and paths
//! (made-up paths for untitled buffers), positions in the negotiated encoding, ranges,
//! edits, locations and diagnostics.

use millpath_core::diag::{Diagnostic as CoreDiagnostic, Origin, Severity};
use millpath_ide::{Analysis, LineIndex, Pos, Workspace};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use tower_lsp_server::ls_types::*;

/// Buffers opened with the language id `millpath` whose file name is not `*.mpath`.
pub(crate) static TEXT_BUFFERS: Mutex<Vec<String>> = Mutex::new(Vec::new());

/// Made-up paths and the documents they stand for, so answers go back to the editor's URI.
pub(crate) static MADE_UP: Mutex<Vec<(PathBuf, String)>> = Mutex::new(Vec::new());

pub(crate) fn made_up(path: PathBuf, uri: &Uri) -> PathBuf {
    if let Ok(mut m) = MADE_UP.lock() {
        if !m.iter().any(|(p, _)| *p == path) {
            m.push((path.clone(), uri.as_str().to_string()));
        }
    }
    path
}

/// The path of a document. A `file:` URI is its path; any other (an editor's `untitled:`
/// buffer, …) and a buffer opened as `millpath` get a made-up `*.mpath` path: text, never a
/// drawing to load.
pub(crate) fn to_path(uri: &Uri) -> Option<PathBuf> {
    let text = TEXT_BUFFERS
        .lock()
        .is_ok_and(|b| b.iter().any(|u| u == uri.as_str()));
    if uri.scheme().as_str() != "file" {
        let name: String = uri
            .as_str()
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' || c == '.' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        return Some(made_up(
            std::env::temp_dir()
                .join("millpath-buffers")
                .join(format!("{name}.mpath")),
            uri,
        ));
    }
    let p = uri.to_file_path()?.into_owned();
    Some(if text && !millpath_core::load::fs::is_text_file(&p) {
        let ext = format!(
            "{}.mpath",
            p.extension().and_then(|e| e.to_str()).unwrap_or("")
        );
        made_up(p.with_extension(ext), uri)
    } else {
        p
    })
}

pub(crate) fn to_uri(path: &Path) -> Option<Uri> {
    let original = MADE_UP.lock().ok().and_then(|m| {
        m.iter()
            .find(|(p, _)| p == path)
            .and_then(|(_, u)| u.parse::<Uri>().ok())
    });
    original.or_else(|| Uri::from_file_path(path))
}

pub(crate) fn pos(p: Pos) -> Position {
    Position {
        line: p.line,
        character: p.col,
    }
}

pub(crate) fn range(idx: &LineIndex, start: usize, end: usize) -> Range {
    Range {
        start: pos(idx.pos(start)),
        end: pos(idx.pos(end)),
    }
}

pub(crate) fn offset(a: &Analysis, p: Position) -> usize {
    a.index.offset(Pos {
        line: p.line,
        col: p.character,
    })
}

pub(crate) fn internal_error_diagnostic() -> Vec<Diagnostic> {
    vec![Diagnostic {
        message: "millpath: internal error while analysing this file".into(),
        severity: Some(DiagnosticSeverity::ERROR),
        ..Default::default()
    }]
}

/// Applies one incremental change (an LSP range in the negotiated encoding) to a text.
/// The text is scanned up to the edited lines only (no index of every line, no copy: this is
/// on the way from a keystroke to its diagnostics).
pub fn apply_edit(text: &mut String, r: Range, new_text: &str, utf8: bool) {
    let at = |p: Position| {
        LineIndex::offset_in(
            text,
            Pos {
                line: p.line,
                col: p.character,
            },
            utf8,
        )
    };
    let (start, end) = (at(r.start), at(r.end));
    let (start, end) = (start.min(end), end.max(start));
    text.replace_range(start..end, new_text);
}

pub(crate) fn location(origin: &Origin, ws: &Workspace) -> Option<Location> {
    match origin {
        Origin::Span {
            file, start, end, ..
        } => {
            let text = ws.text(&file.path)?;
            let idx = ws.line_index(&text);
            Some(Location {
                uri: to_uri(&file.path)?,
                range: range(&idx, *start as usize, *end as usize),
            })
        }
        Origin::Entity(e) => {
            let line = e.line.saturating_sub(1) as u32;
            let p = Position { line, character: 0 };
            Some(Location {
                uri: to_uri(&e.file.path)?,
                range: Range { start: p, end: p },
            })
        }
        _ => None,
    }
}

pub(crate) fn to_lsp_diagnostic(a: &Analysis, ws: &Workspace, d: &CoreDiagnostic) -> Diagnostic {
    let lang = a.settings.settings.lang;
    let related: Vec<DiagnosticRelatedInformation> = d
        .related
        .iter()
        .filter_map(|r| {
            Some(DiagnosticRelatedInformation {
                location: location(&r.origin, ws)?,
                message: r.note.clone(),
            })
        })
        .collect();
    Diagnostic {
        range: millpath_ide::diagnostic_range(a, &d.origin)
            .map(|(s, e)| range(&a.index, s, e))
            .unwrap_or_default(),
        severity: Some(if d.severity == Severity::Error {
            DiagnosticSeverity::ERROR
        } else {
            DiagnosticSeverity::WARNING
        }),
        code: Some(NumberOrString::String(d.msg.code())),
        source: Some("millpath".into()),
        message: d.message(lang),
        related_information: if related.is_empty() {
            None
        } else {
            Some(related)
        },
        ..Default::default()
    }
}

/// All diagnostics of a document as LSP diagnostics.
pub(crate) fn lsp_diagnostics(a: &Analysis, ws: &Workspace) -> Vec<Diagnostic> {
    a.diagnostics
        .iter()
        .map(|d| to_lsp_diagnostic(a, ws, d))
        .collect()
}

pub(crate) fn edit(a: &Analysis, e: &millpath_ide::TextEdit) -> TextEdit {
    TextEdit {
        range: range(&a.index, e.start, e.end),
        new_text: e.text.clone(),
    }
}

pub(crate) fn loc(l: &millpath_ide::Location) -> Option<Location> {
    Some(Location {
        uri: to_uri(&l.path)?,
        range: Range {
            start: pos(l.start),
            end: pos(l.end),
        },
    })
}
