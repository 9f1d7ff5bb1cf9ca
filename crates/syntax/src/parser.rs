//! The error-recovering parser (chumsky over logos tokens). Every syntax error becomes a
//! [`SyntaxError`] with a span; a bad line is skipped and the rest of the file is parsed.
//! Plain segment lines (`mill (x, y) -> (x, y)  params`) are read by a short-cut without the
//! combinators (`plain_segment`), which gives the same tree and errors (property test
//! `tests/properties.rs` against [`parse_without_shortcut`]).

use crate::ast::*;
use crate::ast::{Span, Spanned};
pub use crate::error::SyntaxError;
use crate::error::{decimal_comma, nearest, ErrorKind, Expected, Found, KIND_WORDS};
use crate::lexer::{split_params, unquote, Token};
use crate::tokens::{TokenList, Tokens};
use chumsky::error::{LabelError, RichPattern};
use chumsky::prelude::*;

/// Custom errors travel through chumsky as text: a tag, then the offending word.
const NOT_A_NUMBER: &str = "number\u{1f}";
const MISSING_BRACE: &str = "brace\u{1f}";

type Extra<'t, 's> = extra::Err<Rich<'t, Token<'s>, SimpleSpan>>;
type In<'t, 's> = Tokens<'t, 's>;

/// Byte range of a span; empty matches can come back inverted, which is normalised here so
/// that every span can be used to slice the source.
fn range(s: SimpleSpan) -> Span {
    s.start.min(s.end)..s.start.max(s.end)
}

/// Raw element pieces before the parameter tokens are cut from the source.
#[derive(Debug, Clone)]
struct RawElement {
    kind: Spanned<Kind>,
    geometry: Spanned<Geometry>,
    /// Byte range of everything between the geometry and the comment / line end.
    params: Span,
    comment: Option<Spanned<String>>,
    span: Span,
}

#[derive(Debug, Clone)]
enum RawItem {
    Blank,
    Comment(Spanned<String>),
    Path {
        name: Spanned<String>,
        comment: Option<Spanned<String>>,
        /// Finished as they are parsed: a list of raw items beside the finished ones
        /// would hold a long path twice.
        items: Vec<PathItem>,
        close_comment: Option<Spanned<String>>,
        span: Span,
    },
    Error(Span),
}

fn kw<'t, 's: 't>(word: &'static str) -> impl Parser<'t, In<'t, 's>, (), Extra<'t, 's>> + Clone {
    just(Token::Word(word)).ignored().labelled(word)
}

fn number<'t, 's: 't>() -> impl Parser<'t, In<'t, 's>, f64, Extra<'t, 's>> + Clone {
    select! { Token::Word(w) => w }
        .labelled("number")
        .try_map(|w: &str, span| {
            parse_num(w).ok_or_else(|| Rich::custom(span, format!("{NOT_A_NUMBER}{w}")))
        })
}

fn parse_num(w: &str) -> Option<f64> {
    if w.is_empty()
        || !w
            .chars()
            .all(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E'))
    {
        return None;
    }
    w.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// `r10` / `r 10`, `d2` / `d 2`.
fn prefixed<'t, 's: 't>(
    prefix: &'static str,
) -> impl Parser<'t, In<'t, 's>, f64, Extra<'t, 's>> + Clone {
    let attached = select! { Token::Word(w) if w.len() > 1 && w.starts_with(prefix) => w }.try_map(
        move |w: &str, span| {
            parse_num(&w[prefix.len()..])
                .ok_or_else(|| Rich::custom(span, format!("{prefix}\u{1f}{w}")))
        },
    );
    let separate = kw(prefix).ignore_then(number());
    attached.or(separate).labelled(prefix)
}

fn point<'t, 's: 't>() -> impl Parser<'t, In<'t, 's>, Point, Extra<'t, 's>> + Clone {
    number()
        .then_ignore(just(Token::Comma))
        .then(number())
        .delimited_by(just(Token::LParen), just(Token::RParen))
        .map(|(x, y)| Point { x, y })
        .labelled("point `(x, y)`")
}

