//! `millpath fmt`: MillPath files in their canonical form.

use crate::inputs::collect_files;
use crate::output::print_human;
use crate::{report, write};
use millpath_core::diag::{os_error_text, Severity};
use millpath_core::Lang;
use std::path::PathBuf;

pub fn run(check: bool, paths: &[PathBuf], lang: Lang) -> u8 {
    let error = report::severity_word(Severity::Error, lang);
    let not_formatted = match lang {
        Lang::En => "not formatted",
        Lang::De => "nicht formatiert",
    };
    let mut files = Vec::new();
    collect_files(paths, millpath_core::load::fs::is_text_file, &mut files);
    let mut status = 0;
    for f in files {
        let src = match std::fs::read_to_string(&f) {
            Ok(s) => s,
            Err(e) => {
                eprintln!(
                    "{error}: {}: {}",
                    f.display(),
                    os_error_text(&e.to_string(), lang)
                );
                status = 1;
                continue;
            }
        };
        let fref = millpath_core::diag::FileRef::new(f.clone());
        match millpath_core::convert::format_text(&src, &fref) {
            Ok(formatted) if formatted == src => {}
            Ok(formatted) => {
                if check {
                    outln!("{}: {not_formatted}", f.display());
                    status = 1;
                } else if let Err(e) = write::write_atomic(&f, &formatted) {
                    eprintln!(
                        "{error}: {}: {}",
                        f.display(),
                        os_error_text(&e.to_string(), lang)
                    );
                    status = 1;
                }
            }
            Err(diags) => {
                print_human(&diags, lang);
                status = 1;
            }
        }
    }
    status
}
