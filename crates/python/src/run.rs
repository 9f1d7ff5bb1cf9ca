//! `compile` and `check` of one drawing held in memory: the command line's `compile_file` in
//! a session of its own over a [`MemFileSystem`], its outputs returned instead of written.
//! Plain Rust: the Python types are `lib.rs`'s.

use crate::settings::settings_of;
use millpath_core::diag::Origin;
use millpath_core::{compile_file, Diagnostic, Lang, MemFileSystem, Session, Severity};
use std::path::Path;

/// One diagnostic as plain values (the fields of `millpath check --format json`).
#[derive(Debug, Clone, PartialEq)]
pub struct Diag {
    pub code: String,
    pub name: String,
    pub severity: &'static str,
    pub message: String,
    pub file: Option<String>,
    pub line: Option<u64>,
    pub column: Option<u64>,
    /// `file:line:col: message`, as the command line prints it.
    pub located: String,
}

/// One compiled path's statistics.
#[derive(Debug, Clone, PartialEq)]
pub struct Stat {
    pub path: String,
    pub lines: Vec<String>,
    pub seconds: f64,
    pub time: String,
}

/// What a compile or check gives.
#[derive(Debug, Default)]
pub struct Outcome {
    /// Output file name → text, in the order compile writes them.
    pub files: Vec<(String, String)>,
    pub diagnostics: Vec<Diag>,
    pub statistics: Vec<Stat>,
    pub removed_volume: Option<f64>,
    pub info: Vec<String>,
}

/// The request: the drawing `file_name` (its bytes in `files`), the settings' TOML text.
pub struct Request<'a> {
    pub file_name: &'a str,
    pub files: &'a MemFileSystem,
    pub settings: Option<&'a str>,
    pub check: bool,
}

/// Compiles (or checks) the drawing. `Err`: the settings are unusable (the messages).
pub fn run(r: &Request) -> Result<Outcome, Vec<String>> {
    let mut settings = settings_of(r.settings, r.files, !r.check).map_err(|e| vec![e])?;
    let lang = settings.lang;
    if r.check {
        settings.check = true;
        // as check's: with the machine values compile needs, the top level's S is compile's
        settings.check_sweep_height = settings_of(r.settings, r.files, true).is_ok();
    }
    let mut session = Session::new(settings, r.files)
        .map_err(|errs| errs.iter().map(|d| located(d, lang)).collect::<Vec<_>>())?;
    session.one_file = true;
    let input = Path::new(r.file_name);
    let outcome = compile_file(&mut session, input, &millpath_core::banner());
    let files = outcome
        .outputs
        .iter()
        .map(|o| {
            let name = o.path.file_name().map(|n| n.to_string_lossy().into_owned());
            (name.unwrap_or_default(), o.content.clone())
        })
        .collect();
    let statistics = outcome
        .stats
        .iter()
        .map(|(path, s)| Stat {
            path: path.clone(),
            lines: s.lines(lang).to_vec(),
            seconds: s.seconds(),
            time: s.time_line(lang),
        })
        .collect();
    Ok(Outcome {
        files,
        diagnostics: session.diags.list.iter().map(|d| diag(d, lang)).collect(),
        statistics,
        removed_volume: outcome.removed_volume,
        info: std::mem::take(&mut session.info),
    })
}

/// A diagnostic's plain values in `lang`.
pub fn diag(d: &Diagnostic, lang: Lang) -> Diag {
    let (line, column) = match &d.origin {
        Origin::Span { line, col, .. } => (Some(u64::from(*line)), Some(u64::from(*col))),
        Origin::Entity(e) => (Some(e.line as u64), None),
        Origin::FileLine { line, .. } => (Some(*line as u64), None),
        _ => (None, None),
    };
    let file = match &d.origin {
        Origin::FileLine { file, .. } => Some(file.to_string()),
        o => o.file().map(|f| f.path.display().to_string()),
    };
    Diag {
        code: d.msg.code(),
        name: d.msg.name(),
        severity: if d.severity == Severity::Error {
            "error"
        } else {
            "warning"
        },
        message: d.located_message(lang),
        file,
        line,
        column,
        located: located(d, lang),
    }
}

/// `location: message` (the message alone where there is no location).
pub fn located(d: &Diagnostic, lang: Lang) -> String {
    match d.origin.location_in(lang) {
        Some(at) => format!("{at}: {}", d.located_message(lang)),
        None => d.located_message(lang),
    }
}