fn line_geometry<'t, 's: 't>() -> impl Parser<'t, In<'t, 's>, Geometry, Extra<'t, 's>> + Clone {
    // `(a) -> (b)`, or the hand-writing form of an arc `(a) -> (b) ccw around (c)`
    let turn = choice((kw("ccw").to(true), kw("cw").to(false)))
        .then_ignore(kw("around"))
        .then(point());
    let line = point()
        .then_ignore(just(Token::Arrow))
        .then(point())
        .then(turn.or_not())
        .map(|((a, b), around)| match around {
            None => Geometry::Line(a, b),
            Some((ccw, c)) => Geometry::arc_through(a, b, c, ccw),
        });
    let arc = kw("arc")
        .ignore_then(point())
        .then(prefixed("r"))
        .then_ignore(kw("from"))
        .then(number())
        .then_ignore(kw("to"))
        .then(number())
        .map(|(((c, r), a0), a1)| Geometry::Arc { c, r, a0, a1 });
    arc.or(line)
}

fn circle_geometry<'t, 's: 't>() -> impl Parser<'t, In<'t, 's>, Geometry, Extra<'t, 's>> + Clone {
    point()
        .then(prefixed("d"))
        .map(|(c, d)| Geometry::Circle { c, d })
}

fn element<'t, 's: 't>() -> impl Parser<'t, In<'t, 's>, RawElement, Extra<'t, 's>> + Clone {
    let marker = choice((
        kw("start").to(Kind::Start),
        kw("end").to(Kind::End),
        kw("turn").to(Kind::Turn),
        kw("probe").to(Kind::Probe),
        kw("noprobe").to(Kind::NoProbe),
    ))
    .map_with(|k, e| Spanned::new(k, range(e.span())))
    .then(
        point()
            .map(Geometry::Point)
            .map_with(|g, e| Spanned::new(g, range(e.span()))),
    );
    let style = choice((kw("mark").to(Style::Mark), kw("bars").to(Style::Bars)))
        .or_not()
        .map(|s| s.unwrap_or(Style::Mill));
    let circle = style
        .then(choice((kw("drill").to(true), kw("helix").to(false))))
        .map(|(s, drill)| {
            if drill {
                Kind::Drill(s)
            } else {
                Kind::Helix(s)
            }
        })
        .map_with(|k, e| Spanned::new(k, range(e.span())))
        .then(circle_geometry().map_with(|g, e| Spanned::new(g, range(e.span()))));
    let segment = choice((
        kw("mill").to(Kind::Mill),
        kw("mark").to(Kind::Mark),
        kw("bars").to(Kind::Bars),
        kw("sub").to(Kind::Sub),
        kw("sweep").to(Kind::Sweep),
        kw("move").to(Kind::Move),
        kw("skip").to(Kind::Skip),
    ))
    .map_with(|k, e| Spanned::new(k, range(e.span())))
    .then(line_geometry().map_with(|g, e| Spanned::new(g, range(e.span()))));
    let linetype = select! {
        Token::Word(w) => w.to_string(),
        Token::Str(s) => unquote(s),
    }
    .labelled("line type");
    let raw = kw("raw")
        .ignore_then(linetype)
        .map_with(|lt, e| Spanned::new(Kind::Raw(lt), range(e.span())))
        .then(
            choice((
                line_geometry(),
                circle_geometry(),
                point().map(Geometry::Point),
            ))
            .map_with(|g, e| Spanned::new(g, range(e.span()))),
        );
    let params = any()
        .filter(|t: &Token| !matches!(t, Token::Newline | Token::Comment(_)))
        .repeated()
        .map_with(|_, e| range(e.span()));
    let comment = select! { Token::Comment(c) => c.to_string() }
        .map_with(|c, e| Spanned::new(c, range(e.span())));
    choice((marker, circle, segment, raw))
        .then(params)
        .then(comment.or_not())
        .then_ignore(just(Token::Newline).ignored().or(end()))
        .map_with(|(((kind, geometry), params), comment), e| RawElement {
            kind,
            geometry,
            params,
            comment,
            span: range(e.span()),
        })
}

