//! `compile`'s program written as it is generated (`Settings::stage_outputs`): every line
//! goes to a temporary file beside the output and to the second opinion, so a program many
//! times the size of its drawing is never held. The caller renames the file into place with
//! the rest of the set (all or none) or removes it; the set's digest is stamped into the
//! staged file once the program is complete.

use crate::diag::{Diagnostic, Msg, Origin};
use crate::emit::LineSink;
use crate::probe::adjustz::{banner_index_of_first, banner_with_digest, set_digest_lines};
use crate::second_opinion::Reviewer;
use crate::{args, emit::as_comment};
use std::collections::HashMap;
use std::fs::File;
use std::io::{BufRead, BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};

/// The program going to its temporary file and to the checker.
pub(crate) struct Staging {
    path: PathBuf,
    out: Option<BufWriter<File>>,
    error: Option<std::io::Error>,
    reviewer: Reviewer,
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
                .and_then(|()| out.write_all(b"\n"))
            {
                self.error = Some(e);
                self.out = None;
            }
        }
        self.reviewer.line(text, source);
    }
}

/// A temporary file beside `output` (same folder, so that the rename is atomic), named
/// `.NAME.<pid>.stage<k>`.
fn sibling(output: &Path, k: u8) -> PathBuf {
    let dir = output
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = output
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    dir.join(format!(".{name}.{}.stage{k}", std::process::id()))
}

fn cannot_write(path: &Path, e: std::io::Error) -> Diagnostic {
    Diagnostic::error(Msg::CannotWrite, Origin::Options, args![path.display(), e])
}

impl Staging {
    /// Where the program of `output` is staged.
    pub(crate) fn path_for(output: &Path) -> PathBuf {
        sibling(output, 1)
    }

    /// A staging file for the program of `output`; `Err` when it cannot be created.
    pub(crate) fn new(output: &Path, reviewer: Reviewer) -> Result<Staging, Diagnostic> {
        let path = Staging::path_for(output);
        match File::create(&path) {
            Ok(f) => Ok(Staging {
                path,
                out: Some(BufWriter::with_capacity(1 << 16, f)),
                error: None,
                reviewer,
            }),
            Err(e) => Err(cannot_write(output, e)),
        }
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
                let _ = std::fs::remove_file(&self.path);
                Err(cannot_write(&self.path, e))
            }
        }
    }
}

impl Staged {
    /// The texts of the lines `wanted` (1-based, sorted) of the closed file.
    pub(crate) fn line_texts(&self, wanted: &[usize]) -> HashMap<usize, String> {
        let mut texts = HashMap::new();
        let Ok(f) = File::open(&self.path) else {
            return texts;
        };
        let mut next = wanted.iter().copied().peekable();
        for (idx, line) in BufReader::new(f).lines().enumerate() {
            let Some(&want) = next.peek() else { break };
            let Ok(line) = line else { break };
            if want == idx + 1 {
                texts.insert(want, line);
                while next.peek() == Some(&want) {
                    next.next();
                }
            }
        }
        texts
    }

    /// The set's digest over `z_txt` and the staged program, stamped into its banner line
    /// (a second file, then the first removed). Returns the stamped banner line.
    pub(crate) fn stamp_set(&mut self, banner: &str, z_txt: &str) -> Result<String, Diagnostic> {
        let read = || -> std::io::Result<_> {
            Ok(BufReader::new(File::open(&self.path)?)
                .lines()
                .map_while(Result::ok))
        };
        let fail = |e: std::io::Error, path: &Path| cannot_write(path, e);
        let digest = set_digest_lines(z_txt, read().map_err(|e| fail(e, &self.path))?);
        let stamped = as_comment(0, &banner_with_digest(banner, &digest));
        let first = read().map_err(|e| fail(e, &self.path))?;
        let stamped_path = sibling(&self.path, 2);
        let written = (|| -> std::io::Result<()> {
            let mut out = BufWriter::with_capacity(1 << 16, File::create(&stamped_path)?);
            let mut lines = first.peekable();
            let at = banner_index_of_first(lines.peek().map(String::as_str));
            for (i, line) in lines.enumerate() {
                out.write_all(if i == at { &stamped } else { &line }.as_bytes())?;
                out.write_all(b"\n")?;
            }
            out.into_inner().map_err(|e| e.into_error())?.sync_all()
        })();
        let _ = std::fs::remove_file(&self.path);
        match written {
            Ok(()) => {
                self.path = stamped_path;
                Ok(stamped)
            }
            Err(e) => {
                let _ = std::fs::remove_file(&stamped_path);
                Err(fail(e, &stamped_path))
            }
        }
    }

    /// Removes the staged file (the compile failed after all).
    pub(crate) fn discard(&self) {
        let _ = std::fs::remove_file(&self.path);
    }
}
