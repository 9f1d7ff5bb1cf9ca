//! Which files a command works on.

use crate::args::{patterns_for, MachineArgs};
use crate::report;
use millpath_core::complete_input;
use millpath_core::diag::{Diagnostic, Msg, Origin};
use millpath_core::Lang;
use std::path::{Path, PathBuf};

/// The files `compile` compiles: a folder gives every drawing below it (never `folder.dxf`);
/// a name without extension gets `.dxf` as in the reference.
pub fn compile_inputs(files: &[String]) -> Result<Vec<PathBuf>, String> {
    let mut inputs = Vec::new();
    for f in files {
        let p = Path::new(f);
        if p.is_dir() {
            let before = inputs.len();
            collect_files(&[p.to_path_buf()], is_drawing, &mut inputs);
            if inputs.len() == before {
                return Err(f.clone());
            }
        } else {
            inputs.push(complete_input(f));
        }
    }
    Ok(inputs)
}

/// Files given, and below directories given the files `accept` takes, sorted.
pub fn collect_files(paths: &[PathBuf], accept: fn(&Path) -> bool, out: &mut Vec<PathBuf>) {
    for p in paths {
        if p.is_dir() {
            let mut entries: Vec<PathBuf> = std::fs::read_dir(p)
                .map(|r| r.filter_map(|e| e.ok().map(|e| e.path())).collect())
                .unwrap_or_default();
            entries.sort();
            let (dirs, files): (Vec<PathBuf>, Vec<PathBuf>) =
                entries.into_iter().partition(|e| e.is_dir());
            out.extend(files.into_iter().filter(|f| accept(f)));
            collect_files(&dirs, accept, out);
        } else {
            out.push(p.clone());
        }
    }
}

pub fn is_drawing(f: &Path) -> bool {
    f.extension().is_some_and(|e| e.eq_ignore_ascii_case("dxf"))
        || millpath_core::load::fs::is_text_file(f)
}

/// Settings, patterns and the input bytes of a conversion; `Err(exit status)` after reporting.
pub fn conversion_input(
    file: &Path,
    m: &MachineArgs,
) -> Result<
    (
        std::sync::Arc<millpath_core::load::names::Patterns>,
        Lang,
        Vec<u8>,
    ),
    u8,
> {
    let (patterns, lang) = patterns_for(m, file).map_err(|e| {
        let lang = crate::args::lang_of(m, Some(file));
        eprintln!(
            "{}: {e}",
            report::severity_word(millpath_core::diag::Severity::Error, lang)
        );
        2
    })?;
    let bytes = std::fs::read(file).map_err(|e| {
        let d = Diagnostic::error(
            Msg::CannotRead,
            Origin::Input,
            millpath_core::args![file.display(), e],
        );
        eprintln!("{}", report::human(&d, lang));
        1
    })?;
    Ok((patterns, lang, bytes))
}