/// The common segment line `mill (x, y) -> (x, y)  params  # comment`, read without the
/// combinators (a drawing of 100,000 segments is mostly these lines): the element the full
/// grammar gives, with the same spans. Any other line (a marker, a circle, an arc, `ccw
/// around`, a word that is no number, a line that does not end) fails where it starts with
/// the error the first alternative after it (a blank line) reports there, so the full
/// grammar reads it and reports exactly what it reports without this short-cut.
fn plain_segment<'t, 's: 't>() -> impl Parser<'t, In<'t, 's>, RawElement, Extra<'t, 's>> + Clone {
    custom(|inp| {
        let start = inp.save();
        match plain_segment_at(inp) {
            Some(e) => Ok(e),
            None => {
                inp.rewind(start.clone());
                let found = inp.next_maybe();
                let span = inp.span_since(start.cursor());
                inp.rewind(start);
                Err(<Rich<'t, Token<'s>, SimpleSpan> as LabelError<
                    't,
                    In<'t, 's>,
                    RichPattern<'t, Token<'s>>,
                >>::expected_found(
                    [RichPattern::Token(Token::Newline.into())],
                    found,
                    span,
                ))
            }
        }
    })
}

fn plain_segment_at<'t, 's: 't>(
    inp: &mut chumsky::input::InputRef<'t, '_, In<'t, 's>, Extra<'t, 's>>,
) -> Option<RawElement> {
    let start = inp.cursor();
    let kind = match inp.next()? {
        Token::Word("mill") => Kind::Mill,
        Token::Word("mark") => Kind::Mark,
        Token::Word("bars") => Kind::Bars,
        Token::Word("sub") => Kind::Sub,
        Token::Word("sweep") => Kind::Sweep,
        Token::Word("move") => Kind::Move,
        Token::Word("skip") => Kind::Skip,
        _ => return None,
    };
    let kind = Spanned::new(kind, range(inp.span_since(&start)));
    let at = inp.cursor();
    let point = |inp: &mut chumsky::input::InputRef<'t, '_, In<'t, 's>, Extra<'t, 's>>| {
        let num = |inp: &mut chumsky::input::InputRef<'t, '_, In<'t, 's>, Extra<'t, 's>>| match inp
            .next()?
        {
            Token::Word(w) => parse_num(w),
            _ => None,
        };
        (inp.next()? == Token::LParen).then_some(())?;
        let x = num(inp)?;
        (inp.next()? == Token::Comma).then_some(())?;
        let y = num(inp)?;
        (inp.next()? == Token::RParen).then_some(Point { x, y })
    };
    let a = point(inp)?;
    (inp.next()? == Token::Arrow).then_some(())?;
    let b = point(inp)?;
    let geometry = Spanned::new(Geometry::Line(a, b), range(inp.span_since(&at)));
    // `ccw around (c)`: the full grammar decides
    if matches!(inp.peek(), Some(Token::Word("ccw" | "cw"))) {
        return None;
    }
    let at = inp.cursor();
    while !matches!(inp.peek(), None | Some(Token::Newline | Token::Comment(_))) {
        inp.skip();
    }
    let params = range(inp.span_since(&at));
    let comment = match inp.peek() {
        Some(Token::Comment(c)) => {
            let at = inp.cursor();
            inp.skip();
            Some(Spanned::new(c.to_string(), range(inp.span_since(&at))))
        }
        _ => None,
    };
    match inp.peek() {
        Some(Token::Newline) => inp.skip(),
        None => {}
        Some(_) => return None,
    }
    Some(RawElement {
        kind,
        geometry,
        params,
        comment,
        span: range(inp.span_since(&start)),
    })
}

