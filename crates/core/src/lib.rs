//! millpath core: drawing model → validated path model → G-code, probing program, `_Z.txt`;
//! and adjust-z. No file-system I/O of its own: files are read through [`FileSystem`] and
//! outputs are returned to the caller, which writes them. The one exception is asked for by
//! the caller: a staged program (`Settings::stage_outputs`, `stage.rs`) is written to a
//! temporary file as it is generated, and the caller renames it.
//!
//! `compile_file`: one command-line file → outputs (reference-input.md §7.5); check mode is the
//! same code without writing, the reference's `/c` keeps its rules.

pub mod build;
pub mod convert;
pub mod diag;
pub mod digest;
pub mod emit;
pub mod front;
pub mod geom;
pub mod load;
pub mod machine;
pub mod model;
pub mod params;
pub mod probe;
pub mod second_opinion;
pub mod stage;
pub mod stock;
pub mod temporaries;

pub use diag::{Diagnostic, Diags, Lang, Msg, Origin, Severity};
pub use front::options::InputMode;
pub use load::fs::{FileSystem, MemFileSystem, OsFileSystem};
pub use load::paths::{complete_input, output_prefix};
pub use load::session::Session;
pub use load::settings::Settings;
pub use machine::Dialect;

use emit::{generate_for, stats::Stats, Controller, Output};
use std::path::{Path, PathBuf};

/// The program banner written as line 2 of every G-code file.
pub fn banner() -> String {
    format!("millpath V.{}", env!("CARGO_PKG_VERSION"))
}

/// A file to be written.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputFile {
    pub path: PathBuf,
    /// The text (empty when `staged`).
    pub content: String,
    /// The text is in this temporary file beside `path` already (`Settings::stage_outputs`):
    /// the caller renames it into place, or removes it.
    pub staged: Option<PathBuf>,
}

impl OutputFile {
    /// The first `n` lines of the text, from memory or from the staged file.
    pub fn head(&self, n: usize) -> String {
        match &self.staged {
            None => self
                .content
                .lines()
                .take(n)
                .map(|l| format!("{l}\n"))
                .collect(),
            Some(p) => stage::file_head(p, n),
        }
    }
}

/// The result of compiling one input file.
#[derive(Debug, Default)]
pub struct FileOutcome {
    /// Files to write (empty when anything went wrong).
    pub outputs: Vec<OutputFile>,
    /// Statistics of the compiled path(s).
    pub stats: Vec<(String, Stats)>,
    /// Material removed by the written program (mm³, the second opinion's stock model).
    pub removed_volume: Option<f64>,
    /// The start marker of the path whose outputs these are (its text holds the `R` that
    /// names them): where messages about the output names point.
    pub start: Option<Origin>,
}

