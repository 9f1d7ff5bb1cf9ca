//! Printing diagnostics and progress, and writing output files, as every command does.
//!
//! Printing diagnostics, statistics and progress; writing a drawing's outputs as one set
//! (`write_outputs`), and for `compile` removing that drawing's outputs of an earlier compile that
//! a failed compile or another set leaves behind (`write_drawing_outputs`, `remove_with` shared
//! with adjust-z).

use crate::measured::ZWrite;
use crate::{out, report, write};
use millpath_core::diag::{Diagnostic, Diags, Msg, Origin};
use millpath_core::probe::adjustz;
use millpath_core::{Lang, Session};
use std::path::{Path, PathBuf};

/// Writes the outputs of one drawing as one set, all or none ([`write::write_set`]);
/// "Writing …" is printed for each file once the set is in place. False when it failed.
pub fn write_outputs(outputs: &[millpath_core::OutputFile], lang: Lang, diags: &mut Diags) -> bool {
    write_reported(outputs, lang, diags).is_ok()
}

/// [`write_outputs`]; `Err` names the file that could not be written.
fn write_reported(
    outputs: &[millpath_core::OutputFile],
    lang: Lang,
    diags: &mut Diags,
) -> Result<(), PathBuf> {
    let verb = if lang == Lang::De {
        "Schreiben von"
    } else {
        "Writing"
    };
    let files: Vec<(&Path, write::Content)> = outputs
        .iter()
        .map(|o| {
            let content = match &o.staged {
                Some(tmp) => write::Content::Staged(tmp),
                None => write::Content::Text(&o.content),
            };
            (o.path.as_path(), content)
        })
        .collect();
    match write::write_set(&files) {
        Ok(()) => {
            for o in outputs {
                eprintln!("---- {verb} {}", o.path.display());
            }
            Ok(())
        }
        Err((path, e)) => {
            diags.error(
                Msg::CannotWrite,
                Origin::Options,
                millpath_core::args![path.display(), e],
            );
            Err(path)
        }
    }
}

/// The endings of a drawing's outputs: a milling program, or a probing set.
const MILLING: &[&str] = &["_Milling.gcode"];
const PROBING: &[&str] = &["_Probing.gcode", "_Z.txt", "_Clean.gcode"];

/// `compile`'s writing of one drawing: the set all or none, and no output of an earlier
/// compile of the same drawing left beside it that does not belong to this one (`verify`
/// and `adjust-z` would take it for current). After a failed compile that is its
/// `_Milling.gcode`, `_Probing.gcode` and `_Clean.gcode` (a filled-in `_Z.txt` holds the
/// machinist's measurements and cannot be used without its `_Clean.gcode`: it stays);
/// after a milling program, an older probing program and `_Clean.gcode`; after a probing
/// set, a `_Milling.gcode` adjusted from another set. A filled-in `_Z.txt` of the same
/// probes stays as it is; of other probes it is kept beside (`measured.rs`). False when
/// nothing was written.
pub fn write_drawing_outputs(
    input: &Path,
    outcome: &millpath_core::FileOutcome,
    lang: Lang,
    diags: &mut Diags,
) -> bool {
    let drawing = input
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    if outcome.outputs.is_empty() {
        // a drawing that is not there (a mistyped name) has no outputs of its own
        if !input.is_file() {
            return false;
        }
        let prefix = millpath_core::output_prefix(input, "");
        for end in ["_Milling.gcode", "_Probing.gcode", "_Clean.gcode"] {
            remove_stale(&with_end(&prefix, end), diags);
        }
        other_posts(&prefix, &drawing, None, diags);
        return false;
    }
    let ends = |o: &millpath_core::OutputFile, end: &str| o.path.to_string_lossy().ends_with(end);
    // the new set's digest, read before its staged program is renamed into place
    let ours = outcome
        .outputs
        .iter()
        .find(|o| ends(o, PROBING[2]))
        .and_then(|clean| adjustz::stored_digest(&clean.head(3)).map(str::to_string));
    let mut outputs = outcome.outputs.clone();
    let mut kept = None;
    let mut aside = None;
    if let Some(zi) = outputs.iter().position(|o| ends(o, PROBING[1])) {
        let probing = outputs.iter().find(|o| ends(o, PROBING[0]));
        let probing = probing.map_or("", |o| o.content.as_str());
        let z = &outputs[zi];
        match crate::measured::prepare(&z.path, &z.content, probing, ours.as_deref(), lang) {
            Ok(ZWrite::AsIs) => {}
            Ok(ZWrite::Keep) => kept = Some(outputs.remove(zi).path),
            Ok(ZWrite::Replace {
                content,
                side,
                said,
            }) => {
                outputs[zi].content = content;
                aside = Some((side, said));
            }
            Err(d) => {
                diags.push(d);
                for tmp in outputs.iter().filter_map(|o| o.staged.as_ref()) {
                    let _ = std::fs::remove_file(tmp);
                }
                return false;
            }
        }
    }
    if let Err(failed) = write_reported(&outputs, lang, diags) {
        if outputs.len() > 1 {
            diags.push(Diagnostic::warning(
                Msg::OutputSetRestored,
                Origin::Options,
                millpath_core::args![failed.display()],
            ));
        }
        // the old _Z.txt is back in place: its second name is not needed
        if let Some((side, _)) = aside {
            let _ = std::fs::remove_file(side);
        }
        return false;
    }
    if let Some(z) = kept {
        let verb = match lang {
            Lang::En => "Keeping (measured values of the same probes)",
            Lang::De => "Behalten (Messwerte derselben Messpunkte)",
        };
        eprintln!("---- {verb} {}", z.display());
    }
    if let Some((_, said)) = aside {
        diags.push(said);
    }
    let written = |end: &str| {
        outcome.outputs.iter().find_map(|o| {
            let s = o.path.to_string_lossy();
            s.strip_suffix(end).map(PathBuf::from)
        })
    };
    // a post's own extension: xcam's `_Milling.NCC`
    let milling = outcome.outputs.iter().find_map(|o| {
        let s = o.path.to_string_lossy();
        s.rfind("_Milling.").map(|i| PathBuf::from(&s[..i]))
    });
    if let Some(prefix) = written(MILLING[0]).or(milling) {
        for end in ["_Probing.gcode", "_Clean.gcode"] {
            remove_stale(&with_end(&prefix, end), diags);
        }
        let program = outcome
            .outputs
            .iter()
            .find(|o| o.path.to_string_lossy().contains("_Milling."));
        other_posts(&prefix, &drawing, program.map(|o| o.path.as_path()), diags);
    } else if let Some(prefix) = written(PROBING[2]) {
        // `_Milling.gcode` beside a probing set follows the digest rule below
        for found in crate::other_post::find(&prefix, &drawing, None, &["gcode"]) {
            apply(found, diags);
        }
        // an adjusted program of this very set (same digest) is still right; its banner
        // line is among its first lines (the program may be long)
        let milling = with_end(&prefix, MILLING[0]);
        let theirs = millpath_core::stage::file_head(&milling, 3);
        let same = ours.is_some() && adjustz::stored_digest(&theirs) == ours.as_deref();
        if !same {
            remove_stale(&milling, diags);
        }
    }
    true
}

