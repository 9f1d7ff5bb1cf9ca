//! What the checker reports: a small enum of findings, each with its message in English and
//! German. Rendering happens late (`message(lang)`), so a caller can show the same finding in
//! the language of its user.

use crate::Dialect;

/// Message language.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Lang {
    #[default]
    En,
    De,
}

/// How bad a finding is. `Error` means the program must not run as it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    Error,
    Warning,
    Note,
}

impl Severity {
    pub fn word(self, lang: Lang) -> &'static str {
        match (self, lang) {
            (Severity::Error, Lang::En) => "error",
            (Severity::Error, Lang::De) => "Fehler",
            (Severity::Warning, Lang::En) => "warning",
            (Severity::Warning, Lang::De) => "Warnung",
            (Severity::Note, Lang::En) => "note",
            (Severity::Note, Lang::De) => "Hinweis",
        }
    }
}

/// One finding: where (1-based G-code line and its text) and what.
#[derive(Debug, Clone, PartialEq)]
pub struct Finding {
    /// 1-based line of the G-code program; `None` for findings about the program as a whole
    /// (e.g. "stock checks skipped").
    pub line: Option<usize>,
    /// The text of that line (trimmed, at most 200 characters); empty without a line.
    pub text: String,
    pub kind: FindingKind,
    pub severity: Severity,
}

impl Finding {
    pub fn message(&self, lang: Lang) -> String {
        self.kind.message(lang)
    }
    /// A stable machine-readable name of the kind, e.g. `rapid-into-material`.
    pub fn code(&self) -> &'static str {
        self.kind.code()
    }
}

/// Lexical and grammatical problems of a line; the line is not executed.
#[derive(Debug, Clone, PartialEq)]
pub enum SyntaxError {
    UnclosedComment,
    /// `(` inside a parenthesised comment (LinuxCNC rejects it; not fatal for the line).
    NestedComment,
    UnexpectedChar(char),
    /// U+FEFF, mostly a byte-order mark an editor saved before the first `%`: LinuxCNC stops
    /// there ("Bad character"), and the character cannot be seen in the line.
    ByteOrderMark,
    MissingNumber(char),
    DuplicateWord(char),
    /// Two codes of one modal group on one line, e.g. `G00 G01`.
    SameModalGroup(String, String),
    /// X/Y/Z with no motion mode in effect (G80 or none yet).
    AxesWithoutMotion,
    LineTooLong(usize),
    TextAfterPercent,
    /// G04 without P, or a negative P.
    BadDwell,
    /// A G or M code no controller knows, e.g. `G07.5`, `M1234`.
    UnknownCode(String),
    /// A code or word GRBL 1.1 does not have (it refuses the line: `error:20`), e.g. `M6`,
    /// `G64`, the word `E`.
    NotInGrbl(String),
    /// A value word no command of the line uses (GRBL refuses the line: `error:36`), e.g. `R`
    /// on a straight move, `P` outside G4/G10.
    UnusedWord(char),
    /// A motion code given without axis words that needs them (GRBL: `error:26`), e.g. `G02`.
    NoAxisWords(String),
}

/// A line its family's controller reads otherwise than written ([`Dialect::rules`]).
#[derive(Debug, Clone, PartialEq)]
pub enum FamilyProblem {
    /// `N` with a negative, fractional or too large number (`max`: the family's largest).
    LineNumber { text: String, max: u32 },
    /// `N` after another word.
    LineNumberNotFirst,
    /// A `( )` comment where the controller reads only `;` comments.
    ParenComment,
    /// A `%` line where the controller has none.
    Percent,
    /// A second command on a line that takes one (the controller ignores it).
    SecondCommand { code: String },
    /// A line that does not start with its command (`word` comes first).
    CommandNotFirst { word: String },
    /// Axis words without G0–G3 on their line where motion is not modal.
    NoMotionWord,
    /// G02/G03 while the post writes arcs as lines.
    ArcNotAllowed { code: String },
    /// Marlin's M30 deletes a file on the SD card.
    M30DeletesFile,
    /// A code this family's controller does not have.
    NoSuchCode { code: String },
    /// The dwell after a spindle start is shorter than
    /// [`SHORT_SPINDLE_DWELL`](crate::SHORT_SPINDLE_DWELL) where `G4 P` is milliseconds.
    ShortSpindleDwell { seconds: f64 },
}

