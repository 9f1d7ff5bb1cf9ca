//! Adjust-z refuses a probing set whose files come from different compiles: the digest
//! (`digest.rs`) stored in `_Clean.gcode`'s banner line against the one its `_Z.txt` gives.

use super::bounds::line_origin;
use crate::args;
use crate::diag::{Diags, Msg};
use crate::digest::{banner_index, set_digest, stored_digest};

/// One file of a set as adjust-z read it.
#[derive(Clone, Copy)]
pub struct SetFile<'a> {
    pub name: &'a str,
    pub text: &'a str,
}

impl SetFile<'_> {
    /// The file without a leading byte-order mark: an editor on Windows (Notepad) may save
    /// `_Clean.gcode` or `_Z.txt` with one, and the reference (.NET) reads past it too.
    pub fn without_bom(self) -> Self {
        SetFile {
            text: self.text.strip_prefix('\u{feff}').unwrap_or(self.text),
            ..self
        }
    }
}

/// Refuses a mix: `_Clean.gcode`'s digest must be that of `_Clean.gcode` with this `_Z.txt`,
/// and a `_Probing.gcode` with a digest must carry the same. A `_Clean.gcode` without a
/// digest (older files, hand-made ones) is accepted as before. False after an error.
pub fn check_set(clean: SetFile, z: SetFile, probing: Option<SetFile>, diags: &mut Diags) -> bool {
    let Some(stored) = stored_digest(clean.text) else {
        return true;
    };
    let banner_line = banner_index(clean.text) + 1;
    let mut ok = true;
    if set_digest(z.text, clean.text) != stored {
        diags.error(
            Msg::ZSetMismatch,
            line_origin(clean.name, banner_line),
            args![clean.name, z.name],
        );
        ok = false;
    }
    if let Some(p) = probing {
        if stored_digest(p.text).is_some_and(|d| d != stored) {
            diags.error(
                Msg::ZSetMismatch,
                line_origin(p.name, banner_index(p.text) + 1),
                args![p.name, clean.name],
            );
            ok = false;
        }
    }
    ok
}

#[cfg(test)]
mod tests {
    use super::*;

    const CLEAN: &str = "%\n(millpath V.1)\nG01 Z0.800(=0.800+1.000*[#51-2.000])\nM30\n%\n";
    const Z: &str = "([1.000 2.000]/T=2.000) #51=\n";

    fn stamped(clean: &str, z: &str) -> String {
        let d = set_digest(z, clean);
        clean.replace("(millpath V.1)", &format!("(millpath V.1 set={d})"))
    }

    fn msgs(clean: &str, z: &str, probing: Option<&str>) -> Vec<String> {
        let mut d = Diags::default();
        check_set(
            SetFile {
                name: "c",
                text: clean,
            },
            SetFile { name: "z", text: z },
            probing.map(|text| SetFile { name: "p", text }),
            &mut d,
        );
        d.list.iter().map(|x| x.message(crate::Lang::En)).collect()
    }

    #[test]
    fn mixes_are_refused_naming_the_files() {
        let clean = stamped(CLEAN, Z);
        assert!(msgs(&clean, "([1.000 2.000]/T=2.000) #51=2.1\n", None).is_empty());
        let moved = "([1.000 9.000]/T=2.000) #51=2.1\n";
        let m = msgs(&clean, moved, None);
        assert_eq!(m.len(), 1);
        assert!(
            m[0].starts_with("c and z are not from the same compile"),
            "{m:?}"
        );
        // a probing program of another compile
        let other = stamped(&CLEAN.replace("0.800", "0.700"), Z);
        let m = msgs(&clean, Z, Some(&other));
        assert_eq!(m.len(), 1);
        assert!(m[0].starts_with("p and c are not"), "{m:?}");
        assert!(msgs(&clean, Z, Some(&clean)).is_empty());
        // files without a digest are accepted as before
        assert!(msgs(CLEAN, moved, Some(&other)).is_empty());
        assert!(msgs(&clean, Z, Some("%\n(PathDxf2GCode)\nM30\n%\n")).is_empty());
    }
}
