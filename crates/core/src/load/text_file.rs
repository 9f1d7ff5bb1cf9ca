//! The bytes of a `.mpath` file as text: the one place that knows encodings and line ends.
//!
//! UTF-8 is the language's encoding. A UTF-8 byte-order mark (Windows editors write one) is
//! dropped, so spans and columns count from the first real character; UTF-16 with a mark
//! (PowerShell 5's `>` writes UTF-16 LE) is decoded. A file with NUL bytes and no mark is
//! refused: UTF-16 without a mark, or no text at all. Other bytes that are not UTF-8 read as
//! U+FFFD, as before. CRLF and LF line ends both read as line ends (the lexer takes `\r\n`).

use std::borrow::Cow;

/// How a text file was stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    Utf8,
    /// UTF-8 after a byte-order mark.
    Utf8Bom,
    Utf16Le,
    Utf16Be,
}

impl Encoding {
    pub fn name(self) -> &'static str {
        match self {
            Encoding::Utf8 => "UTF-8",
            Encoding::Utf8Bom => "UTF-8 with BOM",
            Encoding::Utf16Le => "UTF-16 LE",
            Encoding::Utf16Be => "UTF-16 BE",
        }
    }
}

/// A file's text and how it was stored.
#[derive(Debug, Clone, PartialEq)]
pub struct Decoded<'a> {
    /// The text without a byte-order mark.
    pub text: Cow<'a, str>,
    pub encoding: Encoding,
}

/// Why bytes are no text: they hold NUL bytes and start with no byte-order mark.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NulBytes;

/// The text of a file's bytes (see the module comment).
pub fn decode(bytes: &[u8]) -> Result<Decoded<'_>, NulBytes> {
    let (text, encoding) = match encoding_rs::Encoding::for_bom(bytes) {
        Some((enc, bom)) if enc == encoding_rs::UTF_8 => {
            (String::from_utf8_lossy(&bytes[bom..]), Encoding::Utf8Bom)
        }
        Some((enc, bom)) => {
            let (text, _) = enc.decode_without_bom_handling(&bytes[bom..]);
            let which = if enc == encoding_rs::UTF_16BE {
                Encoding::Utf16Be
            } else {
                Encoding::Utf16Le
            };
            (text, which)
        }
        None if bytes.contains(&0) => return Err(NulBytes),
        None => (String::from_utf8_lossy(bytes), Encoding::Utf8),
    };
    Ok(Decoded { text, encoding })
}

/// What [`text_of`] says of bytes that hold NUL bytes and no byte-order mark (German in
/// `diag::os_error_text`).
pub const NO_MARK: &str =
    "holds NUL bytes and no byte-order mark (UTF-16 without a mark?): save it as UTF-8";

/// A whole file's bytes as text, as [`decode`] reads them, for the files beside a drawing
/// that are read whole (`_Z.txt`, `_Clean.gcode`, probe logs, `millpath.toml`, a program
/// to verify): a file Notepad saved as "Unicode" (UTF-16 with a mark) reads as the same
/// text. No mark and NUL bytes is an `InvalidData` error whose text says what to do.
pub fn text_of(bytes: Vec<u8>) -> std::io::Result<String> {
    // the usual case without a copy
    let bytes = match String::from_utf8(bytes) {
        Ok(s) if !s.starts_with('\u{FEFF}') && !s.contains('\0') => return Ok(s),
        Ok(s) => s.into_bytes(),
        Err(e) => e.into_bytes(),
    };
    decode(&bytes)
        .map(|d| d.text.into_owned())
        .map_err(|NulBytes| std::io::Error::new(std::io::ErrorKind::InvalidData, NO_MARK))
}

/// The line ends of a text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineEnds {
    /// Only `\n` (also: no line end at all).
    Lf,
    /// Only `\r\n`.
    Crlf,
    /// Both: how many of each.
    Mixed { crlf: usize, lf: usize },
}

impl LineEnds {
    pub fn of(text: &str) -> LineEnds {
        let all = text.matches('\n').count();
        let crlf = text.matches("\r\n").count();
        match (crlf, all - crlf) {
            (0, _) => LineEnds::Lf,
            (_, 0) => LineEnds::Crlf,
            (crlf, lf) => LineEnds::Mixed { crlf, lf },
        }
    }

