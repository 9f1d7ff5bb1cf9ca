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
use crate::emit::comment::comment_line;
use crate::emit::dialect::Controller;
use crate::emit::extent::cut_extent;
use crate::emit::{as_comment, Item, NamedProbe};
use crate::geom::{f3, F3, P2};
use crate::machine::Dialect;
use crate::model::Model;
use crate::probe::heightmap::{var_name, Grid, Heightmap};

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

/// `(PROBEOPEN log_name)` in linuxcnc, where LinuxCNC writes each probe contact to the
/// file itself (nothing elsewhere: GRBL and the reference have no such command). Drawn
/// probes and height maps both open their log this way.
pub(crate) fn probe_open(ctl: &Controller, log_name: &str) -> Option<String> {
    (ctl.dialect == Dialect::LinuxCnc).then(|| {
        // the name made safe as comment text, then the active word LinuxCNC acts on
        let safe = comment_line(ctl.dialect, 0, log_name);
        let safe = safe.trim_start_matches('(').trim_end_matches(')');
        format!("(PROBEOPEN {safe})")
    })
}

/// `(PROBECLOSE)` where [`probe_open`] opened a log.
pub(crate) fn probe_close(ctl: &Controller) -> Option<String> {
    (ctl.dialect == Dialect::LinuxCnc).then(|| "(PROBECLOSE)".to_string())
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
    pl.push(format!(
        "(MILLPATH-HEIGHTMAP X0={} Y0={} X1={} Y1={} NX={} NY={} STEP={})",
        f3(lo.x),
        f3(lo.y),
        f3(hi.x),
        f3(hi.y),
        grid.xs.len(),
        grid.ys.len(),
        f3(hm.step)
    ));
    pl.extend(probe_open(ctl, log_name));
    let mut cur = P2::default();
    for p in &points {
        if p.dist(cur) > 0.0 {
            pl.push(format!("G00 X{} Y{}", F3(p.x), F3(p.y)));
        }
        cur = *p;
        pl.push(format!("G00 Z{}", F3(t + o)));
        pl.push(format!("G38.2 Z{} F{}", F3(t - hm.probe_depth), F3(feed)));
        pl.push(format!("G00 Z{}", F3(s)));
    }
    pl.extend(probe_close(ctl));
    if cur.dist(P2::default()) > 0.0 {
        pl.push("G00 X0.000 Y0.000".into());
    }
    pl.push(format!("G00 Z{}", F3(s)));
    pl.extend(ctl.epilogue(false));
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
