//! `millpath dxf2text`: a DXF drawing as MillPath text (also git's textconv driver).

use crate::args::{lang_of, settings_for, MachineArgs};
use crate::inputs::conversion_input;
use crate::output::{emit, print_human};
use crate::report;
use millpath_core::Lang;
use std::path::{Path, PathBuf};

pub fn run(file: &Path, output: Option<PathBuf>, textconv: bool, m: &MachineArgs) -> u8 {
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
    let fref = millpath_core::diag::FileRef::new(file.to_path_buf());
    // conversion_input has already reported settings that do not load
    let input = settings_for(m, Some(file), false).map_or_else(|_| Default::default(), |s| s.input);
    match millpath_core::convert::dxf_to_text(&bytes, &fref, &patterns, input) {
        Ok((text, diags)) => {
            // what the text cannot carry (texts that belong to no element, …) is reported
            print_human(&diags, lang);
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