    /// The line end a rewritten file gets: the file's own, or the more frequent of mixed
    /// ones (LF on a tie).
    pub fn written_crlf(self) -> bool {
        match self {
            LineEnds::Lf => false,
            LineEnds::Crlf => true,
            LineEnds::Mixed { crlf, lf } => crlf > lf,
        }
    }
}

/// `text` (LF line ends) with CRLF line ends when `crlf`.
pub fn with_line_ends(text: String, crlf: bool) -> String {
    if crlf {
        text.replace('\n', "\r\n")
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn utf16(text: &str, big_endian: bool) -> Vec<u8> {
        let mut out = if big_endian {
            vec![0xFE, 0xFF]
        } else {
            vec![0xFF, 0xFE]
        };
        for u in text.encode_utf16() {
            let b = if big_endian {
                u.to_be_bytes()
            } else {
                u.to_le_bytes()
            };
            out.extend_from_slice(&b);
        }
        out
    }

    #[test]
    fn every_stored_form_gives_the_same_text() {
        let text = "path X {  # Fräse\n}\n";
        let plain = decode(text.as_bytes()).unwrap();
        assert_eq!(
            (plain.text.as_ref(), plain.encoding),
            (text, Encoding::Utf8)
        );
        let mut bom = b"\xEF\xBB\xBF".to_vec();
        bom.extend_from_slice(text.as_bytes());
        let d = decode(&bom).unwrap();
        assert_eq!((d.text.as_ref(), d.encoding), (text, Encoding::Utf8Bom));
        let (le, be) = (utf16(text, false), utf16(text, true));
        let d = decode(&le).unwrap();
        assert_eq!((d.text.as_ref(), d.encoding), (text, Encoding::Utf16Le));
        let d = decode(&be).unwrap();
        assert_eq!((d.text.as_ref(), d.encoding), (text, Encoding::Utf16Be));
    }

    #[test]
    fn utf16_without_a_mark_is_refused_and_bad_utf8_is_replaced() {
        let no_mark: Vec<u8> = utf16("path X {\n", false)[2..].to_vec();
        assert_eq!(decode(&no_mark), Err(NulBytes));
        let d = decode(b"# \xFF\n").unwrap();
        assert_eq!(d.text, "# \u{FFFD}\n");
        // an odd UTF-16 byte count ends in U+FFFD, never a panic
        let mut odd = utf16("ab", false);
        odd.push(b'c');
        assert_eq!(decode(&odd).unwrap().text, "ab\u{FFFD}");
    }

    #[test]
    fn whole_files_read_as_text_in_every_stored_form() {
        let text = "(a [1 2]/T=3.000) #51=3,1\r\n";
        let mut bom = b"\xEF\xBB\xBF".to_vec();
        bom.extend_from_slice(text.as_bytes());
        for bytes in [
            text.as_bytes().to_vec(),
            bom,
            utf16(text, false),
            utf16(text, true),
        ] {
            assert_eq!(text_of(bytes).unwrap(), text);
        }
        let no_mark = utf16(text, false)[2..].to_vec();
        let e = text_of(no_mark).unwrap_err();
        assert_eq!(
            (e.kind(), e.to_string()),
            (std::io::ErrorKind::InvalidData, NO_MARK.to_string())
        );
        assert_eq!(text_of(b"T=\xFF".to_vec()).unwrap(), "T=\u{FFFD}");
    }

    #[test]
    fn line_ends_are_told_and_kept() {
        assert_eq!(LineEnds::of("a\nb\n"), LineEnds::Lf);
        assert_eq!(LineEnds::of("a"), LineEnds::Lf);
        assert_eq!(LineEnds::of("a\r\nb\r\n"), LineEnds::Crlf);
        let mixed = LineEnds::of("a\r\nb\nc\r\n");
        assert_eq!(mixed, LineEnds::Mixed { crlf: 2, lf: 1 });
        assert!(mixed.written_crlf());
        assert!(!LineEnds::Mixed { crlf: 1, lf: 1 }.written_crlf());
        assert_eq!(with_line_ends("a\nb\n".into(), true), "a\r\nb\r\n");
        assert_eq!(with_line_ends("a\nb\n".into(), false), "a\nb\n");
    }
}