pub use crate::number_problem::NumberProblem;

/// Why a cutting move has no feed rate.
#[derive(Debug, Clone, PartialEq)]
pub enum NoFeedReason {
    /// No F was given before it.
    NeverSet,
    /// The feed mode word `code` on line `line` reset the feed rate (LinuxCNC: G93/G94/G95;
    /// grbl: leaving G93).
    ResetBy {
        code: String,
        line: usize,
        dialect: Dialect,
    },
    /// Inverse time mode (G93) needs F on every cutting line.
    InverseTime,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArcProblem {
    /// Neither I/J nor R.
    NoCentre,
    /// The centre is the start point.
    ZeroRadius,
    /// R shorter than half the chord.
    RadiusTooSmall,
}

/// Why the stock model did not run (or stopped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StockSkip {
    /// T and/or O unknown (no option, no `(MILLPATH-STOCK …)` comment).
    MissingParams { top: bool, tool: bool },
    /// The moves span an area too large for a grid fine enough for the tool.
    AreaTooLarge { cell: f64 },
    /// The stock model stopped at this line: the program needs too much work.
    WorkLimit { line: usize },
}

#[derive(Debug, Clone, PartialEq)]
pub enum StockCommentProblem {
    /// `KEY=TEXT` is not a usable number.
    BadValue { key: String, text: String },
    /// A later `(MILLPATH-STOCK …)` comment with other values; the first one counts.
    Conflicting,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Limit {
    /// More lines than the checker reads; the rest is not checked.
    Lines(usize),
    /// More findings than are listed.
    Findings(usize),
}

/// Every kind of finding.
#[derive(Debug, Clone, PartialEq)]
pub enum FindingKind {
    Syntax(SyntaxError),
    BadNumber {
        letter: char,
        text: String,
        problem: NumberProblem,
    },
    /// A code or word the controller knows but the checker does not model (`G41`, `G28`, an A
    /// axis …): the simulation may be off after it.
    Unsupported {
        what: String,
    },
    /// A G02/G03 in plane G18 or G19: not simulated.
    ArcPlane {
        plane: String,
    },
    /// A G00 whose tool passes through stock higher than its tip; `depth` is how far the tip
    /// is below the stock surface at (x, y).
    RapidIntoMaterial {
        depth: f64,
        x: f64,
        y: f64,
    },
    /// A cutting (or probing) move without a positive feed rate.
    NoFeed {
        motion: String,
        reason: NoFeedReason,
    },
    /// `F0` or a negative F.
    FeedNotPositive {
        value: f64,
    },
    /// A cutting move below the deepest drawn depth.
    BelowBottom {
        z: f64,
        bottom: f64,
    },
    /// The arc's radius at the start and at the end differ by more than 0.002 mm.
    ArcRadiusMismatch {
        start: f64,
        end: f64,
    },
    ArcInvalid(ArcProblem),
    /// A cutting move whose start is unknown (no earlier move set X, Y and Z).
    UnknownPosition {
        motion: String,
    },
    /// No M2/M30 and no closing `%`: the program is probably truncated.
    MissingProgramEnd,
    /// The tool (a cylinder of diameter O from its tip upward) touches a keep-out box.
    ClampHit {
        name: String,
        min: [f64; 3],
        max: [f64; 3],
        /// The tool radius the move was judged with.
        radius: f64,
    },
    /// Clamps are given but the tool diameter is not: only the tool's axis is checked.
    ClampsWithoutTool,
    /// Code after M2/M30: the controller ignores it.
    AfterProgramEnd,
    StockSkipped(StockSkip),
    StockComment(StockCommentProblem),
    Limit(Limit),
    /// A program adjusted to a measured surface (`(==…)` lines).
    Adjusted(AdjustedProblem),
    /// The program's `(MILLPATH-SURFACE …)` record cannot be read: its moves are judged at
    /// their written heights.
    Surface(crate::surface::SurfaceProblem),
    /// A line its family's controller reads otherwise than written.
    Family {
        problem: FamilyProblem,
        dialect: Dialect,
    },
    /// A lean checker's second reading (`Verifier::lean`) was not the program it read first:
    /// (lines, moves) read again of those read first.
    RereadDiffers {
        lines: (usize, usize),
        moves: (usize, usize),
    },
    /// A line of an xCAM `.NCC` file the reader cannot take (`ncc.rs`).
    Ncc(crate::ncc_problem::NccProblem),
}

/// Problems of a program adjusted by adjust-z.
#[derive(Debug, Clone, PartialEq)]
pub enum AdjustedProblem {
    /// The written Z is not the value of its probe expression with the measured heights.
    ZMismatch { z: f64, expected: f64 },
    /// The probe expression after `(==` cannot be read.
    Unreadable,
    /// A probe of the expression has no measured height in `(MILLPATH-PROBES …)`.
    NoValue { name: String },
    /// A word of `(MILLPATH-PROBES …)` is not `#n=<number>`.
    BadValue { text: String },
    /// Adjusted lines but no measured heights: checked at the drawn heights only.
    NoValues,
}

fn f3(v: f64) -> String {
    format!("{v:.3}")
}

impl FindingKind {
    pub fn code(&self) -> &'static str {
        match self {
            FindingKind::Syntax(_) => "syntax",
            FindingKind::BadNumber { .. } => "bad-number",
            FindingKind::Unsupported { .. } => "unsupported",
            FindingKind::ArcPlane { .. } => "arc-plane",
            FindingKind::RapidIntoMaterial { .. } => "rapid-into-material",
            FindingKind::NoFeed { .. } => "no-feed",
            FindingKind::FeedNotPositive { .. } => "feed-not-positive",
            FindingKind::BelowBottom { .. } => "below-bottom",
            FindingKind::ArcRadiusMismatch { .. } => "arc-radius-mismatch",
            FindingKind::ArcInvalid(_) => "arc-invalid",
            FindingKind::UnknownPosition { .. } => "unknown-position",
            FindingKind::MissingProgramEnd => "missing-program-end",
            FindingKind::ClampHit { .. } => "clamp-hit",
            FindingKind::ClampsWithoutTool => "clamps-without-tool",
            FindingKind::AfterProgramEnd => "after-program-end",
            FindingKind::StockSkipped(_) => "stock-skipped",
            FindingKind::StockComment(_) => "stock-comment",
            FindingKind::Limit(_) => "limit",
            FindingKind::Adjusted(_) => "adjusted",
            FindingKind::Surface(_) => "surface-record",
            FindingKind::RereadDiffers { .. } => "reread-differs",
            FindingKind::Family { .. } => "family",
            FindingKind::Ncc(_) => "ncc",
        }
    }

