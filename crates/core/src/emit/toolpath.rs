//! The moves of a program as the machine makes them, for the toolpath view: one move per
//! G-code line that moves, with what it makes, its source segment, its line in the written
//! program and its time in the statistics' model.
//!
//! The moves as the machine makes them, for the toolpath view: one per G-code move (after the
//! optimizer) with what it makes (`Shape`: mill/mark/bars/drill/helix, set by the emitter per
//! element and segment), its segment's source, its line in the written program, feed and time
//! (`timing::item_times` or the reference's length / F · 1.4).

use crate::diag::{Diagnostic, Origin};
use crate::emit::stats::Stats;
use crate::emit::Kind;
use crate::emit::{emit_until, Controller};
use crate::geom::{P2, P3};
use crate::model::*;

/// One move of the toolpath view.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// `rapid`, or what the cut makes: `mill`, `mark`, `bars`, `drill`, `helix`.
    pub kind: &'static str,
    pub from: P3,
    pub to: P3,
    /// Centre and direction (counter-clockwise?) of arcs.
    pub arc: Option<(P2, bool)>,
    /// The element (for chains: the segment) the move comes from.
    pub source: Option<Origin>,
    /// Its line (1-based) in the milling program (the clean program when there are probes).
    pub line: usize,
    /// Feed in mm/min (rapids: the sweep speed of the time estimate).
    pub feed: f64,
    /// Its time in seconds as the statistics estimate it.
    pub seconds: f64,
    /// The text of its line.
    pub gcode: String,
}

/// A probe of the probing program: name, position and the height it touches at.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbePoint {
    pub name: String,
    pub pos: P2,
    pub z: f64,
}

/// The moves of a path as the machine makes them (after the optimizer), its probes and
/// statistics.
#[derive(Debug, Clone, PartialEq)]
pub struct Toolpath {
    pub moves: Vec<Move>,
    pub probes: Vec<ProbePoint>,
    /// The probe grid of `[heightmap]` (its points probed at the nominal top), when the
    /// program has one.
    pub heightmap: Option<crate::probe::heightmap::Grid>,
    /// Where the program starts (above the origin at the start height).
    pub start: P3,
    pub stats: Stats,
}

/// The toolpath of a top-level model as `ctl` writes it, with the times of the statistics
/// (`sweep_speed` in mm/min for the reference's model).
pub fn toolpath(
    model: &Model,
    ctl: &Controller,
    sweep_speed: f64,
) -> Result<Toolpath, Vec<Diagnostic>> {
    toolpath_until(model, ctl, sweep_speed, None)
}

/// [`toolpath`] that gives up when `stop()` turns true (`Err` without diagnostics then).
pub fn toolpath_until(
    model: &Model,
    ctl: &Controller,
    sweep_speed: f64,
    stop: Option<&dyn Fn() -> bool>,
) -> Result<Toolpath, Vec<Diagnostic>> {
    let e = emit_until(model, false, ctl, stop)?;
    let start = P3 {
        x: 0.0,
        y: 0.0,
        z: e.sx,
    };
    let mut stats = Stats::timed(&e.rec.items, sweep_speed, start, ctl.machine.as_ref());
    stats.split = e.split;
    let planned = ctl
        .machine
        .as_ref()
        .map(|m| m.item_times(&e.rec.items, start));
    // the body follows the prologue (as `generate` writes it)
    let first_line = ctl.prologue("", "", model, e.sx, true).len() + 1;
    let mut pos = start;
    let mut moves = Vec::new();
    // each move's text: its line of the emitted text (lines in order, so one walk)
    let mut texts = e.rec.text.split('\n');
    let mut next_line = 0usize;
    for (i, it) in e.rec.items.iter().enumerate() {
        let line = e.rec.item_lines[i] as usize;
        let gcode = texts
            .nth(line.saturating_sub(next_line))
            .unwrap_or_default()
            .to_string();
        next_line = line + 1;
        let rapid = matches!(it.kind, Kind::HSweep | Kind::VSweep);
        let kind = match it.kind {
            Kind::Comment => continue,
            _ if rapid => "rapid",
            _ => it.shape.name(),
        };
        let t = it.target;
        let to = P3 {
            x: t.x.unwrap_or(pos.x),
            y: t.y.unwrap_or(pos.y),
            z: t.z.unwrap_or(pos.z),
        };
        let feed = if rapid { sweep_speed } else { it.feed };
        let seconds = match &planned {
            Some(times) => times[i],
            // the reference's model: length / F · 1.4
            None if feed > 0.0 => it.len / feed * 1.4 * 60.0,
            None => 0.0,
        };
        moves.push(Move {
            kind,
            from: pos,
            to,
            arc: t.arc,
            source: it.source.and_then(|k| e.sources.get(k as usize).cloned()),
            line: first_line + line,
            feed,
            seconds,
            gcode,
        });
        pos = to;
    }
    let probes = e
        .probes
        .iter()
        .map(|p| ProbePoint {
            name: p.name.clone(),
            pos: p.placed.pos,
            z: p.placed.height(),
        })
        .collect();
    // the grid as compile makes it; a refused one (check says why) is not shown
    let heightmap = ctl.heightmap.as_ref().and_then(|hm| {
        let drawn = &e.probes;
        crate::emit::heightmap_program::grid_of(hm, ctl, model, &e.rec.items, drawn).ok()
    });
    Ok(Toolpath {
        moves,
        probes,
        heightmap,
        start,
        stats,
    })
}
