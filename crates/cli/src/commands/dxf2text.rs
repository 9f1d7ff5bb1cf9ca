//! `millpath dxf2text`: a DXF drawing as MillPath text (also git's textconv driver).

use crate::args::{lang_of, settings_for, MachineArgs};
use crate::inputs::conversion_input;
use crate::output::{emit, print_human};
use crate::report;
use millpath_core::diag::FileRef;
use millpath_core::{args, Diagnostic, Lang, Msg, Origin};
use std::path::{Path, PathBuf};

/// `flags`: `--textconv` and `--force`.
pub fn run(file: &Path, output: Option<PathBuf>, flags: (bool, bool), m: &MachineArgs) -> u8 {
    let (textconv, force) = flags;
    let output = output.as_deref();
    let (patterns, lang, bytes) = match conversion_input(file, m) {
        Ok(x) => x,
        Err(code) if textconv => {
            // git shows this line as the file's text instead of giving up on the diff
            let what = if lang_of(m, Some(file)) == Lang::De {
                "nicht lesbar"
            } else {
                "unreadable"
            };
            return emit(
                output,
                &format!("# millpath: {} {what}\n", file.display()),
                lang_of(m, Some(file)),
            )
            .max(u8::from(code == 2));
        }
        Err(code) => return code,
    };
    let fref = FileRef::new(file.to_path_buf());
    // conversion_input has already reported settings that do not load
    let input = settings_for(m, Some(file), false).map_or_else(|_| Default::default(), |s| s.input);
    match millpath_core::convert::dxf_to_text(&bytes, &fref, &patterns, input) {
        Ok((text, diags)) => {
            // what the text cannot carry (texts that belong to no element, …) is reported
            print_human(&diags, lang);
            if let (Some(out), false) = (output, force) {
                if other_text_there(out, &text) {
                    let d = Diagnostic::error(
                        Msg::TextWouldBeReplaced,
                        Origin::File(FileRef::new(out.to_path_buf())),
                        args![out.display(), file.display()],
                    );
                    eprintln!("{}", report::human(&d, lang));
                    return 1;
                }
            }
            emit(output, &text, lang)
        }
        Err(d) if textconv => {
            // the error as the text (one line per line of the message), exit 0: `git diff`
            // shows what is wrong with the drawing instead of dying
            eprintln!("{}", report::human(&d, lang));
            let text: String = report::human(&d, lang)
                .lines()
                .map(|l| format!("# {l}\n"))
                .collect();
            emit(output, &text, lang)
        }
        Err(d) => {
            eprintln!("{}", report::human(&d, lang));
            1
        }
    }
}

/// Whether `out` is a file that holds something else than `text`: a text the user edited
/// after an earlier `dxf2text` (the edits not yet written back with `text2dxf --into`), or
/// comments, which a drawing does not keep. Replacing it would lose them without a word.
/// (The same text again is written as before, so a read-only file is still refused.)
fn other_text_there(out: &Path, text: &str) -> bool {
    match std::fs::read(out) {
        Ok(bytes) => {
            // the same text in another encoding or with CRLF line ends is no edit
            let same = millpath_core::load::text_file::decode(&bytes)
                .is_ok_and(|d| d.text.replace("\r\n", "\n") == text);
            !same && !bytes.is_empty()
        }
        // nothing there (or a folder, which the write then reports)
        Err(_) => false,
    }
}
