//! The probing program and `_Z.txt` of a height map (`[heightmap]`, linuxcnc and grbl):
//! the grid points in serpentine order, each approached at the sweep height, lowered to
//! T + O as drawn probes are, probed with `G38.2` down to T − `probe_depth`, and left at
//! the sweep height again. LinuxCNC logs the contacts itself (`PROBEOPEN`); GRBL reports
//! each as `[PRB:x,y,z:1]` in the sender's console.
//!
//! A height map's probing set (linuxcnc, grbl): the grid in serpentine order, `G38.2` to T −
//! `probe_depth`, `(PROBEOPEN NAME_probes.txt)` … `(PROBECLOSE)` in linuxcnc
//! (`probe_open`/`probe_close`, drawn probes' program too), `_Z.txt` lines `#1000` ….

use crate::diag::{Diagnostic, Msg};
use crate::emit::dialect::Controller;
use crate::emit::extent::cut_extent;
use crate::emit::{as_comment, Item, NamedProbe};
use crate::geom::{f3, F3, P2};
use crate::machine::Dialect;
use crate::model::Model;
use crate::probe::heightmap::{var_name, Grid, Heightmap};
use millpath_post::{Event, Globals, Value, Var};

/// The probing program's lines (without the set's digest) and the `_Z.txt` lines.
pub(crate) struct GridSet {
    pub probing: Vec<String>,
    pub z_lines: Vec<String>,
}

/// The grid of a height map over the cutting moves in `items`, or why there is none: the
/// reference dialect, drawn probes beside it (both would correct the same Z twice), no
/// cuts, too many points, cuts outside an explicit area. `check` and `compile` both ask.
pub(crate) fn grid_of(
    hm: &Heightmap,
    ctl: &Controller,
    model: &Model,
    items: &[Item],
    drawn: &[NamedProbe],
) -> Result<Grid, Diagnostic> {
    let origin = model.raw.origin();
    if ctl.dialect == Dialect::Reference {
        // Settings refuse this already; a second guard where the program is made
        return Err(Diagnostic::error(
            Msg::HeightmapReferenceDialect,
            origin,
            vec![],
        ));
    }
    if !drawn.is_empty() {
        let names: Vec<&str> = drawn.iter().map(|p| p.name.as_str()).collect();
        let msg = if ctl.heightmap_in_drawing {
            Msg::HeightmapKWithDrawnProbes
        } else {
            Msg::HeightmapWithDrawnProbes
        };
        return Err(Diagnostic::error(
            msg,
            origin,
            crate::args![model.name(), names.join(", ")],
        ));
    }
    let extent = cut_extent(items, P2::default());
    Grid::of_program(hm, extent, model.name(), &origin)
}

/// The post's probe log opening (LinuxCNC's `(PROBEOPEN log_name)`, where the controller
/// writes each probe contact to the file itself; posts without `probe_log` write nothing).
/// Drawn probes and height maps both open their log this way.
pub(crate) fn probe_open(ctl: &Controller, log_name: &str, g: &Globals, out: &mut Vec<String>) {
    if ctl.post.capabilities.probe_log {
        // the name made safe as comment text (the log command is a comment)
        let safe = millpath_post::comment::safe_text(&ctl.post.comments, log_name);
        ctl.lines(
            Event::ProbeLogOpen,
            &[(Var::LogFile, Value::Text(&safe))],
            g,
            out,
        );
    }
}

/// The log's closing where [`probe_open`] opened one.
pub(crate) fn probe_close(ctl: &Controller, g: &Globals, out: &mut Vec<String>) {
    if ctl.post.capabilities.probe_log {
        ctl.lines(Event::ProbeLogClose, &[], g, out);
    }
}

/// The probing set of a height map's `grid`. `log_name` is the file LinuxCNC writes the
/// contacts to (`NAME_probes.txt`).
pub(crate) fn grid_set(
    hm: &Heightmap,
    ctl: &Controller,
    model: &Model,
    grid: &Grid,
    banner: &str,
    file_name: &str,
    log_name: &str,
) -> GridSet {
    let points = grid.serpentine();
    let (s, t, o) = (model.params.s, model.params.t, model.params.o);
    let feed = hm.probe_feed.unwrap_or(model.params.f);
    let g = Controller::globals(model, file_name);
    let mut pl = ctl.prologue(banner, file_name, model, s, false);
    let (lo, hi) = (
        P2 {
            x: grid.xs[0],
            y: grid.ys[0],
        },
        P2 {
            x: grid.xs[grid.xs.len() - 1],
            y: grid.ys[grid.ys.len() - 1],
        },
    );
    // the grid for adjust-z and the checker: millpath's own record, a comment in any post
    let record = format!(
        "MILLPATH-HEIGHTMAP X0={} Y0={} X1={} Y1={} NX={} NY={} STEP={}",
        f3(lo.x),
        f3(lo.y),
        f3(hi.x),
        f3(hi.y),
        grid.xs.len(),
        grid.ys.len(),
        f3(hm.step)
    );
    pl.push(ctl.post.comment(0, &record, &g));
    probe_open(ctl, log_name, &g, &mut pl);
    let mut cur = P2::default();
    for p in &points {
        if p.dist(cur) > 0.0 {
            ctl.rapid_xy(&g, *p, &mut pl);
        }
        cur = *p;
        ctl.rapid_z(&g, Event::RapidZ, t + o, &mut pl);
        let probe = [
            (Var::X, Value::Num(p.x)),
            (Var::Y, Value::Num(p.y)),
            (Var::Z, Value::Num(t - hm.probe_depth)),
            (Var::Feed, Value::Num(feed)),
        ];
        ctl.lines(Event::GridProbe, &probe, &g, &mut pl);
        ctl.rapid_z(&g, Event::Retract, s, &mut pl);
    }
    probe_close(ctl, &g, &mut pl);
    if cur.dist(P2::default()) > 0.0 {
        ctl.rapid_xy(&g, P2::default(), &mut pl);
    }
    ctl.rapid_z(&g, Event::Retract, s, &mut pl);
    pl.extend(ctl.epilogue(false, &g));
    let z_lines = points
        .iter()
        .enumerate()
        .map(|(k, p)| {
            format!(
                "{} {}=",
                as_comment(0, &format!("{p}/T={}", F3(t))),
                var_name(k)
            )
        })
        .collect();
    GridSet {
        probing: pl,
        z_lines,
    }
}
