//! Tree-sitter grammar of the MillPath text language, for editors (highlighting, folding).
//! The generated parser (`src/parser.c`) is committed; `tree-sitter generate` in this folder
//! regenerates it from `grammar.js`.

use tree_sitter_language::LanguageFn;

extern "C" {
    fn tree_sitter_millpath() -> *const ();
}

/// The tree-sitter language of MillPath.
pub const LANGUAGE: LanguageFn = unsafe { LanguageFn::from_raw(tree_sitter_millpath) };

/// Syntax highlighting query.
pub const HIGHLIGHTS_QUERY: &str = include_str!("../../queries/highlights.scm");
