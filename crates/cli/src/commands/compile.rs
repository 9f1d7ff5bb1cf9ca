//! `millpath compile`: drawings to G-code files beside them. Each drawing stands alone (a
//! session of its own): a bad one stops only itself, and a summary names those not written.

use crate::args::{lang_of, settings_for, MachineArgs};
use crate::claims::Claims;
use crate::inputs::compile_inputs;
use crate::output::{flush_info, print_human, print_stats, write_drawing_outputs};
use crate::report;
use crate::stale::Sweeper;
use millpath_core::diag::{Diags, FileRef, Severity};
use millpath_core::{compile_file, Diagnostic, Lang, Msg, Origin, OsFileSystem, Session, Settings};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

pub fn run(m: &MachineArgs, files: &[String]) -> u8 {
    // the language of every message, also of those before the settings are read
    let early = lang_of(m, files.first().map(std::path::Path::new));
    let inputs = match compile_inputs(files) {
        Ok(i) => i,
        Err(dir) => {
            eprintln!(
                "{}",
                match early {
                    Lang::En => format!("error: no drawings (*.dxf, *.mpath) found in {dir}"),
                    Lang::De =>
                        format!("Fehler: keine Zeichnungen (*.dxf, *.mpath) in {dir} gefunden"),
                }
            );
            return 3;
        }
    };
    // each drawing's settings: the millpath.toml nearest to it, then the options; any that
    // cannot be had (or holds invalid patterns or numbers) stops the run before a drawing
    let mut each = Vec::with_capacity(inputs.len());
    for input in &inputs {
        let settings = match settings_for(m, Some(input), true) {
            // the program goes to a temporary file as it is generated, never held whole
            Ok(s) => Settings {
                stage_outputs: true,
                ..s
            },
            Err(e) => {
                eprintln!("{}: {e}", report::severity_word(Severity::Error, early));
                return 2;
            }
        };
        if let Err(errs) = Session::new(settings.clone(), &OsFileSystem) {
            print_human(&errs, settings.lang);
            return 2;
        }
        each.push(settings);
    }
    let lang = each.first().map_or(early, |s| s.lang);
    let mut not_written = Vec::new();
    let mut sweeper = Sweeper::default();
    let mut claims = Claims::default();
    let colliding = same_outputs(&inputs);
    for (i, (input, settings)) in inputs.iter().zip(&each).enumerate() {
        if let Some(other) = colliding.get(&i) {
            let d = Diagnostic::error(
                Msg::OutputsCollide,
                Origin::File(FileRef::new(input.clone())),
                millpath_core::args![
                    input.display(),
                    inputs[*other].display(),
                    millpath_core::output_prefix(input, "").display()
                ],
            );
            print_human(&[d], settings.lang);
            not_written.push(input.as_path());
            continue;
        }
        if !compile_one(settings, input, &mut sweeper, &mut claims) {
            not_written.push(input.as_path());
        }
    }
    if inputs.len() > 1 {
        eprintln!("{}", summary(inputs.len(), &not_written, lang));
    }
    u8::from(!not_written.is_empty())
}

/// The inputs whose outputs would be the same files as another input's (`part.dxf` and
/// `part.mpath` in one folder, as the two-ways workflow leaves them: both write
/// `part_Milling.gcode`), each with one of the others. The later one's program would replace
/// the earlier one's without a word, so neither is compiled. One file given twice is no
/// such pair. On Windows and macOS file names ignore case, and so does the comparison.
fn same_outputs(inputs: &[PathBuf]) -> HashMap<usize, usize> {
    let key = |input: &Path| -> Option<(PathBuf, String)> {
        let dir = match input.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let stem = input.file_stem()?.to_string_lossy().into_owned();
        let stem = if cfg!(any(windows, target_os = "macos")) {
            stem.to_lowercase()
        } else {
            stem
        };
        Some((dunce::canonicalize(dir).ok()?, stem))
    };
    let mut first: HashMap<(PathBuf, String), (usize, Option<PathBuf>)> = HashMap::new();
    let mut pairs = HashMap::new();
    for (i, input) in inputs.iter().enumerate() {
        let Some(k) = key(input) else { continue };
        let me = dunce::canonicalize(input).ok();
        match first.get(&k) {
            Some((j, theirs)) if me.is_none() || *theirs != me => {
                pairs.insert(i, *j);
                pairs.entry(*j).or_insert(i);
            }
            Some(_) => {}
            None => {
                first.insert(k, (i, me));
            }
        }
    }
    pairs
}

/// The files a compile writes beside a drawing.
const OUTPUT_ENDS: [&str; 5] = [
    "_Milling.gcode",
    "_Milling.NCC",
    "_Probing.gcode",
    "_Z.txt",
    "_Clean.gcode",
];

