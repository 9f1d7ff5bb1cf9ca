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
//!   program end (a truncated file);
//! * what the program's family ([`Dialect`], [`Dialect::rules`]) reads otherwise than
//!   written: line numbers, comments, `%`, Marlin's one command a line, its dwell units.
//!
//! An xCAM `.NCC` file (the `xcam` family) is not G-code: `ncc.rs` rebuilds the moves of its
//! contours, millings and drillings, and the same checks run on them.
//!
//! Every [`Finding`] carries the 1-based line and its text, so a caller that knows which
//! source element wrote which line can map findings back to the drawing.
//!
//! Memory and time are bounded for any input: at most [`Limits::max_lines`] lines are read,
//! the grid has at most [`Limits::max_cells`] cells, and the stock model stops after
//! [`Limits::max_work`] cell visits (each with a finding saying so).
//!
//! `verify` and `verify_on_surface`: the whole-program scans (adjustment, surface record), then
//! `Verifier` over the lines (`stream.rs`); `program_top`. Options and limits are in `options.rs`,
//! the report in `report.rs`, the `(MILLPATH-STOCK …)` comment in `stock_comment.rs`.

mod adjusted;
mod checks;
mod clamps;
mod dialect;
mod execute;
mod finding;
mod grbl;
mod machine;
mod magnitude;
mod ncc;
mod ncc_problem;
mod number_problem;
mod options;
mod parse;
mod report;
mod reread;
mod stock;
mod stock_comment;
mod stock_view;
mod stream;
pub mod surface;
mod surface_frame;

pub use adjusted::PROBES_WORD;
pub use clamps::{Clamp, MAX_CLAMPS};
pub use dialect::{Dialect, DwellUnit, Rules};
pub use finding::{
    AdjustedProblem, ArcProblem, FamilyProblem, Finding, FindingKind, Lang, Limit, NoFeedReason,
    NumberProblem, Severity, StockCommentProblem, StockSkip, SyntaxError,
};
pub use machine::SHORT_SPINDLE_DWELL;
pub use magnitude::MAX_MAGNITUDE;
pub use ncc::{MAX_REPLAYED, RAPID_CLEARANCE};
pub use ncc_problem::NccProblem;
pub use options::{Limits, Options, XY_TOLERANCE, Z_TOLERANCE};
pub use parse::{only_a_comment, parse_line, Block, Word};
pub use report::{Report, StockInfo};
pub use stock_comment::{parse_stock_comment, stock_comment, StockParams};
pub use stock_view::{StockView, ViewRequest};
pub use stream::{feed_lines, Verifier};
pub use surface::{HeightMap, SurfaceProblem};
pub use surface_frame::{ROUNDING as SURFACE_ROUNDING, SPLIT_TOLERANCE};

/// Checks one program.
pub fn verify(program: &str, options: &Options) -> Report {
    verify_on_surface(program, options, None)
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
