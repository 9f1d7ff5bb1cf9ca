//! Adjust-z's bounds on what it reads (largest number, longest line, deepest expression),
//! the `--max` option's check, and the file-and-line origin of its messages.

use crate::args;
use crate::diag::{Diagnostic, Msg, Origin};

/// Largest absolute value of any number adjust-z reads or writes (mm).
pub const LIMIT: f64 = 1e6;
/// Longest line of `_Clean.gcode` or `_Z.txt`, in bytes.
pub const MAX_LINE: usize = 10_000;
/// Deepest nesting of `(`, `[` and unary `-` in a probe expression.
pub const MAX_DEPTH: usize = 64;

/// The limit option as the user spelled it: `/m` (reference command line) or `--max`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MaxOption {
    Slash,
    Long,
}

impl MaxOption {
    pub fn name(self) -> &'static str {
        match self {
            MaxOption::Slash => "/m",
            MaxOption::Long => "--max",
        }
    }
}

/// `None` when `max` is a usable limit (finite, > 0, ≤ [`LIMIT`]), else the option error.
pub fn check_max(max: f64, text: &str, opt: MaxOption) -> Option<Diagnostic> {
    if max.is_finite() && max > 0.0 && max <= LIMIT {
        None
    } else {
        Some(Diagnostic::error(
            Msg::MaxInvalid,
            Origin::Options,
            args![opt.name(), text],
        ))
    }
}

pub(crate) fn line_origin(file: &str, line: usize) -> Origin {
    Origin::FileLine {
        file: file.into(),
        line,
    }
}
