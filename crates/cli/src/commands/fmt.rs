//! `millpath fmt`: MillPath files in their canonical form.
//!
//! The canonical form keeps what a checkout decides: the file's line ends (CRLF stays CRLF;
//! mixed ones become the more frequent) and a UTF-8 byte-order mark. UTF-16 is written as
//! UTF-8 (git shows UTF-16 as binary, and the tools read UTF-8 everywhere), and says so.

use crate::inputs::collect_files;
use crate::output::print_human;
use crate::write;
use millpath_core::diag::{Diagnostic, FileRef, Msg, Origin};
use millpath_core::load::text_file::{decode, Encoding, LineEnds};
use millpath_core::Lang;
use std::path::{Path, PathBuf};

/// `lang`: `--lang`, else `lang` of the first path's millpath.toml.
pub fn run(check: bool, paths: &[PathBuf], lang: Lang) -> u8 {
    let mut files = Vec::new();
    collect_files(paths, millpath_core::load::fs::is_text_file, &mut files);
    let mut status = 0;
    for f in files {
        status = status.max(one(check, &f, lang));
    }
    status
}

/// What `fmt` makes of one file's bytes.
#[derive(Debug, PartialEq)]
pub(crate) enum Outcome {
    /// Already canonical.
    Same,
    /// The canonical bytes, and why they differ.
    Changed { bytes: Vec<u8>, why: Why },
}

#[derive(Debug, PartialEq)]
pub(crate) enum Why {
    /// The text itself.
    Text,
    /// Only the line ends: the file mixes them.
    MixedLineEnds { crlf: usize, lf: usize },
    /// UTF-16, written as UTF-8 (and maybe more).
    Utf16(Encoding),
}

/// The canonical bytes of a file (see the module comment); `Err` with the diagnostics.
pub(crate) fn format_bytes(bytes: &[u8], file: &Path) -> Result<Outcome, Vec<Diagnostic>> {
    let fref = FileRef::new(file.to_path_buf());
    let decoded = decode(bytes).map_err(|_| {
        vec![Diagnostic::error(
            Msg::TextNulBytes,
            Origin::File(fref.clone()),
            millpath_core::args![file.display()],
        )]
    })?;
    let formatted = millpath_core::convert::format_text(&decoded.text, &fref)?;
    let mut out = Vec::with_capacity(formatted.len() + 3);
    if decoded.encoding == Encoding::Utf8Bom {
        out.extend_from_slice(b"\xEF\xBB\xBF");
    }
    out.extend_from_slice(formatted.as_bytes());
    if out == bytes {
        return Ok(Outcome::Same);
    }
    let unix = |s: &str| s.replace("\r\n", "\n");
    let why = match (decoded.encoding, LineEnds::of(&decoded.text)) {
        (e @ (Encoding::Utf16Le | Encoding::Utf16Be), _) => Why::Utf16(e),
        (_, LineEnds::Mixed { crlf, lf }) if unix(&decoded.text) == unix(&formatted) => {
            Why::MixedLineEnds { crlf, lf }
        }
        _ => Why::Text,
    };
    Ok(Outcome::Changed { bytes: out, why })
}

/// The line `fmt --check` prints for a file that is not canonical, or that `fmt` prints
/// after rewriting it (`None`: nothing to say beyond the rewrite).
fn note(why: &Why, check: bool, lang: Lang) -> Option<String> {
    let de = lang == Lang::De;
    Some(match why {
        Why::Text if check => if de {
            "nicht formatiert"
        } else {
            "not formatted"
        }
        .into(),
        Why::Text => return None,
        Why::MixedLineEnds { crlf, lf } => {
            let to = if crlf > lf { "CRLF" } else { "LF" };
            match (check, de) {
                (true, false) => format!("only line endings differ (mixed: {crlf} CRLF, {lf} LF; fmt writes {to})"),
                (true, true) => format!("nur die Zeilenenden unterscheiden sich (gemischt: {crlf} CRLF, {lf} LF; fmt schreibt {to})"),
                (false, false) => format!("line endings made {to} (were mixed: {crlf} CRLF, {lf} LF)"),
                (false, true) => format!("Zeilenenden einheitlich {to} (waren gemischt: {crlf} CRLF, {lf} LF)"),
            }
        }
        Why::Utf16(e) => match (check, de) {
            (true, false) => format!("{}: fmt writes it as UTF-8", e.name()),
            (true, true) => format!("{}: fmt schreibt die Datei als UTF-8", e.name()),
            (false, false) => format!("converted from {} to UTF-8", e.name()),
            (false, true) => format!("von {} nach UTF-8 umgewandelt", e.name()),
        },
    })
}