fn error_line<'t, 's: 't>(
    stop: Token<'s>,
) -> impl Parser<'t, In<'t, 's>, Span, Extra<'t, 's>> + Clone {
    none_of([Token::Newline, stop])
        .then(none_of([Token::Newline]).repeated())
        .then_ignore(just(Token::Newline).ignored().or(end()))
        .map_with(|_, e| range(e.span()))
}

/// A long list collected in pieces and then moved into one list of its exact size: a list
/// that grows by doubling copies itself each time and holds both copies for a moment (a path
/// of half a million lines: 80 MB more for that moment).
struct Pieces<T>(Vec<T>);

impl<T> FromIterator<T> for Pieces<T> {
    fn from_iter<I: IntoIterator<Item = T>>(iter: I) -> Self {
        const PIECE: usize = 1 << 14;
        let mut full: Vec<Vec<T>> = Vec::new();
        let mut last = Vec::new();
        for x in iter {
            if last.len() == PIECE {
                full.push(std::mem::replace(&mut last, Vec::with_capacity(PIECE)));
            }
            last.push(x);
        }
        if full.is_empty() {
            return Pieces(last);
        }
        let mut all = Vec::with_capacity(full.len() * PIECE + last.len());
        // each piece is given back as soon as it is moved
        for piece in full {
            all.extend(piece);
        }
        all.extend(last);
        Pieces(all)
    }
}

fn file_parser<'t, 's: 't>(
    src: &'s str,
    shortcut: bool,
) -> impl Parser<'t, In<'t, 's>, Vec<RawItem>, Extra<'t, 's>> {
    let comment = select! { Token::Comment(c) => c.to_string() }
        .map_with(|c, e| Spanned::new(c, range(e.span())));
    let newline = just(Token::Newline);
    let plain = plain_segment().map(move |e| PathItem::Element(finish_element(e, src)));
    let path_item = choice((
        plain.filter(move |_| shortcut),
        newline.to(PathItem::Blank),
        comment
            .then_ignore(newline.ignored().or(end()))
            .map(PathItem::Comment),
        element()
            .map(move |e| PathItem::Element(finish_element(e, src)))
            .recover_with(via_parser(error_line(Token::RBrace).map(PathItem::Error))),
    ));
    let name = select! {
        Token::Word(w) => w.to_string(),
        Token::Str(s) => unquote(s),
    }
    .labelled("path name")
    .map_with(|n, e| Spanned::new(n, range(e.span())));
    // the comment after `}` is kept: the formatter writes it back
    let close = just(Token::RBrace)
        .ignore_then(comment.or_not())
        .then_ignore(newline.ignored().or(end()))
        .or_not()
        .validate(|c, e, emitter| {
            if c.is_none() {
                emitter.emit(Rich::custom(e.span(), MISSING_BRACE));
            }
            c.flatten()
        });
    let path = kw("path")
        .ignore_then(name)
        .then_ignore(just(Token::LBrace))
        .then(comment.or_not())
        .then_ignore(newline)
        .then(path_item.repeated().collect::<Pieces<_>>().map(|p| p.0))
        .then(close)
        .map_with(
            |(((name, comment), items), close_comment), e| RawItem::Path {
                name,
                comment,
                items,
                close_comment,
                span: range(e.span()),
            },
        );
    let item = choice((
        newline.to(RawItem::Blank),
        comment
            .then_ignore(newline.ignored().or(end()))
            .map(RawItem::Comment),
        path.recover_with(via_parser(error_line(Token::Newline).map(RawItem::Error))),
    ))
    .recover_with(via_parser(error_line(Token::Newline).map(RawItem::Error)));
    item.repeated().collect::<Vec<_>>().then_ignore(end())
}

/// Parses a file. The tree is always returned; errors are listed beside it.
pub fn parse(src: &str) -> (File, Vec<SyntaxError>) {
    parse_with(src, true)
}

