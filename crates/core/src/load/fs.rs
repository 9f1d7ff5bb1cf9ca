//! File access through a trait, so that editors can serve unsaved buffers and tests can use memory.
//!
//! The `FileSystem` trait (`OsFileSystem`, `MemFileSystem`; file stamps for the parse cache);
//! `with_file_bytes`: a read buffer each thread reuses, filled by one `read` per file.

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
    /// [`FileSystem::read_into`] and the stamp of the version read, taken before reading (a
    /// change while reading then makes the next stamp differ instead of pairing new bytes
    /// with an old stamp).
    fn read_into_stamped(
        &self,
        path: &Path,
        buf: &mut Vec<u8>,
    ) -> std::io::Result<Option<FileStamp>> {
        let stamp = self.stamp(path);
        self.read_into(path, buf)?;
        Ok(stamp)
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
        open_and_read(path, buf).map(drop)
    }
    fn read_into_stamped(
        &self,
        path: &Path,
        buf: &mut Vec<u8>,
    ) -> std::io::Result<Option<FileStamp>> {
        // the open file's own metadata: no second look-up of the path
        open_and_read(path, buf).map(|meta| FileStamp::of_metadata(&meta))
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

/// Opens `path` and reads it whole into `buf`; the file's metadata, had before reading.
fn open_and_read(path: &Path, buf: &mut Vec<u8>) -> std::io::Result<std::fs::Metadata> {
    let mut file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    if meta.len() > MAX_FILE_BYTES {
        return Err(too_large());
    }
    read_sized(&mut file, meta.len(), buf)?;
    Ok(meta)
}

/// The error for a file over [`MAX_FILE_BYTES`]; the reader reports this kind in the user's
/// language (`Msg::FileTooLarge`).
fn too_large() -> std::io::Error {
    std::io::Error::from(std::io::ErrorKind::FileTooLarge)
}

/// The largest file [`read_sized`] reads into zeroed memory (a drawing of 100,000 segments
/// is 13 MB).
const PREFILL_MAX: usize = 16 << 20;

/// Reads all of `file`, which says it holds `size` bytes, into `buf` (its old bytes replaced).
///
/// One `read` for the whole file and one that finds its end, where `read_to_end` starts at
/// 8 KiB and doubles (four calls for a 50 KB drawing, and a system call costs more than
/// parsing a kilobyte). The bytes `buf` already holds are overwritten, not zeroed first: a
/// reused buffer is filled once per file, not twice. Files over [`PREFILL_MAX`] go by
/// `read_to_end`. A file longer than it said (growing, or `/proc`-like with no size) is read
/// on to its end, still bounded by [`MAX_FILE_BYTES`].
fn read_sized(file: &mut impl std::io::Read, size: u64, buf: &mut Vec<u8>) -> std::io::Result<()> {
    use std::io::{ErrorKind, Read};
    let size = usize::try_from(size).map_err(|_| too_large())?;
    let mut filled = 0;
    if size > PREFILL_MAX {
        // reserved, not zeroed: a size that lies (a file cut short while read) costs no
        // memory, and a few system calls more are nothing beside reading this much
        buf.clear();
        buf.try_reserve_exact(size)?;
    } else {
        // one byte more than said: reading it shows a file longer than its size
        let want = size + 1;
        if buf.len() < want {
            buf.try_reserve_exact(want - buf.len())?;
            buf.resize(want, 0);
        }
        while filled < buf.len() {
            match file.read(&mut buf[filled..]) {
                Ok(0) => {
                    buf.truncate(filled);
                    return Ok(());
                }
                Ok(n) => filled += n,
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => {
                    buf.clear();
                    return Err(e);
                }
            }
        }
        buf.truncate(filled);
    }
    let rest = (MAX_FILE_BYTES + 1).saturating_sub(filled as u64);
    if let Err(e) = file.take(rest).read_to_end(buf) {
        buf.clear();
        return Err(e);
    }
    if buf.len() as u64 > MAX_FILE_BYTES {
        buf.clear();
        return Err(too_large());
    }
    Ok(())
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
    with_reused_buffer(|buf| match fs.read_into(path, buf) {
        Ok(()) => f(Ok(buf)),
        Err(e) => f(Err(e)),
    })
}

/// [`with_file_bytes`] with the stamp of the version read ([`FileSystem::read_into_stamped`]).
pub fn with_stamped_file_bytes<R>(
    fs: &dyn FileSystem,
    path: &Path,
    f: impl FnOnce(std::io::Result<(&[u8], Option<FileStamp>)>) -> R,
) -> R {
    with_reused_buffer(|buf| match fs.read_into_stamped(path, buf) {
        Ok(stamp) => f(Ok((buf, stamp))),
        Err(e) => f(Err(e)),
    })
}

/// Lends this thread's read buffer to `f`.
fn with_reused_buffer<R>(f: impl FnOnce(&mut Vec<u8>) -> R) -> R {
    use std::cell::RefCell;
    /// A buffer larger than this is given back after use: a big drawing gains nothing from
    /// reuse, and must not keep its size in every thread for the rest of the process.
    const KEEP: usize = 1 << 20;
    thread_local! {
        static BUF: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
    }
    // taken out for the call: a nested read (none today) would get a buffer of its own
    let mut buf = BUF.with(|b| std::mem::take(&mut *b.borrow_mut()));
    let out = f(&mut buf);
    // kept with its bytes: the next read overwrites them instead of zeroing them first
    if buf.capacity() <= KEEP {
        BUF.with(|b| *b.borrow_mut() = buf);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::{ErrorKind, Read};

    /// Hands out `data` a few bytes per call, with an interruption before each piece.
    struct Trickle<'a> {
        data: &'a [u8],
        step: usize,
        interrupt: bool,
    }

    impl Read for Trickle<'_> {
        fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
            self.interrupt = !self.interrupt;
            if self.interrupt {
                return Err(ErrorKind::Interrupted.into());
            }
            let n = self.step.min(out.len()).min(self.data.len());
            out[..n].copy_from_slice(&self.data[..n]);
            self.data = &self.data[n..];
            Ok(n)
        }
    }

    fn read(data: &[u8], said: u64, buf: &mut Vec<u8>) -> std::io::Result<()> {
        let mut file = Trickle {
            data,
            step: 7,
            interrupt: false,
        };
        read_sized(&mut file, said, buf)
    }

    #[test]
    fn a_file_is_read_whole_whatever_size_it_said() {
        let data: Vec<u8> = (0..200u8).collect();
        for said in [200, 0, 1, 199, 201, 5000] {
            let mut buf = Vec::new();
            read(&data, said, &mut buf).unwrap();
            assert_eq!(buf, data, "said {said}");
        }
    }

    #[test]
    fn a_file_that_says_it_is_big_is_read_as_it_is() {
        let mut buf = b"old".to_vec();
        read(b"short after all", 200 << 20, &mut buf).unwrap();
        assert_eq!(buf, b"short after all");
        let data = vec![7u8; PREFILL_MAX + 10];
        for said in [data.len() as u64, PREFILL_MAX as u64 + 1, 0] {
            read(&data, said, &mut buf).unwrap();
            assert_eq!(buf, data);
        }
    }

    #[test]
    fn a_reused_buffer_holds_only_the_new_file() {
        let mut buf = vec![b'x'; 500];
        read(b"0\nEOF\n", 6, &mut buf).unwrap();
        assert_eq!(buf, b"0\nEOF\n");
        read(b"", 0, &mut buf).unwrap();
        assert!(buf.is_empty());
        read(b"longer than before", 3, &mut buf).unwrap();
        assert_eq!(buf, b"longer than before");
    }

    #[test]
    fn an_error_while_reading_leaves_no_bytes() {
        struct Broken;
        impl Read for Broken {
            fn read(&mut self, _: &mut [u8]) -> std::io::Result<usize> {
                Err(ErrorKind::BrokenPipe.into())
            }
        }
        let mut buf = b"old".to_vec();
        assert!(read_sized(&mut Broken, 10, &mut buf).is_err());
        assert!(buf.is_empty());
    }

    #[test]
    fn a_disk_file_is_read_with_the_stamp_of_its_version() {
        let dir = std::env::temp_dir().join(format!("millpath-fs-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.dxf");
        std::fs::write(&path, b"0\nEOF\n").unwrap();
        let mut buf = b"stale bytes of another file".to_vec();
        let stamp = OsFileSystem.read_into_stamped(&path, &mut buf).unwrap();
        assert_eq!(buf, b"0\nEOF\n");
        assert_eq!(stamp, FileStamp::of_disk_file(&path));
        assert!(stamp.is_some());
        let missing = OsFileSystem.read_into_stamped(&dir.join("none.dxf"), &mut buf);
        assert_eq!(missing.unwrap_err().kind(), ErrorKind::NotFound);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
