//! `millpath text2dxf`: MillPath text as a DXF drawing, or written into an existing drawing
//! (`--into`). It never destroys a drawing: an existing DXF that holds anything it would not
//! write back is overwritten only with `--force`, and `--into` deletes the paths the text
//! does not define only with `--delete-missing-paths`.

use crate::args::MachineArgs;
use crate::inputs::conversion_input;
use crate::output::print_human;
use crate::{report, write};
use millpath_core::convert::IntoOutcome;
use millpath_core::diag::FileRef;
use millpath_core::{args, Diagnostic, InputMode, Lang, Msg, Origin};
use std::path::{Path, PathBuf};

pub fn run(
    file: &Path,
    output: Option<&Path>,
    into: Option<&Path>,
    force: bool,
    delete_missing_paths: bool,
    m: &MachineArgs,
) -> u8 {
    let (patterns, lang, bytes) = match conversion_input(file, m) {
        Ok(x) => x,
        Err(code) => return code,
    };
    let input = if m.extended {
        InputMode::Extended
    } else {
        InputMode::Reference
    };
    let fref = FileRef::new(file.to_path_buf());
    // a BOM, UTF-16 and CRLF read as in `check` (load/text_file.rs)
    let Ok(decoded) = millpath_core::load::text_file::decode(&bytes) else {
        return fail(Msg::TextNulBytes, file, args![file.display()], lang);
    };
    let src = decoded.text;
    // `-o -`: standard output; else the file to write
    let dest: Option<PathBuf> = match (output, into) {
        (Some(o), _) if o.as_os_str() == "-" => None,
        (Some(o), _) => Some(o.to_path_buf()),
        (None, Some(d)) => Some(d.to_path_buf()),
        (None, None) => Some(file.with_extension("dxf")),
    };
    let result = match into {
        Some(drawing) => {
            let target = match std::fs::read(drawing) {
                Ok(t) => t,
                Err(e) => return fail(Msg::CannotRead, drawing, args![drawing.display(), e], lang),
            };
            let tref = FileRef::new(drawing.to_path_buf());
            let out = millpath_core::convert::text_into_dxf(
                &src,
                &fref,
                &patterns,
                &target,
                &tref,
                input,
                delete_missing_paths,
            );
            if out.is_ok() && input == InputMode::Reference {
                warn_kept_extended(drawing, &target, &src, &fref, &patterns, lang);
            }
            match out {
                // the drawing already holds these paths: not touched (git sees no change)
                Ok(IntoOutcome::Unchanged) if dest.as_deref() == Some(drawing) => return 0,
                Ok(IntoOutcome::Unchanged) => Ok(target),
                Ok(IntoOutcome::Written(dxf)) => Ok(dxf),
                Err(d) => Err(d),
            }
        }
        None => {
            if let (Some(d), false) = (&dest, force) {
                if let Some(code) = refuse_to_destroy(d, &src, &fref, &patterns, input, lang) {
                    return code;
                }
            }
            millpath_core::convert::text_to_dxf(&src, &fref, &patterns).map(String::into_bytes)
        }
    };
    match result {
        Ok(dxf) => match dest {
            None => {
                crate::out::write_bytes(&dxf);
                0
            }
            Some(d) => match write::write_atomic_bytes(&d, &dxf) {
                Ok(()) => 0,
                Err(e) => fail(Msg::CannotWrite, &d, args![d.display(), e], lang),
            },
        },
        Err(diags) => {
            print_human(&diags, lang);
            1
        }
    }
}

/// Warns when `--into` kept polylines or block references on the path layers that a text
/// from `dxf2text --extended` holds as elements too.
fn warn_kept_extended(
    drawing: &Path,
    target: &[u8],
    src: &str,
    file: &std::sync::Arc<FileRef>,
    patterns: &millpath_core::load::names::Patterns,
    lang: Lang,
) {
    let kept = millpath_core::convert::kept_extended_geometry(target, src, file, patterns);
    if !kept.is_empty() {
        let d = Diagnostic::warning(
            Msg::IntoKeptExtended,
            Origin::File(FileRef::new(drawing.to_path_buf())),
            args![drawing.display(), kept.describe(lang)],
        );
        eprintln!("{}", report::human(&d, lang));
    }
}

fn fail(msg: Msg, path: &Path, a: Vec<String>, lang: Lang) -> u8 {
    let d = Diagnostic::error(msg, Origin::File(FileRef::new(path.to_path_buf())), a);
    eprintln!("{}", report::human(&d, lang));
    1
}

/// `Some(1)` with the message printed when writing `dest` would destroy drawing content:
/// it exists and holds what the text does not write back, or is no DXF we can read.
fn refuse_to_destroy(
    dest: &Path,
    src: &str,
    file: &std::sync::Arc<FileRef>,
    patterns: &millpath_core::load::names::Patterns,
    input: InputMode,
    lang: Lang,
) -> Option<u8> {
    // a missing file loses nothing; one we cannot read we do not overwrite either
    let existing = match std::fs::read(dest) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return None,
        Err(e) => return Some(fail(Msg::CannotRead, dest, args![dest.display(), e], lang)),
    };
    match millpath_core::convert::overwrite_losses(&existing, src, file, patterns, input) {
        Ok(l) if l.is_empty() => None,
        Ok(l) => Some(fail(
            Msg::WouldLoseDrawing,
            dest,
            args![dest.display(), l.describe(lang)],
            lang,
        )),
        Err(e) => Some(fail(
            Msg::NotOursToOverwrite,
            dest,
            vec![
                dest.display().to_string(),
                millpath_core::diag::dxf_error_arg(&e),
            ],
            lang,
        )),
    }
}
