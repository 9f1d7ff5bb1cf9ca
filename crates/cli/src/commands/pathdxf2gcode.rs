//! `millpath pathdxf2gcode`: the reference PathDxf2GCode command line, unchanged.

use crate::compat;
use crate::output::{flush_info, print_stats, write_outputs};
use millpath_core::diag::{Diagnostic, Diags, FileRef, Msg, Origin, Severity};
use millpath_core::{compile_file, complete_input, OsFileSystem, Session};

/// `millpath pathdxf2gcode …`: the reference command line.
pub fn run(args: &[String]) -> u8 {
    let parsed = compat::parse(args, compat::Tool::Dxf2GCode);
    let lang = parsed.settings.lang;
    eprintln!(
        "---- {} (PathDxf2GCode-compatible)",
        millpath_core::banner()
    );
    eprintln!();
    if let Some(code) = compat::refused(args, &parsed, compat::help_dxf2gcode(lang)) {
        return code;
    }
    let fs = OsFileSystem;
    let mut settings = parsed.settings;
    // `/c` as the reference checks; one session for every file (its "no error so far" rule)
    settings.reference_check = true;
    let mut session = match Session::new(settings, &fs) {
        Ok(s) => s,
        Err(errs) => {
            for e in errs {
                eprintln!("{}", e.reference_line(lang));
            }
            eprintln!();
            eprintln!("{}", compat::help_dxf2gcode(lang));
            return 2;
        }
    };
    let mut write_errors = Diags::default();
    for f in &parsed.files {
        let input = complete_input(f);
        let outcome = compile_file(&mut session, &input, &millpath_core::banner());
        flush_info(&mut session);
        // a _Z.txt with measured values is kept beside before the reference's empty one
        // replaces it (the files written stay the reference's)
        let mut kept = Vec::new();
        let mut keep_failed = false;
        for z in outcome
            .outputs
            .iter()
            .filter(|o| o.path.to_string_lossy().ends_with("_Z.txt"))
        {
            match crate::measured::keep_filled_for_reference(&z.path, &z.content) {
                Ok(Some(side)) => kept.push(Diagnostic::warning(
                    Msg::ZKeptForReference,
                    Origin::File(FileRef::new(z.path.clone())),
                    millpath_core::args![z.path.display(), side.display()],
                )),
                Ok(None) => {}
                Err(d) => {
                    keep_failed = true;
                    write_errors.push(d);
                }
            }
        }
        if keep_failed {
            for tmp in outcome.outputs.iter().filter_map(|o| o.staged.as_ref()) {
                let _ = std::fs::remove_file(tmp);
            }
            continue;
        }
        if write_outputs(&outcome.outputs, lang, &mut write_errors) {
            print_stats(&outcome, lang);
        }
        // not a `****`/`++++` line: the reference has no such words
        for d in kept {
            eprintln!("{}", crate::report::human(&d, lang));
        }
    }
    let mut failed = false;
    // the reference prints no word on entity order, nor on the entities it ignores: those
    // warnings are for check, compile and the editor
    let ours = |d: &&Diagnostic| {
        !matches!(
            d.msg,
            Msg::OrderDecides
                | Msg::OrderDecidesText
                | Msg::OrderDecidesNoPin
                | Msg::OrderDecidesPiece
                | Msg::IgnoredEntity
                | Msg::TextTakenFirst
                | Msg::CommentTextChanged
        )
    };
    for d in session
        .diags
        .list
        .iter()
        .chain(write_errors.list.iter())
        .filter(ours)
    {
        eprintln!("{}", d.reference_line(lang));
        failed |= d.severity == Severity::Error;
    }
    u8::from(failed)
}
