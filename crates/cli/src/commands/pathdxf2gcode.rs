//! `millpath pathdxf2gcode`: the reference PathDxf2GCode command line, unchanged.

use crate::compat;
use crate::output::{flush_info, print_stats, write_outputs};
use millpath_core::diag::{Diagnostic, Diags, Msg, Severity};
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
        if write_outputs(&outcome.outputs, lang, &mut write_errors) {
            print_stats(&outcome, lang);
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
