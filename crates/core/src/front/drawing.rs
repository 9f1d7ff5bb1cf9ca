//! The drawing model both front-ends produce: paths with their markers, probes and segments,
//! each with its raw parameter text and its origin. From here on everything is shared.
//!
//! Drawn objects and `build_paths`: special circles, drill/helix by O, line types
//! (reference-input.md §1.4–§1.6), `RawPath`/`RawSegment`/`SegKind`, allowed keys
//! (reference-input.md §4.1; `K`, a height map, at the path start outside the reference dialect),
//! `@` resolution (reference-input.md §4.5).

use crate::args;
use crate::diag::{Diagnostic, Diags, FileRef, Msg, Origin};
use crate::geom::{f3, near};
use crate::geom::{Geom, P2};
use crate::load::name_regex::NameRegex;
use crate::params::ParamText;
use crate::params::{parse_number, MAX_MAGNITUDE};
use std::collections::HashMap;
use std::sync::Arc;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Style {
    /// CONTINUOUS: milled to B.
    Mill,
    /// DIVIDE: marked to D.
    Mark,
    /// BORDER: milled to B with support bars up to D.
    Support,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SweepKind {
    /// DASHED: a sweep that may carry S and N.
    Dashed,
    /// HIDDEN: a sweep without parameters.
    Hidden,
    /// DOT: a skipped subpath embedding, travelled as a sweep.
    Dot,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SegKind {
    Drill(Style),
    Helix(Style),
    Subpath,
    Mill(Style),
    Sweep(SweepKind),
}

impl SegKind {
    /// Tie-break preference of the traversal (§5.1).
    pub fn preference(self) -> u8 {
        match self {
            SegKind::Drill(_) => 1,
            SegKind::Helix(_) => 2,
            SegKind::Subpath => 3,
            SegKind::Mill(_) => 4,
            SegKind::Sweep(_) => 5,
        }
    }
    /// Keys accepted in the element's text (reference-input.md §4.1), besides `:`.
    pub fn allowed_keys(self) -> &'static str {
        match self {
            SegKind::Mill(_) => "BCDFINPQSUW",
            SegKind::Sweep(_) => "NS",
            SegKind::Drill(Style::Mark) => "CDFQ",
            SegKind::Drill(_) => "BCFQ",
            SegKind::Helix(Style::Mill) => "BFIQ",
            SegKind::Helix(Style::Mark) => "DFIQ",
            SegKind::Helix(Style::Support) => "BDFIPQU",
            SegKind::Subpath => "HMNOT>",
        }
    }
}

/// Keys accepted in a path start text.
/// (`@` is not among them: a resolved start text no longer has it, an unresolved one reports it.)
pub const PATH_KEYS: &str = "ABCDEFIMOPRSTUWZ";
/// A path start text in the `linuxcnc` and `grbl` dialects: also `K`, the height map said in
/// the drawing (`K<step>` or `K<step>+<margin>`, mm). The reference knows no `K`: in the
/// reference dialect it stays "Unsupported", as PathDxf2GCode reports it.
pub const PATH_KEYS_HEIGHTMAP: &str = "ABCDEFIKMOPRSTUWZ";
/// The height-map key of a path start text.
pub const HEIGHTMAP_KEY: char = 'K';
/// Keys the chain level accepts from its first segment (P and U missing is a reference quirk).
pub const CHAIN_KEYS: &str = "NICWFBSQD";
/// Keys accepted at a z-probe.
pub const PROBE_KEYS: &str = "HLTZ";

#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    Circle { c: P2, r: f64 },
    Path(Geom),
}

