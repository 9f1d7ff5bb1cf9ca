//! Decoding: the file to text, code pages and `\U+XXXX` escapes.

use encoding_rs::Encoding;
use std::borrow::Cow;

/// A file as text, decoded once: borrowed when the file is valid UTF-8 (every ASCII file
/// is), otherwise a copy with each invalid sequence replaced by U+FFFD, exactly as
/// [`String::from_utf8_lossy`] does. [`FileText::raw`] gives back the file's bytes of any
/// part of the text, for code-page decoding.
pub(crate) struct FileText<'a> {
    pub(crate) text: Cow<'a, str>,
    bytes: &'a [u8],
    /// For each U+FFFD put in: its offset in `text`, and the end of the bytes it replaces.
    replaced: Vec<(usize, usize)>,
}

impl<'a> FileText<'a> {
    pub(crate) fn new(bytes: &'a [u8]) -> Self {
        let mut replaced = Vec::new();
        let text = match std::str::from_utf8(bytes) {
            Ok(text) => Cow::Borrowed(text),
            // `from_utf8_lossy`, but with the validator's fast path for the long valid runs
            // (code-page files have a few high bytes, in layer names and texts)
            Err(_) => {
                let mut out = String::with_capacity(bytes.len() + 16);
                let mut pos = 0;
                while pos < bytes.len() {
                    let (valid, bad_end) = match std::str::from_utf8(&bytes[pos..]) {
                        Ok(valid) => (valid, None),
                        Err(e) => {
                            let valid_end = pos + e.valid_up_to();
                            let bad_end = e.error_len().map_or(bytes.len(), |n| valid_end + n);
                            // valid by the error's word; checked again, as we use no `unsafe`
                            let valid = std::str::from_utf8(&bytes[pos..valid_end]).unwrap_or("");
                            (valid, Some(bad_end))
                        }
                    };
                    out.push_str(valid);
                    let Some(bad_end) = bad_end else { break };
                    replaced.push((out.len(), bad_end));
                    out.push(char::REPLACEMENT_CHARACTER);
                    pos = bad_end;
                }
                Cow::Owned(out)
            }
        };
        FileText {
            text,
            bytes,
            replaced,
        }
    }

    /// The file's bytes of `s`, a part of [`FileText::text`] that starts and ends at
    /// neither end of a replacement (as a line does).
    pub(crate) fn raw<'s>(&'s self, s: &'s str) -> &'s [u8] {
        if self.replaced.is_empty() || !s.contains(char::REPLACEMENT_CHARACTER) {
            // nothing replaced in `s`: its text is its bytes
            return s.as_bytes();
        }
        let start = (s.as_ptr() as usize).wrapping_sub(self.text.as_ptr() as usize);
        debug_assert!(start <= self.text.len(), "not a part of the text");
        let (from, to) = (self.raw_offset(start), self.raw_offset(start + s.len()));
        self.bytes.get(from..to).unwrap_or(s.as_bytes())
    }

    /// The offset in the file of the text offset `x`.
    fn raw_offset(&self, x: usize) -> usize {
        let len = char::REPLACEMENT_CHARACTER.len_utf8();
        match self.replaced.partition_point(|&(t, _)| t + len <= x) {
            0 => x,
            // the bytes after a replacement are the text after it
            n => {
                let (t, bad_end) = self.replaced[n - 1];
                bad_end + (x - (t + len))
            }
        }
    }
}

/// Picks the decoder for string values: AC1021 and later are UTF-8, older files use
/// `$DWGCODEPAGE` (`ANSI_1252` → windows-1252); unknown code pages fall back to windows-1252,
/// the code page of the CAD programs our users export from.
pub(crate) fn encoding_for(version: &str, codepage: &str) -> &'static Encoding {
    let modern = version
        .strip_prefix("AC")
        .and_then(|v| v.parse::<u32>().ok())
        .is_some_and(|v| v >= 1021);
    if modern {
        return encoding_rs::UTF_8;
    }
    let cp = codepage.trim().to_ascii_uppercase();
    let label = if let Some(num) = cp.strip_prefix("ANSI_") {
        format!("windows-{num}")
    } else if let Some(num) = cp.strip_prefix("DOS") {
        format!("ibm{num}")
    } else {
        cp
    };
    Encoding::for_label(label.as_bytes()).unwrap_or(encoding_rs::WINDOWS_1252)
}

/// Decodes `\U+XXXX` escapes (`U` or `u`, four hex digits). Like the reference's DXF library,
/// an escape is only decoded when at least seven characters follow the backslash, so an
/// escape that ends exactly at the end of the string stays as it is.
pub fn decode_unicode_escapes(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    decode_unicode_escapes_into(s, &mut out);
    out
}

