//! The template language: literal text with placeholders `{name}` naming a variable of the
//! event ([`crate::event`]); `{{` and `}}` are literal braces; a line break in the template
//! starts a new program line. There is nothing else: no includes, no loops, no expressions,
//! so a template expands in one pass to at most its own length plus its variables' texts.

use crate::event::{Event, Var};

/// Longest template text (bytes): far beyond any controller's header.
pub const MAX_TEMPLATE: usize = 4096;

#[derive(Debug, Clone, PartialEq)]
pub enum Piece {
    Text(String),
    Var(Var),
}

/// A parsed template: its pieces in order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Template {
    pub pieces: Vec<Piece>,
    /// The text as written in the post file (for `post show`).
    pub source: String,
}

/// Why a template does not parse: the problem and its byte offset in the template text.
#[derive(Debug, Clone, PartialEq)]
pub enum TemplateError {
    /// `{name}` names no variable of the event.
    UnknownVariable(String),
    /// The variable exists but not in this event.
    NotInEvent(String),
    /// `{` without `}` (or a lone `}`).
    Unbalanced,
    TooLong(usize),
    /// A control character other than a line break.
    ControlCharacter,
}

impl Template {
    /// Parses `text` as the template of `event`; `Err((offset, problem))`.
    pub fn parse(event: Event, text: &str) -> Result<Template, (usize, TemplateError)> {
        if text.len() > MAX_TEMPLATE {
            return Err((0, TemplateError::TooLong(text.len())));
        }
        let mut pieces = Vec::new();
        let mut lit = String::new();
        let mut chars = text.char_indices().peekable();
        while let Some((at, c)) = chars.next() {
            match c {
                '{' if chars.peek().map(|p| p.1) == Some('{') => {
                    chars.next();
                    lit.push('{');
                }
                '}' if chars.peek().map(|p| p.1) == Some('}') => {
                    chars.next();
                    lit.push('}');
                }
                '}' => return Err((at, TemplateError::Unbalanced)),
                '{' => {
                    let rest = &text[at + 1..];
                    let Some(end) = rest.find(['}', '{', '\n']) else {
                        return Err((at, TemplateError::Unbalanced));
                    };
                    if rest.as_bytes()[end] != b'}' {
                        return Err((at, TemplateError::Unbalanced));
                    }
                    let name = rest[..end].trim();
                    let var = Var::from_name(name)
                        .ok_or_else(|| (at, TemplateError::UnknownVariable(name.to_string())))?;
                    if !event.allows(var) {
                        return Err((at, TemplateError::NotInEvent(name.to_string())));
                    }
                    if !lit.is_empty() {
                        pieces.push(Piece::Text(std::mem::take(&mut lit)));
                    }
                    pieces.push(Piece::Var(var));
                    // skip the name and its brace
                    while let Some((i, _)) = chars.peek() {
                        if *i > at + end + 1 {
                            break;
                        }
                        chars.next();
                    }
                }
                '\r' => {}
                c if c.is_control() && c != '\n' && c != '\t' => {
                    return Err((at, TemplateError::ControlCharacter))
                }
                c => lit.push(c),
            }
        }
        if !lit.is_empty() {
            pieces.push(Piece::Text(lit));
        }
        Ok(Template {
            pieces,
            source: text.to_string(),
        })
    }

    /// No text at all: the event writes no line.
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    pub fn uses(&self, var: Var) -> bool {
        self.pieces.contains(&Piece::Var(var))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placeholders_and_braces() {
        let t = Template::parse(Event::RapidXy, "G00 X{x} Y{ y } {{c}}").unwrap();
        assert_eq!(
            t.pieces,
            [
                Piece::Text("G00 X".into()),
                Piece::Var(Var::X),
                Piece::Text(" Y".into()),
                Piece::Var(Var::Y),
                Piece::Text(" {c}".into()),
            ]
        );
        let bad = |s: &str| Template::parse(Event::RapidXy, s).unwrap_err();
        assert_eq!(bad("G00 X{x"), (5, TemplateError::Unbalanced));
        assert_eq!(bad("G00 X}"), (5, TemplateError::Unbalanced));
        assert_eq!(bad("G00 X{x{y}}"), (5, TemplateError::Unbalanced));
        assert_eq!(
            bad("G00 {zz}"),
            (4, TemplateError::UnknownVariable("zz".into()))
        );
        assert_eq!(
            bad("G00 {feed}"),
            (4, TemplateError::NotInEvent("feed".into()))
        );
        assert!(Template::parse(Event::RapidXy, "{file_name}").is_ok());
    }
}
