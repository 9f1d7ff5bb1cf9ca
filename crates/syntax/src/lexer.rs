//! Tokens of the MillPath language (logos).
//!
//! Logos tokens (a byte-order mark reads as blank); quoting of words and parameter tokens;
//! splitting the parameter part.

use logos::Logos;
use std::ops::Range;

#[derive(Logos, Debug, Clone, Copy, PartialEq, Eq, Hash)]
// a byte-order mark reads as blank space (readers strip it; an editor's buffer may keep it)
#[logos(skip r"[ \t\f\u{FEFF}]+")]
pub enum Token<'a> {
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token(",")]
    Comma,
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[token("->", priority = 20)]
    Arrow,
    #[regex(r"\r?\n")]
    Newline,
    /// `# …` up to the end of the line; only where a token starts (`B1#x` is one word).
    #[regex(r"#[^\r\n]*", allow_greedy = true)]
    Comment(&'a str),
    /// A quoted token (`"#5"`), with `\"` and `\\` escapes.
    #[regex(r#""([^"\\\r\n]|\\.)*""#)]
    Str(&'a str),
    /// Keywords, numbers, names and parameter tokens.
    #[regex(r#"[^\s(){},#"\u{FEFF}][^\s(){},"\u{FEFF}]*"#)]
    Word(&'a str),
    /// Anything the lexer does not understand (reported by the parser).
    Error,
}

impl std::fmt::Display for Token<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Token::LParen => write!(f, "`(`"),
            Token::RParen => write!(f, "`)`"),
            Token::Comma => write!(f, "`,`"),
            Token::LBrace => write!(f, "`{{`"),
            Token::RBrace => write!(f, "`}}`"),
            Token::Arrow => write!(f, "`->`"),
            Token::Newline => write!(f, "end of line"),
            Token::Comment(_) => write!(f, "comment"),
            Token::Str(s) => write!(f, "{s}"),
            Token::Word(w) => write!(f, "`{w}`"),
            Token::Error => write!(f, "invalid character"),
        }
    }
}

/// All tokens with their byte ranges; lexer errors become [`Token::Error`]. (The parser
/// keeps them smaller: `tokens.rs`.)
pub fn lex(src: &str) -> Vec<(Token<'_>, Range<usize>)> {
    Token::lexer(src)
        .spanned()
        .map(|(t, span)| (t.unwrap_or(Token::Error), span))
        .collect()
}

/// Undoes the quoting of a [`Token::Str`].
pub fn unquote(s: &str) -> String {
    let inner = s
        .strip_prefix('"')
        .and_then(|x| x.strip_suffix('"'))
        .unwrap_or(s);
    let mut out = String::with_capacity(inner.len());
    let mut chars = inner.chars();
    while let Some(c) = chars.next() {
        if c == '\\' {
            match chars.next() {
                Some('t') => out.push('\t'),
                Some(n) => out.push(n),
                None => out.push('\\'),
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// Quotes a token when it could not be read back as one plain word.
pub fn quote_if_needed(s: &str) -> String {
    let plain = !s.is_empty()
        && !s.starts_with(['#', '"'])
        && !s
            .chars()
            .any(|c| c.is_whitespace() || "(){},\"".contains(c))
        && s != "->";
    if plain {
        s.to_string()
    } else {
        quote(s)
    }
}

/// `"…"` with `\"`, `\\` and `\t` escapes.
fn quote(s: &str) -> String {
    let mut q = String::from("\"");
    for c in s.chars() {
        match c {
            '"' | '\\' => {
                q.push('\\');
                q.push(c);
            }
            '\t' => q.push_str("\\t"),
            _ => q.push(c),
        }
    }
    q.push('"');
    q
}

/// Quotes a parameter token when it would otherwise read as a comment, a quoted token or
/// several tokens.
pub fn quote_param(s: &str) -> String {
    if s.is_empty() || s.starts_with(['#', '"']) || s.chars().any(char::is_whitespace) {
        quote(s)
    } else {
        s.to_string()
    }
}

/// Splits the parameter part of a line into tokens: whitespace-separated, `"…"` quoted.
/// Returns each token with its byte range relative to `src`.
pub fn split_params(src: &str) -> Vec<(String, Range<usize>)> {
    let mut out = Vec::new();
    let bytes: Vec<(usize, char)> = src.char_indices().collect();
    let mut i = 0;
    while i < bytes.len() {
        let (start, c) = bytes[i];
        if c.is_whitespace() {
            i += 1;
            continue;
        }
        if c == '"' {
            let mut j = i + 1;
            while j < bytes.len() && bytes[j].1 != '"' {
                if bytes[j].1 == '\\' {
                    j += 1;
                }
                j += 1;
            }
            let end = if j < bytes.len() {
                bytes[j].0 + 1
            } else {
                src.len()
            };
            out.push((unquote(&src[start..end]), start..end));
            i = j + 1;
        } else {
            let mut j = i;
            while j < bytes.len() && !bytes[j].1.is_whitespace() {
                j += 1;
            }
            let end = if j < bytes.len() {
                bytes[j].0
            } else {
                src.len()
            };
            out.push((src[start..end].to_string(), start..end));
            i = j;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens() {
        let toks: Vec<Token> = lex("mill (0, -1.5)->(2,3) B-0,3 :Q#x # note\n}")
            .into_iter()
            .map(|t| t.0)
            .collect();
        assert_eq!(
            toks,
            vec![
                Token::Word("mill"),
                Token::LParen,
                Token::Word("0"),
                Token::Comma,
                Token::Word("-1.5"),
                Token::RParen,
                Token::Arrow,
                Token::LParen,
                Token::Word("2"),
                Token::Comma,
                Token::Word("3"),
                Token::RParen,
                Token::Word("B-0"),
                Token::Comma,
                Token::Word("3"),
                Token::Word(":Q#x"),
                Token::Comment("# note"),
                Token::Newline,
                Token::RBrace,
            ]
        );
    }

    #[test]
    fn quoting_round_trips() {
        for s in ["#5", "a b", "x\"y", "t\tab", "(", "->", "plain"] {
            let q = quote_if_needed(s);
            let toks = lex(&q);
            assert_eq!(toks.len(), 1, "{q}");
            let back = match toks[0].0 {
                Token::Str(x) => unquote(x),
                Token::Word(w) => w.to_string(),
                t => panic!("{t:?}"),
            };
            assert_eq!(back, s);
        }
        assert_eq!(quote_if_needed("B-0,3"), "\"B-0,3\"");
    }

    #[test]
    fn params_split_and_quote() {
        let toks: Vec<String> = split_params("T2  B-0,3 \"#5\" \"a b\" :Q#")
            .into_iter()
            .map(|t| t.0)
            .collect();
        assert_eq!(toks, ["T2", "B-0,3", "#5", "a b", ":Q#"]);
        for s in ["#5", "a b", "\"x", "B-0,3", "t\tx"] {
            let q = quote_param(s);
            assert_eq!(
                split_params(&q)
                    .into_iter()
                    .map(|t| t.0)
                    .collect::<Vec<_>>(),
                [s],
                "{q}"
            );
        }
        assert_eq!(quote_param("B-0,3"), "B-0,3");
    }
}
