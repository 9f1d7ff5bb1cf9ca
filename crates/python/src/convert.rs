//! `dxf2text`, `text2dxf` and `format` of texts and bytes held in memory: the command line's
//! conversions (`millpath_core::convert`) with the default name patterns. Plain Rust.

use crate::run::located;
use millpath_core::convert::{self, IntoOutcome};
use millpath_core::diag::FileRef;
use millpath_core::load::names::Patterns;
use millpath_core::{Diagnostic, InputMode, Lang, Settings};
use std::path::PathBuf;
use std::sync::Arc;

/// The default `/n` and `/p` patterns (the settings' defaults).
fn patterns() -> Result<Arc<Patterns>, String> {
    let s = Settings::default();
    Patterns::shared(&s.path_pattern, &s.file_pattern)
        .map_err(|(c, p, e)| format!("/{c} '{p}': {e}"))
}

fn messages(diags: &[Diagnostic], lang: Lang) -> String {
    let all: Vec<String> = diags.iter().map(|d| located(d, lang)).collect();
    all.join("\n")
}

/// The canonical text of a DXF drawing, and the warnings about what the text cannot hold.
pub fn dxf2text(
    bytes: &[u8],
    name: &str,
    extended: bool,
    lang: Lang,
) -> Result<(String, Vec<Diagnostic>), String> {
    let file = FileRef::new(PathBuf::from(name));
    let input = if extended {
        InputMode::Extended
    } else {
        InputMode::Reference
    };
    let patterns = patterns()?;
    convert::dxf_to_text(bytes, &file, &patterns, input).map_err(|d| located(&d, lang))
}

/// The DXF of a text; with `into`, that drawing with its path objects replaced by the text's
/// (paths of the drawing the text lacks are refused, as `--into` refuses them).
pub fn text2dxf(src: &str, name: &str, into: Option<&[u8]>, lang: Lang) -> Result<Vec<u8>, String> {
    let file = FileRef::new(PathBuf::from(name));
    let patterns = patterns()?;
    match into {
        None => convert::text_to_dxf(src, &file, &patterns)
            .map(String::into_bytes)
            .map_err(|d| messages(&d, lang)),
        Some(target) => {
            let target_file = FileRef::new(PathBuf::from("into.dxf"));
            let out = convert::text_into_dxf(
                src,
                &file,
                &patterns,
                target,
                &target_file,
                InputMode::Reference,
                false,
            );
            match out {
                Ok(IntoOutcome::Written(dxf)) => Ok(dxf),
                Ok(IntoOutcome::Unchanged) => Ok(target.to_vec()),
                Err(d) => Err(messages(&d, lang)),
            }
        }
    }
}

/// The canonical form of a text (`millpath fmt`); syntax errors refuse it.
pub fn format(src: &str, name: &str, lang: Lang) -> Result<String, String> {
    let file = FileRef::new(PathBuf::from(name));
    convert::format_text(src, &file).map_err(|d| messages(&d, lang))
}
