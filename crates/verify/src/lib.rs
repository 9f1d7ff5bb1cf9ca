//! `millpath-verify`: a second opinion on a G-code program, written from G-code semantics
//! alone (it knows nothing of the compiler that wrote the program).
//!
//! [`verify`] parses every line (garbage becomes a finding, never a panic), simulates the
//! controller's modal state (motion mode, position, feed and feed mode, units, plane,
//! distance modes) and, when the material top T and the tool diameter O are known, a 2.5-D
//! stock model: a height field over the program's XY extent, initialised to T and lowered by
//! every cutting move with a cylindrical tool of diameter O. It reports
//!
//! * rapid moves (G00) through stock higher than the tool tip, and G00 plunges into stock;
//! * cutting moves without a positive feed rate, by the rules of the chosen [`Dialect`];
//! * cuts below the deepest drawn depth (when known);
//! * moves whose tool (diameter O, from the tip upward) touches a keep-out box
//!   ([`Options::clamps`], `clamps.rs`);
//! * arcs whose start and end radius differ by more than 0.002 mm, arcs outside G17;
//! * non-finite or absurd numbers (|v| > 1e6), unknown codes, syntax errors, a missing
//!   program end (a truncated file).
//!
//! Every [`Finding`] carries the 1-based line and its text, so a caller that knows which
//! source element wrote which line can map findings back to the drawing.
//!
//! Memory and time are bounded for any input: at most [`Limits::max_lines`] lines are read,
//! the grid has at most [`Limits::max_cells`] cells, and the stock model stops after
//! [`Limits::max_work`] cell visits (each with a finding saying so).

mod adjusted;
mod checks;
mod clamps;
mod finding;
mod grbl;
mod machine;
mod parse;
mod reread;
mod stock;
mod stock_view;
mod stream;
pub mod surface;
mod surface_frame;

pub use adjusted::PROBES_WORD;
pub use clamps::{Clamp, MAX_CLAMPS};
pub use finding::{
    AdjustedProblem, ArcProblem, Finding, FindingKind, Lang, Limit, NoFeedReason, NumberProblem,
    Severity, StockCommentProblem, StockSkip, SyntaxError,
};
pub use parse::{parse_line, Block, Word, MAX_MAGNITUDE};
pub use stock_view::{StockView, ViewRequest};
pub use stream::{feed_lines, Verifier};
pub use surface::{HeightMap, SurfaceProblem};
pub use surface_frame::{ROUNDING as SURFACE_ROUNDING, SPLIT_TOLERANCE};

/// Whose rules decide the feed-rate checks (and a few strictness details).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Dialect {
    /// F is modal and never reset (what the reference tool's programs assume).
    #[default]
    Reference,
    /// LinuxCNC's rs274ngc: G93/G94/G95 reset the feed rate (executed before F on the same
    /// line); nested comments are errors; axis words need a motion mode.
    LinuxCnc,
    /// grbl 1.1: F is kept across G94; leaving G93 resets it; starts in G00.
    Grbl,
}

impl Dialect {
    pub fn name(self) -> &'static str {
        match self {
            Dialect::Reference => "reference",
            Dialect::LinuxCnc => "linuxcnc",
            Dialect::Grbl => "grbl",
        }
    }
    /// The controller's name as shown in messages.
    pub fn controller(self) -> &'static str {
        match self {
            Dialect::Reference => "the reference controller",
            Dialect::LinuxCnc => "LinuxCNC",
            Dialect::Grbl => "grbl",
        }
    }
}

impl std::str::FromStr for Dialect {
    type Err = String;
    fn from_str(s: &str) -> Result<Dialect, String> {
        match s.to_ascii_lowercase().as_str() {
            "reference" => Ok(Dialect::Reference),
            "linuxcnc" => Ok(Dialect::LinuxCnc),
            "grbl" => Ok(Dialect::Grbl),
            other => Err(format!(
                "unknown dialect {other:?} (reference, linuxcnc or grbl)"
            )),
        }
    }
}

/// The data the stock checks need; from options or a `(MILLPATH-STOCK …)` comment.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StockParams {
    /// Material top T, mm.
    pub top: Option<f64>,
    /// Tool diameter O, mm.
    pub tool: Option<f64>,
    /// The deepest drawn depth, mm.
    pub bottom: Option<f64>,
}

/// Bounds on the work done for one program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    pub max_lines: usize,
    pub max_line_len: usize,
    pub max_cells: usize,
    /// Cell visits of the stock model.
    pub max_work: u64,
    pub max_findings: usize,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            max_lines: 1_000_000,
            max_line_len: 4096,
            max_cells: 4_000_000,
            max_work: 100_000_000,
            max_findings: 10_000,
        }
    }
}

/// What to check against. `top`/`tool`/`bottom` override a `(MILLPATH-STOCK …)` comment.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Options {
    pub dialect: Dialect,
    pub top: Option<f64>,
    pub tool: Option<f64>,
    pub bottom: Option<f64>,
    pub limits: Limits,
    /// Keep-out boxes in machine coordinates: every move is checked against them.
    pub clamps: Vec<Clamp>,
    /// Leave the stock model out (a quick check of the clamps and the program's words).
    pub skip_stock: bool,
    /// Export the stock's height field for a viewer ([`Report::view`]).
    pub view: Option<ViewRequest>,
}

