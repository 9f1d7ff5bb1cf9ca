//! Syntax errors as data: what was expected and found, and the hints where the fix is known
//! (did-you-mean, decimal point). The words are chosen by the reader's language elsewhere
//! (`millpath_core::front::syntax_msg`); [`SyntaxError::message`] is the English text.

use crate::ast::Span;

/// A syntax error with its byte range.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntaxError {
    pub span: Span,
    pub kind: ErrorKind,
}

#[derive(Debug, Clone, PartialEq)]
pub enum ErrorKind {
    /// A character no token starts with.
    UnexpectedChar(String),
    /// A word where a number belongs.
    NotANumber(String),
    /// `r`/`d` glued to something that is not a number (`rx`).
    NotPrefixedNumber { word: String, prefix: &'static str },
    /// A path block without its closing `}`.
    MissingBrace,
    /// A word where an element kind belongs, and the nearest kind when one is close.
    UnknownKind {
        word: String,
        suggestion: Option<&'static str>,
    },
    /// A misspelt keyword other than a kind (`pat` for `path`, `arround` for `around`).
    DidYouMean {
        word: String,
        suggestion: &'static str,
    },
    /// A number with a decimal comma inside a point: `written` (`12,5`) is `fixed` (`12.5`).
    DecimalComma { written: String, fixed: String },
    /// Anything else: what would have been accepted here, and what stands here.
    Expected {
        expected: Vec<Expected>,
        found: Found,
    },
}

/// One thing the parser would have accepted.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub enum Expected {
    /// A keyword or punctuation, written as in the file (`mill`, `)`).
    Text(String),
    Number,
    Point,
    PathName,
    LineType,
    EndOfLine,
}

/// What stands where the error is.
#[derive(Debug, Clone, PartialEq)]
pub enum Found {
    /// A token as written in the file.
    Text(String),
    EndOfLine,
    EndOfInput,
}

/// Every element kind word, for did-you-mean.
pub const KIND_WORDS: &[&str] = &[
    "start", "end", "turn", "probe", "noprobe", "mill", "mark", "bars", "sub", "sweep", "move",
    "skip", "drill", "helix", "raw",
];

/// The word of `candidates` nearest to `word` when it is near enough to be a typo: the same
/// word in other case, or an edit distance of 1 (2 for words of five letters and more).
pub fn nearest(word: &str, candidates: &[&'static str]) -> Option<&'static str> {
    let lower = word.to_lowercase();
    let limit = if lower.chars().count() >= 5 { 2 } else { 1 };
    candidates
        .iter()
        .map(|c| (strsim::damerau_levenshtein(&lower, c), *c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

impl Expected {
    /// The English words (a keyword or punctuation in backticks).
    pub fn english(&self) -> String {
        match self {
            Expected::Text(t) => format!("`{t}`"),
            Expected::Number => "a number".into(),
            Expected::Point => "a point `(x, y)`".into(),
            Expected::PathName => "a path name".into(),
            Expected::LineType => "a line type".into(),
            Expected::EndOfLine => "the end of the line".into(),
        }
    }
}

impl Found {
    pub fn english(&self) -> String {
        match self {
            Found::Text(t) => format!("`{t}`"),
            Found::EndOfLine => "the end of the line".into(),
            Found::EndOfInput => "the end of the file".into(),
        }
    }
}

/// `a`, `a or b`, `a, b or c`.
pub fn or_list(items: &[String], or: &str) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => format!("{} {or} {last}", rest.join(", ")),
    }
}

impl SyntaxError {
    /// The message in English.
    pub fn message(&self) -> String {
        match &self.kind {
            ErrorKind::UnexpectedChar(c) => format!("unexpected character `{c}`"),
            ErrorKind::NotANumber(w) => format!("`{w}` is not a number"),
            ErrorKind::NotPrefixedNumber { word, prefix } => {
                format!("`{word}` is not {prefix} followed by a number")
            }
            ErrorKind::MissingBrace => "missing `}` at the end of the path".into(),
            ErrorKind::UnknownKind {
                word,
                suggestion: Some(s),
            } => format!("`{word}` is not an element kind: did you mean `{s}`?"),
            ErrorKind::DidYouMean {
                word,
                suggestion: s,
            } => format!("unknown word `{word}`: did you mean `{s}`?"),
            ErrorKind::UnknownKind {
                word,
                suggestion: None,
            } => format!("`{word}` is not an element kind"),
            ErrorKind::DecimalComma { written, fixed } => {
                format!("coordinates need a decimal point: write `{fixed}`, not `{written}`")
            }
            ErrorKind::Expected { expected, found } => {
                let list: Vec<String> = expected.iter().map(Expected::english).collect();
                format!(
                    "expected {}, found {}",
                    or_list(&list, "or"),
                    found.english()
                )
            }
        }
    }
}

/// The first number with a decimal comma (`12,5`: digits, a comma, digits, no space) in
/// `text`, as written and with a decimal point.
pub fn decimal_comma(text: &str) -> Option<(std::ops::Range<usize>, String, String)> {
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b','
            && i > 0
            && b[i - 1].is_ascii_digit()
            && b.get(i + 1).is_some_and(u8::is_ascii_digit)
        {
            let start = text[..i]
                .rfind(|c: char| !(c.is_ascii_digit() || c == '-' || c == '+'))
                .map_or(0, |p| p + 1);
            let end = text[i + 1..]
                .find(|c: char| !c.is_ascii_digit())
                .map_or(text.len(), |p| i + 1 + p);
            let written = text[start..end].to_string();
            let fixed = written.replacen(',', ".", 1);
            return Some((start..end, written, fixed));
        }
        i += 1;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typos_find_their_word_and_nonsense_finds_none() {
        assert_eq!(nearest("mil", KIND_WORDS), Some("mill"));
        assert_eq!(nearest("Mill", KIND_WORDS), Some("mill"));
        assert_eq!(nearest("drlil", KIND_WORDS), Some("drill"));
        assert_eq!(nearest("heilx", KIND_WORDS), Some("helix"));
        assert_eq!(nearest("frobnicate", KIND_WORDS), None);
        assert_eq!(nearest("x", KIND_WORDS), None);
    }

    #[test]
    fn decimal_commas_are_found_with_their_fix() {
        let (r, w, f) = decimal_comma("12,5, 0").unwrap();
        assert_eq!((r, w.as_str(), f.as_str()), (0..4, "12,5", "12.5"));
        let (r, w, f) = decimal_comma("0, -3,25").unwrap();
        assert_eq!((r, w.as_str(), f.as_str()), (3..8, "-3,25", "-3.25"));
        assert_eq!(decimal_comma("1, 2"), None);
    }

    #[test]
    fn lists_read_as_sentences() {
        let l = |v: &[&str]| or_list(&v.iter().map(|s| s.to_string()).collect::<Vec<_>>(), "or");
        assert_eq!(l(&["a"]), "a");
        assert_eq!(l(&["a", "b"]), "a or b");
        assert_eq!(l(&["a", "b", "c"]), "a, b or c");
    }
}
