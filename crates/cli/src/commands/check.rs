//! `millpath check`: every path of every drawing checked, nothing written (the CI lint).

use crate::args::{lang_of, settings_for, Format, MachineArgs};
use crate::inputs::{collect_files, is_drawing};
use crate::output::print_human;
use crate::{out, report, workers};
use millpath_core::diag::{Diagnostic, Msg, Origin, Severity};
use millpath_core::emit::stats::hms;
use millpath_core::{compile_file, Lang, OsFileSystem, Session, Settings};
use std::path::{Path, PathBuf};

/// What checking one file gives: its progress lines and its diagnostics, in order, and the
/// estimated time of each path it planned.
pub struct FileCheck {
    pub info: Vec<String>,
    pub diags: Vec<Diagnostic>,
    pub times: Vec<(String, f64)>,
}

/// The session that checks one file. Each file gets its own (files are checked on their own,
/// like separate lint targets), built inside the worker thread that checks the file.
fn check_session<'a>(
    settings: &Settings,
    fs: &'a OsFileSystem,
) -> Result<Session<'a>, Vec<Diagnostic>> {
    let mut session = Session::new(settings.clone(), fs)?;
    session.one_file = true;
    Ok(session)
}

/// Checks one file in a session of its own.
pub fn check_file(settings: &Settings, input: &Path) -> Result<FileCheck, Vec<Diagnostic>> {
    let fs = OsFileSystem;
    let mut session = check_session(settings, &fs)?;
    let outcome = compile_file(&mut session, input, &millpath_core::banner());
    Ok(FileCheck {
        info: std::mem::take(&mut session.info),
        diags: std::mem::take(&mut session.diags.list),
        times: outcome
            .stats
            .iter()
            .map(|(path, s)| (path.clone(), s.seconds()))
            .collect(),
    })
}

/// From this many files on, `check` shows a progress bar (on a terminal, without `--quiet`).
const PROGRESS_MIN_FILES: usize = 50;

/// Checks every input on all cores; the results come back in input order.
fn check_all(
    settings: &Settings,
    inputs: &[PathBuf],
    quiet: bool,
) -> Vec<Result<FileCheck, Vec<Diagnostic>>> {
    use rayon::prelude::*;
    use std::io::IsTerminal;
    let bar = if !quiet && inputs.len() >= PROGRESS_MIN_FILES && std::io::stderr().is_terminal() {
        let bar = indicatif::ProgressBar::new(inputs.len() as u64);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} files  {elapsed_precise} (eta {eta})",
        ) {
            bar.set_style(style);
        }
        bar
    } else {
        indicatif::ProgressBar::hidden()
    };
    let one = |input: &PathBuf| {
        let r = check_file(settings, input);
        bar.inc(1);
        r
    };
    // no thread to start for one file
    let pool = (inputs.len() > 1).then(workers::check_pool);
    let results = match pool {
        Some(Ok(pool)) => pool.install(|| inputs.par_iter().map(one).collect()),
        _ => inputs.iter().map(one).collect(),
    };
    bar.finish_and_clear();
    results
}