    pub fn message(&self, lang: Lang) -> String {
        let de = lang == Lang::De;
        let pick = |en: String, de_text: String| if de { de_text } else { en };
        match self {
            FindingKind::Syntax(s) => s.message(lang),
            FindingKind::BadNumber {
                letter,
                text,
                problem,
            } => match problem {
                NumberProblem::NonFinite => pick(
                    format!("{letter}{text}: not a finite number"),
                    format!("{letter}{text}: keine endliche Zahl"),
                ),
                NumberProblem::Absurd => pick(
                    format!("{letter}{text}: the magnitude exceeds 1000000 (absurd)"),
                    format!("{letter}{text}: der Betrag übersteigt 1000000 (unsinnig)"),
                ),
                NumberProblem::Exponent => pick(
                    format!("{letter}{text}: exponent notation is not G-code"),
                    format!("{letter}{text}: Exponentenschreibweise ist kein G-Code"),
                ),
            },
            FindingKind::Unsupported { what } => pick(
                format!("{what} is not modelled by the checker; the simulation may be off after this line"),
                format!("{what} wird von der Prüfung nicht nachgebildet; die Simulation kann danach abweichen"),
            ),
            FindingKind::ArcPlane { plane } => pick(
                format!("arc in plane {plane}: only G17 (XY) arcs are simulated"),
                format!("Bogen in der Ebene {plane}: nur G17-Bögen (XY) werden simuliert"),
            ),
            FindingKind::RapidIntoMaterial { depth, x, y } => pick(
                format!(
                    "rapid move (G00) into material: the tool tip passes {} mm below the stock surface at X{} Y{}",
                    f3(*depth), f3(*x), f3(*y)
                ),
                format!(
                    "Eilgang (G00) ins Material: die Werkzeugspitze fährt {} mm unter der Materialoberfläche bei X{} Y{}",
                    f3(*depth), f3(*x), f3(*y)
                ),
            ),
            FindingKind::NoFeed { motion, reason } => {
                let why = match reason {
                    NoFeedReason::NeverSet => pick("no F before it".into(), "kein F davor".into()),
                    NoFeedReason::ResetBy {
                        code,
                        line,
                        dialect,
                    } => pick(
                        format!(
                            "{code} on line {line} resets the feed rate in {}: give F after it",
                            dialect.controller()
                        ),
                        format!(
                            "{code} in Zeile {line} setzt den Vorschub in {} zurück: F danach angeben",
                            dialect.controller()
                        ),
                    ),
                    NoFeedReason::InverseTime => pick(
                        "inverse time mode G93 needs F on every cutting line".into(),
                        "der Inverse-Zeit-Modus G93 braucht F in jeder Fräszeile".into(),
                    ),
                };
                pick(
                    format!("{motion} without a feed rate ({why})"),
                    format!("{motion} ohne Vorschub ({why})"),
                )
            }
            FindingKind::FeedNotPositive { value } => pick(
                format!("feed rate F{} is not positive: cutting moves after it fail", f3(*value)),
                format!("Vorschub F{} ist nicht positiv: Fräsbewegungen danach scheitern", f3(*value)),
            ),
            FindingKind::BelowBottom { z, bottom } => pick(
                format!("cut at Z{}, below the deepest drawn depth {}", f3(*z), f3(*bottom)),
                format!("Schnitt bei Z{}, unter der tiefsten gezeichneten Tiefe {}", f3(*z), f3(*bottom)),
            ),
            FindingKind::ArcRadiusMismatch { start, end } => pick(
                format!(
                    "arc radius differs at start and end: {} / {} mm (more than 0.002 mm apart)",
                    f3(*start), f3(*end)
                ),
                format!(
                    "Bogenradius an Anfang und Ende verschieden: {} / {} mm (mehr als 0,002 mm Unterschied)",
                    f3(*start), f3(*end)
                ),
            ),
            FindingKind::ArcInvalid(p) => match p {
                ArcProblem::NoCentre => pick("arc without I/J or R".into(), "Bogen ohne I/J oder R".into()),
                ArcProblem::ZeroRadius => pick(
                    "arc of radius zero (the centre is the start point)".into(),
                    "Bogen mit Radius null (der Mittelpunkt ist der Anfangspunkt)".into(),
                ),
                ArcProblem::RadiusTooSmall => pick(
                    "arc radius R is smaller than half the distance from start to end".into(),
                    "Bogenradius R ist kleiner als der halbe Abstand von Anfang zu Ende".into(),
                ),
            },
            FindingKind::UnknownPosition { motion } => pick(
                format!("{motion} from an unknown position (no earlier move set X, Y and Z): not simulated"),
                format!("{motion} von unbekannter Position (keine frühere Bewegung setzte X, Y und Z): nicht simuliert"),
            ),
            FindingKind::ClampHit {
                name,
                min,
                max,
                radius,
            } => pick(
                format!(
                    "the tool (radius {} mm, from its tip upward) runs into clamp \"{name}\" (X{}…{} Y{}…{} Z{}…{})",
                    f3(*radius), f3(min[0]), f3(max[0]), f3(min[1]), f3(max[1]), f3(min[2]), f3(max[2])
                ),
                format!(
                    "das Werkzeug (Radius {} mm, von der Spitze aufwärts) fährt in die Spannpratze „{name}“ (X{}…{} Y{}…{} Z{}…{})",
                    f3(*radius), f3(min[0]), f3(max[0]), f3(min[1]), f3(max[1]), f3(min[2]), f3(max[2])
                ),
            ),
            FindingKind::ClampsWithoutTool => pick(
                "clamps are checked with the tool's axis only: the tool diameter is unknown (give --tool or a (MILLPATH-STOCK …) comment)".into(),
                "Spannpratzen werden nur mit der Werkzeugachse geprüft: der Werkzeugdurchmesser ist unbekannt (--tool oder ein Kommentar (MILLPATH-STOCK …) angeben)".into(),
            ),
            FindingKind::MissingProgramEnd => pick(
                "the program has no end (M30, M2 or a closing %): is it truncated?".into(),
                "das Programm hat kein Ende (M30, M2 oder abschließendes %): ist es abgeschnitten?".into(),
            ),
            FindingKind::Adjusted(p) => match p {
                AdjustedProblem::ZMismatch { z, expected } => pick(
                    format!(
                        "Z{} is not the value {} of its probe expression with the measured heights (MILLPATH-PROBES): the line was changed after adjust-z",
                        f3(*z), f3(*expected)
                    ),
                    format!(
                        "Z{} ist nicht der Wert {} seines Messpunkt-Ausdrucks mit den gemessenen Höhen (MILLPATH-PROBES): die Zeile wurde nach adjust-z geändert",
                        f3(*z), f3(*expected)
                    ),
                ),
                AdjustedProblem::Unreadable => pick(
                    "probe expression after '(==' cannot be read: the depth of this line is not known".into(),
                    "Messpunkt-Ausdruck nach '(==' ist nicht lesbar: die Tiefe dieser Zeile ist unbekannt".into(),
                ),
                AdjustedProblem::NoValue { name } => pick(
                    format!("probe {name} has no measured height in the (MILLPATH-PROBES …) comment"),
                    format!("Messpunkt {name} hat keine gemessene Höhe im Kommentar (MILLPATH-PROBES …)"),
                ),
                AdjustedProblem::BadValue { text } => pick(
                    format!("'{text}' in (MILLPATH-PROBES …) is not #n=<number>"),
                    format!("'{text}' in (MILLPATH-PROBES …) ist nicht #n=<Zahl>"),
                ),
                AdjustedProblem::NoValues => pick(
                    "adjusted program without measured heights (no MILLPATH-PROBES comment): depths are checked at the drawn heights only, not below the measured surface".into(),
                    "angepasstes Programm ohne gemessene Höhen (kein Kommentar MILLPATH-PROBES): Tiefen werden nur an den gezeichneten Höhen geprüft, nicht unter der gemessenen Oberfläche".into(),
                ),
            },
            FindingKind::Surface(p) => {
                let what = p.message(lang);
                pick(
                    format!("height map record (MILLPATH-SURFACE …): {what}; the moves are checked at their written heights, not against the measured surface"),
                    format!("Höhenkarten-Eintrag (MILLPATH-SURFACE …): {what}; die Bewegungen werden an ihren geschriebenen Höhen geprüft, nicht gegen die gemessene Oberfläche"),
                )
            }
            FindingKind::AfterProgramEnd => pick(
                "code after the program end (M2/M30) is ignored by the controller".into(),
                "Code nach dem Programmende (M2/M30) wird von der Steuerung ignoriert".into(),
            ),
            FindingKind::StockSkipped(s) => match s {
                StockSkip::MissingParams { top, tool } => {
                    let (en, de_t) = match (top, tool) {
                        (true, true) => ("material top and tool diameter", "Materialoberkante und Werkzeugdurchmesser"),
                        (true, false) => ("material top", "Materialoberkante"),
                        _ => ("tool diameter", "Werkzeugdurchmesser"),
                    };
                    pick(
                        format!("stock checks skipped: {en} unknown (give --top/--tool or a (MILLPATH-STOCK T=… O=…) comment); feed, arc and number checks ran"),
                        format!("Materialprüfungen übersprungen: {de_t} unbekannt (--top/--tool oder einen Kommentar (MILLPATH-STOCK T=… O=…) angeben); Vorschub, Bögen und Zahlen wurden geprüft"),
                    )
                }
                StockSkip::AreaTooLarge { cell } => pick(
                    format!("stock checks skipped: the moves span too large an area for a grid fine enough for the tool (cell {} mm)", f3(*cell)),
                    format!("Materialprüfungen übersprungen: die Bewegungen überdecken eine zu große Fläche für ein Raster, das fein genug für das Werkzeug ist (Zelle {} mm)", f3(*cell)),
                ),
                StockSkip::WorkLimit { line } => pick(
                    format!("stock model stopped at line {line}: the program is too large for it; later moves are not checked against the stock"),
                    format!("Materialmodell bei Zeile {line} angehalten: das Programm ist zu groß; spätere Bewegungen werden nicht gegen das Material geprüft"),
                ),
            },
            FindingKind::StockComment(p) => match p {
                StockCommentProblem::BadValue { key, text } => pick(
                    format!("(MILLPATH-STOCK …): {key}={text} is not a usable value"),
                    format!("(MILLPATH-STOCK …): {key}={text} ist kein brauchbarer Wert"),
                ),
                StockCommentProblem::Conflicting => pick(
                    "a second (MILLPATH-STOCK …) comment with other values: the first one counts".into(),
                    "ein zweiter Kommentar (MILLPATH-STOCK …) mit anderen Werten: der erste gilt".into(),
                ),
            },
            FindingKind::RereadDiffers { lines, moves } => pick(
                format!("the program read a second time for the clamp, depth and stock checks is not the one read first ({} of {} lines, {} of {} moves): those checks are incomplete", lines.0, lines.1, moves.0, moves.1),
                format!("das für die Klemmen-, Tiefen- und Materialprüfungen ein zweites Mal gelesene Programm ist nicht das zuerst gelesene ({} von {} Zeilen, {} von {} Bewegungen): diese Prüfungen sind unvollständig", lines.0, lines.1, moves.0, moves.1),
            ),
            FindingKind::Family { problem, dialect } => problem.message(*dialect, lang),
            FindingKind::Ncc(p) => p.message(lang == Lang::De),
            FindingKind::Limit(l) => match l {
                Limit::Lines(n) => pick(
                    format!("more than {n} lines: the rest is not checked"),
                    format!("mehr als {n} Zeilen: der Rest wird nicht geprüft"),
                ),
                Limit::Findings(n) => pick(
                    format!("more than {n} findings: the rest are not listed"),
                    format!("mehr als {n} Befunde: die weiteren werden nicht aufgeführt"),
                ),
            },
        }
    }
}

