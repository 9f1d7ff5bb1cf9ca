//! The tokens of a file, stored small: a kind, a start and a length, 8 bytes a token instead
//! of the 40 of a token with its text and a `usize` range. A drawing of half a million segments
//! has millions of tokens, so this list is the largest thing a parse holds. The parser reads
//! it through [`Tokens`], a chumsky input that makes each [`Token`] (its text cut from the
//! source) as it is read, with the spans chumsky's own token-and-span input would give.

use crate::lexer::Token;
use chumsky::input::{ExactSizeInput, Input, ValueInput};
use chumsky::span::{SimpleSpan, Span as _};
use logos::Logos;
use std::ops::{Range, RangeFrom};

/// What a stored token is; the text of the three that carry one is its byte range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    LParen,
    RParen,
    Comma,
    LBrace,
    RBrace,
    Arrow,
    Newline,
    Comment,
    Str,
    Word,
    Error,
}

#[derive(Debug, Clone, Copy)]
struct Stored {
    kind: Kind,
    /// The length in bytes; [`LONG`]: in `TokenList::long` (a comment or word of 64 KiB).
    len: u16,
    start: u32,
}

/// The length of a token stored beside the list.
const LONG: u16 = u16::MAX;

/// The tokens of one source text, lexed once.
pub struct TokenList<'s> {
    src: &'s str,
    toks: Vec<Stored>,
    /// (index, end) of the tokens of [`LONG`] length or more, in order.
    long: Vec<(u32, u32)>,
}

