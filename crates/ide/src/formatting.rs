//! Formatting: the canonical form of a document, or of the paths overlapping a range.

use crate::common::{trimmed, TextEdit};
use crate::{file_ref, Analysis};
use millpath_syntax::{File, Item};

/// The canonical form of the document, when it parses.
pub fn format(a: &Analysis) -> Option<String> {
    // settings and post files are TOML, not MillPath text
    if crate::toml_doc::is_toml(&a.path) {
        return None;
    }
    millpath_core::convert::format_text(&a.src, &file_ref(&a.path)).ok()
}

/// Range formatting: each path block overlapping `start..end` in its canonical form (the
/// rest of the document is left alone); nothing when the text has syntax errors or those
/// paths are already formatted.
pub fn format_range(a: &Analysis, start: usize, end: usize) -> Option<Vec<TextEdit>> {
    if !a.syntax_ok {
        return None;
    }
    let mut edits = Vec::new();
    for p in a.ast.paths() {
        if p.span.end < start || p.span.start > end {
            continue;
        }
        let one = File {
            items: vec![Item::Path(p.clone())],
        };
        let formatted = millpath_syntax::format(&one, &a.src);
        let formatted = formatted.trim_end_matches('\n');
        let (s, e) = trimmed(a, &p.span);
        let original = a.src.get(s..e)?;
        if formatted != original {
            edits.push(TextEdit {
                start: s,
                end: e,
                text: formatted.to_string(),
            });
        }
    }
    Some(edits)
}