/// `check`: `quiet` and `--max-warnings` (over millpath.toml's `max_warnings`) in `options`.
pub fn run(m: &MachineArgs, format: Format, options: (bool, Option<u32>), paths: &[PathBuf]) -> u8 {
    let (quiet, max_warnings) = options;
    let mut inputs = Vec::new();
    collect_files(paths, is_drawing, &mut inputs);
    let mut settings = match settings_for(m, inputs.first().map(PathBuf::as_path), false) {
        Ok(s) => s,
        Err(e) => {
            let lang = lang_of(m, inputs.first().or(paths.first()).map(PathBuf::as_path));
            match format {
                Format::Human => {
                    eprintln!("{}: {e}", report::severity_word(Severity::Error, lang))
                }
                // a report a JSON, SARIF or GitHub reader can take, at millpath.toml when
                // the text is its error
                _ => {
                    let file = m
                        .config
                        .clone()
                        .or_else(|| inputs.first().and_then(|i| crate::config::find(i)))
                        .filter(|f| e.starts_with(&f.display().to_string()));
                    let at = match file {
                        Some(f) => settings_error_at(f, &e),
                        None => Origin::Options,
                    };
                    let d = Diagnostic::error(Msg::SettingsUnusable, at, millpath_core::args![e]);
                    print_report(format, &[d], 0, lang);
                }
            }
            return 2;
        }
    };
    settings.check = true;
    // with the machine settings compile needs, the top-level S is compile's, not T+O
    settings.check_sweep_height =
        settings_for(m, inputs.first().map(PathBuf::as_path), true).is_ok();
    let lang = settings.lang;
    if inputs.is_empty() {
        // like the reference's "no files" (exit 3); a report in the format asked for, so that
        // a JSON or SARIF reader gets a document it can parse
        let shown: Vec<String> = paths.iter().map(|p| p.display().to_string()).collect();
        // no drawing to find millpath.toml from: the folder given tells the language
        let lang = lang_of(m, paths.first().map(PathBuf::as_path));
        let d = Diagnostic::error(
            Msg::NoDrawingsFound,
            Origin::Input,
            millpath_core::args![shown.join(", ")],
        );
        match format {
            Format::Human => eprintln!(
                "{}: {}",
                report::severity_word(Severity::Error, lang),
                d.message(lang)
            ),
            _ => print_report(format, &[d], 0, lang),
        }
        return 3;
    }
    let mut all = Vec::new();
    // the estimated time of every planned path, for the JSON report
    let mut times = Vec::new();
    // Printed in input order, whatever order the workers finished in; gathered first and
    // written at once (a write per line cost more than reading a small drawing).
    let mut info = String::new();
    for (input, result) in inputs.iter().zip(check_all(&settings, &inputs, quiet)) {
        match result {
            Ok(file) => {
                for (path, seconds) in file.times {
                    times.push(serde_json::json!({
                        "file": input.display().to_string(),
                        "path": path,
                        "seconds": seconds,
                        "time": hms(seconds),
                    }));
                }
                // --quiet: the report only
                if format == Format::Human && !quiet {
                    for line in file.info {
                        info.push_str(&line);
                        info.push('\n');
                    }
                }
                all.extend(file.diags);
            }
            Err(errs) => {
                eprint!("{info}");
                // settings errors (exit 2) in the format asked for: a JSON or SARIF reader
                // gets a document, GitHub an annotation at the millpath.toml that gave them
                match format {
                    Format::Human => print_human(&errs, lang),
                    _ => print_report(format, &errs, 0, lang),
                }
                return 2;
            }
        }
    }
    eprint!("{info}");
    let all = report::once_each(report::tidy(all));
    let errors = all.iter().filter(|d| d.severity == Severity::Error).count();
    match format {
        Format::Human => {
            // diagnostics and the summary are the report (stdout); progress lines stay on stderr
            let color = report::use_color(std::io::IsTerminal::is_terminal(&std::io::stdout()));
            let mut report = String::new();
            for d in &all {
                report.push_str(&report::human_rich(d, lang, color));
                report.push('\n');
            }
            out::write(&report);
            let warnings = all.len() - errors;
            outln!(
                "{}",
                match lang {
                    Lang::En => format!(
                        "checked {} file(s): {errors} error(s), {warnings} warning(s)",
                        inputs.len()
                    ),
                    Lang::De => format!(
                        "{} Datei(en) geprüft: {errors} Fehler, {warnings} Warnung(en)",
                        inputs.len()
                    ),
                }
            );
        }
        Format::Json => print_json(&all, inputs.len(), &times, lang),
        _ => print_report(format, &all, inputs.len(), lang),
    }
    let warnings = all
        .iter()
        .filter(|d| d.severity == Severity::Warning)
        .count();
    let too_many = match max_warnings.or(settings.max_warnings) {
        Some(max) if warnings > max as usize => {
            // after the report, on standard error: a JSON or SARIF report stays one document
            eprintln!("{}", too_many_warnings(warnings, max, lang));
            true
        }
        _ => false,
    };
    u8::from(errors > 0 || too_many)
}

