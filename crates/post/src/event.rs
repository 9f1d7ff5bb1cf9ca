//! The emitter's events and the variables each one gives its template. This is the whole
//! interface between the emitter and a post: the emitter says *what* happens (a rapid to
//! X Y, an arc with its centre, a probe), the post's template says how it is written.

/// Something the emitter writes. Each has one template in `[templates]`, named as
/// [`Event::key`] says.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Event {
    /// After the banner and file name comments and the stock line: units, plane, modes.
    ProgramStart,
    /// `(MILLPATH-STOCK …)`: the stock and the tool for verifiers (empty: none).
    Stock,
    /// The tool selection.
    Tool,
    SpindleOn,
    SpindleOff,
    /// The wait after the spindle start.
    Dwell,
    ProgramEnd,
    /// A comment line (the text already made safe by `[comments]`).
    Comment,
    /// One line of the statistics block.
    Statistics,
    /// A horizontal rapid.
    RapidXy,
    /// A vertical rapid down (or level).
    RapidZ,
    /// A vertical rapid up.
    Retract,
    /// A vertical feed move down.
    Plunge,
    Linear,
    ArcCw,
    ArcCcw,
    /// A drawn probe (down to Z 0 at most) and the pause after it.
    Probe,
    /// One point of a height map's grid.
    GridProbe,
    ProbeLogOpen,
    ProbeLogClose,
    /// A horizontal rapid the peephole optimizer took out (reference-output.md §13).
    Disabled,
    /// An element starts (a chain, drill, helix, sweep or subpath).
    ContourStart,
    ContourEnd,
    /// The program's first line, before `%` and the banner (a CAM format's part header).
    Header,
    /// A pass starts: the first cutting move (line or arc) after anything else (a rapid, a
    /// plunge); at the move's start point.
    PassStart,
    /// A pass ends: before the next move that is not a line or arc, or at the program end.
    PassEnd,
    /// A drill element, at its start (its plunges follow as moves).
    Drill,
}

impl Event {
    pub const ALL: [Event; 27] = [
        Event::ProgramStart,
        Event::Stock,
        Event::Tool,
        Event::SpindleOn,
        Event::SpindleOff,
        Event::Dwell,
        Event::ProgramEnd,
        Event::Comment,
        Event::Statistics,
        Event::RapidXy,
        Event::RapidZ,
        Event::Retract,
        Event::Plunge,
        Event::Linear,
        Event::ArcCw,
        Event::ArcCcw,
        Event::Probe,
        Event::GridProbe,
        Event::ProbeLogOpen,
        Event::ProbeLogClose,
        Event::Disabled,
        Event::ContourStart,
        Event::ContourEnd,
        Event::Header,
        Event::PassStart,
        Event::PassEnd,
        Event::Drill,
    ];

    /// The template's key in `[templates]`.
    pub fn key(self) -> &'static str {
        match self {
            Event::ProgramStart => "program_start",
            Event::Stock => "stock",
            Event::Tool => "tool",
            Event::SpindleOn => "spindle_on",
            Event::SpindleOff => "spindle_off",
            Event::Dwell => "dwell",
            Event::ProgramEnd => "program_end",
            Event::Comment => "comment",
            Event::Statistics => "statistics",
            Event::RapidXy => "rapid_xy",
            Event::RapidZ => "rapid_z",
            Event::Retract => "retract",
            Event::Plunge => "plunge",
            Event::Linear => "linear",
            Event::ArcCw => "arc_cw",
            Event::ArcCcw => "arc_ccw",
            Event::Probe => "probe",
            Event::GridProbe => "grid_probe",
            Event::ProbeLogOpen => "probe_log_open",
            Event::ProbeLogClose => "probe_log_close",
            Event::Disabled => "disabled",
            Event::ContourStart => "contour_start",
            Event::ContourEnd => "contour_end",
            Event::Header => "header",
            Event::PassStart => "pass_start",
            Event::PassEnd => "pass_end",
            Event::Drill => "drill",
        }
    }

    pub fn from_key(key: &str) -> Option<Event> {
        Event::ALL.into_iter().find(|e| e.key() == key)
    }

    /// Templates every post must have: the moves every program makes. The others may be left
    /// out (no line), but a program that needs one the post lacks is refused
    /// ([`crate::Post::can`]).
    pub fn required(self) -> bool {
        matches!(
            self,
            Event::ProgramStart
                | Event::ProgramEnd
                | Event::Comment
                | Event::Statistics
                | Event::RapidXy
                | Event::RapidZ
                | Event::Retract
                | Event::Plunge
                | Event::Linear
                | Event::ArcCw
                | Event::ArcCcw
                | Event::Disabled
        )
    }

    /// The variables of this event besides the [`GLOBALS`].
    pub fn variables(self) -> &'static [Var] {
        use Var::*;
        match self {
            Event::ProgramStart | Event::Stock | Event::ProgramEnd | Event::SpindleOff => &[],
            Event::ProbeLogClose => &[],
            Event::Tool => &[ToolNumber],
            Event::SpindleOn => &[Rpm],
            Event::Dwell => &[Seconds],
            Event::Comment => &[Indent, Text],
            Event::Statistics => &[Text],
            Event::RapidXy => &[X, Y],
            Event::RapidZ | Event::Retract => &[Z, ZProbe],
            Event::Plunge => &[X, Y, Z, ZProbe, Feed],
            Event::Linear => &[X, Y, Z, ZProbe, Feed],
            Event::ArcCw | Event::ArcCcw => &[X, Y, Z, ZProbe, Feed, I, J, R, CenterX, CenterY],
            Event::Probe | Event::GridProbe => &[X, Y, Z, Feed],
            Event::ProbeLogOpen => &[LogFile],
            Event::Disabled => &[Line],
            Event::ContourStart => &[
                Element,
                Name,
                ClosedContour,
                InfeedDepth,
                InfeedCount,
                Depth,
                Feed,
                FirstX,
                FirstY,
                LastX,
                LastY,
            ],
            Event::ContourEnd => &[Element, Name],
            Event::Header => &[
                FrameXMin, FrameYMin, FrameXMax, FrameYMax, FrameDx, FrameDy, FrameDz,
            ],
            Event::PassStart => &[X, Y, Z, Pass, Feed],
            Event::PassEnd => &[Pass, Depth, CutDepth, Feed],
            Event::Drill => &[X, Y, Z, Depth, CutDepth, Feed],
        }
    }

    /// May `var` appear in this event's template?
    pub fn allows(self, var: Var) -> bool {
        GLOBALS.contains(&var) || self.variables().contains(&var)
    }
}

