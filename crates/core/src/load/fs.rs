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
    /// [`FileSystem::read`] into `buf` (cleared first), so that a caller can reuse one buffer.
    fn read_into(&self, path: &Path, buf: &mut Vec<u8>) -> std::io::Result<()> {
        *buf = self.read(path)?;
        Ok(())
    }
    /// The files of a directory (any order).
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>>;
    fn is_dir(&self, dir: &Path) -> bool;
    /// What identifies the current version of a file, so that its parse can be reused;
    /// `None` (the default) parses it again every time.
    fn stamp(&self, _path: &Path) -> Option<FileStamp> {
        None
    }
}

/// The largest drawing file read (a 100,000-segment chain is 13 MB): a bigger one is an
/// error, not an exhausted memory.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// The real file system.
pub struct OsFileSystem;

impl FileSystem for OsFileSystem {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        let mut buf = Vec::new();
        self.read_into(path, &mut buf)?;
        Ok(buf)
    }
    fn read_into(&self, path: &Path, buf: &mut Vec<u8>) -> std::io::Result<()> {
        use std::io::Read;
        buf.clear();
        let file = std::fs::File::open(path)?;
        let size = file.metadata().map(|m| m.len()).unwrap_or(0);
        // the reader reports this kind in the user's language (`Msg::FileTooLarge`)
        let too_large = || std::io::Error::from(std::io::ErrorKind::FileTooLarge);
        if size > MAX_FILE_BYTES {
            return Err(too_large());
        }
        buf.try_reserve_exact(usize::try_from(size).unwrap_or(0))?;
        // bounded also for files that grow while read or report no size (pipes, /proc)
        file.take(MAX_FILE_BYTES + 1).read_to_end(buf)?;
        if buf.len() as u64 > MAX_FILE_BYTES {
            buf.clear();
            return Err(too_large());
        }
        Ok(())
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

/// Reads `path` into this thread's reused buffer and hands its bytes to `f`: reading many
/// files one after another (`check`) then touches the same memory instead of fresh pages
/// for every file, and page faults cost more than reading a small drawing.
pub fn with_file_bytes<R>(
    fs: &dyn FileSystem,
    path: &Path,
    f: impl FnOnce(std::io::Result<&[u8]>) -> R,
) -> R {
    use std::cell::RefCell;
    /// A buffer larger than this is given back after use: a big drawing gains nothing from
    /// reuse, and must not keep its size in every thread for the rest of the process.
    const KEEP: usize = 1 << 20;
    thread_local! {
        static BUF: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
    }
    // taken out for the call: a nested read (none today) would get a buffer of its own
    let mut buf = BUF.with(|b| std::mem::take(&mut *b.borrow_mut()));
    let out = match fs.read_into(path, &mut buf) {
        Ok(()) => f(Ok(&buf)),
        Err(e) => f(Err(e)),
    };
    if buf.capacity() <= KEEP {
        buf.clear();
        BUF.with(|b| *b.borrow_mut() = buf);
    }
    out
}
