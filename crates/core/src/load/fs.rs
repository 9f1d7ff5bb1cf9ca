//! File access through a trait, so that editors can serve unsaved buffers and tests can use memory.

use crate::load::parse_cache::FileStamp;
use std::path::{Path, PathBuf};

/// `*.mpath`: the text language.
pub fn is_text_file(p: &Path) -> bool {
    p.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mpath"))
}

/// File access, so that editors can serve unsaved buffers and tests can use memory.
pub trait FileSystem {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>>;
    /// The files of a directory (any order).
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>>;
    fn is_dir(&self, dir: &Path) -> bool;
    /// What identifies the current version of a file, so that its parse can be reused;
    /// `None` (the default) parses it again every time.
    fn stamp(&self, _path: &Path) -> Option<FileStamp> {
        None
    }
}

/// The real file system.
pub struct OsFileSystem;

impl FileSystem for OsFileSystem {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        std::fs::read(path)
    }
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        let mut v = Vec::new();
        for e in std::fs::read_dir(dir)? {
            let e = e?;
            if e.file_type().map(|t| t.is_file()).unwrap_or(false) {
                v.push(e.path());
            }
        }
        Ok(v)
    }
    fn is_dir(&self, dir: &Path) -> bool {
        dir.is_dir()
    }
    fn stamp(&self, path: &Path) -> Option<FileStamp> {
        FileStamp::of_disk_file(path)
    }
}

/// Files held in memory (tests, unsaved editor buffers).
#[derive(Debug, Default, Clone)]
pub struct MemFileSystem {
    pub files: std::collections::BTreeMap<PathBuf, Vec<u8>>,
}

impl MemFileSystem {
    pub fn add(&mut self, path: impl Into<PathBuf>, content: impl Into<Vec<u8>>) -> &mut Self {
        self.files.insert(path.into(), content.into());
        self
    }
}

impl FileSystem for MemFileSystem {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        self.files
            .get(path)
            .cloned()
            .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "not found"))
    }
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        let dir = if dir == Path::new(".") {
            Path::new("")
        } else {
            dir
        };
        Ok(self
            .files
            .keys()
            .filter(|p| p.parent() == Some(dir))
            .cloned()
            .collect())
    }
    fn is_dir(&self, dir: &Path) -> bool {
        let dir = if dir == Path::new(".") {
            Path::new("")
        } else {
            dir
        };
        self.files.keys().any(|p| p.parent() == Some(dir))
    }
}
