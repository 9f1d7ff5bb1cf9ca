//! One G-code line → words and comments. Spaces and tabs outside comments are ignored, also
//! inside numbers (as LinuxCNC and grbl do); letters are case-insensitive. Anything else is a
//! finding, never a panic.

use crate::finding::{FindingKind, NumberProblem, SyntaxError};
use crate::magnitude::MAX_MAGNITUDE;

#[derive(Debug, Clone, PartialEq)]
pub struct Word {
    /// Upper-case ASCII letter.
    pub letter: char,
    pub value: f64,
}

#[derive(Debug, Default, Clone, PartialEq)]
pub struct Block {
    pub words: Vec<Word>,
    /// Texts of the parenthesised comments (without the parentheses).
    pub comments: Vec<String>,
    /// The line is a `%` program delimiter.
    pub percent: bool,
    /// A `(` inside a parenthesised comment.
    pub nested_comment: bool,
    /// The text after a `;` (an end-of-line comment), trimmed.
    pub semicolon: Option<String>,
}

impl Block {
    pub fn get(&self, letter: char) -> Option<f64> {
        self.words
            .iter()
            .find(|w| w.letter == letter)
            .map(|w| w.value)
    }
    pub fn has(&self, letter: char) -> bool {
        self.words.iter().any(|w| w.letter == letter)
    }
}

fn syntax(e: SyntaxError) -> FindingKind {
    FindingKind::Syntax(e)
}

/// Parses one line (without its line end).
pub fn parse_line(line: &str) -> Result<Block, FindingKind> {
    let chars: Vec<char> = line.chars().collect();
    let mut block = Block::default();
    let mut i = 0;
    // `%` delimiter line
    let first = chars.iter().position(|c| !c.is_whitespace());
    if let Some(f) = first {
        if chars[f] == '%' {
            block.percent = true;
            i = f + 1;
            while i < chars.len() {
                match chars[i] {
                    c if c.is_whitespace() => i += 1,
                    ';' => break,
                    '(' => {
                        let close = chars[i + 1..].iter().position(|&c| c == ')');
                        match close {
                            Some(n) => i += n + 2,
                            None => return Err(syntax(SyntaxError::UnclosedComment)),
                        }
                    }
                    _ => return Err(syntax(SyntaxError::TextAfterPercent)),
                }
            }
            return Ok(block);
        }
        if chars[f] == '/' {
            // block delete: the line runs unless the operator switches block delete on;
            // check it as if it runs.
            i = f + 1;
        }
    }
    while i < chars.len() {
        let c = chars[i];
        match c {
            ' ' | '\t' | '\r' => i += 1,
            '\u{feff}' => return Err(syntax(SyntaxError::ByteOrderMark)),
            '(' => {
                let rest = &chars[i + 1..];
                let Some(n) = rest.iter().position(|&c| c == ')') else {
                    return Err(syntax(SyntaxError::UnclosedComment));
                };
                let text: String = rest[..n].iter().collect();
                if text.contains('(') {
                    block.nested_comment = true;
                }
                block.comments.push(text);
                i += n + 2;
            }
            ';' => {
                let text: String = chars[i + 1..].iter().collect();
                block.semicolon = Some(text.trim().to_string());
                break;
            }
            c if c.is_ascii_alphabetic() => {
                let letter = c.to_ascii_uppercase();
                i += 1;
                let (value, next) = parse_number(&chars, i, letter)?;
                i = next;
                if letter != 'G' && letter != 'M' && block.has(letter) {
                    return Err(syntax(SyntaxError::DuplicateWord(letter)));
                }
                block.words.push(Word { letter, value });
            }
            other => return Err(syntax(SyntaxError::UnexpectedChar(other))),
        }
    }
    Ok(block)
}

fn skip_blanks(chars: &[char], mut i: usize) -> usize {
    while i < chars.len() && (chars[i] == ' ' || chars[i] == '\t') {
        i += 1;
    }
    i
}

