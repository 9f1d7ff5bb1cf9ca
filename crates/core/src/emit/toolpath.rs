//! The moves of a program as the machine makes them, for the toolpath view.

use crate::diag::{Diagnostic, Origin};
use crate::emit::Kind;
use crate::emit::{emit, Controller};
use crate::geom::{P2, P3};
use crate::model::*;

/// One move of the toolpath view.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// `rapid`, `mill` or `drill`.
    pub kind: &'static str,
    pub from: P3,
    pub to: P3,
    /// Centre and direction (counter-clockwise?) of arcs.
    pub arc: Option<(P2, bool)>,
    /// The element the move comes from.
    pub source: Option<Origin>,
}

/// The moves of a path as the machine makes them (after the optimizer), and its probes.
#[derive(Debug, Clone, PartialEq)]
pub struct Toolpath {
    pub moves: Vec<Move>,
    pub probes: Vec<(String, P2)>,
}

/// The toolpath of a top-level model.
pub fn toolpath(model: &Model) -> Result<Toolpath, Vec<Diagnostic>> {
    let e = emit(model, true, &Controller::reference())?;
    let mut pos = P3 {
        x: 0.0,
        y: 0.0,
        z: e.sx,
    };
    let mut moves = Vec::new();
    for it in &e.items {
        let kind = match it.kind {
            Kind::HSweep | Kind::VSweep => "rapid",
            Kind::Mill => "mill",
            Kind::Drill => "drill",
            Kind::Comment => continue,
        };
        let t = it.target;
        let to = P3 {
            x: t.x.unwrap_or(pos.x),
            y: t.y.unwrap_or(pos.y),
            z: t.z.unwrap_or(pos.z),
        };
        let source = it.source.and_then(|i| e.sources.get(i as usize).cloned());
        moves.push(Move {
            kind,
            from: pos,
            to,
            arc: t.arc,
            source,
        });
        pos = to;
    }
    let probes = e
        .probes
        .iter()
        .map(|p| (p.name.clone(), p.placed.pos))
        .collect();
    Ok(Toolpath { moves, probes })
}