/// A template variable. Numbers are written with the post's number format of their word
/// ([`Var::word`]); whole numbers and texts as they are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Var {
    // the program's, in every template
    FileName,
    ProgramName,
    ToolDiameter,
    Clearance,
    StockTop,
    StockBottom,
    ProgramFeed,
    // the event's
    ToolNumber,
    Rpm,
    Seconds,
    Indent,
    Text,
    X,
    Y,
    Z,
    ZProbe,
    Feed,
    I,
    J,
    R,
    LogFile,
    Line,
    Element,
    Name,
    ClosedContour,
    InfeedDepth,
    InfeedCount,
    Depth,
    FirstX,
    FirstY,
    LastX,
    LastY,
    CenterX,
    CenterY,
    FrameXMin,
    FrameYMin,
    FrameXMax,
    FrameYMax,
    FrameDx,
    FrameDy,
    FrameDz,
    Pass,
    CutDepth,
}

/// Variables every template may use: they hold for the whole program.
pub const GLOBALS: [Var; 7] = [
    Var::FileName,
    Var::ProgramName,
    Var::ToolDiameter,
    Var::Clearance,
    Var::StockTop,
    Var::StockBottom,
    Var::ProgramFeed,
];

impl Var {
    pub const ALL: [Var; 43] = [
        Var::FileName,
        Var::ProgramName,
        Var::ToolDiameter,
        Var::Clearance,
        Var::StockTop,
        Var::StockBottom,
        Var::ProgramFeed,
        Var::ToolNumber,
        Var::Rpm,
        Var::Seconds,
        Var::Indent,
        Var::Text,
        Var::X,
        Var::Y,
        Var::Z,
        Var::ZProbe,
        Var::Feed,
        Var::I,
        Var::J,
        Var::R,
        Var::LogFile,
        Var::Line,
        Var::Element,
        Var::Name,
        Var::ClosedContour,
        Var::InfeedDepth,
        Var::InfeedCount,
        Var::Depth,
        Var::FirstX,
        Var::FirstY,
        Var::LastX,
        Var::LastY,
        Var::CenterX,
        Var::CenterY,
        Var::FrameXMin,
        Var::FrameYMin,
        Var::FrameXMax,
        Var::FrameYMax,
        Var::FrameDx,
        Var::FrameDy,
        Var::FrameDz,
        Var::Pass,
        Var::CutDepth,
    ];

