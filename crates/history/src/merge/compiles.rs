//! Which paths of a text compile with errors: `check` in memory on the text alone. Subpaths
//! in other files are not found in any version alike, so comparing versions stays fair.

use millpath_core::diag::{Origin, Severity};
use millpath_core::{compile_file, MemFileSystem, Session, Settings};
use std::collections::BTreeSet;
use std::path::Path;

/// The names of the paths that `check` reports errors for (an error of the file as a whole
/// counts as the path `""`).
pub fn failing_paths(text: &str, settings: &Settings) -> BTreeSet<String> {
    let name = Path::new("merged.mpath");
    let mut fs = MemFileSystem::default();
    fs.add(name, text.as_bytes().to_vec());
    let mut settings = settings.clone();
    settings.check = true;
    let mut failing = BTreeSet::new();
    let Ok(mut session) = Session::new(settings, &fs) else {
        failing.insert(String::new());
        return failing;
    };
    session.one_file = true;
    compile_file(&mut session, name, &millpath_core::banner());
    // the blocks' line ranges, to place an error by its line
    let (file, _) = millpath_syntax::parse(text);
    let starts = line_starts(text);
    let line_of = |byte: usize| starts.partition_point(|&s| s <= byte);
    let blocks: Vec<(usize, usize, &str)> = file
        .paths()
        .map(|p| {
            (
                line_of(p.span.start),
                line_of(p.span.end),
                p.name.value.as_str(),
            )
        })
        .collect();
    for d in session.diags.list.iter() {
        if d.severity != Severity::Error {
            continue;
        }
        let path = match &d.origin {
            Origin::Path { name, .. } => name.to_string(),
            Origin::Span { line, .. } => blocks
                .iter()
                .find(|(a, b, _)| (*a..=*b).contains(&(*line as usize)))
                .map(|(_, _, n)| n.to_string())
                .unwrap_or_default(),
            _ => String::new(),
        };
        failing.insert(path);
    }
    failing
}

/// The byte offset of each line's start.
fn line_starts(text: &str) -> Vec<usize> {
    std::iter::once(0)
        .chain(text.match_indices('\n').map(|(i, _)| i + 1))
        .collect()
}
