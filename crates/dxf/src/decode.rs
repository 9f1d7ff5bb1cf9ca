//! String decoding: code pages and `\U+XXXX` escapes.

use encoding_rs::Encoding;

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
    if !s.contains('\\') {
        return s.to_string();
    }
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