/// [`parse`] without the short-cut for plain segment lines (`plain_segment`): the tests
/// hold that both give the same tree and errors.
#[doc(hidden)]
pub fn parse_without_shortcut(src: &str) -> (File, Vec<SyntaxError>) {
    parse_with(src, false)
}

fn parse_with(src: &str, shortcut: bool) -> (File, Vec<SyntaxError>) {
    let toks = TokenList::lex(src);
    let mut errors: Vec<SyntaxError> = toks
        .iter()
        .filter(|(t, _)| *t == Token::Error)
        .map(|(_, s)| SyntaxError {
            kind: ErrorKind::UnexpectedChar(src[s.clone()].to_string()),
            span: s,
        })
        .collect();
    let input = toks.input();
    let (out, errs) = file_parser(src, shortcut).parse(input).into_output_errors();
    for e in errs {
        let span = range(*e.span());
        let span = span.start.min(src.len())..span.end.min(src.len());
        if errors.iter().any(|x| x.span == span) {
            continue;
        }
        errors.push(describe(&e, span, src));
    }
    // gone before the top-level items are moved into the tree
    drop(toks);
    let items = out
        .unwrap_or_default()
        .into_iter()
        .map(finish_item)
        .collect();
    errors.sort_by_key(|e| e.span.start);
    (File { items }, errors)
}

/// The error as data, with the hint where the fix is known.
fn describe(e: &Rich<Token, SimpleSpan>, span: Span, src: &str) -> SyntaxError {
    use chumsky::error::{RichPattern, RichReason};
    let kind = match e.reason() {
        RichReason::Custom(msg) => match msg.split_once('\u{1f}') {
            Some(("number", w)) => ErrorKind::NotANumber(w.to_string()),
            Some(("brace", _)) => ErrorKind::MissingBrace,
            Some((prefix, w)) => ErrorKind::NotPrefixedNumber {
                word: w.to_string(),
                prefix: if prefix == "r" { "r" } else { "d" },
            },
            None => ErrorKind::UnexpectedChar(msg.to_string()),
        },
        RichReason::ExpectedFound { expected, found } => {
            let mut exp: Vec<Expected> = expected
                .iter()
                .filter_map(|x| match x {
                    RichPattern::Token(t) => Some(token_expected(t)),
                    RichPattern::Label(l) => Some(label_expected(l)),
                    RichPattern::Identifier(i) => Some(Expected::Text(i.clone())),
                    RichPattern::EndOfInput => Some(Expected::EndOfLine),
                    _ => None,
                })
                .collect();
            exp.sort();
            exp.dedup();
            let found = match found.as_deref() {
                None => Found::EndOfInput,
                Some(Token::Newline) => Found::EndOfLine,
                Some(_) => Found::Text(src.get(span.clone()).unwrap_or("").to_string()),
            };
            return hint(exp, found, span, src);
        }
    };
    SyntaxError { span, kind }
}

fn token_expected(t: &Token) -> Expected {
    match t {
        Token::Newline => Expected::EndOfLine,
        Token::LParen => Expected::Text("(".into()),
        Token::RParen => Expected::Text(")".into()),
        Token::Comma => Expected::Text(",".into()),
        Token::LBrace => Expected::Text("{".into()),
        Token::RBrace => Expected::Text("}".into()),
        Token::Arrow => Expected::Text("->".into()),
        Token::Word(w) => Expected::Text(w.to_string()),
        Token::Str(s) => Expected::Text(s.to_string()),
        Token::Comment(_) | Token::Error => Expected::Text("#".into()),
    }
}

fn label_expected(l: &str) -> Expected {
    match l {
        "number" => Expected::Number,
        "point `(x, y)`" => Expected::Point,
        "path name" => Expected::PathName,
        "line type" => Expected::LineType,
        // `r`, `d` and every keyword are labelled with themselves
        word => Expected::Text(word.to_string()),
    }
}

