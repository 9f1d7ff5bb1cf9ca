//! `compile`'s program written as it is generated (`Settings::stage_outputs`): every line
//! goes to a temporary file beside the output and to the second opinion, so a program many
//! times the size of its drawing is never held. The caller renames the file into place with
//! the rest of the set (all or none) or removes it; the set's digest is stamped into the
//! staged file once the program is complete.
//!
//! `compile`'s program is written to a temporary file beside its output as it is generated and read
//! by the checker at the same time (`Settings::stage_outputs`); read again line by line for the
//! checker's second reading; the set's digest stamped into it after; the command line renames it
//! with the set. `sibling` names every temporary file beside an output, `file_head` reads a long
//! program's banner.
//! The files are registered in `temporaries.rs` (removed when the run is interrupted);
//! the command line's sweep of an interrupted run's files reads `sibling`'s names.

use crate::args;
use crate::diag::{Diagnostic, Msg, Origin};
use crate::digest::{banner_index_of_first, banner_with_digest, set_digest_lines};
use crate::emit::LineSink;
use crate::second_opinion::{replay_lines, Reviewer};
use crate::temporaries;
use std::fs::File;
use std::io::{BufRead, BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};

/// The program going to its temporary file and to the checker.
pub(crate) struct Staging {
    path: PathBuf,
    out: Option<BufWriter<File>>,
    error: Option<std::io::Error>,
    reviewer: Reviewer,
    /// The post's line end.
    line_end: &'static str,
}

/// The complete program in its temporary file.
pub(crate) struct Staged {
    pub(crate) path: PathBuf,
}

impl LineSink for Staging {
    fn line(&mut self, text: &str, source: u32) {
        if let Some(out) = &mut self.out {
            if let Err(e) = out
                .write_all(text.as_bytes())
                .and_then(|()| out.write_all(self.line_end.as_bytes()))
            {
                self.error = Some(e);
                self.out = None;
            }
        }
        self.reviewer.line(text, source);
    }
}

/// A temporary file beside `path` (same folder, so that a rename into place is atomic),
/// named `.NAME.<pid>.<what>`; also the command line's temporaries and kept old files.
pub fn sibling(path: &Path, what: &str) -> PathBuf {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    dir.join(format!(".{name}.{}.{what}", std::process::id()))
}

/// The first `n` lines of a file, each with its `\n` (empty when it cannot be read): the
/// banner of a long program without reading all of it.
pub fn file_head(path: &Path, n: usize) -> String {
    File::open(path)
        .map(|f| {
            BufReader::new(f)
                .lines()
                .map_while(Result::ok)
                .take(n)
                .map(|l| l + "\n")
                .collect()
        })
        .unwrap_or_default()
}

fn cannot_write(path: &Path, e: std::io::Error) -> Diagnostic {
    Diagnostic::error(Msg::CannotWrite, Origin::Options, args![path.display(), e])
}

impl Staging {
    /// A staging file for the program of `output`; `Err` when it cannot be created.
    pub(crate) fn new(
        output: &Path,
        reviewer: Reviewer,
        line_end: &'static str,
    ) -> Result<Staging, Diagnostic> {
        let path = sibling(output, "stage1");
        match temporaries::create(&path) {
            Ok(f) => Ok(Staging {
                path,
                out: Some(BufWriter::with_capacity(1 << 16, f)),
                error: None,
                reviewer,
                line_end,
            }),
            Err(e) => Err(cannot_write(output, e)),
        }
    }

    /// The temporary file.
    pub(crate) fn path(&self) -> &Path {
        &self.path
    }

    /// Ends the writing: flushed and on disk (with the checker that read it), or the file
    /// removed and the reason.
    pub(crate) fn close(mut self) -> Result<(Staged, Reviewer), Diagnostic> {
        let result = match (self.error.take(), self.out.take()) {
            (Some(e), _) => Err(e),
            (None, Some(out)) => out
                .into_inner()
                .map_err(|e| e.into_error())
                .and_then(|f| f.sync_all()),
            (None, None) => Ok(()),
        };
        match result {
            Ok(()) => Ok((Staged { path: self.path }, self.reviewer)),
            Err(e) => {
                temporaries::remove(&self.path);
                Err(cannot_write(&self.path, e))
            }
        }
    }
}

impl Staged {
    /// The closed file's lines again, in order (without their `\n`), to `feed` until it
    /// answers `false`: read through a buffer, never the whole file; a line that cannot be
    /// read ends them (the checker says the reading fell short).
    pub(crate) fn replay(&self, feed: &mut dyn FnMut(&str) -> bool) {
        if let Ok(f) = File::open(&self.path) {
            replay_lines(BufReader::with_capacity(1 << 16, f), feed);
        }
    }

    /// The set's digest over `z_txt` and the staged program, stamped into its banner line
    /// (a second file, then the first removed) as `post` writes a comment. Returns the
    /// stamped banner comment.
    pub(crate) fn stamp_set(
        &mut self,
        banner: &str,
        z_txt: &str,
        post: &millpath_post::Post,
    ) -> Result<String, Diagnostic> {
        let read = || -> std::io::Result<_> {
            Ok(BufReader::new(File::open(&self.path)?)
                .lines()
                .map_while(Result::ok))
        };
        let fail = |e: std::io::Error, path: &Path| cannot_write(path, e);
        let digest = set_digest_lines(z_txt, read().map_err(|e| fail(e, &self.path))?);
        let text = banner_with_digest(banner, &digest);
        let stamped = post.comment(0, &text, &millpath_post::Globals::default());
        let line_end = post.format.line_end.text();
        let first = read().map_err(|e| fail(e, &self.path))?;
        let stamped_path = sibling(&self.path, "stage2");
        let written = (|| -> std::io::Result<()> {
            let file = temporaries::create(&stamped_path)?;
            let mut out = BufWriter::with_capacity(1 << 16, file);
            let mut lines = first.peekable();
            let at = banner_index_of_first(lines.peek().map(String::as_str));
            for (i, line) in lines.enumerate() {
                if i == at {
                    let line = crate::emit::program::stamped_line(&line, &stamped);
                    out.write_all(line.as_bytes())?;
                } else {
                    out.write_all(line.as_bytes())?;
                }
                out.write_all(line_end.as_bytes())?;
            }
            out.into_inner().map_err(|e| e.into_error())?.sync_all()
        })();
        temporaries::remove(&self.path);
        match written {
            Ok(()) => {
                self.path = stamped_path;
                Ok(stamped)
            }
            Err(e) => {
                temporaries::remove(&stamped_path);
                Err(fail(e, &stamped_path))
            }
        }
    }

    /// Removes the staged file (the compile failed after all).
    pub(crate) fn discard(&self) {
        temporaries::remove(&self.path);
    }
}
