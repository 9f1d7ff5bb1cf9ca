//! Which paths of a text compile with errors: `check` on the text standing where the drawing
//! is in the work tree (`at`), so subpaths in other files and `millpath.toml` are found as
//! git's merge leaves them there; without a place, in memory on the text alone.

use millpath_core::diag::{Origin, Severity};
use millpath_core::{compile_file, FileSystem, MemFileSystem, OsFileSystem, Session, Settings};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The disk with one text standing at `at` (over a file of that name, if any).
struct Beside<'a> {
    at: &'a Path,
    text: &'a str,
}

impl FileSystem for Beside<'_> {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        if path == self.at {
            Ok(self.text.as_bytes().to_vec())
        } else {
            OsFileSystem.read(path)
        }
    }
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        let mut v = OsFileSystem.list_dir(dir).unwrap_or_default();
        if self.at.parent() == Some(dir) && !v.iter().any(|p| p == self.at) {
            v.push(self.at.to_path_buf());
        }
        Ok(v)
    }
    fn is_dir(&self, dir: &Path) -> bool {
        self.at.parent() == Some(dir) || OsFileSystem.is_dir(dir)
    }
}

/// The names of the paths that `check` reports errors for (an error of the file as a whole
/// counts as the path `""`); `at`: where the text stands (a `.mpath` path in the work tree),
/// `None`: alone in memory.
pub fn failing_paths(text: &str, settings: &Settings, at: Option<&Path>) -> BTreeSet<String> {
    match at {
        Some(at) => failing_in(text, settings, at, &Beside { at, text }),
        None => {
            let name = Path::new("merged.mpath");
            let mut fs = MemFileSystem::default();
            fs.add(name, text.as_bytes().to_vec());
            failing_in(text, settings, name, &fs)
        }
    }
}

fn failing_in(
    text: &str,
    settings: &Settings,
    name: &Path,
    fs: &dyn FileSystem,
) -> BTreeSet<String> {
    let mut settings = settings.clone();
    settings.check = true;
    let mut failing = BTreeSet::new();
    let Ok(mut session) = Session::new(settings, fs) else {
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
