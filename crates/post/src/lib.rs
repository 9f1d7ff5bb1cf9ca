//! Post-processors as data (issue 32). A post is a TOML file that maps the emitter's events
//! (`event.rs`: program start and end, tool, spindle, dwell, comments, rapids, plunges,
//! lines, arcs, probes, probe logs, the statistics block, contours) to text through
//! templates (`template.rs`: `{variable}` placeholders), with number formats (`number.rs`),
//! comment rules (`comment.rs`), line numbers, modal suppression and line ends
//! (`writer.rs`), and what the machine can do (probing, probe logs, spindle, dwell).
//!
//! A post is validated when it is loaded (`load.rs`): every error is located (file, line,
//! column, key) and worded in English and German (`error.rs`). Expansion is bounded: a
//! template has no includes or loops and at most [`template::MAX_TEMPLATE`] bytes; a post
//! file at most [`MAX_POST_FILE`].
//!
//! The built-in posts are files too (`posts/*.toml`, embedded: `builtin.rs`); `millpath post
//! show NAME` prints one, and that file compiles to the same bytes as the built-in.
//!
//! This crate depends on no other crate of the workspace: core's emitter uses it.

pub mod builtin;
pub mod comment;
pub mod error;
pub mod event;
mod load;
pub mod number;
mod resolve;
pub mod template;
pub mod writer;

pub use comment::{CommentRules, CommentStyle};
pub use error::{ErrorKind, Lang, PostError};
pub use event::{Event, Value, Var, GLOBALS};
pub use load::load;
pub use number::{Decimals, NumberFormat};
pub use resolve::resolve;
pub use template::{Piece, Template};
pub use writer::LineWriter;

use std::collections::BTreeMap;

/// Largest post file (bytes).
pub const MAX_POST_FILE: usize = 256 * 1024;

/// The kind of program a post writes, and so the reader the checker uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// LinuxCNC, Mach3/4, UCCNC, Centroid.
    Rs274,
    /// GRBL, FluidNC, grblHAL.
    Grbl,
    Marlin,
    Xcam,
}

