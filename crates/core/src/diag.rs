//! Structured diagnostics: a message id with its arguments, a severity, a primary origin and
//! related origins. Rendering to text happens late, in the language the user asked for, so
//! the CLI and a language server can show the same diagnostic in their own way.
//!
//! `Msg`: every message in English and German; internal reference texts such as MP063's are
//! reworded for people outside the `****` lines; `Diagnostic`, `Origin`, de-duplicating `Diags`.

use crate::geom::P2;
use std::collections::HashSet;
use std::path::PathBuf;
use std::sync::Arc;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Lang {
    #[default]
    En,
    De,
}

impl Lang {
    /// `de`, `de-DE`, `DE_at` … are German; everything else is English (as upstream).
    pub fn from_name(name: &str) -> Lang {
        if name.to_ascii_lowercase().starts_with("de") {
            Lang::De
        } else {
            Lang::En
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    Error,
    Warning,
}

/// Where something comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum Origin {
    /// A DXF entity.
    Entity(Arc<EntityOrigin>),
    /// A path as a whole: `name[file]`. (Boxed strings here and in `FileLine` keep an origin
    /// at 32 bytes: every element of a drawing carries one.)
    Path { name: Box<str>, file: Arc<FileRef> },
    /// A whole input file.
    File(Arc<FileRef>),
    /// A line of a text file (1-based), e.g. a `_Z.txt` line.
    FileLine { file: Box<str>, line: usize },
    /// A byte span in a text (`.mpath`) file. 32 bits each (files are at most 1 GiB): every
    /// element of a drawing carries an origin, in its object, segment and model.
    Span {
        file: Arc<FileRef>,
        start: u32,
        end: u32,
        /// 1-based line and column of `start`.
        line: u32,
        col: u32,
    },
    /// The command line or the settings.
    Options,
    /// The command-line argument of a file that failed as a whole.
    Input,
}

/// An input file: its path as given and its name without directories.
#[derive(Debug, PartialEq, Eq, Hash)]
pub struct FileRef {
    pub path: PathBuf,
    pub name: String,
}

impl FileRef {
    pub fn new(path: PathBuf) -> Arc<FileRef> {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        Arc::new(FileRef { path, name })
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct EntityOrigin {
    pub file: Arc<FileRef>,
    /// 1-based line of the entity in the DXF file.
    pub line: usize,
    pub handle: String,
    pub layer: String,
    /// `LINE`, `ARC`, `CIRCLE`, `TEXT`, `MTEXT`.
    pub code_name: &'static str,
    pub pos: P2,
    /// Normalised path name of the layer.
    pub path: String,
}

impl Origin {
    /// The reference tool's context text (`MTEXT @ [47.167 229.104] # 8999.1P[8999.01P.dxf]`).
    pub fn context(&self) -> String {
        match self {
            Origin::Entity(e) => {
                format!("{} @ {} # {}[{}]", e.code_name, e.pos, e.path, e.file.name)
            }
            Origin::Path { name, file } => format!("{}[{}]", name, file.name),
            Origin::File(f) => f.path.display().to_string(),
            Origin::FileLine { file, line } => format!("{file}:{line}"),
            Origin::Span {
                file, line, col, ..
            } => format!("{}:{line}:{col}", file.name),
            Origin::Options => "Options".into(),
            Origin::Input => "Input".into(),
        }
    }

    /// A location a person can find: `file:line (layer L, handle H)` for DXF entities.
    pub fn location(&self) -> Option<String> {
        self.location_in(Lang::En)
    }

    /// [`Origin::location`] in the message language.
    pub fn location_in(&self, lang: Lang) -> Option<String> {
        let (on_layer, handle, at) = match lang {
            Lang::En => ("on layer", "handle", "at"),
            Lang::De => ("auf Layer", "Handle", "bei"),
        };
        match self {
            Origin::Entity(e) => Some(format!(
                "{}:{} ({} {on_layer} {}{}, {at} {})",
                e.file.path.display(),
                e.line,
                e.code_name,
                e.layer,
                if e.handle.is_empty() {
                    String::new()
                } else {
                    format!(", {handle} {}", e.handle)
                },
                e.pos
            )),
            Origin::Path { file, .. } | Origin::File(file) => Some(file.path.display().to_string()),
            Origin::FileLine { file, line } => Some(format!("{file}:{line}")),
            Origin::Span {
                file, line, col, ..
            } => Some(format!("{}:{line}:{col}", file.path.display())),
            _ => None,
        }
    }

    pub fn file(&self) -> Option<&Arc<FileRef>> {
        match self {
            Origin::Entity(e) => Some(&e.file),
            Origin::Path { file, .. } | Origin::File(file) | Origin::Span { file, .. } => {
                Some(file)
            }
            _ => None,
        }
    }
}

macro_rules! messages {
    ($($id:ident = $en:literal, $de:literal;)*) => {
        /// Every message the compiler can report, in English and German.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Msg { $($id),* }
        impl Msg {
            pub const ALL: &'static [Msg] = &[$(Msg::$id),*];
            pub fn template(self, lang: Lang) -> &'static str {
                match (self, lang) {
                    $((Msg::$id, Lang::En) => $en, (Msg::$id, Lang::De) => $de,)*
                }
            }
        }
    };
}

messages! {
    // DXF reading
    CannotRead = "Cannot read file {0}: {1}", "Datei {0} kann nicht gelesen werden: {1}";
    CannotLoadDxf = "Cannot load DXF file {0}: {1}", "DXF-Datei {0} kann nicht geladen werden: {1}";
    ZNotZero = "{0}.Z != 0 - cannot convert to a 2-D point", "{0}.Z != 0 - kann nicht in 2-D-Punkt umgewandelt werden";
    BadRadius = "Radius {0} must be > 0", "Radius {0} muss > 0 sein";
    LineTypeNotSupported = "Line type {0} not supported", "Linienart {0} nicht unterstützt";
    TwoStartMarkers = "Two start markers defined at {0} and {1}", "Zwei Anfangspunkte definiert: {0} und {1}";
    TwoEndMarkers = "Two end markers defined at {0} and {1}", "Zwei Endpunkte definiert: {0} und {1}";
    NoSpecialMeaning = "Circle with line type {1} and diameter {0} has no special meaning", "Kreis mit Linientyp {1} mit Durchmesser {0} hat keine spezielle Bedeutung";
    PathNotFoundForElement = "Path definition {0} not found; maybe start marker is not of line type PHANTOM(__ _ _ __)", "Pfaddefinition {0} nicht gefunden; vielleicht hat Start-Markierung nicht Linientyp PHANTOM(__ _ _ __)";
    NoParametersForPath = "No parameters found for path {0}; maybe path text center is not near enough to start marker", "Keine Parameter für Pfad {0} gefunden; vielleicht ist Pfadtext nicht nahe genug an Start-Markierung";
    DiameterSmallerThanO = "Diameter {0} is smaller than O={1}", "Durchmesser {0} ist kleiner als O={1}";
    TextAnchor = "Text {0} must have anchor at center, or be unrotated, with anchor at bottom left or top left", "Text {0} muss Anker in der Mitte haben oder unrotiert mit Anker unten links oder oben links sein";
    NoOverlap = "No overlapping circle, arc or line found for '{0}'; maybe text center is not near enough to element (text circle: {1}, diam. {2}), or there is another overlapping text", "Kein überlappender Kreis, Bogen und keine überlappende Linie für '{0}' gefunden; evtl. Textmitte nicht nahe genug (Textkreis: {1}, Durchm. {2}) oder überlappender weiterer Text";
    // parameter texts
    DuplicateParameter = "The parameter(s) {1} are specified more than once in '{0}'", "Der oder die Parameter {1} kommen in '{0}' öfter als einmal vor";
    NCannotUseVariable = "N parameter '{0}' cannot use variable", "Parameter N mit Wert '{0}' darf keine Variablen verwenden";
    OCannotUseVariable = "O parameter '{0}' cannot use variable", "Parameter O mit Wert '{0}' darf keine Variablen verwenden";
    AtCannotUseVariable = "@ path '{0}' cannot use variable", "@-Pfad '{0}' darf keine Variablen verwenden";
    DuplicateVariable = "Variable {0} is defined more than once in '{1}'", "Variable {0} ist in '{1}' mehrfach definiert";
    Unsupported = "Unsupported {0} value; {1}", "Nicht unterstützter {0}-Wert; {1}";
    NotANumber = "{0} value '{1}' is not a number and is ignored", "{0}-Wert '{1}' ist keine Zahl und wird ignoriert";
    MustBePositive = "{0}={1} must be > 0", "{0}={1} muss > 0 sein";
    SNotAboveT = "S={0} must be above T={1}", "S={0} darf nicht unter oder nahe an T={1} liegen";
    BAboveT = "B={0} must not be larger than T={1}", "B={0} darf nicht über T={1} liegen";
    DAboveT = "D={0} must not be larger than T={1}", "D={0} darf nicht über T={1} liegen";
    DNotAboveB = "D={0} must be larger than B={1}", "D={0} muss über B={1} liegen";
    HelixTooLarge = "Diameter {0} of helix circle is larger than A={1}; possibly replace with arc path", "Helix-Durchmesser {0} ist größer als A={1}; möglichst durch Bogenpfad ersetzen";
    ValueMissing = "{0} value missing", "{0}-Wert fehlt";
    BadE = "E={0} is not a valid regular expression ({1})", "E={0} ist kein gültiger regulärer Ausdruck ({1})";
    // @ references
    AtWithOthers = "@ path '{0}' must not contain other parameters", "@-Pfad '{0}' darf keine anderen Parameter enthalten";
    AtNoMatch = "@ path '{0}' does not match path pattern /{1}/", "@ Pfad '{0}' passt nicht auf Pfadmuster /{1}/";
    AtNotFound = "Path {0} referenced with @ not found in this DXF file", "Pfad {0} nach @ nicht in dieser DXF-Datei gefunden";
    AtNested = "@ not allowed in path '{0}' which is itself referenced by @", "@ darf in Pfad '{0}', der selbst mit @ referenziert wird, nicht verwendet werden";
    // paths, files
    InvalidPathName = "'>{0}' is not a valid path name", "'>{0}' ist kein gültiger Pfadname";
    AlreadyDefined = "Path {0} has already been defined in {1}", "Pfad {0} schon einmal definiert in {1}";
    CouldNotFind = "Could not find path {0} in file(s) {1}", "Pfad {0} nicht in Datei(en) {1} gefunden";
    SearchDirMissing = "Search directory {0} does not exist", "Suchverzeichnis {0} existiert nicht";
    ParametersTextMissing = "Parameters text missing; maybe incorrect start marker", "Parametertext fehlt; evtl. nicht korrekte Start-Markierung";
    StartMissing = "Start marker missing", "Start-Markierung fehlt";
    EndMissing = "End marker missing", "Ende-Markierung fehlt";
    NotReached = "{0} segments (e.g. this one here) not reached - maybe N value is missing", "{0} Segmente (u.a. dieses hier) wurden nicht erreicht - evtl. fehlt N-Auszeichnung";
    NoMoreSegments = "No more segments found after location {0}", "Keine weiteren Segmente ab Punkt {0} gefunden";
    EndNotAtLast = "End marker not near end of last traversed segment, but at {0} - add sweep", "Ende-Markierung ist nicht am Ende des letztes erreichten Segments, sondern an Position {0}; Leerfahrt ergänzen";
    NoSegments = "No segments found", "Keine Segmente gefunden";
    // subpaths
    TLessThanSub = "T={0} at path is less than T={1} at subpath{2}", "T={0} an Pfad ist kleiner als T={1} an Teilpfad{2}";
    Forbidden = "Subpath {0} forbidden by restriction for {1}", "Teilpfad {0} nicht erlaubt in Pfad {1}";
    NestingTooDeep = "Nesting depth deeper than 9 levels at path {0}", "Mehr als 9 verschachtelte Teilpfade bei Einbettung von {0}";
    SizeMismatch = "Subpath size {0} is not equal to size {2} in referenced path {1}", "Teilpfad-Länge {0} ist nicht gleich Länge {2} des referenzierten Teilpfads {1}";
    MMismatch = "M={0} at subpath {1} is different from M={2} in referenced path", "M={0} an Teilpfad {1} weicht von M={2} in referenziertem Modell ab";
    OMismatch = "O={0} at subpath {1} is different from O={2} in referenced path", "O={0} an Teilpfad {1} weicht von O={2} in referenziertem Modell ab";
    TMismatch = "T={0} at subpath {1} is different from T={2} in referenced path", "T={0} an Teilpfad {1} weicht von T={2} in referenziertem Modell ab";
    CannotPlace = "Subpath {0} cannot be placed: its start and end marker coincide or the sizes differ", "Teilpfad {0} kann nicht platziert werden: Anfang und Ende fallen zusammen oder die Längen unterscheiden sich";
    // variables
    RangeFormat = "Range for variable {0} must have format ###~### instead of '{1}'", "Bereich für Variable {0} muss Format Zahl~Zahl (statt Wert '{1}') haben";
    RangeNumber = "Wrong number format in range for variable {0} ({1})", "Falsches Zahlenformat bei Bereich für Variable {0} ({1})";
    DefinitionFormat = "Definition for variable {0} must be comma-separated list, or letters group starting with ?, or range ...~... instead of '{1}'", "Definition für Variable {0} muss kommaseparierte Liste oder Buchstabengruppe nach ? oder Bereich ...~... sein, statt '{1}'";
    EmptyCharList = "Definition for variable {0} has no values", "Definition für Variable {0} hat keine Werte";
    VariableDefinitionError = "Error in variable definition: {0}", "Fehler in Variablendefinition: {0}";
    MissingValues = "Missing values for variables {0}", "Fehlende Werte für Variablen {0}";
    MissingDefinitions = "Missing definitions for variables {0}", "Fehlende Definitionen für Variablen {0}";
    ValueNotInDefinition = "Value '{0}' of variable {2} does not match definition '{1}'", "Wert '{0}' der Variablen {2} passt nicht zu Definition '{1}'";
    SelfReference = "Variable {0} refers to itself (value '{1}')", "Variable {0} verweist auf sich selbst (Wert '{1}')";
    // files
    MoreThanOnePath = "DXF file {0} contains more than one path layer: {1}", "DXF-Datei {0} enthält mehr als einen Pfad-LayerName: {1}";
    NoErrorFreePath = "DXF file {0} contains no error-free path layer", "DXF-Datei {0} enthält keinen Pfad-LayerName ohne Fehler";
    NotNear = "!{0}.Near({1})", "!{0}.Near({1})";
    CannotWrite = "Cannot write {0}: {1}", "{0} kann nicht geschrieben werden: {1}";
    // options
    OptionNotSupported = "Option {0} not supported", "Option {0} nicht unterstützt";
    MissingOptionValue = "Missing value after option {0}", "Fehlende Option nach {0}";
    OptionNotNumber = "Option value {1} for {0} is not a number", "Wert {1} für Option {0} ist keine Zahl";
    OptionNegative = "Option value {1} for {0} is not >= 0", "Wert {1} für Option {0} ist nicht >= 0";
    FMissing = "/f missing or not > 0", "/f nicht angegeben oder nicht größer als 0";
    VMissing = "/v missing or not > 0", "/v nicht angegeben oder nicht größer als 0";
    SMissing = "/s missing or not > 0", "/s nicht angegeben oder nicht größer als 0";
    EFormat = "/e value {0} is not of format regex:regex", "/e-Wert {0} hat nicht das Format regex:regex";
    EInvalid = "/e value {0} contains an invalid regular expression ({1})", "/e-Wert {0} enthält einen ungültigen regulären Ausdruck ({1})";
    BadRegex = "Option {0}: invalid regular expression '{1}' ({2})", "Option {0}: ungültiger regulärer Ausdruck '{1}' ({2})";
    NoDxfFiles = "No dxf files provided", "Keine DXF-Dateien angegeben";
    // adjust-z
    ZLineFormat = "Line does not have format '(comment) #...=value'", "Zeile hat nicht das Format '(Kommentar) #...=Wert'";
    ZNotNumber = "Value '{0}' for {1} is not a valid number", "Wert '{0}' für {1} ist keine gültige Zahl";
    ZTooFar = "Value {0} for {1} differs from {2} by more than /m={3}", "Wert {0} für {1} weicht von {2} um mehr als /m={3} ab";
    ZDuplicate = "{0} is defined more than once", "{0} ist mehrfach definiert";
    ZUnknownVariable = "Unknown variable {0} in expression '{1}'", "Unbekannte Variable {0} in Ausdruck '{1}'";
    ExprEndExpected = "End of expression expected at column {0} in '{1}'", "Ende des Ausdrucks erwartet bei Spalte {0} in '{1}'";
    ExprParenExpected = "')' expected at column {0} in '{1}'", "')' erwartet bei Spalte {0} in '{1}'";
    ExprBracketExpected = "']' expected at column {0} in '{1}'", "']' erwartet bei Spalte {0} in '{1}'";
    ExprUnexpected = "Unexpected symbol '{0}' at column {1} in '{2}'", "Unerwartetes Zeichen '{0}' bei Spalte {1} in '{2}'";
    ExprBadNumber = "Malformed number '{0}' at column {1} in '{2}'", "Ungültige Zahl '{0}' bei Spalte {1} in '{2}'";
    MissingM = "Missing required /m value", "Fehlende /m-Option";
    // text language
    SyntaxError = "{0}", "Syntaxfehler: {0}";
    KindMismatch = "Declared as {0}, but with O={1} this circle is a {2}", "Als {0} angegeben, aber mit O={1} ist dieser Kreis ein {2}";
    PathNameNoMatch = "Path name {0} does not match the path-name pattern /{1}/", "Pfadname {0} passt nicht auf das Pfadmuster /{1}/";
    // hostile input: every number finite and sane, every loop bounded
    NumberNotFinite = "{0} value '{1}' is not a finite number", "{0}-Wert '{1}' ist keine endliche Zahl";
    NumberOutOfRange = "{0} value '{1}' is outside ±{2}", "{0}-Wert '{1}' liegt außerhalb von ±{2}";
    CoordinateOutOfRange = "A coordinate or radius of this element is not finite or outside ±{0} mm", "Eine Koordinate oder ein Radius dieses Elements ist nicht endlich oder liegt außerhalb von ±{0} mm";
    TooManyPasses = "{0} passes from {1} down to {2} with I={3}: more than {4}", "{0} Durchgänge von {1} bis {2} mit I={3}: mehr als {4}";
    TooManyBars = "{0} support bars along this element: more than {1}", "{0} Stege entlang dieses Elements: mehr als {1}";
    TooManyMoves = "The program would have more than {0} moves", "Das Programm hätte mehr als {0} Bewegungen";
    MoveOutOfRange = "The program would move to {0}, outside ±{1} mm (values add up: T, O, S, H, subpath placement)", "Das Programm würde nach {0} fahren, außerhalb von ±{1} mm (Werte addieren sich: T, O, S, H, Teilpfad-Lage)";
    SecondOpinion = "Second opinion on the G-code, line {0} '{1}': {2}", "Zweite Meinung zum G-Code, Zeile {0} '{1}': {2}";
    MachineNeedsAcceleration = "max_velocity needs max_acceleration: the time estimates use both", "max_velocity braucht max_acceleration: die Zeitschätzung verwendet beide";
    SettingNotFinite = "Setting {0}={1} must be a finite number within ±{2}", "Einstellung {0}={1} muss eine endliche Zahl innerhalb von ±{2} sein";
    // adjust-z safety
    MaxInvalid = "{0} value {1} must be a finite number > 0 and at most 1000000", "{0}-Wert {1} muss eine endliche Zahl > 0 und höchstens 1000000 sein";
    ZOutOfRange = "Value '{0}' for {1} is outside ±1000000", "Wert '{0}' für {1} liegt außerhalb von ±1000000";
    ZTooFarMax = "Value {0} for {1} differs from {2} by more than --max={3}", "Wert {0} für {1} weicht von {2} um mehr als --max={3} ab";
    ZNominalMismatch = "T={0} for {1} differs from its nominal height {2} in {3}:{4}", "T={0} für {1} weicht von der Soll-Höhe {2} in {3}:{4} ab";
    ZProbeMissing = "Probe {0} (nominal height {1}) has no measured value in {2}", "Messpunkt {0} (Soll-Höhe {1}) hat keinen Messwert in {2}";
    ZUnknownProbe = "{0} is not a probe of {1}", "{0} ist kein Messpunkt von {1}";
    ZProbeHeightsDiffer = "Probe {0} has nominal height {1} here, but {2} in line {3}", "Messpunkt {0} hat hier die Soll-Höhe {1}, aber {2} in Zeile {3}";
    ZProbeTermForm = "Probe {0} is not used as a term [{0}-height] in '{1}'", "Messpunkt {0} wird in '{1}' nicht als Term [{0}-Höhe] verwendet";
    ZIncompleteProgram = "{0} is not a complete program: it must start with a line %, contain M30 and end with a line %", "{0} ist kein vollständiges Programm: es muss mit einer Zeile % beginnen, M30 enthalten und mit einer Zeile % enden";
    ZAlreadyAdjusted = "Line is already adjusted ('(=='); {0} must be the file written by compile", "Zeile ist schon angepasst ('(=='); {0} muss die von compile geschriebene Datei sein";
    ZUnreadableExpression = "Probe expression that adjust-z cannot rewrite: '{0}'", "Messpunkt-Ausdruck, den adjust-z nicht umschreiben kann: '{0}'";
    LineTooLong = "Line longer than {0} characters", "Zeile länger als {0} Zeichen";
    ExprTooDeep = "Expression nested deeper than {0} levels at column {1} in '{2}'", "Ausdruck tiefer als {0} Ebenen geschachtelt bei Spalte {1} in '{2}'";
    ExprNumberRange = "Number '{0}' at column {1} in '{2}' is outside ±1000000", "Zahl '{0}' bei Spalte {1} in '{2}' liegt außerhalb von ±1000000";
    ExprResultRange = "Expression '{0}' does not give a finite height within ±1000000", "Ausdruck '{0}' ergibt keine endliche Höhe innerhalb von ±1000000";
    StaleMillingRemoved = "Removed {0}: it is not newer than {1}, and no new one was written", "{0} entfernt: die Datei ist nicht neuer als {1}, und es wurde keine neue geschrieben";
    CannotRemove = "Cannot remove outdated {0}: {1}", "Veraltete Datei {0} kann nicht entfernt werden: {1}";
    NoErrorFreePathInFile = "File {0} contains no error-free path", "Datei {0} enthält keinen Pfad ohne Fehler";
    // entity order (appended: codes are indexes)
    OrderDecides = "The drawing's entity order decides here: {0} elements are equally good next steps and the first one in the file is taken, so a CAD re-save can change the G-code; pin the choice with {1} at this element", "Hier entscheidet die Reihenfolge der Elemente in der Zeichnung: {0} Elemente kommen gleichermaßen als nächster Schritt in Frage und das erste in der Datei wird genommen, ein erneutes Speichern im CAD kann also den G-Code ändern; die Wahl mit {1} an diesem Element festlegen";
    OrderDecidesText = "The order of the lines decides here: {0} elements are equally good next steps and the first line is taken (the formatter keeps this order, a CAD re-save of the DXF may not); pin the choice with {1} at this element", "Hier entscheidet die Reihenfolge der Zeilen: {0} Elemente kommen gleichermaßen als nächster Schritt in Frage und die erste Zeile wird genommen (der Formatierer behält diese Reihenfolge, ein erneutes Speichern der DXF im CAD vielleicht nicht); die Wahl mit {1} an diesem Element festlegen";
    OrderDecidesNoPin = "The order of the elements decides here: {0} elements are equally good next steps and the first one is taken, so a CAD re-save or a reordering can change the G-code; no N value at this element alone was found that pins it without changing the walk elsewhere: give the elements that meet here N values in the order wanted (the lower N is taken first)", "Hier entscheidet die Reihenfolge der Elemente: {0} Elemente kommen gleichermaßen als nächster Schritt in Frage und das erste wird genommen, ein erneutes Speichern im CAD oder ein Umordnen kann also den G-Code ändern; es wurde kein N-Wert an diesem Element allein gefunden, der die Wahl festlegt, ohne den Weg anderswo zu ändern: den hier zusammentreffenden Elementen N-Werte in der gewünschten Reihenfolge geben (das niedrigere N wird zuerst genommen)";
    // geometry the reference ignores ({0} = entity type); the extended input mode
    IgnoredEntity = "{0} (line {1}) ignored: the reference reads only LINE, ARC, CIRCLE, TEXT and MTEXT; to include it compile with --extended or set input = \"extended\" in millpath.toml", "{0} (Zeile {1}) ignoriert: die Referenz liest nur LINE, ARC, CIRCLE, TEXT und MTEXT; zum Einbeziehen mit --extended übersetzen oder input = \"extended\" in millpath.toml setzen";
    CurveRefused = "{0} is not supported: convert it to lines and arcs in the CAD program (it is not approximated)", "{0} wird nicht unterstützt: im CAD-Programm in Linien und Bögen umwandeln (es wird nicht angenähert)";
    NotPlanarRefused = "{0} does not lie in the XY plane (3-D polyline, mesh or tilted extrusion)", "{0} liegt nicht in der XY-Ebene (3-D-Polylinie, Netz oder geneigte Extrusion)";
    UnknownBlock = "{0} references block {1}, which the file does not define", "{0} verweist auf Block {1}, den die Datei nicht definiert";
    BlocksTooDeep = "{0}: blocks nested deeper than {1} levels (or a block inserting itself)", "{0}: Blöcke tiefer als {1} Ebenen verschachtelt (oder ein Block fügt sich selbst ein)";
    BlocksTooMany = "{0}: the blocks produce more than {1} entities", "{0}: die Blöcke ergeben mehr als {1} Objekte";
    DistortedArc = "{0} under a non-uniform scale would become an ellipse: scale blocks with arcs equally in X and Y", "{0} würde durch ungleichmäßige Skalierung zur Ellipse: Blöcke mit Bögen in X und Y gleich skalieren";
    BadArray = "{0}: a block array needs at least one row and one column", "{0}: eine Block-Anordnung braucht mindestens eine Zeile und eine Spalte";
    NotFiniteGeometry = "{0} has a coordinate, bulge, scale or angle that is not a finite number", "{0} hat eine Koordinate, Wölbung, Skalierung oder einen Winkel, der keine endliche Zahl ist";
    UnitsScaled = "The drawing's unit is $INSUNITS = {0} ({1} mm per unit): coordinates scaled to millimetres", "Die Einheit der Zeichnung ist $INSUNITS = {0} ({1} mm je Einheit): Koordinaten auf Millimeter skaliert";
    FileTooLarge = "File {0} is larger than {1} MiB, the most a drawing may have", "Datei {0} ist größer als {1} MiB, das Höchstmaß für eine Zeichnung";
    // entity order in the assignment of texts (reference-input.md §2.4)
    TextTakenFirst = "The drawing's entity order decides which element text '{0}' belongs to: it overlaps best the element that text '{1}' took, which comes first in the file, so a CAD re-save can change the G-code; move the texts so that each is nearest to its own element", "Die Reihenfolge der Elemente in der Zeichnung entscheidet, zu welchem Element der Text '{0}' gehört: er überlappt am besten das Element, das der Text '{1}' bekam, der in der Datei zuerst kommt; ein erneutes Speichern im CAD kann also den G-Code ändern; die Texte so verschieben, dass jeder seinem eigenen Element am nächsten liegt";
    // text2dxf never destroys a drawing (issue 20)
    WouldLoseDrawing = "{0} holds drawing content that text2dxf does not write back: {1}. Nothing was written: use --into {0} to write the paths into the drawing and keep the rest, or --force to overwrite it", "{0} enthält Zeichnungsinhalt, den text2dxf nicht zurückschreibt: {1}. Es wurde nichts geschrieben: mit --into {0} die Pfade in die Zeichnung schreiben und den Rest behalten, oder mit --force überschreiben";
    NotOursToOverwrite = "{0} exists and cannot be read as a DXF drawing ({1}). Nothing was written: write elsewhere with -o, or overwrite it with --force", "{0} existiert und kann nicht als DXF-Zeichnung gelesen werden ({1}). Es wurde nichts geschrieben: mit -o anderswohin schreiben oder mit --force überschreiben";
    // entity order at one piece of a polyline or block (extended input): its text is the whole entity's
    OrderDecidesPiece = "The drawing's entity order decides here: {0} elements are equally good next steps and the first one in the file is taken, so a CAD re-save can change the G-code; this element is one piece of a polyline or block (line {1}), and a parameter text there holds for all its pieces: explode it into lines and arcs in the CAD program, then pin the choice with {2} at this piece", "Hier entscheidet die Reihenfolge der Elemente in der Zeichnung: {0} Elemente kommen gleichermaßen als nächster Schritt in Frage und das erste in der Datei wird genommen, ein erneutes Speichern im CAD kann also den G-Code ändern; dieses Element ist ein Stück einer Polylinie oder eines Blocks (Zeile {1}), und ein Parametertext dort gilt für alle Stücke: sie im CAD-Programm in Linien und Bögen auflösen und dann die Wahl mit {2} an diesem Stück festlegen";
    // check ≡ compile, path names and feeds (issue 20)
    VariablesNotGiven = "Path {0} defines variables ({1}) and gets no values when compiled on its own: embed it in a path that assigns them (millpath check checks it with its check values)", "Pfad {0} definiert Variablen ({1}) und bekommt beim Übersetzen allein keine Werte: ihn in einen Pfad einbetten, der sie zuweist (millpath check prüft ihn mit seinen Prüfwerten)";
    PathNameCase = "Path name {0} matches the name pattern {1} only when case is ignored; path names are case-sensitive ({0} and {2} would be two paths): did you mean {2}?", "Pfadname {0} passt nur ohne Beachtung der Groß-/Kleinschreibung zum Namensmuster {1}; Pfadnamen unterscheiden Groß- und Kleinschreibung ({0} und {2} wären zwei Pfade): war {2} gemeint?";
    SubpathNotFoundCase = "Could not find path {0} in file(s) {1}; did you mean {2}? (path names are case-sensitive)", "Pfad {0} nicht in Datei(en) {1} gefunden; war {2} gemeint? (Pfadnamen unterscheiden Groß- und Kleinschreibung)";
    FeedTooSmall = "{0} {1} mm/min is below {2} mm/min: no machine moves that slowly (the program would show F{3}); give the feed in mm/min", "{0} {1} mm/min ist kleiner als {2} mm/min: so langsam fährt keine Maschine (das Programm zeigte F{3}); den Vorschub in mm/min angeben";
    // text in G-code comments made safe for the controller (emit/comment.rs)
    CommentTextChanged = "'{0}' is written as '{1}' in the G-code comments (dialect {2}): a controller would misread it there (a nested parenthesis, an active comment word, a real-time command character or a line too long); rename the file or change the text to keep it as it is", "'{0}' wird in den G-Code-Kommentaren als '{1}' geschrieben (Dialekt {2}): eine Steuerung würde es dort falsch lesen (eine verschachtelte Klammer, ein aktives Kommentarwort, ein Echtzeit-Befehlszeichen oder eine zu lange Zeile); die Datei umbenennen oder den Text ändern, um ihn unverändert zu behalten";
    // `check` on folders without drawings (a report in every format)
    NoDrawingsFound = "no drawings (*.dxf, *.mpath) found in {0}", "keine Zeichnungen (*.dxf, *.mpath) in {0} gefunden";
    // one drawing's outputs are one set (issue 20): unfilled _Z.txt, mixed sets, stale outputs
    ZNoValue = "No measured value for probe {0} (nominal height {1}): type the height the probing program measured after '='", "Kein Messwert für Messpunkt {0} (Soll-Höhe {1}): die vom Antastprogramm gemessene Höhe nach '=' eintragen";
    ZSetMismatch = "{0} and {1} are not from the same compile: compile the drawing again, run the new probing program and fill in the new _Z.txt", "{0} und {1} stammen nicht aus derselben Übersetzung: die Zeichnung neu übersetzen, das neue Antastprogramm laufen lassen und die neue _Z.txt ausfüllen";
    StaleOutputRemoved = "Removed {0}: an output of an earlier compile of this drawing, and this compile wrote no new one", "{0} entfernt: eine Ausgabe einer früheren Übersetzung dieser Zeichnung, und diese Übersetzung hat keine neue geschrieben";
    OutputSetRestored = "{0} could not be written: the outputs of this drawing were left as they were before this compile", "{0} konnte nicht geschrieben werden: die Ausgaben dieser Zeichnung sind geblieben, wie sie vor dieser Übersetzung waren";
    // text files: encodings and syntax errors ({0} of SyntaxExpected/{1}: words per language)
    SyntaxExpected = "Expected {0}, found {1}", "Erwartet: {0}; gefunden: {1}";
    SyntaxUnknownKind = "`{0}` is not an element kind", "`{0}` ist keine Elementart";
    SyntaxKindDidYouMean = "`{0}` is not an element kind: did you mean `{1}`?", "`{0}` ist keine Elementart: `{1}` gemeint?";
    SyntaxDidYouMean = "Unknown word `{0}`: did you mean `{1}`?", "Unbekanntes Wort `{0}`: `{1}` gemeint?";
    SyntaxDecimalComma = "Coordinates need a decimal point: write `{1}`, not `{0}` (the decimal comma is only for parameter texts)", "Koordinaten brauchen einen Dezimalpunkt: `{1}` statt `{0}` schreiben (das Dezimalkomma gilt nur in Parametertexten)";
    SyntaxNotANumber = "`{0}` is not a number", "`{0}` ist keine Zahl";
    SyntaxNotPrefixed = "`{0}` is not {1} followed by a number", "`{0}` ist nicht {1} mit einer Zahl dahinter";
    SyntaxMissingBrace = "Missing `}` at the end of the path", "`}` am Ende des Pfades fehlt";
    SyntaxUnexpectedChar = "Unexpected character `{0}`", "Unerwartetes Zeichen `{0}`";
    TextNulBytes = "{0} is not a text file in UTF-8: it holds NUL bytes (UTF-16 without a byte-order mark?); save it as UTF-8", "{0} ist keine Textdatei in UTF-8: sie enthält NUL-Bytes (UTF-16 ohne Byte-Order-Mark?); als UTF-8 speichern";
    // height map as a setting (issue 21): the grid and its probing program (probe/heightmap.rs)
    HeightmapStepTooSmall = "{0}={1} mm is below the smallest grid step, {2} mm", "{0}={1} mm ist kleiner als der kleinste Rasterabstand, {2} mm";
    HeightmapNegative = "{0}={1} must be >= 0", "{0}={1} muss >= 0 sein";
    HeightmapAreaEmpty = "heightmap.area = [{0}, {1}, {2}, {3}] must be [xmin, ymin, xmax, ymax] with xmin <= xmax and ymin <= ymax", "heightmap.area = [{0}, {1}, {2}, {3}] muss [xmin, ymin, xmax, ymax] mit xmin <= xmax und ymin <= ymax sein";
    HeightmapTooManyPoints = "The height map's grid would have {0} × {1} = {2} probe points, more than {3}: choose a larger heightmap.step or a smaller area", "Das Raster der Höhenkarte hätte {0} × {1} = {2} Messpunkte, mehr als {3}: einen größeren heightmap.step oder eine kleinere Fläche wählen";
    HeightmapReferenceDialect = "[heightmap] needs the linuxcnc or grbl dialect: the reference dialect writes PathDxf2GCode's programs, which know no height map", "[heightmap] braucht den Dialekt linuxcnc oder grbl: der Dialekt reference schreibt die Programme von PathDxf2GCode, die keine Höhenkarte kennen";
    HeightmapWithDrawnProbes = "Path {0} has drawn Z probes ({1}) and millpath.toml has a [heightmap]: use one or the other (both would correct the same Z twice)", "Pfad {0} hat gezeichnete Z-Messpunkte ({1}) und millpath.toml eine [heightmap]: nur eines von beiden verwenden (beide würden dasselbe Z doppelt korrigieren)";
    HeightmapNoCuts = "Path {0} has no cutting moves: the height map has no area to cover (give heightmap.area)", "Pfad {0} hat keine Fräsbewegungen: die Höhenkarte hat keine Fläche (heightmap.area angeben)";
    HeightmapAreaTooSmall = "The cutting moves of path {0} reach {1} to {2}, outside heightmap.area [{3}, {4}, {5}, {6}]: the height map must cover every cut", "Die Fräsbewegungen von Pfad {0} reichen von {1} bis {2}, außerhalb von heightmap.area [{3}, {4}, {5}, {6}]: die Höhenkarte muss jeden Schnitt abdecken";
    // adjust-z --probe-log: measured heights read from the controller's log (issue 21)
    ProbeLogUnknownFormat = "Not a probe log millpath reads: expected LinuxCNC's PROBEOPEN log (nine numbers a line), GRBL reports [PRB:x,y,z:1], lines of x y z (bCNC .probe) or a filled-in _Z.txt", "Kein Antast-Protokoll, das millpath liest: erwartet werden das PROBEOPEN-Protokoll von LinuxCNC (neun Zahlen je Zeile), GRBL-Meldungen [PRB:x,y,z:1], Zeilen mit x y z (bCNC .probe) oder eine ausgefüllte _Z.txt";
    ProbeLogBadLine = "Expected {0} numbers on this line of the {1} log, found `{2}`", "Erwartet: {0} Zahlen in dieser Zeile des {1}-Protokolls; gefunden: `{2}`";
    ProbeLogBadNumber = "`{0}` is not a finite number within ±1000000", "`{0}` ist keine endliche Zahl innerhalb von ±1000000";
    ProbeLogNoContact = "GRBL reports no contact here ({0}): the probe did not touch the surface; probe this point again", "GRBL meldet hier keine Berührung ({0}): der Taster hat die Oberfläche nicht erreicht; diesen Punkt neu antasten";
    ProbeLogGrblOffset = "GRBL reports probe contacts in machine coordinates: the log must also hold the work offset [G54:x,y,z] (send $# in the same session)", "GRBL meldet Berührungen in Maschinenkoordinaten: das Protokoll muss auch den Werkstück-Nullpunkt [G54:x,y,z] enthalten (im selben Lauf $# senden)";
    ProbeLogGrblOffsetChanged = "The work offset changes within the log ({0}, then {1}): probe again with one offset", "Der Werkstück-Nullpunkt ändert sich im Protokoll ({0}, dann {1}): mit einem Nullpunkt neu antasten";
    ProbeLogExtra = "The measurement at X{0} Y{1} matches no probe point of {2} (within {3} mm)", "Die Messung bei X{0} Y{1} passt zu keinem Antastpunkt von {2} (auf {3} mm)";
    ProbeLogDuplicate = "A second measurement for probe {0} at X{1} Y{2} (the first is on line {3})", "Eine zweite Messung für Messpunkt {0} bei X{1} Y{2} (die erste steht in Zeile {3})";
    ProbeLogMissing = "No measurement in {0} for probe {1} at X{2} Y{3}", "Keine Messung in {0} für Messpunkt {1} bei X{2} Y{3}";
    ProbeLogTooFar = "Measured height {0} for probe {1} differs from its nominal height {2} by more than --max={3}", "Gemessene Höhe {0} für Messpunkt {1} weicht von der Soll-Höhe {2} um mehr als --max={3} ab";
    ProbeLogTooLarge = "The probe log is larger than {0}: not a probe log of one probing program", "Das Antast-Protokoll ist größer als {0}: kein Protokoll eines Antastprogramms";
    ProbeLogNoProbing = "--probe-log needs {0}: its probe points say which probe each measurement belongs to", "--probe-log braucht {0}: seine Antastpunkte sagen, zu welchem Messpunkt jede Messung gehört";
    ProbeLogProbingMismatch = "{0} probes {1} points, but {2} lists {3} probes", "{0} tastet {1} Punkte an, aber {2} nennt {3} Messpunkte";
    ProbeLogToleranceInvalid = "--tolerance value {0} must be a finite number > 0 and at most 1", "--tolerance-Wert {0} muss eine endliche Zahl > 0 und höchstens 1 sein";
    ProbeLogOneProgram = "--probe-log holds the measurements of one probing program: give one program, not {0}", "--probe-log enthält die Messungen eines Antastprogramms: ein Programm angeben, nicht {0}";
    ProbeLogCutOff = "The log's last line has no line end: it was cut off (still being written, or copied in part); a cut number would be read as another height", "Die letzte Zeile des Protokolls hat kein Zeilenende: es ist abgeschnitten (wird noch geschrieben oder wurde nur teilweise kopiert); eine abgeschnittene Zahl würde als andere Höhe gelesen";
    // adjust-z on a program that already follows a measured surface (issue 21)
    HeightMapAlreadyAdjusted = "{0} already follows a measured surface (its MILLPATH-SURFACE record): adjust the _Clean.gcode that compile wrote", "{0} folgt schon einer gemessenen Oberfläche (ihr MILLPATH-SURFACE-Eintrag): die _Clean.gcode anpassen, die compile geschrieben hat";
    // moves that follow a height map (adjust-z, issue 21)
    SurfaceMoveOffMap = "This move reaches X{0} Y{1}, outside the probed area X{2}…{3} Y{4}…{5}: the height map must cover every cut (give a larger heightmap.margin or heightmap.area, compile and probe again); nothing was written", "Diese Bewegung erreicht X{0} Y{1}, außerhalb der angetasteten Fläche X{2}…{3} Y{4}…{5}: die Höhenkarte muss jeden Schnitt abdecken (größeren heightmap.margin oder heightmap.area angeben, neu übersetzen und antasten); es wurde nichts geschrieben";
    SurfaceRapidOffMapLow = "This rapid move leaves the probed area at Z{0}, not above the highest measured point Z{1}: it could hit the surface there (raise sweep_height); nothing was written", "Diese Eilgangbewegung verlässt die angetastete Fläche auf Z{0}, nicht über dem höchsten gemessenen Punkt Z{1}: sie könnte dort die Oberfläche treffen (sweep_height erhöhen); es wurde nichts geschrieben";
    SurfaceLineUnsupported = "adjust-z cannot make '{0}' on this line follow the surface: adjust the _Clean.gcode that compile wrote", "adjust-z kann '{0}' in dieser Zeile nicht der Oberfläche folgen lassen: die _Clean.gcode anpassen, die compile geschrieben hat";
    SurfaceNoSafeHeight = "A move below the safe height before the program's first 'G00 Z' and 'G00 X Y': where the tool is, is unknown; adjust the _Clean.gcode that compile wrote", "Eine Bewegung unter der sicheren Höhe vor dem ersten 'G00 Z' und 'G00 X Y' des Programms: wo das Werkzeug steht, ist unbekannt; die _Clean.gcode anpassen, die compile geschrieben hat";
    SurfacePointMissing = "The height map has no measured point at X{0} Y{1}: every point of the grid needs one", "Die Höhenkarte hat keinen gemessenen Punkt bei X{0} Y{1}: jeder Punkt des Rasters braucht einen";
    SurfacePointTwice = "Two measured points of the height map at X{0} Y{1}", "Zwei gemessene Punkte der Höhenkarte bei X{0} Y{1}";
    SurfaceGridSize = "The height map lists {0} points, more than {1}", "Die Höhenkarte nennt {0} Punkte, mehr als {1}";
    SurfaceTooManyLines = "Following the surface would write more than {0} lines: choose a larger heightmap.step", "Der Oberfläche zu folgen würde mehr als {0} Zeilen schreiben: einen größeren heightmap.step wählen";
    SurfaceAboveSafeHeight = "The measured surface reaches Z{0} at X{1} Y{2}, not below the safe height Z{3}: the sweeps would hit it (raise sweep_height, or check the log); nothing was written", "Die gemessene Oberfläche reicht bei X{1} Y{2} bis Z{0}, nicht unter die sichere Höhe Z{3}: die Leerfahrten würden sie treffen (sweep_height erhöhen oder das Protokoll prüfen); es wurde nichts geschrieben";
    // probe_split: drawn probes' correction applied along long moves (issue 21)
    ProbeSplitTooSmall = "{0}={1} mm is below the shortest piece, {2} mm", "{0}={1} mm ist kürzer als das kürzeste Teilstück, {2} mm";
    ProbeSplitReferenceDialect = "{0} needs the linuxcnc or grbl dialect: the reference dialect writes PathDxf2GCode's programs, which correct each move at its start only", "{0} braucht den Dialekt linuxcnc oder grbl: der Dialekt reference schreibt die Programme von PathDxf2GCode, die jede Bewegung nur an ihrem Anfang korrigieren";
    ProbeSplitTooManyPieces = "This move is {0} mm long: in pieces of at most probe_split={1} mm it would be {2} moves, more than {3}; choose a larger probe_split", "Diese Bewegung ist {0} mm lang: in Teilstücken von höchstens probe_split={1} mm wären es {2} Bewegungen, mehr als {3}; ein größeres probe_split wählen";
    // a height map said in the drawing: K at the path start (issue 21)
    HeightmapKeyBad = "K{0} is no height map: write K<step> or K<step>+<margin> in mm (e.g. K10+2), step at least {1} mm, margin at least 0", "K{0} ist keine Höhenkarte: K<Abstand> oder K<Abstand>+<Rand> in mm schreiben (z. B. K10+2), Abstand mindestens {1} mm, Rand mindestens 0";
    HeightmapKWithDrawnProbes = "Path {0} has drawn Z probes ({1}) and a height map in its start text (K): use one or the other (both would correct the same Z twice)", "Pfad {0} hat gezeichnete Z-Messpunkte ({1}) und eine Höhenkarte in seinem Starttext (K): nur eines von beiden verwenden (beide würden dasselbe Z doppelt korrigieren)";
    // clamps and fixtures: keep-out boxes of millpath.toml (issue 24)
    ClampHit = "The tool (diameter {3} mm, from its tip upward) runs into clamp '{0}' at G-code line {1} '{2}'", "Das Werkzeug (Durchmesser {3} mm, von der Spitze aufwärts) fährt in die Spannpratze '{0}' bei G-Code-Zeile {1} '{2}'";
    ClampTooMany = "millpath.toml declares {0} clamps, more than {1}", "millpath.toml gibt {0} Spannpratzen an, mehr als {1}";
    ClampEmpty = "Clamp '{0}': min must be below max on {1} (min {2}, max {3})", "Spannpratze '{0}': min muss auf {1} unter max liegen (min {2}, max {3})";
    // found by fuzzing both front-ends (issue 25)
    NoTextHere = "A {0} element takes no parameters: a DXF cannot attach a text to it ('{1}')", "Ein {0}-Element nimmt keine Parameter: eine DXF kann ihm keinen Text zuordnen ('{1}')";
    // text2dxf --into without --extended over polylines and blocks on path layers (issue 20)
    IntoKeptExtended = "{0} keeps on its path layers what text2dxf replaces only with --extended: {1}. If the text came from dxf2text --extended, these paths are now drawn twice: restore the drawing and run text2dxf --extended --into {0}", "{0} behält auf seinen Pfad-Layern, was text2dxf nur mit --extended ersetzt: {1}. Stammt der Text aus dxf2text --extended, sind diese Pfade jetzt doppelt gezeichnet: die Zeichnung wiederherstellen und text2dxf --extended --into {0} ausführen";
    // memory proportional to the input (issue 25)
    TooManyLines = "The program would have more than {0} lines", "Das Programm hätte mehr als {0} Zeilen";
    // check's report when the settings cannot be read (issue 20): the reader's own words
    SettingsUnusable = "{0}", "{0}";
    // nothing the user made is lost (issue 31): measured values, paths of a library drawing
    ZKeptAside = "{0} held {2} measured value(s) of another probing set: kept as {1}. {3} carried over to the new {0} (the same point in the drawing and in the program, the same nominal height); {4} probe(s) of the new set have no value yet", "{0} enthielt {2} Messwert(e) eines anderen Antastsatzes: als {1} aufbewahrt. {3} in die neue {0} übernommen (derselbe Punkt in der Zeichnung und im Programm, dieselbe Soll-Höhe); {4} Messpunkt(e) des neuen Satzes haben noch keinen Wert";
    ZKeptAsideUnchecked = "{0} held {2} measured value(s) of another probing set, but its probing program is missing or of another compile, so no probe point could be compared: kept as {1}; the new {0} has no values", "{0} enthielt {2} Messwert(e) eines anderen Antastsatzes, aber sein Antastprogramm fehlt oder stammt aus einer anderen Übersetzung, also ließ sich kein Messpunkt vergleichen: als {1} aufbewahrt; die neue {0} hat keine Werte";
    ZKeptAsideUnreadable = "{0} could not be read as a _Z.txt ({2}): kept as {1}; the new {0} has no values", "{0} ließ sich nicht als _Z.txt lesen ({2}): als {1} aufbewahrt; die neue {0} hat keine Werte";
    ZCannotKeepAside = "{0} may hold measured values and could not be kept as {1} ({2}): nothing of this drawing was written; move {0} away and compile again", "{0} kann Messwerte enthalten und ließ sich nicht als {1} aufbewahren ({2}): von dieser Zeichnung wurde nichts geschrieben; {0} beiseitelegen und neu übersetzen";
    IntoWouldDeletePaths = "{0} holds paths that {2} does not define: {1}. --into would delete them; nothing was written: add them to the text (dxf2text {0} writes them), or pass --delete-missing-paths to delete them", "{0} enthält Pfade, die {2} nicht definiert: {1}. --into würde sie löschen; es wurde nichts geschrieben: sie in den Text aufnehmen (dxf2text {0} schreibt sie), oder mit --delete-missing-paths löschen";
    // posts (issue 32): what a post cannot write is refused, never dropped
    PostCannot = "The post {0} cannot write {1}: it has no `{2}` (in [capabilities] or [templates]); choose a post that can, or leave {1} out", "Der Post {0} kann {1} nicht schreiben: ihm fehlt `{2}` (in [capabilities] oder [templates]); einen Post wählen, der es kann, oder {1} weglassen";
    // every post's output is checked (issue 32, item 4): a family the checker cannot read is refused
    PostNotVerifiable = "The post {0} writes programs of the {1} family, which the second opinion (verify) cannot read yet: nothing is written unchecked; choose a post of the rs274, grbl or marlin family", "Der Post {0} schreibt Programme der Familie {1}, die die Zweitprüfung (verify) noch nicht lesen kann: ungeprüft wird nichts geschrieben; einen Post der Familie rs274, grbl oder marlin wählen";
    // the merge driver (issue 34): a conflict keeps our file and writes the merge beside it
    MergeConflicts = "{0}: {1} conflict(s) in the paths, written with git's conflict markers to {2}: {3}", "{0}: {1} Konflikt(e) in den Pfaden, mit den Konfliktmarken von git nach {2} geschrieben: {3}";
    MergeOtherContent = "{0}: their side changed the drawing outside the paths ({1}); this is a conflict, nothing of it is merged: carry the change over in CAD (the merged paths are in {2})", "{0}: ihre Seite hat die Zeichnung außerhalb der Pfade geändert ({1}); das ist ein Konflikt, davon wird nichts zusammengeführt: die Änderung im CAD übernehmen (die zusammengeführten Pfade stehen in {2})";
    MergeBreaksCompile = "{0}: the merged path(s) {1} do not compile, while both sides did: a conflict; the merged text is in {2}", "{0}: die zusammengeführten Pfade {1} lassen sich nicht übersetzen, obwohl beide Seiten es taten: ein Konflikt; der zusammengeführte Text steht in {2}";
    // the operator's feed override in the time estimate (issue 33)
    FeedOverrideRange = "feed_override={0} must be a percentage from {1} to {2}", "feed_override={0} muss ein Prozentwert von {1} bis {2} sein";
    // dxf2text -o over a text the user may have edited (issue 31 review): refused, not replaced
    TextWouldBeReplaced = "{0} exists and is not the text of {1}: it may hold edits (or comments) not written back to the drawing. Nothing was written: write the edits back first (text2dxf {0} --into {1}), write elsewhere with -o, or replace it with --force", "{0} existiert und ist nicht der Text von {1}: er kann Änderungen (oder Kommentare) enthalten, die nicht in die Zeichnung zurückgeschrieben sind. Es wurde nichts geschrieben: die Änderungen erst zurückschreiben (text2dxf {0} --into {1}), mit -o anderswohin schreiben, oder mit --force ersetzen";
    // compile of a folder holding part.dxf and part.mpath: both would write part_Milling.gcode
    OutputsCollide = "{0} and {1} would write the same files ({2}_Milling.gcode …): neither was compiled, so that no program silently replaces the other's; compile the one you mean by name, or move the other away", "{0} und {1} würden dieselben Dateien schreiben ({2}_Milling.gcode …): keine wurde übersetzt, damit kein Programm stillschweigend das andere ersetzt; die gemeinte mit Namen übersetzen oder die andere wegräumen";
    // render --svg part.mpath: an output named like the drawing it is made of
    OutputIsInput = "{0} is the drawing this command reads: it is not overwritten by the {1}; name another file", "{0} ist die Zeichnung, die dieser Befehl liest: sie wird nicht mit {1} überschrieben; eine andere Datei angeben";
    // pathdxf2gcode over a filled _Z.txt: the reference's empty file is written, the values kept beside
    ZKeptForReference = "{0} held measured values: kept as {1} (pathdxf2gcode writes the reference's {0}, without values; millpath compile keeps them in place)", "{0} enthielt Messwerte: als {1} behalten (pathdxf2gcode schreibt die {0} der Referenz, ohne Werte; millpath compile behält sie an ihrem Platz)";
    // a post change (issue 32): the program of this drawing for the earlier post
    OtherPostProgramRemoved = "Removed {0}: this drawing's program of an earlier compile for another post; this compile wrote {1}", "{0} entfernt: das Programm dieser Zeichnung aus einer früheren Übersetzung für einen anderen Post; diese Übersetzung hat {1} geschrieben";
    OtherPostProgramKept = "{0} is this drawing's program for another post and holds measured heights (adjust-z): kept, but it is not the program of this compile ({1}); delete it once you no longer need it", "{0} ist das Programm dieser Zeichnung für einen anderen Post und enthält gemessene Höhen (adjust-z): behalten, aber es ist nicht das Programm dieser Übersetzung ({1}); löschen, sobald es nicht mehr gebraucht wird";
    OutputTakenInRun = "{0} would write {1}, which {2} wrote in this run (an R suffix gives both the same output name): not written, so that no program silently replaces the other's; change the R value or the file name of one of them", "{0} würde {1} schreiben, das {2} in diesem Lauf geschrieben hat (ein R-Suffix gibt beiden denselben Ausgabenamen): nicht geschrieben, damit kein Programm stillschweigend das andere ersetzt; den R-Wert oder den Dateinamen einer der beiden ändern";
}

impl Msg {
    /// A stable, machine-readable code (`MP` + index), used in JSON and SARIF reports.
    /// The wording for people. Where the reference's text is an internal one (kept
    /// byte-exact in the `****` lines, RO §16), it says what happened instead.
    pub fn human_template(self, lang: Lang) -> &'static str {
        match (self, lang) {
            (Msg::NotNear, Lang::En) => "The toolpath does not continue here: {0} and {1} should be the same point (an internal consistency check); the element is skipped",
            (Msg::NotNear, Lang::De) => "Die Werkzeugbahn setzt hier nicht fort: {0} und {1} müssten derselbe Punkt sein (interne Konsistenzprüfung); das Element wird übersprungen",
            _ => self.template(lang),
        }
    }
    pub fn code(self) -> String {
        let idx = Msg::ALL.iter().position(|m| *m == self).unwrap_or(0);
        format!("MP{:03}", idx + 1)
    }
    pub fn name(self) -> String {
        format!("{self:?}")
    }
}

/// Fills `{0}`, `{1}` … in a template.
/// `FILE:LINE:COL`, the place of a text file's parameter text.
fn is_text_place(s: &str) -> bool {
    let mut parts = s.rsplitn(3, ':');
    let numbers = (parts.next(), parts.next());
    matches!(numbers, (Some(col), Some(line))
        if !col.is_empty() && !line.is_empty()
            && col.bytes().all(|b| b.is_ascii_digit())
            && line.bytes().all(|b| b.is_ascii_digit()))
        && parts.next().is_some_and(|f| !f.is_empty())
}

pub fn fill(template: &str, args: &[String]) -> String {
    let mut out = String::with_capacity(template.len() + 16);
    let mut rest = template;
    while let Some(pos) = rest.find('{') {
        out.push_str(&rest[..pos]);
        let after = &rest[pos + 1..];
        match after
            .find('}')
            .and_then(|e| after[..e].parse::<usize>().ok().map(|i| (e, i)))
        {
            Some((e, i)) => {
                out.push_str(args.get(i).map(String::as_str).unwrap_or(""));
                rest = &after[e + 1..];
            }
            None => {
                out.push('{');
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// An operating-system error's text (`No such file or directory (os error 2)`, as Rust's
/// `io::Error` shows it) in the message language; other texts stay as they are.
pub fn os_error_text(text: &str, lang: Lang) -> String {
    const DE: &[(&str, &str)] = &[
        (
            "No such file or directory",
            "Datei oder Verzeichnis nicht gefunden",
        ),
        ("Permission denied", "Zugriff verweigert"),
        ("Is a directory", "ist ein Verzeichnis"),
        ("Not a directory", "ist kein Verzeichnis"),
        ("Read-only file system", "Dateisystem nur lesbar"),
        ("No space left on device", "kein Platz mehr auf dem Gerät"),
        ("File exists", "Datei existiert schon"),
        ("Directory not empty", "Verzeichnis nicht leer"),
        ("Operation not permitted", "Vorgang nicht erlaubt"),
        (
            "stream did not contain valid UTF-8",
            "Datei ist kein gültiges UTF-8",
        ),
        // cli/src/write.rs: a file another program holds open (Windows)
        (
            "another program has the file open (a G-code sender or an editor?): close it there and run again",
            "ein anderes Programm hat die Datei geöffnet (ein G-Code-Sender oder ein Editor?): dort schließen und noch einmal ausführen",
        ),
        // load/text_file.rs: a file that is no text
        (
            "holds NUL bytes and no byte-order mark (UTF-16 without a mark?): save it as UTF-8",
            "enthält NUL-Bytes und keine Byte-Order-Mark (UTF-16 ohne Markierung?): als UTF-8 speichern",
        ),
        // cli/src/write.rs: a read-only output is kept
        (
            "read-only: not replaced (make it writable to replace it)",
            "schreibgeschützt: nicht ersetzt (den Schreibschutz aufheben, um sie zu ersetzen)",
        ),
        (
            "read-only: not removed (make it writable to remove it)",
            "schreibgeschützt: nicht entfernt (den Schreibschutz aufheben, um sie zu entfernen)",
        ),
        ("os error", "OS-Fehler"),
    ];
    let mut out = text.to_string();
    if lang == Lang::De {
        for (en, de) in DE {
            out = out.replace(en, de);
        }
    }
    out
}

#[derive(Debug, Clone, PartialEq)]
pub struct Related {
    pub origin: Origin,
    pub note: String,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    pub msg: Msg,
    pub args: Vec<String>,
    pub severity: Severity,
    pub origin: Origin,
    pub related: Vec<Related>,
}

impl Diagnostic {
    pub fn error(msg: Msg, origin: Origin, args: Vec<String>) -> Diagnostic {
        Diagnostic {
            msg,
            args,
            severity: Severity::Error,
            origin,
            related: Vec::new(),
        }
    }
    pub fn warning(msg: Msg, origin: Origin, args: Vec<String>) -> Diagnostic {
        Diagnostic {
            msg,
            args,
            severity: Severity::Warning,
            origin,
            related: Vec::new(),
        }
    }
    pub fn with_related(mut self, origin: Origin, note: impl Into<String>) -> Diagnostic {
        self.related.push(Related {
            origin,
            note: note.into(),
        });
        self
    }
    /// The message for people (editor, human and JSON reports).
    pub fn message(&self, lang: Lang) -> String {
        let template = self.human_text(lang);
        if lang == Lang::De {
            // operating-system errors among the arguments are English texts of the OS
            let args: Vec<String> = args_in(&self.args, lang)
                .iter()
                .map(|a| os_error_text(a, lang))
                .collect();
            return fill(template, &args);
        }
        fill(template, &args_in(&self.args, lang))
    }

    /// The template for people, where the arguments call for another wording than the
    /// reference's: "Could not find path X in file(s) …" for a path that was found but has
    /// errors of its own says so ({2}: its file, {4} = `known`); with no file it says where
    /// it looked ({2}: the folders searched, {3}: the file-name pattern).
    fn human_text(&self, lang: Lang) -> &'static str {
        // a post without a dwell (Mach3, UCCNC: G4's P unit is a setting there): the way out
        // is no dwell, not leaving spindle_dwell out (its default is 2 s)
        if self.msg == Msg::PostCannot && self.args.get(2).is_some_and(|a| a == "dwell") {
            return match lang {
                Lang::En => "The post {0} cannot write {1}: it has no `{2}` (in [capabilities] or [templates]); set spindle_dwell = 0 (or --spindle-dwell 0) and let the controller's own spindle delay wait, or choose a post that can",
                Lang::De => "Der Post {0} kann {1} nicht schreiben: ihm fehlt `{2}` (in [capabilities] oder [templates]); spindle_dwell = 0 (oder --spindle-dwell 0) setzen und die Spindelverzögerung der Steuerung warten lassen, oder einen Post wählen, der es kann",
            };
        }
        let no_file = self.args.get(1).is_some_and(String::is_empty);
        match (self.msg, no_file, self.args.get(4).map(String::as_str), lang) {
            (Msg::CouldNotFind, _, Some("known"), Lang::En) => "Path {0} (in {2}) cannot be embedded: it has errors of its own",
            (Msg::CouldNotFind, _, Some("known"), Lang::De) => "Pfad {0} (in {2}) kann nicht eingebettet werden: er hat eigene Fehler",
            (Msg::CouldNotFind, true, Some(_), Lang::En) => "Could not find path {0}: no drawing in {2} has a file name that covers it (file-name pattern /{3}/)",
            (Msg::CouldNotFind, true, Some(_), Lang::De) => "Pfad {0} nicht gefunden: keine Zeichnung in {2} hat einen Dateinamen, der ihn abdeckt (Dateinamen-Muster /{3}/)",
            _ => self.msg.human_template(lang),
        }
    }
    /// The message as the reports print it beside its location: an unsupported value's
    /// message without its own `FILE:LINE:COL` suffix (the location says it already).
    pub fn located_message(&self, lang: Lang) -> String {
        let text = self.message(lang);
        let place = match (self.msg, self.args.get(1)) {
            (Msg::Unsupported, Some(place)) if is_text_place(place) => place,
            _ => return text,
        };
        match text
            .strip_suffix(place.as_str())
            .and_then(|t| t.strip_suffix("; "))
        {
            Some(t) => t.to_string(),
            None => text,
        }
    }
    /// The message exactly as the reference prints it in its `****` lines.
    pub fn reference_message(&self, lang: Lang) -> String {
        fill(self.msg.template(lang), &args_in(&self.args, lang))
    }
    /// The reference's error line: `**** <context>: <message>` (CR LF in contexts → `|`).
    pub fn reference_line(&self, lang: Lang) -> String {
        let ctx = self.origin.context().replace("\r\n", "|");
        let mark = if self.severity == Severity::Error {
            "****"
        } else {
            "++++"
        };
        format!("{mark} {ctx}: {}", self.reference_message(lang))
    }
}

/// Separates the two wordings of an argument made by [`arg_per_lang`] (no text has it).
const LANG_SEP: char = '\u{1e}';

/// An argument that is itself words (a list like "a number or `)`" inside a syntax error):
/// both wordings, of which a message shows the one of its language.
pub fn arg_per_lang(en: &str, de: &str) -> String {
    format!("{en}{LANG_SEP}{de}")
}

/// Why a DXF file cannot be read, as an argument in both languages.
pub fn dxf_error_arg(e: &millpath_dxf::DxfError) -> String {
    arg_per_lang(&e.to_string(), &e.german())
}

/// The arguments with the wording of `lang` where they have two.
fn args_in(args: &[String], lang: Lang) -> std::borrow::Cow<'_, [String]> {
    if !args.iter().any(|a| a.contains(LANG_SEP)) {
        return std::borrow::Cow::Borrowed(args);
    }
    let pick = |a: &String| match a.split_once(LANG_SEP) {
        Some((en, de)) => if lang == Lang::De { de } else { en }.to_string(),
        None => a.clone(),
    };
    std::borrow::Cow::Owned(args.iter().map(pick).collect())
}

/// Builds an argument list from anything printable.
#[macro_export]
macro_rules! args {
    ($($a:expr),* $(,)?) => { vec![$($a.to_string()),*] };
}

/// Collected diagnostics of a run, de-duplicated by their full text like the reference.
#[derive(Debug, Default)]
pub struct Diags {
    pub list: Vec<Diagnostic>,
    seen: HashSet<String>,
    /// Errors pushed so far, repeats included (the list drops repeats).
    errors_reported: usize,
}

impl Diags {
    pub fn push(&mut self, d: Diagnostic) {
        if d.severity == Severity::Error {
            self.errors_reported += 1;
        }
        let key = d.reference_line(Lang::En);
        if self.seen.insert(key) {
            self.list.push(d);
        }
    }
    pub fn error(&mut self, msg: Msg, origin: Origin, args: Vec<String>) {
        self.push(Diagnostic::error(msg, origin, args));
    }
    pub fn error_count(&self) -> usize {
        self.list
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .count()
    }
    pub fn has_errors(&self) -> bool {
        self.error_count() > 0
    }
    /// Errors pushed so far, counting repeats: compare two readings to learn whether a step
    /// reported any error, even one already in the list.
    pub fn errors_reported(&self) -> usize {
        self.errors_reported
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_message_has_both_languages_and_matching_placeholders() {
        for m in Msg::ALL {
            let (en, de) = (m.template(Lang::En), m.template(Lang::De));
            assert!(!en.is_empty() && !de.is_empty(), "{m:?}");
            for i in 0..5 {
                let p = format!("{{{i}}}");
                assert_eq!(en.contains(&p), de.contains(&p), "{m:?} placeholder {p}");
            }
        }
    }

    #[test]
    fn an_argument_worded_per_language_shows_in_the_message_language() {
        let d = Diagnostic::error(
            Msg::SyntaxExpected,
            Origin::Options,
            vec![arg_per_lang("a number", "eine Zahl"), "`x`".into()],
        );
        assert_eq!(d.message(Lang::En), "Expected a number, found `x`");
        assert_eq!(d.message(Lang::De), "Erwartet: eine Zahl; gefunden: `x`");
    }

    #[test]
    fn fill_replaces_placeholders() {
        assert_eq!(
            fill("F={0} must be > {1}", &["-3".to_string(), "0".to_string()]),
            "F=-3 must be > 0"
        );
        assert_eq!(fill("a {x} b", &[]), "a {x} b");
    }

    #[test]
    fn duplicates_are_collected_once() {
        let mut d = Diags::default();
        d.error(Msg::StartMissing, Origin::Options, vec![]);
        d.error(Msg::StartMissing, Origin::Options, vec![]);
        assert_eq!(d.list.len(), 1);
        assert_eq!(
            d.list[0].reference_line(Lang::De),
            "**** Options: Start-Markierung fehlt"
        );
    }

    /// The reference's internal consistency text stays byte-exact in `****` lines; people
    /// (editor, human and JSON reports) read what happened, in both languages.
    #[test]
    fn the_consistency_message_is_worded_for_people_outside_reference_lines() {
        let d = Diagnostic::error(
            Msg::NotNear,
            Origin::Options,
            args!["[35.000 0.000]", "[5.000 0.000]"],
        );
        assert_eq!(
            d.reference_line(Lang::En),
            "**** Options: ![35.000 0.000].Near([5.000 0.000])"
        );
        assert_eq!(
            d.reference_line(Lang::De),
            "**** Options: ![35.000 0.000].Near([5.000 0.000])"
        );
        for lang in [Lang::En, Lang::De] {
            let m = d.message(lang);
            assert!(!m.contains(".Near("), "{m}");
            assert!(
                m.contains("[35.000 0.000]") && m.contains("[5.000 0.000]"),
                "{m}"
            );
        }
        assert!(d.message(Lang::De).contains("übersprungen"));
        for m in Msg::ALL {
            let (en, de) = (m.human_template(Lang::En), m.human_template(Lang::De));
            for i in 0..5 {
                let p = format!("{{{i}}}");
                assert_eq!(en.contains(&p), m.template(Lang::En).contains(&p), "{m:?}");
                assert_eq!(de.contains(&p), m.template(Lang::De).contains(&p), "{m:?}");
            }
        }
    }
}
