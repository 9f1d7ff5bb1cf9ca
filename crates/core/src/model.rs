//! The validated path model: traversal order, chains, effective parameters, support-bar
//! geometry and subpath connections (reference-input.md §4–§6).
//!
//! The built model (`Model`, `Element`, `Chain`, …): the contract between `build/` and `emit/`.

use crate::diag::Origin;
use crate::front::drawing::{RawPath, Style};
use crate::geom::{Geom, Transform, P2};
use crate::params::Vars;
use std::sync::Arc;

/// Effective values of a path start text.
#[derive(Debug, Clone, PartialEq)]
pub struct PathParams {
    pub f: f64,
    /// NaN when missing (reported).
    pub t: f64,
    /// NaN when missing (reported).
    pub o: f64,
    pub s: f64,
    pub a: f64,
    pub z: f64,
    pub v: f64,
    pub b: Option<f64>,
    pub d: Option<f64>,
    pub i: Option<f64>,
    pub w: Option<f64>,
    pub p: Option<f64>,
    pub u: Option<f64>,
    pub c: Option<i64>,
    pub m: Option<String>,
    pub e: Option<String>,
    pub r: String,
    /// `K`: a height map said in the drawing (linuxcnc, grbl); only the compiled path's
    /// counts (a subpath's is not its project's).
    pub heightmap: Option<DrawnHeightmap>,
}

/// `K<step>` or `K<step>+<margin>` of a path start text (mm), checked: step at least
/// `probe::heightmap::MIN_STEP`, margin ≥ 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawnHeightmap {
    pub step: f64,
    pub margin: Option<f64>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct ChainSeg {
    /// Geometry in traversal direction.
    pub geom: Geom,
    pub style: Style,
    pub f: f64,
    pub b: Option<f64>,
    pub d: Option<f64>,
    /// Boxed like `bars`: a chain can have millions of segments, nearly all without.
    pub q: Option<Box<str>>,
    pub bt: bool,
    /// Support-bar pieces along `geom` (BORDER segments long enough for bars).
    pub bars: Option<Box<[Geom]>>,
    pub origin: Origin,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    pub segs: Vec<ChainSeg>,
    pub i: Option<f64>,
    pub w: Option<f64>,
    pub origin: Origin,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Drill {
    pub c: P2,
    pub style: Style,
    pub f: f64,
    pub b: Option<f64>,
    pub d: Option<f64>,
    pub q: Option<String>,
    pub origin: Origin,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Helix {
    pub c: P2,
    pub r: f64,
    pub style: Style,
    pub f: f64,
    pub b: Option<f64>,
    pub d: Option<f64>,
    pub i: Option<f64>,
    pub q: Option<String>,
    /// Support-bar pieces along the milling circle (BORDER helixes).
    pub bars: Option<Vec<Geom>>,
    pub origin: Origin,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    pub a: P2,
    pub b: P2,
    pub s: f64,
    pub bt: bool,
    pub origin: Origin,
}

#[derive(Debug, Clone)]
pub struct Embedding {
    /// Entry and exit of the embedding line in traversal direction.
    pub a: P2,
    pub b: P2,
    pub h: f64,
    pub target: Option<Arc<Model>>,
    pub origin: Origin,
}

#[derive(Debug, Clone)]
pub enum Element {
    Chain(Chain),
    Drill(Drill),
    Helix(Helix),
    Sweep(Sweep),
    Subpath(Embedding),
}

#[derive(Debug, Clone, PartialEq)]
pub struct Probe {
    pub center: P2,
    pub t: f64,
    pub h: f64,
    pub l: Option<String>,
    pub z: f64,
    pub origin: Origin,
}

/// A built path.
#[derive(Debug)]
pub struct Model {
    pub raw: Arc<RawPath>,
    pub vars: Vars,
    pub start: P2,
    pub end: P2,
    pub params: PathParams,
    pub elements: Vec<Element>,
    pub probes: Vec<Probe>,
    /// Errors were reported while building it or a path it embeds: `compile` refuses it, and
    /// so nothing runs its emitter (its values may be missing, negative or absurd).
    pub has_errors: bool,
}

impl Model {
    pub fn name(&self) -> &str {
        &self.raw.name
    }
    /// `name[file]`, as in comments and messages.
    pub fn label(&self) -> String {
        format!("{}[{}]", self.raw.name, self.raw.file.name)
    }
}

/// The transformation of an embedded target in output coordinates.
pub fn sub_transform(target: &Model, emb: &Embedding, outer: &Transform) -> Option<Transform> {
    Transform::between(
        target.start,
        target.end,
        outer.apply(emb.a),
        outer.apply(emb.b),
    )
}
