//! Errors in a post file, located (file, line, column, key) and worded in English and German.

use crate::template::TemplateError;

/// The language of a message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Lang {
    #[default]
    En,
    De,
}

#[derive(Debug, Clone, PartialEq)]
pub enum ErrorKind {
    /// The TOML does not parse (toml's own message, which names what it expected).
    Syntax(String),
    Template(TemplateError),
    /// A required template is missing.
    MissingTemplate(&'static str),
    /// `[templates]` has a key that is no event.
    UnknownTemplate(String),
    /// A number format's `decimals` is not 0 to 9 or "shortest".
    BadDecimals(String),
    /// A value out of its range or of the wrong kind: what is expected.
    BadValue(&'static str),
    /// The post file is larger than [`crate::MAX_POST_FILE`].
    TooLarge(usize),
    /// No built-in post has this name (the name, the built-in names).
    Unknown(String, String),
    /// The file could not be read.
    Unreadable(String),
}

/// A located error in a post file.
#[derive(Debug, Clone, PartialEq)]
pub struct PostError {
    /// The post's file (or `builtin:NAME`).
    pub file: String,
    /// 1-based; 0 when the error is about the whole file.
    pub line: usize,
    pub column: usize,
    /// The dotted key (`templates.linear`, `format.decimals`); empty for the file.
    pub key: String,
    pub kind: ErrorKind,
}

impl PostError {
    pub fn message(&self, lang: Lang) -> String {
        use ErrorKind::*;
        use TemplateError as T;
        let de = lang == Lang::De;
        match &self.kind {
            Syntax(m) if de => format!("TOML-Syntaxfehler: {m}"),
            Syntax(m) => format!("TOML syntax error: {m}"),
            Template(T::UnknownVariable(v)) if de => {
                format!("unbekannte Variable {{{v}}} (die Liste zeigt `millpath post show`)")
            }
            Template(T::UnknownVariable(v)) => {
                format!("unknown variable {{{v}}} (`millpath post show` lists them)")
            }
            Template(T::NotInEvent(v)) if de => {
                format!("die Variable {{{v}}} gibt es in dieser Vorlage nicht")
            }
            Template(T::NotInEvent(v)) => format!("this template has no variable {{{v}}}"),
            Template(T::Unbalanced) if de => {
                "unausgeglichene Klammer: `{` ohne `}` oder `}` ohne `{` (wörtlich: `{{`, `}}`)"
                    .into()
            }
            Template(T::Unbalanced) => {
                "unbalanced brace: `{` without `}` or `}` without `{` (literal: `{{`, `}}`)".into()
            }
            Template(T::TooLong(n)) if de => format!(
                "Vorlage mit {n} Bytes ist zu lang (höchstens {})",
                crate::template::MAX_TEMPLATE
            ),
            Template(T::TooLong(n)) => format!(
                "template of {n} bytes is too long (at most {})",
                crate::template::MAX_TEMPLATE
            ),
            Template(T::ControlCharacter) if de => {
                "Steuerzeichen in der Vorlage (nur Zeilenumbruch und Tabulator)".into()
            }
            Template(T::ControlCharacter) => {
                "control character in the template (only line breaks and tabs)".into()
            }
            MissingTemplate(k) if de => format!("die Vorlage `{k}` fehlt in [templates]"),
            MissingTemplate(k) => format!("the template `{k}` is missing from [templates]"),
            UnknownTemplate(k) if de => format!("`{k}` ist kein Ereignis des Emitters"),
            UnknownTemplate(k) => format!("`{k}` is no event of the emitter"),
            BadDecimals(v) if de => format!(
                "decimals = {v}: erwartet eine ganze Zahl von 0 bis {} oder \"shortest\"",
                crate::number::MAX_DECIMALS
            ),
            BadDecimals(v) => format!(
                "decimals = {v}: expected a whole number from 0 to {} or \"shortest\"",
                crate::number::MAX_DECIMALS
            ),
            BadValue(what) if de => format!("ungültiger Wert: erwartet {}", german(what)),
            BadValue(what) => format!("invalid value: expected {what}"),
            TooLarge(n) if de => format!(
                "die Post-Datei hat {n} Bytes, höchstens {} sind erlaubt",
                crate::MAX_POST_FILE
            ),
            TooLarge(n) => format!(
                "the post file has {n} bytes, at most {} are allowed",
                crate::MAX_POST_FILE
            ),
            Unknown(n, known) if de => {
                format!("kein Post `{n}`: weder eingebaut ({known}) noch eine Datei")
            }
            Unknown(n, known) => format!("no post `{n}`: neither built in ({known}) nor a file"),
            Unreadable(e) if de => format!("nicht lesbar: {e}"),
            Unreadable(e) => format!("cannot be read: {e}"),
        }
    }

    /// `file:line:column: key: message` (the parts known).
    pub fn render(&self, lang: Lang) -> String {
        let mut s = self.file.clone();
        if self.line > 0 {
            s.push_str(&format!(":{}:{}", self.line, self.column));
        }
        if !self.key.is_empty() {
            s.push_str(&format!(": {}", self.key));
        }
        format!("{s}: {}", self.message(lang))
    }
}

impl std::fmt::Display for PostError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.render(Lang::En))
    }
}

impl std::error::Error for PostError {}

/// The German of each [`ErrorKind::BadValue`] expectation.
fn german(what: &str) -> &str {
    match what {
        "a name of letters, digits, `-` and `_`" => {
            "einen Namen aus Buchstaben, Ziffern, `-` und `_`"
        }
        "\"rs274\", \"grbl\", \"marlin\" or \"xcam\"" => {
            "\"rs274\", \"grbl\", \"marlin\" oder \"xcam\""
        }
        "a file extension of letters and digits" => "eine Dateiendung aus Buchstaben und Ziffern",
        "one character, not a digit, sign or blank" => {
            "ein Zeichen, keine Ziffer, kein Vorzeichen, kein Leerzeichen"
        }
        "\"lf\" or \"crlf\"" => "\"lf\" oder \"crlf\"",
        "a line length from 40 to 100000" => "eine Zeilenlänge von 40 bis 100000",
        "\"ij\", \"r\" or \"lines\"" => "\"ij\", \"r\" oder \"lines\"",
        "a chord tolerance from 0.0001 to 1 mm" => "eine Sehnentoleranz von 0,0001 bis 1 mm",
        "a radius above 0 and at most 100000 mm" => "einen Radius über 0 und höchstens 100000 mm",
        "a word letter (A–Z) or \"motion\"" => "einen Wortbuchstaben (A–Z) oder \"motion\"",
        "a single letter A–Z" => "einen einzelnen Buchstaben A–Z",
        "a whole number from 0 to 1000000" => "eine ganze Zahl von 0 bis 1000000",
        "a step from 1 to 1000" => "eine Schrittweite von 1 bis 1000",
        "a width from 0 to 9" => "eine Breite von 0 bis 9",
        "\"parens\" or \"semicolon\"" => "\"parens\" oder \"semicolon\"",
        "printable ASCII characters" => "druckbare ASCII-Zeichen",
        "a word of letters" => "ein Wort aus Buchstaben",
        "\"none\", \"G38.2\", \"G38.3\" or \"G31\"" => {
            "\"none\", \"G38.2\", \"G38.3\" oder \"G31\""
        }
        other => other,
    }
}
