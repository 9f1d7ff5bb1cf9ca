//! `millpath check` over the whole workspace for pull diagnostics: each drawing's
//! analysis (or why it cannot be read), and a fingerprint of everything an analysis read,
//! so an unchanged file is not analysed again.
//!
//! Pull diagnostics of the whole workspace: the drawings (walk + open buffers), each checked as
//! `check` does (a file that cannot be read: `check`'s message), and the fingerprint of what an
//! analysis read (stamps and folder listings).

use crate::walk::{drawing_files, Walk};
use crate::{analyze_with, Analysis, Workspace};
use millpath_core::diag::{Diagnostic, FileRef, Origin};
use millpath_core::load::fs::{is_text_file, FileSystem};
use millpath_core::Msg;
use std::collections::hash_map::DefaultHasher;
use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

/// The drawings of the workspace folders (bounded walk) and the open text buffers.
pub fn workspace_drawings(ws: &Workspace) -> Walk {
    let mut w = drawing_files(&ws.roots);
    let mut open: Vec<&PathBuf> = ws
        .overlays
        .keys()
        .filter(|p| is_text_file(p) && !w.files.contains(p))
        .collect();
    open.sort();
    w.files.extend(open.into_iter().cloned());
    w
}

/// One drawing checked: its analysis, or the error that stops reading it (as `check`
/// words it).
pub enum FileCheck {
    Analysed(Box<Analysis>),
    Unreadable(Diagnostic),
}

/// Checks one drawing as `millpath check` does (`None` when `cancelled`).
pub fn check_file(ws: &Workspace, path: &Path, cancelled: &dyn Fn() -> bool) -> Option<FileCheck> {
    if is_text_file(path) && !ws.overlays.contains_key(path) {
        // an analysis reads a text it cannot read as empty: say why instead
        let origin = Origin::File(FileRef::new(path.to_path_buf()));
        match ws.fs().read(path) {
            Err(e) => {
                let d = if e.kind() == std::io::ErrorKind::FileTooLarge {
                    Diagnostic::error(
                        Msg::FileTooLarge,
                        origin,
                        millpath_core::args![
                            path.display(),
                            millpath_core::load::fs::MAX_FILE_BYTES >> 20
                        ],
                    )
                } else {
                    Diagnostic::error(
                        Msg::CannotRead,
                        origin,
                        millpath_core::args![path.display(), e],
                    )
                };
                return Some(FileCheck::Unreadable(d));
            }
            Ok(b) if millpath_core::load::text_file::decode(&b).is_err() => {
                return Some(FileCheck::Unreadable(Diagnostic::error(
                    Msg::TextNulBytes,
                    origin,
                    millpath_core::args![path.display()],
                )));
            }
            Ok(_) => {}
        }
    }
    analyze_with(ws, path, cancelled).map(|a| FileCheck::Analysed(Box::new(a)))
}

/// What an analysis read: the file itself, its dependencies and the folders it searched.
#[derive(Debug, Clone, Default)]
pub struct Inputs {
    pub files: Vec<PathBuf>,
    pub dirs: Vec<PathBuf>,
}

impl Inputs {
    pub fn of(a: &Analysis) -> Inputs {
        let mut files = vec![a.path.clone()];
        files.extend(a.deps.iter().cloned());
        Inputs {
            files,
            dirs: a.dirs.iter().cloned().collect(),
        }
    }

    /// A hash of the versions of the files (buffers by content, disk files by stamp) and of
    /// the folders' listings; `dirs` remembers listings within one pull.
    pub fn fingerprint(&self, ws: &Workspace, dirs: &mut HashMap<PathBuf, u64>) -> u64 {
        let fs = ws.fs();
        let mut h = DefaultHasher::new();
        for f in &self.files {
            f.hash(&mut h);
            fs.stamp(f).hash(&mut h);
        }
        for d in &self.dirs {
            let listing = *dirs.entry(d.clone()).or_insert_with(|| {
                let mut l = fs.list_dir(d).unwrap_or_default();
                l.sort();
                let mut h = DefaultHasher::new();
                l.hash(&mut h);
                h.finish()
            });
            listing.hash(&mut h);
        }
        h.finish()
    }
}
