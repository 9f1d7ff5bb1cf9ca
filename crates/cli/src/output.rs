//! Printing diagnostics and progress, and writing output files, as every command does.

use crate::{out, report, write};
use millpath_core::diag::{Diagnostic, Diags, Msg, Origin};
use millpath_core::{Lang, Session};
use std::path::Path;

/// Writes the outputs; "Writing …" is printed only for a file that was written. False when
/// any write failed.
pub fn write_outputs(outputs: &[millpath_core::OutputFile], lang: Lang, diags: &mut Diags) -> bool {
    let verb = if lang == Lang::De {
        "Schreiben von"
    } else {
        "Writing"
    };
    let mut ok = true;
    for o in outputs {
        match write::write_atomic(&o.path, &o.content) {
            Ok(()) => eprintln!("---- {verb} {}", o.path.display()),
            Err(e) => {
                ok = false;
                diags.error(
                    Msg::CannotWrite,
                    Origin::Options,
                    millpath_core::args![o.path.display(), e],
                );
            }
        }
    }
    ok
}

pub fn print_stats(outcome: &millpath_core::FileOutcome, lang: Lang) {
    for (_, s) in &outcome.stats {
        let l = s.lines(lang);
        eprintln!("  {};  {};", l[0], l[1]);
        eprintln!("  {};  {};  {};", l[2], l[3], l[4]);
        if let Some(m) = s.model_line(lang) {
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
