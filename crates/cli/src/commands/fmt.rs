//! `millpath fmt`: MillPath files in their canonical form.

use crate::inputs::collect_files;
use crate::output::print_human;
use crate::write;
use millpath_core::Lang;
use std::path::PathBuf;

pub fn run(check: bool, paths: &[PathBuf]) -> u8 {
    let mut files = Vec::new();
    collect_files(paths, millpath_core::load::fs::is_text_file, &mut files);
    let mut status = 0;
    for f in files {
        let src = match std::fs::read_to_string(&f) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("error: {}: {e}", f.display());
                status = 1;
                continue;
            }
        };
        let fref = millpath_core::diag::FileRef::new(f.clone());
        match millpath_core::convert::format_text(&src, &fref) {
            Ok(formatted) if formatted == src => {}
            Ok(formatted) => {
                if check {
                    outln!("{}: not formatted", f.display());
                    status = 1;
                } else if let Err(e) = write::write_atomic(&f, &formatted) {
                    eprintln!("error: {}: {e}", f.display());
                    status = 1;
                }
            }
            Err(diags) => {
                print_human(&diags, Lang::En);
                status = 1;
            }
        }
    }
    status
}