impl FamilyProblem {
    /// The message, naming the controller of `dialect`.
    pub fn message(&self, dialect: Dialect, lang: Lang) -> String {
        let de = lang == Lang::De;
        let pick = |en: String, de_text: String| if de { de_text } else { en };
        let who = dialect.controller();
        let family = dialect.family();
        match self {
            FamilyProblem::LineNumber { text, max } => pick(
                format!("line number {text}: {who} takes whole numbers from 0 to {max} (family {family})"),
                format!("Satznummer {text}: {who} nimmt ganze Zahlen von 0 bis {max} (Familie {family})"),
            ),
            FamilyProblem::LineNumberNotFirst => pick(
                format!("the line number N is not the first word: {who} reads it only at the start of the line"),
                format!("die Satznummer N ist nicht das erste Wort: {who} liest sie nur am Zeilenanfang"),
            ),
            FamilyProblem::ParenComment => pick(
                format!("a ( ) comment: {who} reads only ; comments (parentheses need PAREN_COMMENTS)"),
                format!("ein ( )-Kommentar: {who} liest nur ;-Kommentare (Klammern brauchen PAREN_COMMENTS)"),
            ),
            FamilyProblem::Percent => pick(
                format!("a % line: {who} has no program delimiters and rejects it"),
                format!("eine %-Zeile: {who} kennt keine Programmbegrenzer und lehnt sie ab"),
            ),
            FamilyProblem::SecondCommand { code } => pick(
                format!("{code} is a second command on this line: {who} reads one command a line and ignores it"),
                format!("{code} ist ein zweiter Befehl in dieser Zeile: {who} liest einen Befehl je Zeile und übergeht ihn"),
            ),
            FamilyProblem::CommandNotFirst { word } => pick(
                format!("the line starts with {word}, not with its command: {who} reads the first word as the command"),
                format!("die Zeile beginnt mit {word}, nicht mit ihrem Befehl: {who} liest das erste Wort als Befehl"),
            ),
            FamilyProblem::NoMotionWord => pick(
                format!("axis words without G0/G1/G2/G3 on their line: motion is not modal in {who}"),
                format!("Achsenwörter ohne G0/G1/G2/G3 in ihrer Zeile: in {who} ist die Bewegungsart nicht modal"),
            ),
            FamilyProblem::ArcNotAllowed { code } => pick(
                format!("{code}: the post writes arcs as lines (arcs = \"lines\"), so its program has no arcs"),
                format!("{code}: der Post schreibt Bögen als Strecken (arcs = \"lines\"), sein Programm hat keine Bögen"),
            ),
            FamilyProblem::M30DeletesFile => pick(
                format!("M30 deletes a file on the SD card in {who}; it does not end the program (end with M5)"),
                format!("M30 löscht in {who} eine Datei auf der SD-Karte; es beendet das Programm nicht (mit M5 enden)"),
            ),
            FamilyProblem::NoSuchCode { code } => pick(
                format!("{who} has no {code}: it answers \"Unknown command\" and goes on without it"),
                format!("{who} kennt kein {code}: es meldet „Unknown command“ und fährt ohne es fort"),
            ),
            FamilyProblem::ShortSpindleDwell { seconds } => pick(
                format!("the dwell after the spindle start lasts {} s: {who} reads G4 P in milliseconds (G4 S in seconds)", f3(*seconds)),
                format!("die Pause nach dem Spindelstart dauert {} s: {who} liest G4 P in Millisekunden (G4 S in Sekunden)", f3(*seconds)),
            ),
        }
    }
}

