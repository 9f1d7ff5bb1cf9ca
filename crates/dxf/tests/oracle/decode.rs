//! Decoding of kept string values: code pages and `\U+XXXX` escapes.

use encoding_rs::Encoding;

/// A kept string value: decoded with the file's code page, then `\U+XXXX` escapes.
pub(crate) fn decode_value_into(enc: &'static Encoding, raw: &[u8], out: &mut String) {
    // ASCII reads the same in every ASCII-compatible code page (and has no byte order mark)
    if enc.is_ascii_compatible() {
        if let Some(s) = std::str::from_utf8(raw).ok().filter(|s| s.is_ascii()) {
            if out.is_empty() && !raw.contains(&b'\\') {
                // the usual name or text: one allocation of the right size
                *out = s.to_owned();
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