    /// The name in a template (`{name}`), after seed 004's variables where one fits
    /// (`~ZClearance~` → `clearance`, `~InfeedDepth~` → `infeed_depth`, …).
    pub fn name(self) -> &'static str {
        match self {
            Var::FileName => "file_name",
            Var::ProgramName => "program_name",
            Var::ToolDiameter => "tool_diameter",
            Var::Clearance => "clearance",
            Var::StockTop => "stock_top",
            Var::StockBottom => "stock_bottom",
            Var::ProgramFeed => "program_feed",
            Var::ToolNumber => "tool_number",
            Var::Rpm => "rpm",
            Var::Seconds => "seconds",
            Var::Indent => "indent",
            Var::Text => "text",
            Var::X => "x",
            Var::Y => "y",
            Var::Z => "z",
            Var::ZProbe => "z_probe",
            Var::Feed => "feed",
            Var::I => "i",
            Var::J => "j",
            Var::R => "r",
            Var::LogFile => "log_file",
            Var::Line => "line",
            Var::Element => "element",
            Var::Name => "name",
            Var::ClosedContour => "closed_contour",
            Var::InfeedDepth => "infeed_depth",
            Var::InfeedCount => "infeed_count",
            Var::Depth => "depth",
            Var::FirstX => "first_x",
            Var::FirstY => "first_y",
            Var::LastX => "last_x",
            Var::LastY => "last_y",
            Var::CenterX => "center_x",
            Var::CenterY => "center_y",
            Var::FrameXMin => "frame_x_min",
            Var::FrameYMin => "frame_y_min",
            Var::FrameXMax => "frame_x_max",
            Var::FrameYMax => "frame_y_max",
            Var::FrameDx => "frame_dx",
            Var::FrameDy => "frame_dy",
            Var::FrameDz => "frame_dz",
            Var::Pass => "pass",
            Var::CutDepth => "cut_depth",
        }
    }

    pub fn from_name(name: &str) -> Option<Var> {
        Var::ALL.into_iter().find(|v| v.name() == name)
    }

    /// The G-code word whose number format a numeric value takes (`[format.words]`).
    pub fn word(self) -> char {
        match self {
            Var::X | Var::FirstX | Var::LastX => 'X',
            Var::FrameXMin | Var::FrameXMax | Var::FrameDx => 'X',
            Var::Y | Var::FirstY | Var::LastY => 'Y',
            Var::FrameYMin | Var::FrameYMax | Var::FrameDy => 'Y',
            Var::Z | Var::Clearance | Var::StockTop | Var::StockBottom | Var::Depth => 'Z',
            Var::InfeedDepth | Var::FrameDz | Var::CutDepth => 'Z',
            Var::CenterX => 'I',
            Var::CenterY => 'J',
            Var::Feed | Var::ProgramFeed => 'F',
            Var::I => 'I',
            Var::J => 'J',
            Var::R => 'R',
            Var::Rpm => 'S',
            Var::Seconds => 'P',
            Var::ToolDiameter => 'D',
            _ => 'N',
        }
    }

    /// What the variable means, for `millpath post show` and the manual.
    pub fn meaning(self) -> &'static str {
        match self {
            Var::FileName => "the drawing's file name",
            Var::ProgramName => "the path's name",
            Var::ToolDiameter => "the tool diameter O (mm)",
            Var::Clearance => "the safe height S of the top-level path (mm)",
            Var::StockTop => "the stock top T (mm)",
            Var::StockBottom => "the lowest drawn depth (mm)",
            Var::ProgramFeed => "the program's feed F (mm/min)",
            Var::ToolNumber => "the tool number",
            Var::Rpm => "the spindle speed (1/min)",
            Var::Seconds => "the wait in seconds",
            Var::Indent => "the comment's indentation (blanks)",
            Var::Text => "the comment's or statistics line's text",
            Var::X | Var::Y | Var::Z => "the end point of the move (mm)",
            Var::ZProbe => "with probes: the Z expression comment that adjust-z evaluates",
            Var::Feed => "the feed of the move (mm/min)",
            Var::I | Var::J => "the arc centre relative to its start (mm)",
            Var::R => "the arc radius, negative beyond a half circle (mm)",
            Var::LogFile => "the probe log's file name",
            Var::Line => "the line taken out",
            Var::Element => "the element kind: chain, drill, helix, sweep or subpath",
            Var::Name => "the element's path name",
            Var::ClosedContour => "1 for a closed chain, else 0",
            Var::InfeedDepth => "the infeed I of a chain or helix (mm)",
            Var::InfeedCount => "the number of passes",
            Var::Depth => "the final depth of the element (mm)",
            Var::FirstX | Var::FirstY => "the start of the contour's first element (mm)",
            Var::LastX | Var::LastY => "the end of the contour's last element (mm)",
            Var::CenterX | Var::CenterY => "the arc centre, absolute (mm)",
            Var::FrameXMin | Var::FrameYMin => "the low corner of the cutting moves' extent (mm)",
            Var::FrameXMax | Var::FrameYMax => "the high corner of the cutting moves' extent (mm)",
            Var::FrameDx | Var::FrameDy => "the size of the cutting moves' extent (mm)",
            Var::FrameDz => "the stock top less the lowest drawn depth (mm)",
            Var::Pass => "the pass's number, from 1",
            Var::CutDepth => "the stock top less the depth (mm, positive below the top)",
        }
    }
}

/// A variable's value as the emitter gives it.
#[derive(Debug, Clone, PartialEq)]
pub enum Value<'a> {
    /// A number in the format of the variable's word.
    Num(f64),
    /// A whole number, written without decimals (`I0`, `T1`).
    Int(i64),
    Text(&'a str),
}