/// Compiles one command-line file (reference-input.md §7.5). Errors go to `session.diags`.
///
/// Check mode (`settings.check`) is the same code without writing: it reports what `compile`
/// would, except that a file with several paths is a library whose every path is checked
/// (compile refuses it, MP061). The reference's `/c` (`settings.reference_check`) keeps its
/// own rules: every built path is generated even after errors, no file-level errors.
pub fn compile_file(session: &mut Session, input: &Path, banner: &str) -> FileOutcome {
    let mut names = session.load_file(input);
    // as compile's rule: any error so far (the session of a check or an editor analysis
    // holds this file only; the editor has already reported its buffer's syntax)
    let load_failed = session.diags.errors_reported() > 0;
    let file_name = input
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let check = session.settings.check;
    let reference_check = check && session.settings.reference_check;
    let mut outcome = FileOutcome::default();
    if check {
        names.sort();
    }
    // the built models, each with whether errors came while building it
    let mut built = Vec::new();
    let mut aborted = false;
    for name in &names {
        if session.stopped() {
            return outcome;
        }
        if check {
            let verb = if session.lang() == Lang::De {
                "Prüfen von"
            } else {
                "Checking"
            };
            session.info.push(format!("---- {verb} {name}"));
        }
        if !check && !session.settings.reference_check {
            warn_variables_not_given(session, name);
        }
        let before = session.diags.errors_reported();
        match session.build_top(name) {
            Err(abort) => {
                session.diags.push(abort);
                aborted = true;
                if !check {
                    return outcome;
                }
            }
            Ok(Some(m)) => {
                let clean = session.diags.errors_reported() == before && !m.has_errors;
                built.push((m, clean));
            }
            Ok(None) => {}
        }
    }
    if session.one_file {
        session.release_segments();
    }
    let file_origin = Origin::File(diag::FileRef::new(input.to_path_buf()));
    if !check && built.len() > 1 {
        let mut list: Vec<&str> = built.iter().map(|(m, _)| m.name()).collect();
        list.sort();
        session.diags.error(
            Msg::MoreThanOnePath,
            file_origin,
            args![input.display(), list.join(", ")],
        );
        return outcome;
    }
    // "no error-free path" only where no error says why already (the reference's command
    // line keeps its rule: it prints the line after the errors too)
    let explained = session.diags.errors_reported() > 0 && !session.settings.reference_check;
    if built.is_empty() && !aborted && !reference_check && !explained {
        // "DXF file" only for a DXF file
        let msg = if crate::load::fs::is_text_file(input) {
            Msg::NoErrorFreePathInFile
        } else {
            Msg::NoErrorFreePath
        };
        session
            .diags
            .error(msg, file_origin, args![input.display()]);
        return outcome;
    }
    if check {
        for (model, clean) in built {
            // compile generates nothing after an error: neither does its check
            let generates = reference_check || (clean && !load_failed);
            if !generates {
                continue;
            }
            if session.stopped() {
                return outcome;
            }
            if !reference_check {
                for d in
                    emit::comment::comment_changes(&model, &file_name, session.settings.dialect)
                {
                    session.diags.push(d);
                }
            }
            if session.settings.quick_check && !reference_check {
                // the editor: the diagnostics alone (its lenses compile for the statistics)
                let ctl = Controller::for_model(&session.settings, &model);
                match emit::quick_check_until(&model, &ctl, session.stop) {
                    Ok(()) if !session.settings.clamps.is_empty() => {
                        // the clamps are checked as you type (on the program compile writes)
                        generate_and_review_as(session, &model, &file_name, banner, true, None);
                    }
                    Ok(()) => {}
                    Err(errs) => errs.into_iter().for_each(|e| session.diags.push(e)),
                }
            } else if reference_check {
                match emit::check_until(
                    &model,
                    session.settings.sweep_speed,
                    &Controller::for_model(&session.settings, &model),
                    session.stop,
                ) {
                    Ok(stats) => outcome.stats.push((model.name().to_string(), stats)),
                    Err(errs) => errs.into_iter().for_each(|e| session.diags.push(e)),
                }
            } else if let Some(r) = generate_and_review(session, &model, &file_name, banner) {
                outcome
                    .stats
                    .push((model.name().to_string(), r.generated.stats));
            }
        }
        return outcome;
    }
    let Some((model, _)) = built.pop() else {
        return outcome;
    };
    if session.diags.has_errors() {
        return outcome;
    }
    for d in emit::comment::comment_changes(&model, &file_name, session.settings.dialect) {
        session.diags.push(d);
    }
    let prefix = output_prefix(input, &model.params.r);
    outcome.start = model.raw.start.as_ref().map(|m| m.origin.clone());
    let with = |s: &str| PathBuf::from(format!("{}{s}", prefix.display()));
    // the milling program's extension is its post's (`.gcode`, xcam's `.NCC`)
    let milling = format!(
        "_Milling.{}",
        emit::Controller::of(&session.settings).post.extension
    );
    let stage_at = session.settings.stage_outputs.then(|| with(&milling));
    let Some(Reviewed {
        generated,
        removed_volume,
        staged,
    }) = generate_and_review_as(
        session,
        &model,
        &file_name,
        banner,
        false,
        stage_at.as_deref(),
    )
    else {
        return outcome;
    };
    outcome.removed_volume = removed_volume;
    if session.diags.has_errors() {
        // a controller dialect whose checker objects: nothing is written
        if let Some(s) = &staged {
            s.discard();
        }
        return outcome;
    }
    let output = |path: PathBuf, content: String| OutputFile {
        path,
        content,
        staged: None,
    };
    outcome.outputs = match (generated.output, staged) {
        (Output::Milling(g), staged) => vec![OutputFile {
            staged: staged.map(|s| s.path),
            ..output(with(&milling), g)
        }],
        (
            Output::Probing {
                probing,
                z_txt,
                clean,
            },
            None,
        ) => vec![
            output(with("_Probing.gcode"), probing),
            output(with("_Z.txt"), z_txt),
            output(with("_Clean.gcode"), clean),
        ],
        (Output::Probing { probing, z_txt, .. }, Some(mut staged)) => {
            // the digest of a staged set: over the file, stamped into it and the probing program
            let post = emit::Controller::of(&session.settings).post;
            match staged.stamp_set(banner, &z_txt, &post) {
                Ok(stamped) => vec![
                    output(
                        with("_Probing.gcode"),
                        emit::program::stamp_banner(probing, &stamped),
                    ),
                    output(with("_Z.txt"), z_txt),
                    OutputFile {
                        staged: Some(staged.path),
                        ..output(with("_Clean.gcode"), String::new())
                    },
                ],
                Err(d) => {
                    session.diags.push(d);
                    return outcome;
                }
            }
        }
    };
    outcome
        .stats
        .push((model.name().to_string(), generated.stats));
    outcome
}