/// The programs of this drawing for another post (`other_post.rs`): stale ones removed,
/// measured ones kept, each said.
fn other_posts(prefix: &Path, drawing: &str, written: Option<&Path>, diags: &mut Diags) {
    // after a failed compile `_Milling.gcode` was handled above
    let skip: &[&str] = if written.is_none() { &["gcode"] } else { &[] };
    for found in crate::other_post::find(prefix, drawing, written, skip) {
        apply(found, diags);
    }
}

fn apply(found: crate::other_post::Found, diags: &mut Diags) {
    match found {
        crate::other_post::Found::Stale(path, said) => remove_with(&path, said, diags),
        crate::other_post::Found::Measured(said) => diags.push(said),
    }
}

fn with_end(prefix: &Path, end: &str) -> PathBuf {
    PathBuf::from(format!("{}{end}", prefix.display()))
}

/// Removes `path`, an output of an earlier compile, with a warning; nothing when it is not
/// a file.
pub fn remove_stale(path: &Path, diags: &mut Diags) {
    remove_with(
        path,
        Diagnostic::warning(
            Msg::StaleOutputRemoved,
            Origin::File(millpath_core::diag::FileRef::new(path.to_path_buf())),
            millpath_core::args![path.display()],
        ),
        diags,
    );
}

/// Removes the file `path` and reports `said` (a warning naming it), or why it could not.
pub fn remove_with(path: &Path, said: Diagnostic, diags: &mut Diags) {
    if !std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file()) {
        return;
    }
    match write::remove_output(path) {
        Ok(()) => diags.push(said),
        Err(e) => diags.error(
            Msg::CannotRemove,
            Origin::Input,
            millpath_core::args![path.display(), e],
        ),
    }
}

pub fn print_stats(outcome: &millpath_core::FileOutcome, lang: Lang) {
    for (_, s) in &outcome.stats {
        let l = s.lines(lang);
        eprintln!("  {};  {};", l[0], l[1]);
        eprintln!("  {};  {};  {};", l[2], l[3], l[4]);
        if let Some(m) = s.model_line(lang) {
            eprintln!("  {m}");
        }
        if let Some(m) = s.split_line(lang) {
            eprintln!("  {m}");
        }
    }
}

pub fn flush_info(session: &mut Session) {
    for line in session.info.drain(..) {
        eprintln!("{line}");
    }
}

pub fn print_human(diags: &[Diagnostic], lang: Lang) {
    let color = report::use_color(std::io::IsTerminal::is_terminal(&std::io::stderr()));
    for d in diags {
        eprintln!("{}", report::human_rich(d, lang, color));
    }
}

/// Writes `content` to `output`, or to standard output.
pub fn emit(output: Option<&Path>, content: &str, lang: Lang) -> u8 {
    match output {
        Some(p) => match write::write_atomic(p, content) {
            Ok(()) => 0,
            Err(e) => {
                let d = Diagnostic::error(
                    Msg::CannotWrite,
                    Origin::Options,
                    millpath_core::args![p.display(), e],
                );
                eprintln!("{}", report::human(&d, lang));
                1
            }
        },
        None => {
            out::write(content);
            0
        }
    }
}

/// An output named like a drawing the command reads (`--svg part.mpath` for `--svg
/// part.svg`): printed as MP215 and `true`, so the command writes nothing. `outputs` are
/// (file, what it holds: "SVG"); `inputs` are canonical paths.
pub fn output_is_input(outputs: &[(Option<&Path>, &str)], inputs: &[PathBuf], lang: Lang) -> bool {
    for &(out, what) in outputs {
        let Some(out) = out else { continue };
        if dunce::canonicalize(out).is_ok_and(|o| inputs.contains(&o)) {
            let d = Diagnostic::error(
                Msg::OutputIsInput,
                Origin::File(millpath_core::diag::FileRef::new(out.to_path_buf())),
                millpath_core::args![out.display(), what],
            );
            eprintln!("{}", report::human(&d, lang));
            return true;
        }
    }
    false
}