/// An expected/found error made specific where the fix is known: a misspelt kind or
/// keyword, a decimal comma inside a point.
fn hint(expected: Vec<Expected>, found: Found, span: Span, src: &str) -> SyntaxError {
    let words: Vec<&'static str> = expected
        .iter()
        .filter_map(|e| match e {
            // one-letter keywords (`r`, `d`) are a distance of 1 from every other letter
            Expected::Text(t) if t.len() > 1 => KEYWORDS.iter().find(|k| *k == t).copied(),
            _ => None,
        })
        .collect();
    if let Found::Text(w) = &found {
        let is_word = w.chars().next().is_some_and(char::is_alphabetic);
        if is_word && words.iter().any(|k| KIND_WORDS.contains(k)) && words.contains(&"mill") {
            let kind = ErrorKind::UnknownKind {
                word: w.clone(),
                suggestion: nearest(w, KIND_WORDS),
            };
            return SyntaxError { span, kind };
        }
        if is_word {
            if let Some(s) = nearest(w, &words) {
                let kind = ErrorKind::DidYouMean {
                    word: w.clone(),
                    suggestion: s,
                };
                return SyntaxError { span, kind };
            }
        }
        // `(12,5, 0)`: the comma of a number read as the one between x and y
        let in_point = expected.contains(&Expected::Text(")".into()));
        if w == "," && in_point {
            let line_start = src[..span.start].rfind('\n').map_or(0, |p| p + 1);
            if let Some(open) = src[line_start..span.start].rfind('(') {
                let open = line_start + open + 1;
                let close = src[open..]
                    .find([')', '\n'])
                    .map_or(src.len(), |p| open + p);
                if let Some((r, written, fixed)) = decimal_comma(&src[open..close]) {
                    let kind = ErrorKind::DecimalComma { written, fixed };
                    return SyntaxError {
                        span: open + r.start..open + r.end,
                        kind,
                    };
                }
            }
        }
    }
    SyntaxError {
        span,
        kind: ErrorKind::Expected { expected, found },
    }
}

/// Every keyword of the language (element kinds and the words inside elements).
const KEYWORDS: &[&str] = &[
    "path", "start", "end", "turn", "probe", "noprobe", "mill", "mark", "bars", "sub", "sweep",
    "move", "skip", "drill", "helix", "raw", "arc", "from", "to", "ccw", "cw", "around", "r", "d",
];

fn finish_item(i: RawItem) -> Item {
    match i {
        RawItem::Blank => Item::Blank,
        RawItem::Comment(c) => Item::Comment(c),
        RawItem::Error(s) => Item::Error(s),
        RawItem::Path {
            name,
            comment,
            items,
            close_comment,
            span,
        } => Item::Path(PathBlock {
            name,
            comment,
            items,
            close_comment,
            span,
        }),
    }
}

fn finish_element(e: RawElement, src: &str) -> Element {
    let base = e.params.start;
    let text = src.get(e.params.clone()).unwrap_or("");
    let params = split_params(text)
        .into_iter()
        .map(|(t, r)| Spanned::new(t, base + r.start..base + r.end))
        .collect();
    Element {
        kind: e.kind,
        geometry: e.geometry,
        params,
        comment: e.comment.map(Box::new),
        span: e.span,
    }
}

#[cfg(test)]
mod pieces_tests {
    use super::Pieces;

    #[test]
    fn pieces_keep_the_order_and_end_in_a_list_of_exact_size() {
        for n in [0usize, 1, 16_383, 16_384, 16_385, 70_000] {
            let Pieces(v) = (0..n).collect::<Pieces<usize>>();
            assert_eq!(v.len(), n);
            assert!(v.iter().copied().eq(0..n));
            if n > 16_384 {
                // a list grown by doubling would have room for 131,072 here
                assert!(v.capacity() < n + n / 2, "one list of the size needed");
            }
        }
    }
}
