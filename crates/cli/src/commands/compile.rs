//! `millpath compile`: drawings to G-code files beside them.

use crate::args::{lang_of, settings_for, MachineArgs};
use crate::inputs::compile_inputs;
use crate::output::{flush_info, print_human, print_stats, write_drawing_outputs};
use crate::report;
use millpath_core::diag::{Diagnostic, Diags, Severity};
use millpath_core::{compile_file, Lang, OsFileSystem, Session};
use std::path::PathBuf;

pub fn run(m: &MachineArgs, files: &[String]) -> u8 {
    let inputs = match compile_inputs(files) {
        Ok(i) => i,
        Err(dir) => {
            eprintln!(
                "{}",
                match lang_of(m) {
                    Lang::En => format!("error: no drawings (*.dxf, *.mpath) found in {dir}"),
                    Lang::De =>
                        format!("Fehler: keine Zeichnungen (*.dxf, *.mpath) in {dir} gefunden"),
                }
            );
            return 3;
        }
    };
    let settings = match settings_for(m, inputs.first().map(PathBuf::as_path), true) {
        Ok(s) => s,
        Err(e) => {
            eprintln!(
                "{}: {e}",
                report::severity_word(Severity::Error, lang_of(m))
            );
            return 2;
        }
    };
    let lang = settings.lang;
    let fs = OsFileSystem;
    let mut session = match Session::new(settings, &fs) {
        Ok(s) => s,
        Err(errs) => {
            print_human(&errs, lang);
            return 2;
        }
    };
    let mut write_errors = Diags::default();
    for input in inputs {
        let outcome = compile_file(&mut session, &input, &millpath_core::banner());
        flush_info(&mut session);
        if write_drawing_outputs(&input, &outcome, lang, &mut write_errors) {
            print_stats(&outcome, lang);
            if let (Some(v), false) = (outcome.removed_volume, outcome.outputs.is_empty()) {
                // not in pathdxf2gcode's output, which stays the reference's
                let label = if lang == Lang::De {
                    "Abgetragenes Volumen"
                } else {
                    "Removed volume"
                };
                eprintln!("  {label}: {v:.0} mm³");
            }
        }
    }
    let all: Vec<Diagnostic> = session
        .diags
        .list
        .iter()
        .chain(write_errors.list.iter())
        .cloned()
        .collect();
    let all = report::tidy(all);
    print_human(&all, lang);
    u8::from(all.iter().any(|d| d.severity == Severity::Error))
}