impl Shape {
    /// Every coordinate and radius finite and within ±[`MAX_MAGNITUDE`] (radius > 0 is
    /// checked where circles are classified).
    pub fn is_sane(&self) -> bool {
        let ok = |v: f64| v.is_finite() && v.abs() <= MAX_MAGNITUDE;
        let p = |q: P2| ok(q.x) && ok(q.y);
        match *self {
            Shape::Circle { c, r } => p(c) && ok(r),
            Shape::Path(Geom::Line { a, b }) => p(a) && p(b),
            Shape::Path(Geom::Arc { c, r, a0, a1, .. }) => p(c) && ok(r) && ok(a0) && ok(a1),
        }
    }
    pub fn start(&self) -> P2 {
        match self {
            Shape::Circle { c, .. } => *c,
            Shape::Path(g) => g.start(),
        }
    }
    pub fn end(&self) -> P2 {
        match self {
            Shape::Circle { c, .. } => *c,
            Shape::Path(g) => g.end(),
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct RawSegment {
    /// Index of the drawn object it comes from.
    pub object: usize,
    pub kind: SegKind,
    pub shape: Shape,
    /// Boxed: most segments have no text, and a drawing can have millions of segments.
    pub text: Option<Box<ParamText>>,
    pub origin: Origin,
}

impl RawSegment {
    /// Traversal order key: N (or 9998); drills −10⁶, helixes −10⁶ + radius.
    pub fn order(&self) -> f64 {
        match (&self.kind, &self.shape) {
            (SegKind::Drill(_), _) => -1_000_000.0,
            (SegKind::Helix(_), Shape::Circle { r, .. }) => -1_000_000.0 + r,
            (SegKind::Sweep(SweepKind::Hidden), _) => 9998.0,
            _ => self
                .text
                .as_ref()
                .and_then(|t| t.order())
                .map_or(9998.0, |n| n as f64),
        }
    }
    /// `N5555` marks a legacy "backtracking" segment (only visible in comments).
    pub fn backtrack(&self) -> bool {
        !matches!(self.kind, SegKind::Sweep(SweepKind::Hidden))
            && self.text.as_ref().and_then(|t| t.order()) == Some(5555)
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    pub pos: P2,
    pub origin: Origin,
}

#[derive(Debug, Clone, PartialEq)]
pub struct ProbeDef {
    pub center: P2,
    pub text: Option<ParamText>,
    pub origin: Origin,
}

/// One path as drawn, before traversal.
#[derive(Debug, Clone, PartialEq)]
pub struct RawPath {
    pub name: String,
    pub file: Arc<FileRef>,
    pub start: Option<Marker>,
    pub end: Option<Marker>,
    /// Turn markers (Ø 1.5 mm): dead ends with automatic return.
    pub turns: Vec<Marker>,
    /// The start text after `@` resolution.
    pub start_text: Option<ParamText>,
    /// The path whose start text this one uses (`@` reference).
    pub at_ref: Option<String>,
    pub probes: Vec<ProbeDef>,
    pub segments: Vec<RawSegment>,
    /// Lines of the path's text did not parse: a marker or segment "missing" may be in them,
    /// so only the syntax errors are reported for it (no cascade of structure messages).
    pub broken: bool,
}

impl RawPath {
    pub fn new(name: String, file: Arc<FileRef>) -> RawPath {
        RawPath {
            name,
            file,
            start: None,
            end: None,
            turns: Vec::new(),
            start_text: None,
            at_ref: None,
            probes: Vec::new(),
            segments: Vec::new(),
            broken: false,
        }
    }
    pub fn origin(&self) -> Origin {
        Origin::Path {
            name: self.name.as_str().into(),
            file: self.file.clone(),
        }
    }
    /// The path without its segments: what a built model keeps of its drawing (names,
    /// markers and texts for its messages; the segments live on in the model's elements).
    pub fn head(&self) -> RawPath {
        RawPath {
            name: self.name.clone(),
            file: self.file.clone(),
            start: self.start.clone(),
            end: self.end.clone(),
            turns: self.turns.clone(),
            start_text: self.start_text.clone(),
            at_ref: self.at_ref.clone(),
            probes: self.probes.clone(),
            segments: Vec::new(),
            broken: self.broken,
        }
    }
    /// The origin used for path-level messages: the start marker, else the path.
    pub fn start_origin(&self) -> Origin {
        self.start
            .as_ref()
            .map_or_else(|| self.origin(), |m| m.origin.clone())
    }
}

/// All paths of one input file, in the order they were created.
#[derive(Debug, Clone, Default)]
pub struct DrawingFile {
    pub paths: Vec<RawPath>,
    /// Lines of the `/x` debug output.
    pub debug: Vec<String>,
    /// e.g. `AC1015` for DXF.
    pub version: String,
}

/// Whether a drawn element can carry a parameter text: in a DXF, texts are never assigned
/// to HIDDEN elements (`move`) or end markers (PHANTOM Ø 2), so a text file may not give
/// them one either.
pub fn takes_text(linetype: &str, shape: &Shape) -> bool {
    match shape {
        Shape::Circle { r, .. } => {
            !(linetype == "HIDDEN" || (linetype == "PHANTOM" && near(*r, 1.0)))
        }
        Shape::Path(_) => linetype != "HIDDEN",
    }
}

/// Start-text checks and `@` resolution, per file (reference-input.md §4.5, §5.1).
pub fn resolve_start_texts(
    paths: &mut [RawPath],
    path_pattern: &NameRegex,
    pattern_text: &str,
    diags: &mut Diags,
) {
    for p in paths.iter() {
        if p.start.is_none() {
            diags.error(Msg::ParametersTextMissing, p.origin(), vec![]);
        }
    }
    let snapshot: Vec<(String, bool, Option<ParamText>)> = paths
        .iter()
        .map(|p| (p.name.clone(), p.start.is_some(), p.start_text.clone()))
        .collect();
    for p in paths.iter_mut() {
        let Some(text) = &p.start_text else { continue };
        let Some(target) = text.raw('@').map(str::to_string) else {
            continue;
        };
        let ctx = p.start_origin();
        if text.params.len() > 1 {
            diags.error(Msg::AtWithOthers, ctx, args![target]);
            continue;
        }
        if !path_pattern.is_match(&target) {
            diags.error(Msg::AtNoMatch, ctx, args![target, pattern_text]);
            continue;
        }
        let Some((_, _, Some(referenced))) = snapshot
            .iter()
            .find(|(n, has_start, _)| *n == target && *has_start)
        else {
            diags.error(Msg::AtNotFound, ctx, args![target]);
            continue;
        };
        if let Some(inner) = referenced.raw('@') {
            diags.error(Msg::AtNested, ctx, args![inner]);
            continue;
        }
        let mut resolved = referenced.clone();
        resolved.origin = text.origin.clone();
        p.start_text = Some(resolved);
        p.at_ref = Some(target);
    }
}

/// One element as drawn: path, line type, shape and its parameter text. Both front-ends
/// produce these; [`build_paths`] turns them into paths.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawnObject {
    /// Normalised path name of the layer (shared by the objects of a layer: a drawing can
    /// have millions of objects, and these are held whole while its paths are made).
    pub path: Arc<str>,
    /// Shared like `path`: a drawing has a handful of line types.
    pub linetype: Arc<str>,
    pub shape: Shape,
    /// Boxed: most objects have no text.
    pub text: Option<Box<ParamText>>,
    pub origin: Origin,
}

/// One shared copy of each of a drawing's few names (layers' paths, line types) for its
/// many objects.
#[derive(Default)]
pub struct SharedNames(HashMap<Arc<str>, (), foldhash::fast::RandomState>);

impl SharedNames {
    pub fn get(&mut self, name: &str) -> Arc<str> {
        if let Some((k, _)) = self.0.get_key_value(name) {
            return k.clone();
        }
        let k: Arc<str> = Arc::from(name);
        self.0.insert(k.clone(), ());
        k
    }
}

/// Circles, lines and arcs → paths: markers, probes, drills and helixes (by the path's O),
/// segments by line type (reference-input.md §1.4–§1.6, §4.5). `Err` aborts the file.
pub fn build_paths(
    objs: &[DrawnObject],
    file: &Arc<FileRef>,
    path_pattern: &NameRegex,
    pattern_text: &str,
    diags: &mut Diags,
) -> Result<Vec<RawPath>, Diagnostic> {
    // 3. special circles create the paths
    let mut paths: Vec<RawPath> = Vec::new();
    let mut index: HashMap<String, usize> = HashMap::new();
    let mut get_path = |paths: &mut Vec<RawPath>, name: &str| -> usize {
        *index.entry(name.to_string()).or_insert_with(|| {
            paths.push(RawPath::new(name.to_string(), file.clone()));
            paths.len() - 1
        })
    };
    // elements with absurd numbers are reported and take no further part
    let insane: Vec<bool> = objs
        .iter()
        .map(|o| {
            let bad = !o.shape.is_sane();
            if bad {
                diags.error(
                    Msg::CoordinateOutOfRange,
                    o.origin.clone(),
                    args![MAX_MAGNITUDE],
                );
            }
            bad
        })
        .collect();
    let mut special = vec![false; objs.len()];
    for (i, o) in objs.iter().enumerate() {
        let Shape::Circle { c, r } = o.shape else {
            continue;
        };
        if insane[i] {
            continue;
        }
        let lt = &*o.linetype;
        if !matches!(lt, "PHANTOM" | "DOT" | "DASHDOT") {
            continue;
        }
        special[i] = true;
        let pi = get_path(&mut paths, &o.path);
        let p = &mut paths[pi];
        let marker = Marker {
            pos: c,
            origin: o.origin.clone(),
        };
        if lt == "PHANTOM" && near(r, 0.5) {
            match &p.start {
                Some(first) => diags.push(
                    Diagnostic::error(Msg::TwoStartMarkers, o.origin.clone(), args![first.pos, c])
                        .with_related(first.origin.clone(), "first start marker"),
                ),
                None => {
                    p.start = Some(marker);
                    p.start_text = Some(
                        o.text
                            .as_deref()
                            .cloned()
                            .unwrap_or_else(|| empty_text(o.origin.clone())),
                    );
                }
            }
        } else if lt == "PHANTOM" && near(r, 1.0) {
            match &p.end {
                Some(first) => diags.push(
                    Diagnostic::error(Msg::TwoEndMarkers, o.origin.clone(), args![first.pos, c])
                        .with_related(first.origin.clone(), "first end marker"),
                ),
                None => p.end = Some(marker),
            }
        } else if lt == "PHANTOM" && near(r, 0.75) {
            p.turns.push(marker);
        } else if (lt == "PHANTOM" || lt == "DASHDOT") && near(r, 3.0) {
            p.probes.push(ProbeDef {
                center: c,
                text: o.text.as_deref().cloned(),
                origin: o.origin.clone(),
            });
        } else if lt == "DOT" && near(r, 3.0) {
            // ignored z-probe
        } else {
            diags.error(
                Msg::NoSpecialMeaning,
                o.origin.clone(),
                args![f3(2.0 * r), lt],
            );
        }
    }

    // 4. start texts and @ references
    resolve_start_texts(&mut paths, path_pattern, pattern_text, diags);

    // 5. drills and helixes, then lines, then arcs
    let find = |paths: &[RawPath], o: &DrawnObject| -> Result<usize, Diagnostic> {
        paths
            .iter()
            .position(|p| *p.name == *o.path)
            .ok_or_else(|| {
                Diagnostic::error(Msg::PathNotFoundForElement, o.origin.clone(), args![o.path])
            })
    };
    // room for every object a path may get at once: a path of a million segments is not
    // copied as it grows (objects of the same layer mostly follow each other)
    let mut room = vec![0usize; paths.len()];
    let mut last: Option<(&str, usize)> = None;
    for (i, o) in objs.iter().enumerate() {
        if special[i] || insane[i] {
            continue;
        }
        let pi = match last {
            Some((name, pi)) if name == &*o.path => Some(pi),
            _ => paths.iter().position(|p| *p.name == *o.path),
        };
        if let Some(pi) = pi {
            room[pi] += 1;
            last = Some((&o.path, pi));
        }
    }
    for (p, n) in paths.iter_mut().zip(room) {
        p.segments.reserve_exact(n);
    }
    for (i, o) in objs.iter().enumerate() {
        let Shape::Circle { r, .. } = o.shape else {
            continue;
        };
        if special[i] || insane[i] {
            continue;
        }
        let pi = find(&paths, o)?;
        let p = &mut paths[pi];
        let start_text = p.start_text.as_ref().filter(|t| t.has_keys());
        let Some(start_text) = start_text else {
            diags.error(Msg::NoParametersForPath, p.start_origin(), args![p.name]);
            continue;
        };
        let Some(o_value) = start_text.raw('O').and_then(parse_number) else {
            diags.error(Msg::ValueMissing, o.origin.clone(), args!["O"]);
            continue;
        };
        let lt = &*o.linetype;
        let kind = if near(r, o_value / 2.0) {
            if lt.starts_with("DIVIDE") {
                SegKind::Drill(Style::Mark)
            } else if lt.starts_with("CONTINUOUS") {
                SegKind::Drill(Style::Mill)
            } else {
                diags.error(Msg::LineTypeNotSupported, o.origin.clone(), args![lt]);
                continue;
            }
        } else if r > o_value / 2.0 {
            if lt.starts_with("CONTINUOUS") {
                SegKind::Helix(Style::Mill)
            } else if lt.starts_with("DIVIDE") {
                SegKind::Helix(Style::Mark)
            } else if lt.starts_with("BORDER") {
                SegKind::Helix(Style::Support)
            } else {
                diags.error(Msg::LineTypeNotSupported, o.origin.clone(), args![lt]);
                continue;
            }
        } else {
            diags.error(
                Msg::DiameterSmallerThanO,
                o.origin.clone(),
                args![f3(2.0 * r), f3(o_value)],
            );
            continue;
        };
        p.segments.push(RawSegment {
            object: i,
            kind,
            shape: o.shape.clone(),
            text: o.text.clone(),
            origin: o.origin.clone(),
        });
    }
    for want_line in [true, false] {
        for (i, o) in objs.iter().enumerate() {
            let Shape::Path(g) = &o.shape else { continue };
            if matches!(g, Geom::Line { .. }) != want_line || insane[i] {
                continue;
            }
            let pi = find(&paths, o)?;
            let lt = &*o.linetype;
            let kind = if lt.starts_with("CONTINUOUS") {
                SegKind::Mill(Style::Mill)
            } else if lt.starts_with("DIVIDE") {
                SegKind::Mill(Style::Mark)
            } else if lt.starts_with("BORDER") {
                SegKind::Mill(Style::Support)
            } else if lt.starts_with("DASHDOT") {
                SegKind::Subpath
            } else if lt.starts_with("DASHED") {
                SegKind::Sweep(SweepKind::Dashed)
            } else if lt.starts_with("HIDDEN") {
                SegKind::Sweep(SweepKind::Hidden)
            } else if lt.starts_with("DOT") {
                SegKind::Sweep(SweepKind::Dot)
            } else {
                diags.error(Msg::LineTypeNotSupported, o.origin.clone(), args![lt]);
                continue;
            };
            paths[pi].segments.push(RawSegment {
                object: i,
                kind,
                shape: o.shape.clone(),
                text: o.text.clone(),
                origin: o.origin.clone(),
            });
        }
    }
    Ok(paths)
}

fn empty_text(origin: Origin) -> ParamText {
    ParamText {
        text: String::new(),
        params: Vec::new(),
        vars: Vec::new(),
        tokens: Vec::new(),
        origin,
    }
}
