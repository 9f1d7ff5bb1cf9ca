//! What the `.NCC` reader (`ncc.rs`, xCAM's exchange format) finds wrong in a line, in
//! English and German.

use crate::number_problem::NumberProblem;

#[derive(Debug, Clone, PartialEq)]
pub enum NccProblem {
    /// A line that starts with no command of the format.
    UnknownCommand(String),
    /// A part of the line that is not `NAME=value`.
    NotAPair(String),
    /// A string value without its closing `"`.
    UnclosedString(String),
    /// A value that is not a number where the format has one.
    NotANumber { name: String, text: String },
    /// A number that is not finite, absurd, or in exponent notation.
    Number {
        name: String,
        text: String,
        problem: NumberProblem,
    },
    /// A variable the command needs is missing.
    Missing { command: String, name: String },
    /// A variable given twice on one line.
    Duplicate(String),
    /// The first command is not the header `H`.
    HeaderNotFirst,
    /// A second header.
    SecondHeader,
    /// A `G1`/`G5` with no contour started (`G0`) before it.
    NoContour(String),
    /// A milling names a contour the file has not defined before it.
    UnknownContour(String),
    /// A contour name used a second time.
    DuplicateContour(String),
    /// `DIR` is neither 1 nor -1.
    BadDirection(String),
    /// The millings replay more contour elements than the reader models.
    ReplayLimit(usize),
    /// The file ends before what it started is whole: no header, a standard contour without
    /// its milling, or a last line cut.
    Incomplete,
}

impl NccProblem {
    /// The message, in German when `de`.
    pub fn message(&self, de: bool) -> String {
        let pick = |en: String, de_text: String| if de { de_text } else { en };
        match self {
            NccProblem::UnknownCommand(c) => pick(
                format!("NCC: {c:?} is no command of the xCAM format"),
                format!("NCC: {c:?} ist kein Befehl des xCAM-Formats"),
            ),
            NccProblem::NotAPair(t) => pick(
                format!("NCC: {t:?} is not NAME=value"),
                format!("NCC: {t:?} ist nicht NAME=Wert"),
            ),
            NccProblem::UnclosedString(n) => pick(
                format!("NCC: the string of {n} has no closing \""),
                format!("NCC: der Text von {n} hat kein schließendes \""),
            ),
            NccProblem::NotANumber { name, text } => pick(
                format!("NCC: {name}={text} is not a number"),
                format!("NCC: {name}={text} ist keine Zahl"),
            ),
            NccProblem::Number {
                name,
                text,
                problem,
            } => {
                let (en, de_text) = match problem {
                    NumberProblem::NonFinite => ("not a finite number", "keine endliche Zahl"),
                    NumberProblem::Absurd => (
                        "the magnitude exceeds 1000000 (absurd)",
                        "der Betrag übersteigt 1000000 (unsinnig)",
                    ),
                    NumberProblem::Exponent => (
                        "exponent notation is not the format's",
                        "Exponentenschreibweise gehört nicht zum Format",
                    ),
                };
                pick(
                    format!("NCC: {name}={text}: {en}"),
                    format!("NCC: {name}={text}: {de_text}"),
                )
            }
            NccProblem::Missing { command, name } => pick(
                format!("NCC: {command} needs {name}"),
                format!("NCC: {command} braucht {name}"),
            ),
            NccProblem::Duplicate(n) => pick(
                format!("NCC: {n} is given twice on this line"),
                format!("NCC: {n} steht zweimal in dieser Zeile"),
            ),
            NccProblem::HeaderNotFirst => pick(
                "NCC: the header H must be the first line".into(),
                "NCC: der Programmkopf H muss die erste Zeile sein".into(),
            ),
            NccProblem::SecondHeader => pick(
                "NCC: a second header H".into(),
                "NCC: ein zweiter Programmkopf H".into(),
            ),
            NccProblem::NoContour(c) => pick(
                format!("NCC: {c} outside a contour (no G0 before it)"),
                format!("NCC: {c} außerhalb einer Kontur (kein G0 davor)"),
            ),
            NccProblem::UnknownContour(n) => pick(
                format!("NCC: the milling names the contour {n:?}, which is not defined before it"),
                format!("NCC: die Fräsung nennt die Kontur {n:?}, die davor nicht definiert ist"),
            ),
            NccProblem::DuplicateContour(n) => pick(
                format!("NCC: a second contour named {n:?} (names must be unique)"),
                format!("NCC: eine zweite Kontur namens {n:?} (Namen müssen eindeutig sein)"),
            ),
            NccProblem::BadDirection(t) => pick(
                format!("NCC: DIR={t}: an arc's direction is 1 (clockwise) or -1"),
                format!("NCC: DIR={t}: die Drehrichtung eines Bogens ist 1 (im Uhrzeigersinn) oder -1"),
            ),
            NccProblem::ReplayLimit(n) => pick(
                format!("NCC: the millings replay more than {n} contour elements: the rest is not checked"),
                format!("NCC: die Fräsungen wiederholen mehr als {n} Konturelemente: der Rest wird nicht geprüft"),
            ),
            NccProblem::Incomplete => pick(
                "NCC: the file ends before it is whole (no header H, a contour without its milling GIN, or a last line cut): is it truncated?".into(),
                "NCC: die Datei endet, bevor sie vollständig ist (kein Programmkopf H, eine Kontur ohne ihre Fräsung GIN oder eine abgeschnittene letzte Zeile): ist sie abgeschnitten?".into(),
            ),
        }
    }
}
