//! One version of a drawing as the diff and the merge see it: its canonical text and, per
//! path, its elements (kind, geometry, parameter words, line in the text).
//!
//! A DXF is read through `dxf2text` (the text the compiler's conversions guarantee compiles
//! alike), a `.mpath` through `fmt`; both give the same text for the same drawing, so an old
//! DXF compares with a new `.mpath`. Several blocks of one path name form one path.

use millpath_core::diag::FileRef;
use millpath_core::load::names::Patterns;
use millpath_core::{Diagnostic, InputMode, Msg, Origin};
use millpath_syntax::{Geometry, Kind};
use std::path::Path;

/// An element of a path in one version.
#[derive(Debug, Clone, PartialEq)]
pub struct Element {
    pub kind: Kind,
    pub geometry: Geometry,
    /// The parameter words as written (`T2`, `B-0,3`, `>8998.2P`).
    pub params: Vec<String>,
    /// Its line in the version's canonical text (1-based).
    pub line: usize,
    /// Its byte offset in the canonical text (the editor's analysis finds it by this).
    pub offset: usize,
}

/// A path of one version: its name and its elements in text order.
#[derive(Debug, Clone, PartialEq)]
pub struct PathVersion {
    pub name: String,
    pub elements: Vec<Element>,
}

/// One version of a drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct Version {
    /// The canonical text (what `dxf2text` or `fmt` writes).
    pub text: String,
    /// Paths sorted by name.
    pub paths: Vec<PathVersion>,
    /// The parsed text when it has no syntax errors (the compile of the version reads it
    /// instead of parsing again).
    pub tree: Option<std::sync::Arc<millpath_syntax::File>>,
}

impl Version {
    /// Reads a version from a file's bytes; `path` says the kind (`.mpath` is text, anything
    /// else a DXF) and locates the errors. A file that does not read (binary, truncated,
    /// syntax errors) is an error with its location.
    pub fn read(
        path: &Path,
        bytes: &[u8],
        patterns: &Patterns,
        input: InputMode,
    ) -> Result<Version, Vec<Diagnostic>> {
        let file = FileRef::new(path.to_path_buf());
        let text = if millpath_core::load::fs::is_text_file(path) {
            let decoded = millpath_core::load::text_file::decode(bytes).map_err(|_| {
                vec![Diagnostic::error(
                    Msg::TextNulBytes,
                    Origin::File(file.clone()),
                    millpath_core::args![path.display()],
                )]
            })?;
            // the canonical form with LF line ends: a CRLF checkout compares as its LF twin
            let (text, tree) = millpath_core::convert::format_text_parsed(&decoded.text, &file)?;
            if text == decoded.text && !text.contains('\r') {
                // canonical already: its tree is the version's (one parse)
                return Ok(Version::of_parsed(text, tree, true));
            }
            text.replace("\r\n", "\n")
        } else {
            millpath_core::convert::dxf_to_text(bytes, &file, patterns, input)
                .map_err(|d| vec![d])?
                .0
        };
        Ok(Version::of_text(text))
    }

    /// A version from canonical text (a text that does not parse gives the paths it has).
    pub fn of_text(text: String) -> Version {
        let (ast, errors) = millpath_syntax::parse(&text);
        let clean = errors.is_empty();
        Version::of_parsed(text, ast, clean)
    }

    /// A version from canonical text and its tree (`clean`: without syntax errors).
    fn of_parsed(text: String, ast: millpath_syntax::File, clean: bool) -> Version {
        let starts = line_starts(&text);
        let mut paths: Vec<PathVersion> = Vec::new();
        for block in ast.paths() {
            let elements = block.elements().map(|e| Element {
                kind: e.kind.value.clone(),
                geometry: e.geometry.value,
                params: e.params.iter().map(|p| p.value.clone()).collect(),
                line: starts.partition_point(|&s| s <= e.span.start),
                offset: e.span.start,
            });
            match paths.iter_mut().find(|p| p.name == block.name.value) {
                Some(p) => p.elements.extend(elements),
                None => paths.push(PathVersion {
                    name: block.name.value.clone(),
                    elements: elements.collect(),
                }),
            }
        }
        paths.sort_by(|a, b| a.name.cmp(&b.name));
        Version {
            text,
            paths,
            tree: clean.then(|| std::sync::Arc::new(ast)),
        }
    }

    /// The path of this name.
    pub fn path(&self, name: &str) -> Option<&PathVersion> {
        self.paths.iter().find(|p| p.name == name)
    }

    /// The number of elements of all paths.
    pub fn element_count(&self) -> usize {
        self.paths.iter().map(|p| p.elements.len()).sum()
    }
}

/// Byte offsets where each line starts.
fn line_starts(text: &str) -> Vec<usize> {
    std::iter::once(0)
        .chain(text.match_indices('\n').map(|(i, _)| i + 1))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_of_one_name_form_one_path_with_lines() {
        let v = Version::of_text(
            "path 2001.1P {\n  start (0, 0)  T3\n}\n\npath 2001.1P {\n  end (30, 0)\n}\n".into(),
        );
        assert_eq!(v.paths.len(), 1);
        let e = &v.paths[0].elements;
        assert_eq!((e[0].line, e[1].line), (2, 6));
        assert_eq!(e[0].params, vec!["T3".to_string()]);
    }
}
