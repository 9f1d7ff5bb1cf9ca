//! Subpath search: which files of the drawing's folder and the search directories may hold a path (reference-input.md §3.3).

use crate::args;
use crate::diag::{Diagnostic, Msg, Origin};
use crate::load::fs::is_text_file;
use crate::load::session::{Abort, Session};
use std::ffi::OsStr;
use std::path::{Path, PathBuf};

impl Session<'_> {
    /// Finds the files that may contain `name` and loads them; returns the matching files.
    pub(crate) fn search(&mut self, name: &str, near_file: &Path) -> Result<Vec<PathBuf>, Abort> {
        let mut dirs = vec![near_file
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default()];
        dirs.extend(self.settings.search_dirs.iter().cloned());
        let mut matching = Vec::new();
        for dir in dirs {
            let dir_or_cwd = if dir.as_os_str().is_empty() {
                PathBuf::from(".")
            } else {
                dir.clone()
            };
            if !self.fs.is_dir(&dir_or_cwd) {
                return Err(Diagnostic::error(
                    Msg::SearchDirMissing,
                    Origin::Options,
                    args![dir_or_cwd.display()],
                ));
            }
            let mut files = self.fs.list_dir(&dir_or_cwd).unwrap_or_default();
            files.retain(|f| {
                f.extension().is_some_and(|e| e.eq_ignore_ascii_case("dxf")) || is_text_file(f)
            });
            // the files of one folder: their names decide `Path`'s order, which compares
            // component by component: that sort cost more than listing the folder
            let mut named: Vec<(&OsStr, &PathBuf)> = files
                .iter()
                .map(|f| (f.file_name().unwrap_or_default(), f))
                .collect();
            named.sort_unstable();
            for (_, f) in named {
                let stem = f
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default();
                if self.patterns.file_contains(&stem, name) {
                    let f = if dir.as_os_str().is_empty() {
                        PathBuf::from(f.file_name().unwrap_or_default())
                    } else {
                        f.clone()
                    };
                    self.load_file(&f);
                    matching.push(f);
                }
            }
        }
        Ok(matching)
    }
}
