//! Each drawing file is read and parsed once per process while it is unchanged: a subpath
//! file embedded by many top-level files of a `check` run, or by the buffers an editor
//! analyses again on every keystroke, is parsed the first time only. Entries are keyed by
//! the file's stamp (modification time and length on disk, a content hash for an editor's
//! buffer) and by the settings that change what parsing produces.
//!
//! Each file parsed once per process while unchanged (key: path, stamp, settings); drawings beyond
//! 20,000 segments are not kept (a part, not a library: its parse would stay beside its model).

use crate::diag::{Diagnostic, Lang};
use crate::front::drawing::RawPath;
use crate::load::regex_cache::Memo;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

/// What a file system says identifies one version of a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct FileStamp {
    /// Modification time in nanoseconds, or a content hash.
    pub version: u128,
    pub len: u64,
}

impl FileStamp {
    /// The stamp of a file on disk; `None` when it cannot be had (then nothing is cached).
    pub fn of_disk_file(path: &Path) -> Option<FileStamp> {
        FileStamp::of_metadata(&std::fs::metadata(path).ok()?)
    }
    /// The stamp of a file on disk from its metadata.
    pub fn of_metadata(meta: &std::fs::Metadata) -> Option<FileStamp> {
        let modified = meta.modified().ok()?;
        let since = modified.duration_since(std::time::UNIX_EPOCH).ok()?;
        Some(FileStamp {
            version: since.as_nanos(),
            len: meta.len(),
        })
    }
    /// The stamp of contents held in memory (an unsaved buffer).
    pub fn of_contents(bytes: &[u8]) -> FileStamp {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        bytes.hash(&mut h);
        FileStamp {
            version: u128::from(h.finish()) | 1 << 100,
            len: bytes.len() as u64,
        }
    }
}

/// The outcome of parsing one file, replayed into every session that loads it.
#[derive(Debug)]
pub struct ParsedFile {
    /// The file's paths, or the error that made it unreadable.
    pub result: Result<Vec<Arc<RawPath>>, Diagnostic>,
    /// Diagnostics found while parsing.
    pub diags: Vec<Diagnostic>,
    /// Progress lines (`---- Reading …`).
    pub info: Vec<String>,
}

#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct ParseKey {
    pub path: PathBuf,
    pub stamp: FileStamp,
    /// Settings that change the parse: path pattern, `/x` pattern, language of the info lines.
    pub path_pattern: String,
    pub debug_pattern: Option<String>,
    pub lang: Lang,
    pub input: crate::InputMode,
}

/// Files kept at most; when full the table starts again.
const CAPACITY: usize = 4096;

/// Drawings with more segments than this are not kept for the command line's one-file
/// sessions: such a file is a part of its own, not a library that many files embed, and
/// keeping its parse would hold it beside its model for the whole run (a check's memory
/// would be its drawing twice over). The editor keeps them: it analyses them again and again.
pub const MAX_KEPT_SEGMENTS: usize = 20_000;

fn memo() -> &'static Memo<ParseKey, Arc<ParsedFile>> {
    static MEMO: OnceLock<Memo<ParseKey, Arc<ParsedFile>>> = OnceLock::new();
    MEMO.get_or_init(|| Memo::with_capacity(CAPACITY))
}

/// The process-wide table of parsed files.
pub fn parsed(key: ParseKey, parse: impl FnOnce() -> ParsedFile) -> Arc<ParsedFile> {
    let parsed = memo().get_or(&key, || Arc::new(parse()));
    remember_path(&key.path);
    parsed
}

/// Drops the parse of `key` from the table (its holders keep it).
pub fn forget(key: &ParseKey) {
    memo().forget(key);
}

impl ParsedFile {
    /// The segments of all its paths.
    pub fn segment_count(&self) -> usize {
        self.result
            .as_ref()
            .map_or(0, |paths| paths.iter().map(|p| p.segments.len()).sum())
    }
}

/// The paths the table has seen (some perhaps forgotten since, when it started again).
fn seen() -> std::sync::MutexGuard<'static, std::collections::HashSet<PathBuf>> {
    static SEEN: OnceLock<Mutex<std::collections::HashSet<PathBuf>>> = OnceLock::new();
    let seen = SEEN.get_or_init(Mutex::default);
    // a panic elsewhere while holding the lock leaves a usable set
    seen.lock().unwrap_or_else(|e| e.into_inner())
}

fn remember_path(path: &Path) {
    let mut seen = seen();
    if !seen.contains(path) {
        if seen.len() >= CAPACITY {
            seen.clear();
        }
        seen.insert(path.to_path_buf());
    }
}

/// Whether `path` may have a parse in the table. A file never parsed (each top-level file of
/// a `check` run) is read at once and stamped from the open file, which saves looking its
/// path up on disk once more; a file parsed before is stamped first, so that an unchanged one
/// is not read again. Either answer is safe: only the number of system calls depends on it.
pub fn may_hold(path: &Path) -> bool {
    seen().contains(path)
}
