//! What the DXF front-end needs from the settings: the path-name patterns, `/x` and the
//! input mode (reference or extended reading).

use crate::load::name_regex::NameRegex;
use regex::Regex;

/// How a DXF drawing's geometry is read.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum InputMode {
    /// As the reference: LINE, ARC, CIRCLE, TEXT, MTEXT; a warning for the rest.
    #[default]
    Reference,
    /// Also polylines, blocks, line-type aliases and units.
    Extended,
}

/// What the front-end needs from the settings.
pub struct FrontOptions<'a> {
    /// The path-name pattern, anchored and case-insensitive (`^(?i:…)$`).
    pub layer_pattern: &'a NameRegex,
    /// The path-name pattern, unanchored and case-sensitive (for `@`).
    pub path_pattern: &'a NameRegex,
    pub pattern_text: &'a str,
    /// `/x`: print the text assignments whose text matches.
    pub debug: Option<&'a Regex>,
    /// Reference or extended reading of polylines, blocks, line types and units.
    pub input: InputMode,
}