/// The grid the stock model used.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StockInfo {
    pub top: f64,
    pub tool_diameter: f64,
    /// Cell edge, mm.
    pub cell: f64,
    pub nx: usize,
    pub ny: usize,
    /// Lower left corner of the grid.
    pub x0: f64,
    pub y0: f64,
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct Report {
    /// Sorted by line (findings about the whole program first).
    pub findings: Vec<Finding>,
    /// ∫ (T − height) over the grid, mm³; 0 when the stock model did not run.
    pub removed_volume_mm3: f64,
    /// The grid, when the stock model ran.
    pub stock: Option<StockInfo>,
    /// The values used (options over the program's comment).
    pub params: StockParams,
    /// Lines read.
    pub lines: usize,
    /// Moves executed (G00/G01/G02/G03/G38.x with known start or end).
    pub moves: usize,
    /// The measured surface the moves were judged against (given, or the program's
    /// `(MILLPATH-SURFACE …)` record).
    pub surface: Option<HeightMap>,
    /// The stock after the program and its lowerings, when [`Options::view`] asked for it.
    pub view: Option<StockView>,
}

impl Report {
    pub fn count(&self, severity: Severity) -> usize {
        self.findings
            .iter()
            .filter(|f| f.severity == severity)
            .count()
    }
    pub fn has_errors(&self) -> bool {
        self.findings.iter().any(|f| f.severity == Severity::Error)
    }
}

/// How far (mm) the tool tip may be below the stock before a rapid counts as a collision.
pub const Z_TOLERANCE: f64 = 0.001;
/// Extra tolerance (mm) on the footprint radius of rapids, besides one grid cell.
pub const XY_TOLERANCE: f64 = 0.01;

/// The structured comment our compiler writes:
/// `(MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300)` (BOTTOM only when known).
pub fn stock_comment(top: f64, tool: f64, bottom: Option<f64>) -> String {
    match bottom {
        Some(b) => format!("(MILLPATH-STOCK T={top:.3} O={tool:.3} BOTTOM={b:.3})"),
        None => format!("(MILLPATH-STOCK T={top:.3} O={tool:.3})"),
    }
}

/// Reads the text of a comment (without parentheses). `None`: not a stock comment. Keys are
/// T, O and BOTTOM; unknown keys are ignored (for later additions).
pub fn parse_stock_comment(text: &str) -> Option<Result<StockParams, StockCommentProblem>> {
    let rest = text.trim().strip_prefix("MILLPATH-STOCK")?;
    if !rest.is_empty() && !rest.starts_with(char::is_whitespace) {
        return None;
    }
    let mut p = StockParams::default();
    for tok in rest.split_whitespace() {
        let (key, value) = tok.split_once('=').unwrap_or((tok, ""));
        let key = key.to_ascii_uppercase();
        let plain = !value.is_empty()
            && value
                .chars()
                .all(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+'));
        let v = value
            .parse::<f64>()
            .ok()
            .filter(|v| plain && v.is_finite() && v.abs() <= MAX_MAGNITUDE);
        let slot = match key.as_str() {
            "T" => &mut p.top,
            "O" => &mut p.tool,
            "BOTTOM" => &mut p.bottom,
            _ => continue,
        };
        match v {
            Some(v) if key != "O" || v > 0.0 => *slot = Some(v),
            _ => {
                return Some(Err(StockCommentProblem::BadValue {
                    key,
                    text: value.to_string(),
                }))
            }
        }
    }
    Some(Ok(p))
}

/// Checks one program.
pub fn verify(program: &str, options: &Options) -> Report {
    verify_on_surface(program, options, None)
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

/// The nominal top of a program: its `(MILLPATH-SURFACE T=…)` record's, else its
/// `(MILLPATH-STOCK T=…)` comment's.
pub fn program_top(program: &str) -> Option<f64> {
    let lines = || program.lines().take(Limits::default().max_lines);
    if let Some(Ok(map)) = HeightMap::read_comments(lines()) {
        return Some(map.top());
    }
    lines()
        .flat_map(|l| l.split('(').skip(1))
        .filter_map(|c| c.split_once(')').map(|(t, _)| t))
        .find_map(|c| parse_stock_comment(c)?.ok()?.top)
}

/// Checks one program against a measured surface: `surface` (measured on the machine)
/// replaces the program's own `(MILLPATH-SURFACE …)` record; without either, [`verify`].
pub fn verify_on_surface(
    program: &str,
    options: &Options,
    surface_map: Option<&HeightMap>,
) -> Report {
    let max_lines = options.limits.max_lines;
    let body = program.strip_suffix('\n').unwrap_or(program);
    // adjust-z's programs: heights back to the drawing's frame (adjusted.rs)
    let (surface, problems) = adjusted::Surface::scan(body.split('\n').take(max_lines));
    // a height map: given, or the program's own record (a broken one is an error)
    let map = match surface_map {
        Some(m) => Ok(Some(m.clone())),
        None => match HeightMap::read_comments(body.split('\n').take(max_lines)) {
            Some(Ok(m)) => Ok(Some(m)),
            Some(Err(e)) => Err(e),
            None => Ok(None),
        },
    };
    Verifier::scanned(options.clone(), surface, problems, map).read_text(program)
}

/// Moves the Z of a line of an adjusted program to the drawing's frame ([`adjusted`]).
pub(crate) fn to_drawing_frame(
    b: &mut parse::Block,
    surface: &adjusted::Surface,
    rise: f64,
) -> Result<(), AdjustedProblem> {
    let Some(z) = b.words.iter_mut().find(|w| w.letter == 'Z') else {
        return Ok(());
    };
    match b.comments.iter().find_map(|c| c.strip_prefix("==")) {
        Some(expr) => {
            z.value = surface.nominal_z(z.value, expr)?;
        }
        None => z.value -= rise,
    }
    Ok(())
}