/// Where in millpath.toml its error is: at the line and column the TOML reader names
/// ("at line 2, column 15", in German "in Zeile 2, Spalte 15"), else the file as a whole.
fn settings_error_at(file: PathBuf, error: &str) -> Origin {
    use millpath_core::diag::FileRef;
    let number_after = |word: &str| -> Option<u32> {
        let rest = &error[error.find(word)? + word.len()..];
        let digits = rest.split(|c: char| !c.is_ascii_digit()).next()?;
        digits.parse().ok().filter(|n| *n > 0)
    };
    let line = number_after(" at line ").or_else(|| number_after(" in Zeile "));
    let col = number_after(", column ")
        .or_else(|| number_after(", Spalte "))
        .unwrap_or(1);
    let Some(line) = line else {
        return Origin::File(FileRef::new(file));
    };
    // the byte offset of that place, for the JSON report's span (the file was read a moment
    // ago; if it is gone now, the line start of nothing is 0)
    let text = crate::read::text(&file).unwrap_or_default();
    let line_start: usize = text
        .split_inclusive('\n')
        .take(line as usize - 1)
        .map(str::len)
        .sum();
    let start = text[line_start.min(text.len())..]
        .char_indices()
        .nth(col as usize - 1)
        .map_or(text.len(), |(i, _)| line_start + i);
    let start = u32::try_from(start).unwrap_or(u32::MAX);
    Origin::Span {
        file: FileRef::new(file),
        start,
        end: start,
        line,
        col,
    }
}

/// The line that says why a check with no error failed.
fn too_many_warnings(warnings: usize, max: u32, lang: Lang) -> String {
    match lang {
        Lang::En => format!(
            "error: {warnings} warning(s), more than the {max} allowed (--max-warnings, max_warnings in millpath.toml)"
        ),
        Lang::De => format!(
            "Fehler: {warnings} Warnung(en), mehr als die erlaubten {max} (--max-warnings, max_warnings in millpath.toml)"
        ),
    }
}

/// The JSON report with the estimated time of each path (`times`: file, path, seconds and
/// `h:mm:ss`; with `[machine]` LinuxCNC's planner model, else the reference's).
fn print_json(all: &[Diagnostic], files: usize, times: &[serde_json::Value], lang: Lang) {
    let errors = all.iter().filter(|d| d.severity == Severity::Error).count();
    let v: Vec<serde_json::Value> = all.iter().map(|d| report::json_value(d, lang)).collect();
    outln!(
        "{}",
        serde_json::to_string_pretty(&serde_json::json!({
            "files": files,
            "errors": errors,
            "diagnostics": v,
            "times": times,
        }))
        .unwrap_or_default()
    );
}

/// The machine-readable reports (JSON, GitHub annotations, SARIF) of `files` checked files.
fn print_report(format: Format, all: &[Diagnostic], files: usize, lang: Lang) {
    let errors = all.iter().filter(|d| d.severity == Severity::Error).count();
    match format {
        Format::Human => {}
        Format::Json => {
            let v: Vec<serde_json::Value> =
                all.iter().map(|d| report::json_value(d, lang)).collect();
            outln!(
                "{}",
                serde_json::to_string_pretty(
                    &serde_json::json!({ "files": files, "errors": errors, "diagnostics": v })
                )
                .unwrap_or_default()
            );
        }
        Format::Github => {
            let lines: String = all
                .iter()
                .map(|d| format!("{}\n", report::github(d, lang)))
                .collect();
            out::write(&lines);
        }
        Format::Sarif => {
            outln!(
                "{}",
                serde_json::to_string_pretty(&report::sarif(all, lang)).unwrap_or_default()
            );
        }
    }
}
