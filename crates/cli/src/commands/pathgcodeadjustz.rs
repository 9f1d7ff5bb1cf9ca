//! `millpath pathgcodeadjustz`: the reference PathGCodeAdjustZ command line, unchanged.

use crate::compat;

pub fn run(args: &[String]) -> u8 {
    let parsed = compat::parse(args, compat::Tool::AdjustZ);
    let lang = parsed.settings.lang;
    eprintln!(
        "---- {} (PathGCodeAdjustZ-compatible)",
        millpath_core::banner()
    );
    if let Some(code) = compat::refused(args, &parsed, compat::help_adjustz(lang)) {
        return code;
    }
    super::adjust_z::run(
        parsed.m.unwrap_or(0.0),
        parsed.x.as_deref(),
        lang,
        &parsed.files,
        true,
        millpath_core::Dialect::Reference.post(),
    )
}
