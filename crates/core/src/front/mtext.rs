//! Text values: MTEXT formatting codes → plain text, and the `%%` codes (reference-input.md §1.7).

/// The plain text of an MTEXT value (ASCII DXF): formatting codes removed, paragraph breaks
/// as CR LF like the reference tool on Windows.
pub fn mtext_plain(value: &str) -> String {
    let value = value.replace("^I", "\t").replace("^J", "\\P");
    let chars: Vec<char> = value.chars().collect();
    let mut out = String::with_capacity(chars.len());
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        match c {
            '{' | '}' => i += 1,
            '\\' => {
                let Some(&code) = chars.get(i + 1) else {
                    return out;
                };
                match code {
                    '\\' | '{' | '}' => {
                        out.push(code);
                        i += 2;
                    }
                    'L' | 'l' | 'O' | 'o' | 'K' | 'k' => i += 2,
                    'P' | 'X' => {
                        out.push_str("\r\n");
                        i += 2;
                    }
                    'S' => {
                        i += 2;
                        loop {
                            let Some(&s) = chars.get(i) else { return out };
                            match s {
                                ';' => {
                                    i += 1;
                                    break;
                                }
                                '\\' => {
                                    let Some(&n) = chars.get(i + 1) else {
                                        return out;
                                    };
                                    out.push(n);
                                    i += 2;
                                }
                                '^' => {
                                    let Some(&n) = chars.get(i + 1) else {
                                        return out;
                                    };
                                    if n != ' ' {
                                        out.push('^');
                                        out.push(n);
                                    }
                                    i += 2;
                                }
                                '#' => {
                                    out.push('/');
                                    i += 1;
                                }
                                _ => {
                                    out.push(s);
                                    i += 1;
                                }
                            }
                        }
                    }
                    _ => {
                        // \W…; \H…; \f…; \C…; \A…; \T…; \Q…; \~ …: dropped up to the next ';'
                        match chars[i + 2..].iter().position(|&x| x == ';') {
                            Some(p) => i += 2 + p + 1,
                            None => return out,
                        }
                    }
                }
            }
            _ => {
                out.push(c);
                i += 1;
            }
        }
    }
    out
}

/// BeckerCAD encodings of Ø, ° and ±.
pub fn replace_percent_codes(text: &str) -> String {
    text.replace("%%c", "_D")
        .replace("%%d", "_G")
        .replace("%%p", "_+")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_text() {
        assert_eq!(
            mtext_plain("\\W1.135081;M2x20\\PO2\\PT2\\PI1,2\\PB-0,3"),
            "M2x20\r\nO2\r\nT2\r\nI1,2\r\nB-0,3"
        );
        assert_eq!(mtext_plain("{\\fArial|b0;B1}\\PS5"), "B1\r\nS5");
        assert_eq!(mtext_plain("a\\\\b\\{c\\}"), "a\\b{c}");
        assert_eq!(mtext_plain("\\S1#2;x"), "1/2x");
        assert_eq!(mtext_plain("\\S1^ 2;"), "12");
        assert_eq!(mtext_plain("\\Lunder\\l"), "under");
        assert_eq!(mtext_plain("B1\\H2"), "B1");
        assert_eq!(mtext_plain("x^Jy"), "x\r\ny");
        assert_eq!(mtext_plain("end\\"), "end");
    }

    #[test]
    fn percent_codes() {
        assert_eq!(replace_percent_codes("%%c5 %%d %%p %%C"), "_D5 _G _+ %%C");
    }
}