/// [`decode_unicode_escapes`], appending to `out`.
pub(crate) fn decode_unicode_escapes_into(s: &str, out: &mut String) {
    let b = s.as_bytes();
    // `copied`: end of the part of `s` already in `out`
    let (mut copied, mut i) = (0, 0);
    while let Some(n) = b[i..].iter().position(|&c| c == b'\\') {
        i += n;
        // `\`, `U`, `+` and the hex digits are ASCII: bytes and characters coincide, and
        // one more byte after them means one more character.
        let decoded = match b.get(i + 1..i + 8) {
            Some([b'U' | b'u', b'+', hex @ .., _]) if hex.iter().all(u8::is_ascii_hexdigit) => {
                let v = hex
                    .iter()
                    .fold(0u32, |v, &h| v * 16 + (h as char).to_digit(16).unwrap_or(0));
                char::from_u32(v)
            }
            _ => None,
        };
        match decoded {
            Some(ch) => {
                out.push_str(&s[copied..i]);
                out.push(ch);
                i += 7;
                copied = i;
            }
            None => i += 1,
        }
    }
    out.push_str(&s[copied..]);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_decode_only_with_a_following_character() {
        assert_eq!(decode_unicode_escapes("a\\U+00E4b"), "aäb");
        assert_eq!(decode_unicode_escapes("a\\u+00e4bc"), "aäbc");
        // ends exactly at the end of the string: left as is
        assert_eq!(decode_unicode_escapes("a\\U+00E4"), "a\\U+00E4");
        assert_eq!(decode_unicode_escapes("\\PB-0,1\\PS5"), "\\PB-0,1\\PS5");
        assert_eq!(decode_unicode_escapes("x\\U+ZZZZyy"), "x\\U+ZZZZyy");
    }

    /// The first implementation (over a `Vec<char>`), as the reference for the new one.
    fn decode_unicode_escapes_chars(s: &str) -> String {
        let chars: Vec<char> = s.chars().collect();
        let mut out = String::with_capacity(s.len());
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            if c == '\\'
                && chars.len() - i > 7
                && matches!(chars[i + 1], 'U' | 'u')
                && chars[i + 2] == '+'
            {
                let hex: String = chars[i + 3..i + 7].iter().collect();
                if hex.chars().all(|h| h.is_ascii_hexdigit()) {
                    if let Some(ch) = u32::from_str_radix(&hex, 16).ok().and_then(char::from_u32) {
                        out.push(ch);
                        i += 7;
                        continue;
                    }
                }
            }
            out.push(c);
            i += 1;
        }
        out
    }

    #[test]
    fn escapes_match_the_char_implementation() {
        let alphabet: Vec<char> = "\\\\Uu+0Ddf9aGä€😀 xP".chars().collect();
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..200_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let len = (seed % 14) as usize;
            let mut r = seed;
            let s: String = (0..len)
                .map(|_| {
                    r = r
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    alphabet[(r >> 33) as usize % alphabet.len()]
                })
                .collect();
            assert_eq!(
                decode_unicode_escapes(&s),
                decode_unicode_escapes_chars(&s),
                "{s:?}"
            );
        }
        for s in [
            "\\U+D800x",
            "\\U+DFFFxy",
            "\\U+FFFFx",
            "\\U+0041\\u+0042z",
            "\\\\U+0041z",
            "\\U+00e€",
            "ä\\U+00E4ä",
            "\\U+00E",
            "\\",
            "",
        ] {
            assert_eq!(
                decode_unicode_escapes(s),
                decode_unicode_escapes_chars(s),
                "{s:?}"
            );
        }
    }

    #[test]
    fn file_text_is_lossy_utf8_and_maps_back_to_the_bytes() {
        let pieces: &[&[u8]] = &[
            b"ab",
            b"\n",
            b"\r\n",
            b"\xfc",
            b"\xc3\xbc",
            b"\xc3",
            b"\xe2\x82",
            b"\xe2\x82\xac",
            b"\xf0\x9f\x98",
            b"\xf0\x9f\x98\x80",
            b"\xed\xa0\x80",
            b"\xff\xfe",
            b"\xef\xbf\xbd",
            b"\x80",
            b" ",
        ];
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..100_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let mut r = seed;
            let mut bytes = Vec::new();
            for _ in 0..(seed % 12) {
                r = r
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                bytes.extend_from_slice(pieces[(r >> 33) as usize % pieces.len()]);
            }
            let ft = FileText::new(&bytes);
            assert_eq!(ft.text, String::from_utf8_lossy(&bytes), "{bytes:?}");
            // every line maps back to the bytes of the same line
            let raw_lines: Vec<&[u8]> = bytes.split(|&b| b == b'\n').collect();
            let text_lines: Vec<&str> = ft.text.split('\n').collect();
            assert_eq!(raw_lines.len(), text_lines.len());
            for (t, r) in text_lines.iter().zip(&raw_lines) {
                assert_eq!(ft.raw(t), *r, "{bytes:?}");
            }
        }
    }

    #[test]
    fn code_pages() {
        assert_eq!(
            encoding_for("AC1015", "ANSI_1252"),
            encoding_rs::WINDOWS_1252
        );
        assert_eq!(
            encoding_for("AC1015", "ANSI_1251"),
            encoding_rs::WINDOWS_1251
        );
        assert_eq!(encoding_for("AC1024", "ANSI_1252"), encoding_rs::UTF_8);
        assert_eq!(encoding_for("AC1009", ""), encoding_rs::WINDOWS_1252);
    }
}
