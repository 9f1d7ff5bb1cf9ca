//! What the emitter records of each line besides its text: the kind of move, its length,
//! feed and target, its source element and what it makes. The statistics, the time model,
//! the height map's extent and the toolpath view read these.

use crate::geom::{P2, P3};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// `G00 X… Y…`
    HSweep,
    /// `G00 Z…`
    VSweep,
    Mill,
    Drill,
    Comment,
}

/// What a cutting move makes (after the element it belongs to), for the toolpath view.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Shape {
    #[default]
    Mill,
    Mark,
    Bars,
    Drill,
    Helix,
}

impl Shape {
    pub fn name(self) -> &'static str {
        match self {
            Shape::Mill => "mill",
            Shape::Mark => "mark",
            Shape::Bars => "bars",
            Shape::Drill => "drill",
            Shape::Helix => "helix",
        }
    }
}

#[derive(Debug, Clone)]
pub struct Item {
    pub kind: Kind,
    pub len: f64,
    pub feed: f64,
    /// Where a move goes (axes it does not name stay); for the toolpath view.
    pub target: Target,
    /// Index into the emitter's element origins (for chains: the segment's).
    pub source: Option<u32>,
    /// What the move makes (cuts only; sweeps are rapids whatever this says).
    pub shape: Shape,
}

/// The end of a move: the axes it sets, and for arcs the centre and direction.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Target {
    pub x: Option<f64>,
    pub y: Option<f64>,
    pub z: Option<f64>,
    pub arc: Option<(P2, bool)>,
}

impl Target {
    /// Where a move from `from` ends: the axes it names, the others staying.
    pub fn end(&self, from: P3) -> P3 {
        P3 {
            x: self.x.unwrap_or(from.x),
            y: self.y.unwrap_or(from.y),
            z: self.z.unwrap_or(from.z),
        }
    }

    pub(crate) fn z(z: f64) -> Target {
        Target {
            z: Some(z),
            ..Default::default()
        }
    }
    pub(crate) fn xy(x: f64, y: f64) -> Target {
        Target {
            x: Some(x),
            y: Some(y),
            ..Default::default()
        }
    }
    pub(crate) fn xyz(p: P2, z: f64) -> Target {
        Target {
            x: Some(p.x),
            y: Some(p.y),
            z: Some(z),
            arc: None,
        }
    }
    pub(crate) fn arc(p: P2, z: f64, c: P2, ccw: bool) -> Target {
        Target {
            arc: Some((c, ccw)),
            ..Target::xyz(p, z)
        }
    }
}