fn one(check: bool, f: &Path, lang: Lang) -> u8 {
    let bytes = match std::fs::read(f) {
        Ok(b) => b,
        Err(e) => {
            let d = Diagnostic::error(
                Msg::CannotRead,
                Origin::File(FileRef::new(f.to_path_buf())),
                millpath_core::args![f.display(), e],
            );
            print_human(&[d], lang);
            return 1;
        }
    };
    match format_bytes(&bytes, f) {
        Ok(Outcome::Same) => 0,
        Ok(Outcome::Changed { bytes, why }) => {
            if !check {
                if let Err(e) = write::write_atomic_bytes(f, &bytes) {
                    let d = Diagnostic::error(
                        Msg::CannotWrite,
                        Origin::File(FileRef::new(f.to_path_buf())),
                        millpath_core::args![f.display(), e],
                    );
                    print_human(&[d], lang);
                    return 1;
                }
            }
            if let Some(n) = note(&why, check, lang) {
                outln!("{}: {n}", f.display());
            }
            u8::from(check)
        }
        Err(diags) => {
            print_human(&diags, lang);
            1
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CANON: &str = "path X {\n  mill (0, 0) -> (1, 1)  B1\n}\n";

    fn fmt(bytes: &[u8]) -> Outcome {
        format_bytes(bytes, Path::new("a.mpath")).unwrap()
    }

    #[test]
    fn line_ends_and_a_bom_are_kept() {
        assert_eq!(fmt(CANON.as_bytes()), Outcome::Same);
        let crlf = CANON.replace('\n', "\r\n");
        assert_eq!(fmt(crlf.as_bytes()), Outcome::Same);
        let bom = format!("\u{FEFF}{crlf}");
        assert_eq!(fmt(bom.as_bytes()), Outcome::Same);
        let messy = "path   X {\r\n  mill (0,0)->(1,1)   B1\r\n}\r\n";
        assert_eq!(
            fmt(messy.as_bytes()),
            Outcome::Changed {
                bytes: crlf.into_bytes(),
                why: Why::Text
            }
        );
    }

    #[test]
    fn mixed_line_ends_are_named_and_made_one() {
        let mixed = "path X {\r\n  mill (0, 0) -> (1, 1)  B1\r\n}\n";
        assert_eq!(
            fmt(mixed.as_bytes()),
            Outcome::Changed {
                bytes: CANON.replace('\n', "\r\n").into_bytes(),
                why: Why::MixedLineEnds { crlf: 2, lf: 1 }
            }
        );
        let n = note(&Why::MixedLineEnds { crlf: 2, lf: 1 }, true, Lang::En).unwrap();
        assert_eq!(
            n,
            "only line endings differ (mixed: 2 CRLF, 1 LF; fmt writes CRLF)"
        );
    }

    #[test]
    fn utf16_becomes_utf8_and_says_so() {
        let mut le = vec![0xFF, 0xFE];
        le.extend(CANON.encode_utf16().flat_map(u16::to_le_bytes));
        assert_eq!(
            fmt(&le),
            Outcome::Changed {
                bytes: CANON.as_bytes().to_vec(),
                why: Why::Utf16(Encoding::Utf16Le)
            }
        );
        let n = note(&Why::Utf16(Encoding::Utf16Le), false, Lang::De).unwrap();
        assert_eq!(n, "von UTF-16 LE nach UTF-8 umgewandelt");
        let nul = format_bytes(&le[2..], Path::new("a.mpath")).unwrap_err();
        assert_eq!(nul[0].msg, Msg::TextNulBytes);
    }
}
