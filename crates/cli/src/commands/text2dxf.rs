//! `millpath text2dxf`: MillPath text as a DXF drawing.

use crate::args::MachineArgs;
use crate::inputs::conversion_input;
use crate::output::{emit, print_human};
use std::path::Path;

pub fn run(file: &Path, output: Option<&Path>, m: &MachineArgs) -> u8 {
    let (patterns, lang, bytes) = match conversion_input(file, m) {
        Ok(x) => x,
        Err(code) => return code,
    };
    let fref = millpath_core::diag::FileRef::new(file.to_path_buf());
    // a BOM, UTF-16 and CRLF read as in `check` (load/text_file.rs)
    let Ok(decoded) = millpath_core::load::text_file::decode(&bytes) else {
        let d = millpath_core::Diagnostic::error(
            millpath_core::Msg::TextNulBytes,
            millpath_core::Origin::File(fref),
            millpath_core::args![file.display()],
        );
        print_human(&[d], lang);
        return 1;
    };
    let src = decoded.text;
    match millpath_core::convert::text_to_dxf(&src, &fref, &patterns) {
        Ok(dxf) => match output {
            Some(o) if o.as_os_str() == "-" => emit(None, &dxf, lang),
            Some(o) => emit(Some(o), &dxf, lang),
            None => emit(Some(&file.with_extension("dxf")), &dxf, lang),
        },
        Err(diags) => {
            print_human(&diags, lang);
            1
        }
    }
}