impl Family {
    pub fn name(self) -> &'static str {
        match self {
            Family::Rs274 => "rs274",
            Family::Grbl => "grbl",
            Family::Marlin => "marlin",
            Family::Xcam => "xcam",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineEnd {
    Lf,
    CrLf,
}

impl LineEnd {
    pub fn text(self) -> &'static str {
        match self {
            LineEnd::Lf => "\n",
            LineEnd::CrLf => "\r\n",
        }
    }
}

/// How arcs are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArcMode {
    /// Centre relative to the start (I J).
    Ij,
    /// Radius (R; arcs beyond a half circle are written in two).
    R,
    /// As lines within the chord tolerance.
    Lines,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Format {
    pub number: NumberFormat,
    /// Per-word formats (`F`, `S`, …) over [`Format::number`].
    pub words: BTreeMap<char, NumberFormat>,
    /// Words not repeated while their value stays (letters; `motion` for G0–G3).
    pub modal: Vec<String>,
    pub line_end: LineEnd,
    /// Longest line the controller reads (comments are cut to it).
    pub max_line_length: Option<usize>,
    /// `%` lines before and after the program.
    pub percent: bool,
    pub arcs: ArcMode,
    /// With `arcs = "lines"` (and beyond `max_arc_radius`): the largest chord error, mm.
    pub chord_tolerance: f64,
    /// Arcs of a larger radius are written as lines.
    pub max_arc_radius: Option<f64>,
}

impl Format {
    /// The number format of `word`.
    pub fn of(&self, word: char) -> &NumberFormat {
        self.words.get(&word).unwrap_or(&self.number)
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct LineNumbers {
    pub letter: char,
    pub start: u64,
    pub step: u64,
    /// Digits at least (zero-padded).
    pub width: usize,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Probing {
    None,
    G38_2,
    G38_3,
    /// Mach3/4, UCCNC.
    G31,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Capabilities {
    pub probing: Probing,
    pub probe_log: bool,
    pub spindle: bool,
    pub dwell: bool,
}

/// The program-wide values every template may use ([`event::GLOBALS`]).
#[derive(Debug, Clone, Default)]
pub struct Globals<'a> {
    pub file_name: &'a str,
    pub program_name: &'a str,
    pub tool_diameter: f64,
    pub clearance: f64,
    pub stock_top: f64,
    pub stock_bottom: f64,
    pub program_feed: f64,
}

/// A loaded, validated post.
#[derive(Debug, Clone, PartialEq)]
pub struct Post {
    pub name: String,
    pub description: String,
    pub family: Family,
    pub extension: String,
    pub format: Format,
    pub line_numbers: Option<LineNumbers>,
    pub comments: CommentRules,
    pub capabilities: Capabilities,
    /// Every event's template (an event left out has an empty one: no line).
    pub templates: BTreeMap<Event, Template>,
    /// The post file's text.
    pub source: String,
    /// Where it came from (`builtin:NAME` or the file's path).
    pub origin: String,
}

impl Post {
    pub fn template(&self, event: Event) -> &Template {
        static EMPTY: Template = Template {
            pieces: Vec::new(),
            source: String::new(),
        };
        self.templates.get(&event).unwrap_or(&EMPTY)
    }

    /// Does the post write this event (a template that is not empty)?
    pub fn has(&self, event: Event) -> bool {
        !self.template(event).is_empty()
    }

    /// Appends the text of `event` to `out` (lines separated by `\n`, no line end after the
    /// last); the variables from `vars` (the event's) and `g` (the program's).
    pub fn render(&self, event: Event, vars: &[(Var, Value)], g: &Globals, out: &mut String) {
        for piece in &self.template(event).pieces {
            match piece {
                Piece::Text(t) => out.push_str(t),
                Piece::Var(v) => self.value(*v, vars, g, out),
            }
        }
    }

    /// [`Post::render`] as a new string.
    pub fn text(&self, event: Event, vars: &[(Var, Value)], g: &Globals) -> String {
        let mut s = String::new();
        self.render(event, vars, g, &mut s);
        s
    }

    fn value(&self, v: Var, vars: &[(Var, Value)], g: &Globals, out: &mut String) {
        let value = match vars.iter().find(|(k, _)| *k == v) {
            Some((_, value)) => value.clone(),
            None => match v {
                Var::FileName => Value::Text(g.file_name),
                Var::ProgramName => Value::Text(g.program_name),
                Var::ToolDiameter => Value::Num(g.tool_diameter),
                Var::Clearance => Value::Num(g.clearance),
                Var::StockTop => Value::Num(g.stock_top),
                Var::StockBottom => Value::Num(g.stock_bottom),
                Var::ProgramFeed => Value::Num(g.program_feed),
                // an event's variable the emitter did not give: nothing (validation makes
                // sure a template only names its event's variables)
                _ => return,
            },
        };
        match value {
            Value::Num(x) => self.format.of(v.word()).write(x, out),
            Value::Int(i) => {
                use std::fmt::Write;
                let _ = write!(out, "{i}");
            }
            Value::Text(t) => out.push_str(t),
        }
    }

    /// A comment line: `text` made safe by `[comments]`, at `indent` blanks, cut (with
    /// `...`) to the longest line.
    pub fn comment(&self, indent: usize, text: &str, g: &Globals) -> String {
        let body = comment::safe_text(&self.comments, text);
        let blanks = " ".repeat(indent.min(64));
        let render = |t: &str| {
            self.text(
                Event::Comment,
                &[
                    (Var::Indent, Value::Text(&blanks)),
                    (Var::Text, Value::Text(t)),
                ],
                g,
            )
        };
        let line = render(&body);
        match self.format.max_line_length {
            // controllers count bytes
            Some(max) if line.len() > max => {
                let frame = line.len() - body.len();
                let keep = max.saturating_sub(frame + 3);
                let mut cut = String::new();
                for c in body.chars() {
                    if cut.len() + c.len_utf8() > keep {
                        break;
                    }
                    cut.push(c);
                }
                let cut = format!("{}...", cut.trim_end());
                render(&cut)
            }
            _ => line,
        }
    }

    /// The events of a program this post cannot write: the first one needed and missing.
    /// `probes`: drawn probes or a height map; `log`: a probe log is asked for.
    pub fn missing_for(
        &self,
        probes: bool,
        grid: bool,
        spindle: bool,
        dwell: bool,
    ) -> Option<Event> {
        let probing = self.capabilities.probing != Probing::None;
        let needs = [
            (probes && !grid, Event::Probe, probing),
            (grid, Event::GridProbe, probing),
            (spindle, Event::SpindleOn, self.capabilities.spindle),
            (spindle, Event::SpindleOff, self.capabilities.spindle),
            (dwell, Event::Dwell, self.capabilities.dwell),
        ];
        needs
            .into_iter()
            .find(|(needed, e, able)| *needed && (!able || !self.has(*e)))
            .map(|(_, e, _)| e)
    }
}
