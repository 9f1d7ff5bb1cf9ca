//! Formatting: the canonical form of a document.

use crate::{file_ref, Analysis};

/// The canonical form of the document, when it parses.
pub fn format(a: &Analysis) -> Option<String> {
    millpath_core::convert::format_text(&a.src, &file_ref(&a.path)).ok()
}