impl SyntaxError {
    pub fn message(&self, lang: Lang) -> String {
        let de = lang == Lang::De;
        let pick = |en: String, de_text: String| if de { de_text } else { en };
        match self {
            SyntaxError::UnclosedComment => pick(
                "comment not closed: `(` without `)`".into(),
                "Kommentar nicht geschlossen: `(` ohne `)`".into(),
            ),
            SyntaxError::NestedComment => pick(
                "`(` inside a comment: LinuxCNC rejects nested comments; write `[` instead".into(),
                "`(` in einem Kommentar: LinuxCNC lehnt verschachtelte Kommentare ab; stattdessen `[` schreiben".into(),
            ),
            SyntaxError::UnexpectedChar(c) => pick(
                format!("unexpected character {c:?}; the line is not executed"),
                format!("unerwartetes Zeichen {c:?}; die Zeile wird nicht ausgeführt"),
            ),
            SyntaxError::ByteOrderMark => pick(
                "a byte-order mark (U+FEFF, invisible; saved by some Windows editors): LinuxCNC rejects the program here; save the file as UTF-8 without BOM".into(),
                "eine Byte-Order-Markierung (U+FEFF, unsichtbar; von manchen Windows-Editoren gespeichert): LinuxCNC lehnt das Programm hier ab; die Datei als UTF-8 ohne BOM speichern".into(),
            ),
            SyntaxError::MissingNumber(l) => pick(
                format!("word {l} without a number"),
                format!("Wort {l} ohne Zahl"),
            ),
            SyntaxError::DuplicateWord(l) => pick(
                format!("two {l} words on one line"),
                format!("zwei {l}-Wörter in einer Zeile"),
            ),
            SyntaxError::SameModalGroup(a, b) => pick(
                format!("{a} and {b} belong to the same modal group"),
                format!("{a} und {b} gehören zur selben modalen Gruppe"),
            ),
            SyntaxError::AxesWithoutMotion => pick(
                "axis words without a motion mode (G00/G01/G02/G03) in effect".into(),
                "Achsenwörter ohne geltende Bewegungsart (G00/G01/G02/G03)".into(),
            ),
            SyntaxError::LineTooLong(n) => pick(
                format!("line longer than {n} characters: not read"),
                format!("Zeile länger als {n} Zeichen: nicht gelesen"),
            ),
            SyntaxError::TextAfterPercent => pick(
                "text after `%` on its line".into(),
                "Text nach `%` in derselben Zeile".into(),
            ),
            SyntaxError::BadDwell => pick(
                "G04 needs a dwell time P ≥ 0".into(),
                "G04 braucht eine Verweilzeit P ≥ 0".into(),
            ),
            SyntaxError::UnknownCode(c) => {
                pick(format!("unknown code {c}"), format!("unbekannter Code {c}"))
            }
            SyntaxError::NotInGrbl(what) => pick(
                format!("GRBL does not know {what}: it refuses the line"),
                format!("GRBL kennt {what} nicht: es weist die Zeile ab"),
            ),
            SyntaxError::UnusedWord(l) => pick(
                format!("the word {l} is used by no command of the line: GRBL refuses it"),
                format!("das Wort {l} wird von keinem Befehl der Zeile verwendet: GRBL weist sie ab"),
            ),
            SyntaxError::NoAxisWords(code) => pick(
                format!("{code} without axis words: GRBL refuses the line"),
                format!("{code} ohne Achsenwörter: GRBL weist die Zeile ab"),
            ),
        }
    }
}

