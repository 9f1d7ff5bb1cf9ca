//! Decoding of kept string values: code pages and `\U+XXXX` escapes.
//!
//! Kept values: code pages (encoding_rs, ASCII taken as it is) and `\U+XXXX` escapes
//! (reference-input.md §1.1).

use encoding_rs::Encoding;
use std::borrow::Cow;

/// A kept string value: decoded with the file's code page, then `\U+XXXX` escapes.
pub(crate) fn decode_value_into(enc: &'static Encoding, raw: &[u8], out: &mut String) {
    // ASCII reads the same in every ASCII-compatible code page (and has no byte order mark)
    if enc.is_ascii_compatible() {
        // borrowed exactly when `raw` is ASCII (quicker on short values than `from_utf8`)
        if let Cow::Borrowed(s) = encoding_rs::mem::decode_latin1(raw) {
            if !raw.contains(&b'\\') {
                // the usual name or text
                if out.is_empty() {
                    *out = s.to_owned();
                } else {
                    out.push_str(s);
                }
            } else {
                decode_unicode_escapes_into(s, out);
            }
            return;
        }
    }
    let (s, _, _) = enc.decode(raw);
    decode_unicode_escapes_into(&s, out);
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
