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
    // the post of the programs, as adjust-z finds it (a height map's moves are its words)
    let first = parsed.files.first().map(std::path::Path::new);
    let post = match super::adjust_z::post_of(None, first, lang) {
        Ok(post) => post,
        Err(e) => {
            eprintln!("{e}");
            return 2;
        }
    };
    super::adjust_z::run(
        parsed.m.unwrap_or(0.0),
        parsed.x.as_deref(),
        lang,
        &parsed.files,
        true,
        &post,
    )
}