impl crate::surface::SurfaceProblem {
    /// What keeps the heights from being a height map, in `lang`.
    pub fn message(&self, lang: Lang) -> String {
        use crate::surface::{SurfaceProblem as S, MAX_NODES};
        let de = lang == Lang::De;
        let pick = |en: String, de_text: String| if de { de_text } else { en };
        match self {
            S::BadNumber { text } => pick(
                format!("'{text}' is not a sane number"),
                format!("'{text}' ist keine brauchbare Zahl"),
            ),
            S::Size { nx, ny } => pick(
                format!("{nx} × {ny} points (1 to {MAX_NODES} allowed)"),
                format!("{nx} × {ny} Punkte (1 bis {MAX_NODES} erlaubt)"),
            ),
            S::NotAscending => pick(
                "grid lines not in ascending order".into(),
                "Rasterlinien nicht aufsteigend".into(),
            ),
            S::Missing { x, y } => pick(
                format!("no height at X{} Y{}", f3(*x), f3(*y)),
                format!("keine Höhe bei X{} Y{}", f3(*x), f3(*y)),
            ),
            S::Duplicate { x, y } => pick(
                format!("two heights at X{} Y{}", f3(*x), f3(*y)),
                format!("zwei Höhen bei X{} Y{}", f3(*x), f3(*y)),
            ),
            S::Malformed { text } => pick(
                format!("unreadable: {text}"),
                format!("nicht lesbar: {text}"),
            ),
        }
    }
}