/// Compiles one drawing in a session of its own and writes its outputs; prints its progress,
/// statistics and diagnostics. Whether its outputs were written. The temporaries that a
/// killed earlier compile left beside its outputs are swept first (`stale.rs`). Outputs
/// another drawing of the run wrote (through an `R` suffix) are refused (`claims.rs`).
fn compile_one(
    settings: &Settings,
    input: &Path,
    sweeper: &mut Sweeper,
    claims: &mut Claims,
) -> bool {
    let lang = settings.lang;
    let fs = OsFileSystem;
    let mut session = match Session::new(settings.clone(), &fs) {
        Ok(s) => s,
        Err(errs) => {
            print_human(&errs, lang);
            return false;
        }
    };
    session.one_file = true;
    let prefix = millpath_core::output_prefix(input, "");
    let own: Vec<PathBuf> = OUTPUT_ENDS
        .iter()
        .map(|end| PathBuf::from(format!("{}{end}", prefix.display())))
        .collect();
    for o in &own {
        sweeper.sweep(o);
    }
    let outcome = compile_file(&mut session, input, &millpath_core::banner());
    // a drawing's R (its outputs under another name)
    for o in &outcome.outputs {
        sweeper.sweep(&o.path);
    }
    flush_info(&mut session);
    let mut write_errors = Diags::default();
    let paths = || outcome.outputs.iter().map(|o| o.path.as_path());
    let written = if let Some((file, other)) = claims.taken(input, paths()) {
        let at = outcome.start.clone();
        let mut d = Diagnostic::error(
            Msg::OutputTakenInRun,
            at.unwrap_or_else(|| Origin::File(FileRef::new(input.to_path_buf()))),
            millpath_core::args![input.display(), file.display(), other.input.display()],
        );
        if let Some(theirs) = &other.start {
            let note = match lang {
                Lang::En => "start of the other drawing's path",
                Lang::De => "Start des Pfads der anderen Zeichnung",
            };
            d = d.with_related(theirs.clone(), note);
        }
        write_errors.push(d);
        // the other drawing's files stay as it wrote them
        for tmp in outcome.outputs.iter().filter_map(|o| o.staged.as_ref()) {
            let _ = std::fs::remove_file(tmp);
        }
        false
    } else if outcome.outputs.is_empty()
        && claims
            .taken(input, own.iter().map(PathBuf::as_path))
            .is_some()
    {
        // failed, and its outputs' names are another drawing's of this run: those stay
        false
    } else {
        // a failed drawing writes nothing and leaves none of its older outputs looking current
        write_drawing_outputs(input, &outcome, lang, &mut write_errors)
    };
    if written {
        claims.claim(input, outcome.start.clone(), paths());
        print_stats(&outcome, lang);
        // the exact estimate (the statistics above keep the reference's whole minutes);
        // like the volume, not in pathdxf2gcode's output, which stays the reference's
        for (_, s) in &outcome.stats {
            eprintln!("  {}", s.time_line(lang));
        }
        if let Some(v) = outcome.removed_volume {
            let label = if lang == Lang::De {
                "Abgetragenes Volumen"
            } else {
                "Removed volume"
            };
            eprintln!("  {label}: {v:.0} mm³");
        }
    }
    let all = session.diags.list.into_iter().chain(write_errors.list);
    let all = report::tidy(all.collect());
    print_human(&all, lang);
    written
}

/// The last line of a compile of several drawings: how many were written, which were not.
fn summary(total: usize, not_written: &[&Path], lang: Lang) -> String {
    let done = total - not_written.len();
    let names: Vec<String> = not_written
        .iter()
        .map(|p| p.display().to_string())
        .collect();
    match (lang, names.is_empty()) {
        (Lang::En, true) => format!("compiled {done} of {total} drawings"),
        (Lang::En, false) => format!(
            "compiled {done} of {total} drawings; not written: {}",
            names.join(", ")
        ),
        (Lang::De, true) => format!("{done} von {total} Zeichnungen übersetzt"),
        (Lang::De, false) => format!(
            "{done} von {total} Zeichnungen übersetzt; nicht geschrieben: {}",
            names.join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_names_the_drawings_not_written() {
        let bad = [Path::new("a/1.dxf"), Path::new("b.mpath")];
        assert_eq!(
            summary(5, &bad, Lang::En),
            "compiled 3 of 5 drawings; not written: a/1.dxf, b.mpath"
        );
        assert_eq!(
            summary(5, &bad, Lang::De),
            "3 von 5 Zeichnungen übersetzt; nicht geschrieben: a/1.dxf, b.mpath"
        );
        assert_eq!(summary(2, &[], Lang::En), "compiled 2 of 2 drawings");
    }
}
