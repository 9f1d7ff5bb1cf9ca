//! `verify` of a G-code text: `millpath-verify` with the reading rules of a dialect, or of
//! the family of a post (as the second opinion reads that post's programs). Plain Rust.

use millpath_core::load::clamps::errors as clamp_errors;
use millpath_core::machine::checked::Reading;
use millpath_core::Lang;
use millpath_verify::{Clamp, Options, Report};
use std::path::Path;

/// The checker's options for `dialect_or_post`: `reference`, `linuxcnc`, `rs274`, `grbl`,
/// `marlin`, or a built-in post's name.
pub fn options_for(dialect_or_post: &str, lang: Lang) -> Result<Options, String> {
    use millpath_verify::Dialect as V;
    let direct = match dialect_or_post {
        "reference" => Some(V::Reference),
        "linuxcnc" | "rs274" => Some(V::LinuxCnc),
        "grbl" => Some(V::Grbl),
        "marlin" => Some(V::Marlin),
        _ => None,
    };
    if let Some(dialect) = direct {
        return Ok(Options {
            dialect,
            ..Default::default()
        });
    }
    // a post file is not read here: only built-in posts by name
    let none = |_: &Path| Err::<String, String>("no post files here".into());
    let (dialect, post) =
        millpath_core::emit::dialect::select_post(dialect_or_post, Path::new(""), &none, lang)?;
    let post = post.unwrap_or_else(|| dialect.shared_post());
    let reading = Reading::of(dialect, &post).map_err(|family| {
        format!("{dialect_or_post}: the checker cannot read the {family:?} family")
    })?;
    Ok(Options {
        dialect: reading.dialect,
        arcs_as_lines: reading.arcs_as_lines,
        ..Default::default()
    })
}

/// Checks the program; `Err`: unusable options or clamps (the messages).
pub fn verify(
    gcode: &str,
    dialect_or_post: &str,
    clamps: Vec<Clamp>,
    lang: Lang,
) -> Result<Report, String> {
    let mut options = options_for(dialect_or_post, lang)?;
    let errs = clamp_errors(&clamps, None);
    if !errs.is_empty() {
        let m: Vec<String> = errs.iter().map(|d| crate::run::located(d, lang)).collect();
        return Err(m.join("\n"));
    }
    options.clamps = clamps;
    Ok(millpath_verify::verify(gcode, &options))
}