/// A path that defines variables gets no values as a top-level compile (reference-input.md
/// §6.2): what follows (a `>` name with `=X` in it, values that are no numbers) is explained.
fn warn_variables_not_given(session: &mut Session, name: &str) {
    let Some(raw) = session.raw_path(name) else {
        return;
    };
    let Some(text) = raw.start_text.as_ref().filter(|t| !t.vars.is_empty()) else {
        return;
    };
    let vars: String = text.vars.iter().map(|(n, _)| *n).collect();
    session.diags.push(Diagnostic::warning(
        Msg::VariablesNotGiven,
        raw.start_origin(),
        args![name, vars],
    ));
}

/// Generates the program of a model and has the independent checker review it; its
/// findings go to the session. `None` when generation failed.
fn generate_and_review(
    session: &mut Session,
    model: &model::Model,
    file_name: &str,
    banner: &str,
) -> Option<Reviewed> {
    generate_and_review_as(session, model, file_name, banner, false, None)
}

/// A generated program and what the second opinion said.
struct Reviewed {
    generated: emit::Generated,
    /// Material removed, mm³ (the checker's stock model).
    removed_volume: Option<f64>,
    /// Where the program is when it was staged (its text in `generated` is empty then).
    staged: Option<stage::Staged>,
}

/// One program's generation as a session asks for it; the sink its lines go to varies.
struct Generation<'a> {
    model: &'a model::Model,
    file_name: &'a str,
    banner: &'a str,
    sweep_speed: f64,
    lang: Lang,
    ctl: Controller,
    stop: Option<&'a dyn Fn() -> bool>,
}

impl Generation<'_> {
    fn run<S: emit::LineSink>(&self, sink: S) -> Result<(emit::Generated, S), Vec<Diagnostic>> {
        emit::generate_into(
            self.model,
            self.file_name,
            self.banner,
            self.sweep_speed,
            self.lang,
            &self.ctl,
            self.stop,
            sink,
        )
    }
}

