//! `millpath pathgcodeadjustz`: the reference PathGCodeAdjustZ command line, unchanged.

use crate::compat;
use millpath_core::diag::{Diagnostic, Msg, Origin};

pub fn run(args: &[String]) -> u8 {
    let parsed = compat::parse(args, compat::Tool::AdjustZ);
    let lang = parsed.settings.lang;
    eprintln!(
        "---- {} (PathGCodeAdjustZ-compatible)",
        millpath_core::banner()
    );
    if args.is_empty() || parsed.help || !parsed.errors.is_empty() {
        for e in &parsed.errors {
            eprintln!("{}", e.reference_line(lang));
        }
        eprintln!();
        eprintln!("{}", compat::help_adjustz(lang));
        return 2;
    }
    if parsed.files.is_empty() {
        eprintln!(
            "{}",
            Diagnostic::error(Msg::NoDxfFiles, Origin::Options, vec![]).reference_line(lang)
        );
        return 3;
    }
    super::adjust_z::run(
        parsed.m.unwrap_or(0.0),
        parsed.x.as_deref(),
        lang,
        &parsed.files,
        true,
    )
}