/// A number after a word letter: `[+-]digits[.digits]`, blanks allowed anywhere. NaN/inf and
/// exponents are recognised only to report them.
fn parse_number(chars: &[char], start: usize, letter: char) -> Result<(f64, usize), FindingKind> {
    let mut i = skip_blanks(chars, start);
    let mut text = String::new();
    if i < chars.len() && (chars[i] == '+' || chars[i] == '-') {
        text.push(chars[i]);
        i = skip_blanks(chars, i + 1);
    }
    // NaN / inf / infinity
    let alpha_end = {
        let mut j = i;
        while j < chars.len() && chars[j].is_ascii_alphabetic() {
            j += 1;
        }
        j
    };
    let word: String = chars[i..alpha_end].iter().collect::<String>();
    let lower = word.to_ascii_lowercase();
    for special in ["infinity", "nan", "inf"] {
        if lower.starts_with(special) {
            text.push_str(&word[..special.len()]);
            return Err(FindingKind::BadNumber {
                letter,
                text,
                problem: NumberProblem::NonFinite,
            });
        }
    }
    let mut digits = 0;
    let mut dots = 0;
    while i < chars.len() {
        match chars[i] {
            d @ '0'..='9' => {
                text.push(d);
                digits += 1;
            }
            '.' => {
                dots += 1;
                if dots > 1 {
                    return Err(syntax(SyntaxError::UnexpectedChar('.')));
                }
                text.push('.');
            }
            ' ' | '\t' => {}
            _ => break,
        }
        i += 1;
    }
    if digits == 0 {
        return Err(syntax(SyntaxError::MissingNumber(letter)));
    }
    // exponent: e/E, optional sign, at least one digit
    let mut exponent = false;
    if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
        let mut j = i + 1;
        let mut exp = String::from("e");
        if j < chars.len() && (chars[j] == '+' || chars[j] == '-') {
            exp.push(chars[j]);
            j += 1;
        }
        let mut exp_digits = 0;
        while j < chars.len() && chars[j].is_ascii_digit() {
            exp.push(chars[j]);
            exp_digits += 1;
            j += 1;
        }
        if exp_digits > 0 {
            exponent = true;
            text.push_str(&exp);
            i = j;
        }
    }
    let value: f64 = text.parse().unwrap_or(f64::NAN);
    let shown = if letter == 'G' || letter == 'M' {
        text.clone()
    } else {
        text.trim_start_matches('+').to_string()
    };
    let problem = if !value.is_finite() {
        Some(NumberProblem::NonFinite)
    } else if value.abs() > MAX_MAGNITUDE {
        Some(NumberProblem::Absurd)
    } else if exponent {
        Some(NumberProblem::Exponent)
    } else {
        None
    };
    match problem {
        Some(problem) => Err(FindingKind::BadNumber {
            letter,
            text: shown,
            problem,
        }),
        None => Ok((value, i)),
    }
}

/// A line that is one parenthesised comment and nothing else (ASCII blanks around): it moves
/// nothing and changes no mode, so a second reading of the program may skip it (a caller
/// that keeps the lines for one may keep such a line empty). Bytes, so that a reader can
/// tell before it checks the line's UTF-8.
pub fn only_a_comment(line: impl AsRef<[u8]>) -> bool {
    let t = line.as_ref().trim_ascii();
    t.len() >= 2
        && t[0] == b'('
        && t[t.len() - 1] == b')'
        && !t[1..t.len() - 1].iter().any(|&b| b == b'(' || b == b')')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_comments_and_blanks() {
        let b =
            parse_line("G01 F300.000 X 1 . 5 Y-0.000 Z0.800(=0.800+0.794*[#51-2.000])").unwrap();
        let letters: String = b.words.iter().map(|w| w.letter).collect();
        assert_eq!(letters, "GFXYZ");
        assert_eq!(b.get('X'), Some(1.5));
        assert_eq!(b.get('Z'), Some(0.8));
        assert_eq!(b.comments, vec!["=0.800+0.794*[#51-2.000]"]);
        assert!(parse_line("%").unwrap().percent);
        let semi = parse_line("; G00 X1").unwrap();
        assert!(semi.words.is_empty());
        assert_eq!(semi.semicolon.as_deref(), Some("G00 X1"));
        let numbered = parse_line("N10 G01 X1 ; cut (here)").unwrap();
        assert_eq!(numbered.words[0].letter, 'N');
        assert_eq!(numbered.semicolon.as_deref(), Some("cut (here)"));
        assert!(numbered.comments.is_empty());
        assert_eq!(parse_line("g38.3 z0").unwrap().get('G'), Some(38.3));
    }

    #[test]
    fn bad_numbers() {
        for (line, problem) in [
            ("G00 ZNaN", NumberProblem::NonFinite),
            ("G00 X-inf", NumberProblem::NonFinite),
            ("G00 Z1e9", NumberProblem::Absurd),
            ("G00 Z1e-3", NumberProblem::Exponent),
            ("G00 X1000000.1", NumberProblem::Absurd),
        ] {
            match parse_line(line) {
                Err(FindingKind::BadNumber { problem: p, .. }) => assert_eq!(p, problem, "{line}"),
                other => panic!("{line}: {other:?}"),
            }
        }
        assert!(matches!(
            parse_line("G00 X"),
            Err(FindingKind::Syntax(SyntaxError::MissingNumber('X')))
        ));
        assert!(matches!(
            parse_line("G00 X1 X2"),
            Err(FindingKind::Syntax(SyntaxError::DuplicateWord('X')))
        ));
        assert!(matches!(
            parse_line("G00 (open"),
            Err(FindingKind::Syntax(SyntaxError::UnclosedComment))
        ));
        assert!(matches!(
            parse_line("G00 #1"),
            Err(FindingKind::Syntax(SyntaxError::UnexpectedChar('#')))
        ));
    }

    #[test]
    fn a_byte_order_mark_is_named_before_a_percent_and_before_words() {
        // rs274 stops at it ("Bad character '\357' used"), whatever follows
        for line in ["\u{feff}%", "\u{feff}(millpath)", "G00\u{feff} X1"] {
            assert!(
                matches!(
                    parse_line(line),
                    Err(FindingKind::Syntax(SyntaxError::ByteOrderMark))
                ),
                "{line:?}"
            );
        }
    }
}