/// [`generate_and_review`]; `clamps_only`: without the stock model, only the clamps' findings.
/// `stage_at`: the program goes to a temporary file beside this output as it is generated.
/// A check keeps no text at all: the checker reads each line as it is written.
fn generate_and_review_as(
    session: &mut Session,
    model: &model::Model,
    file_name: &str,
    banner: &str,
    clamps_only: bool,
    stage_at: Option<&Path>,
) -> Option<Reviewed> {
    let job = Generation {
        model,
        file_name,
        banner,
        sweep_speed: session.settings.sweep_speed,
        lang: session.lang(),
        ctl: Controller::for_model(&session.settings, model),
        stop: session.stop,
    };
    let reading = machine::Reading::checked(session.settings.dialect, &job.ctl.post);
    let reviewer = || {
        second_opinion::Reviewer::new(
            model,
            reading.clone(),
            &session.settings.clamps,
            clamps_only,
        )
    };
    let lang = job.lang;
    let generated = if let Some(output) = stage_at {
        // compile: the program to a file beside its output, read by the checker meanwhile
        let line_end = emit::Controller::of(&session.settings)
            .post
            .format
            .line_end
            .text();
        stage::Staging::new(output, reviewer(), line_end)
            .map_err(|d| vec![d])
            .and_then(|staging| {
                let path = staging.path().to_path_buf();
                let (generated, staging) = job
                    .run(staging)
                    .inspect_err(|_| temporaries::remove(&path))?;
                let (staged, reviewer) = staging.close().map_err(|d| vec![d])?;
                // the second reading (clamps, depths, stock model) from the file
                let review = reviewer.finish(model, &generated.line_sources, lang, |feed| {
                    staged.replay(feed)
                });
                Ok((generated, review, Some(staged)))
            })
    } else if !session.settings.check {
        // the text is kept (core's callers other than the command line)
        generate_for(model, file_name, banner, job.sweep_speed, lang, &job.ctl).map(|generated| {
            let program = match &generated.output {
                Output::Milling(g) => g,
                Output::Probing { clean, .. } => clean,
            };
            let review = second_opinion::review(
                program,
                model,
                &generated.line_sources,
                lang,
                reading.clone(),
                &session.settings.clamps,
                clamps_only,
            );
            (generated, review, None)
        })
    } else {
        job.run(reviewer().spooling()).map(|(generated, reviewer)| {
            // the second reading (clamps, depths, stock model) from the lines kept compressed
            let review = reviewer.finish_spooled(model, &generated.line_sources, lang);
            (generated, review, None)
        })
    };
    let (generated, review, staged) = match generated {
        Ok(r) => r,
        Err(errs) => {
            errs.into_iter().for_each(|e| session.diags.push(e));
            return None;
        }
    };
    for d in review.diagnostics {
        session.diags.push(d);
    }
    Some(Reviewed {
        generated,
        removed_volume: review.removed_volume,
        staged,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A command line's one-file session drops the drawing's segments once its models are
    /// built; the models keep none, and the program is the same as with them kept.
    #[test]
    fn a_one_file_session_releases_the_drawing_and_compiles_the_same() {
        let mut text =
            String::from("path 3000.1P {\n  start (0, 0)  O2 T2 I1,2 B-0,3\n  end (40, 0)\n");
        for i in 0..40 {
            text.push_str(&format!(
                "  mill ({i}, {}) -> ({}, {})\n",
                i % 2,
                i + 1,
                (i + 1) % 2
            ));
        }
        text.push_str("}\n");
        let mut fs = MemFileSystem::default();
        fs.add("3000.mpath", text.into_bytes());
        let settings = Settings {
            feed: 150.0,
            sweep_speed: 500.0,
            sweep_height: 15.0,
            ..Settings::default()
        };
        let run = |one_file: bool| {
            let mut s = Session::new(settings.clone(), &fs).unwrap();
            s.one_file = one_file;
            let out = compile_file(&mut s, Path::new("3000.mpath"), "test");
            let segments: usize = s.raw.values().map(|p| p.segments.len()).sum();
            let model_segments: usize = s
                .models
                .values()
                .flatten()
                .map(|m| m.raw.segments.len())
                .sum();
            assert!(!s.diags.has_errors(), "{:?}", s.diags.list);
            (out.outputs[0].content.clone(), segments, model_segments)
        };
        let (kept, kept_segments, model_segments) = run(false);
        let (released, released_segments, released_model_segments) = run(true);
        assert_eq!(kept_segments, 40);
        assert_eq!(released_segments, 0);
        assert_eq!((model_segments, released_model_segments), (0, 0));
        assert!(kept.contains("G01"));
        assert_eq!(kept, released);
    }

    #[test]
    fn inputs_and_prefixes() {
        assert_eq!(complete_input("8999.02P"), PathBuf::from("8999.02P.dxf"));
        assert_eq!(complete_input("X.DXF"), PathBuf::from("X.DXF"));
        assert_eq!(
            output_prefix(Path::new("dir/8999.32P.dxf"), "_VAR"),
            PathBuf::from("dir/8999.32P_VAR")
        );
        assert_eq!(
            output_prefix(Path::new("8999.23 Pv.dxf"), ""),
            PathBuf::from("8999.23 Pv")
        );
    }
}