impl<'s> TokenList<'s> {
    /// Lexes `src`. Offsets are 32-bit: a text beyond 4 GiB is cut there (files are read up
    /// to 1 GiB).
    pub fn lex(src: &'s str) -> TokenList<'s> {
        let mut cut = src.len().min(u32::MAX as usize);
        while !src.is_char_boundary(cut) {
            cut -= 1;
        }
        let src = &src[..cut];
        let mut toks = Vec::with_capacity(token_room(src));
        let mut long = Vec::new();
        for (t, span) in Token::lexer(src).spanned() {
            let kind = match t.unwrap_or(Token::Error) {
                Token::LParen => Kind::LParen,
                Token::RParen => Kind::RParen,
                Token::Comma => Kind::Comma,
                Token::LBrace => Kind::LBrace,
                Token::RBrace => Kind::RBrace,
                Token::Arrow => Kind::Arrow,
                Token::Newline => Kind::Newline,
                Token::Comment(_) => Kind::Comment,
                Token::Str(_) => Kind::Str,
                Token::Word(_) => Kind::Word,
                Token::Error => Kind::Error,
            };
            let len = span.end - span.start;
            if len >= usize::from(LONG) {
                long.push((toks.len() as u32, span.end as u32));
            }
            toks.push(Stored {
                kind,
                len: len.min(usize::from(LONG)) as u16,
                start: span.start as u32,
            });
        }
        TokenList { src, toks, long }
    }

    /// The `i`-th token and its span.
    fn get(&self, i: usize) -> Option<(Token<'s>, Range<usize>)> {
        let s = self.toks.get(i)?;
        let end = if s.len == LONG {
            let k = self.long.partition_point(|&(at, _)| (at as usize) < i);
            self.long.get(k)?.1 as usize
        } else {
            s.start as usize + usize::from(s.len)
        };
        let span = s.start as usize..end;
        let text = &self.src[span.clone()];
        let tok = match s.kind {
            Kind::LParen => Token::LParen,
            Kind::RParen => Token::RParen,
            Kind::Comma => Token::Comma,
            Kind::LBrace => Token::LBrace,
            Kind::RBrace => Token::RBrace,
            Kind::Arrow => Token::Arrow,
            Kind::Newline => Token::Newline,
            Kind::Comment => Token::Comment(text),
            Kind::Str => Token::Str(text),
            Kind::Word => Token::Word(text),
            Kind::Error => Token::Error,
        };
        Some((tok, span))
    }

    /// Every token with its span, in order.
    pub fn iter(&self) -> impl Iterator<Item = (Token<'s>, Range<usize>)> + '_ {
        (0..self.toks.len()).filter_map(|i| self.get(i))
    }

    /// The list as the parser's input.
    pub fn input(&self) -> Tokens<'_, 's> {
        Tokens { list: self }
    }
}

/// Room for the tokens of `src`, so that a long list does not grow (growing a list of
/// millions copies it, and for a moment holds it twice): drawings have about 0.4 tokens a
/// byte, so room for one every two bytes (only input like `((((` needs more, and grows). On
/// 64 bits reserving costs only address space, the pages written are taken; a 32-bit target
/// (the browser) reserves real memory and starts smaller.
fn token_room(src: &str) -> usize {
    if cfg!(target_pointer_width = "64") {
        src.len() / 2 + 16
    } else {
        src.len() / 4
    }
}

/// A [`TokenList`] as chumsky input: tokens by value, spans from the first token's start to
/// the last read token's end (the end of input after the last token).
#[derive(Clone, Copy)]
pub struct Tokens<'t, 's> {
    list: &'t TokenList<'s>,
}

/// Where a parse is: the next token's index, and the end of the last token read.
#[derive(Clone, Debug)]
pub struct Cursor {
    at: usize,
    last_end: Option<usize>,
}

impl<'t, 's: 't> Input<'t> for Tokens<'t, 's> {
    type Span = SimpleSpan;
    type Token = Token<'s>;
    type MaybeToken = Token<'s>;
    type Cursor = Cursor;
    type Cache = &'t TokenList<'s>;

    fn begin(self) -> (Cursor, Self::Cache) {
        (
            Cursor {
                at: 0,
                last_end: None,
            },
            self.list,
        )
    }

    fn cursor_location(cursor: &Cursor) -> usize {
        cursor.at
    }

    unsafe fn next_maybe(list: &mut Self::Cache, cursor: &mut Cursor) -> Option<Token<'s>> {
        let (tok, span) = list.get(cursor.at)?;
        cursor.at += 1;
        cursor.last_end = Some(span.end);
        Some(tok)
    }

    unsafe fn span(list: &mut Self::Cache, range: Range<&Cursor>) -> SimpleSpan {
        let eoi = list.src.len();
        match list.get(range.start.at) {
            Some((_, span)) => SimpleSpan::new((), span.start..range.end.last_end.unwrap_or(eoi)),
            None => SimpleSpan::new((), eoi..eoi),
        }
    }
}

impl<'t, 's: 't> ValueInput<'t> for Tokens<'t, 's> {
    unsafe fn next(list: &mut Self::Cache, cursor: &mut Cursor) -> Option<Token<'s>> {
        Self::next_maybe(list, cursor)
    }
}

impl<'t, 's: 't> ExactSizeInput<'t> for Tokens<'t, 's> {
    unsafe fn span_from(list: &mut Self::Cache, range: RangeFrom<&Cursor>) -> SimpleSpan {
        let eoi = list.src.len();
        let start = list.get(range.start.at).map_or(eoi, |(_, s)| s.start);
        SimpleSpan::new((), start..eoi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stored_tokens_are_the_lexers() {
        let long_comment = format!("# {}", "x".repeat(70_000));
        let long_word = "7".repeat(65_535);
        let src = format!(
            "path \"a b\" {{ # c\n  mill (0, -1.5)->(2,3) B-0,3 :Q#x {long_comment}\n{long_word} {long_comment}\n}}\u{0}§"
        );
        let list = TokenList::lex(&src);
        let got: Vec<_> = list.iter().collect();
        assert_eq!(got, crate::lexer::lex(&src));
        assert_eq!(list.long.len(), 3, "two comments and a word of 64 KiB");
        assert!(std::mem::size_of::<Stored>() <= 8);
    }
}
