//! Byte offsets (the compiler's) ↔ UTF-16 offsets (the browser editor's).

/// The UTF-16 offset of byte `byte` of `src` (clamped to the text, rounded down to a char).
pub fn to_utf16(src: &str, byte: usize) -> usize {
    let mut b = byte.min(src.len());
    while !src.is_char_boundary(b) {
        b -= 1;
    }
    src[..b].encode_utf16().count()
}

/// The byte offset of UTF-16 offset `unit` of `src` (clamped; inside a pair → its char).
pub fn from_utf16(src: &str, unit: usize) -> usize {
    let mut seen = 0;
    for (i, c) in src.char_indices() {
        if seen >= unit {
            return i;
        }
        seen += c.len_utf16();
    }
    src.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_over_wide_chars() {
        let s = "aä😀b";
        // a=1 byte/1 unit, ä=2/1, 😀=4/2
        assert_eq!(to_utf16(s, 0), 0);
        assert_eq!(to_utf16(s, 3), 2);
        assert_eq!(to_utf16(s, 7), 4);
        assert_eq!(to_utf16(s, 99), 5);
        assert_eq!(from_utf16(s, 2), 3);
        assert_eq!(from_utf16(s, 4), 7);
        assert_eq!(from_utf16(s, 5), 8);
        for b in [0, 1, 3, 7, 8] {
            assert_eq!(from_utf16(s, to_utf16(s, b)), b);
        }
    }
}
