//! Motion primitives (reference-output.md §5): DrillOrPullZ, sweeps, SafeSweep, MillLine and MillArc, and the probe-weighted Z expressions (§12.4).
//!
//! DrillOrPullZ, sweeps, SafeSweep, MillLine, MillArc (reference-output.md §5), probe Z expressions
//! (§12.4); with `probe_split` a line/arc milled in pieces, each corrected at its own start.

use crate::args;
use crate::diag::{Diagnostic, Msg, Origin};
use crate::emit::{bt, probe_split, Emitter, Kind, NamedProbe, Shape, Target};
use crate::geom::{near, Geom, F3, P2, P3};
use crate::machine::Dialect;
use crate::params::fmt_num;
use millpath_post::{Event, Value, Var};
use std::fmt;

impl Emitter<'_> {
    /// `F3(z)`, or with probes `F3(z)(=F3(z)+w*[#n-TH]…)` weighted by the 4 nearest probes.
    pub(crate) fn zexpr(&self, z: f64, xy: P2) -> ZExpr<'_> {
        ZExpr {
            z,
            xy,
            probes: self.probes,
        }
    }

    pub(crate) fn drill_or_pull(&mut self, xy: P2, from: f64, to: f64, th: f64, feed: f64) {
        if near(to, from) {
            return;
        }
        self.comment(4, || format!("DrillOrPullZFromTo {} {}", F3(from), F3(to)));
        if to > th || to > from {
            self.rapid_z(from, to, xy);
        } else {
            if from > th {
                self.rapid_z(from, th, xy);
            }
            if !near(to, th) {
                // the reference writes no F (the modal feed applies); the other dialects the
                // plunge feed, which the statistics then use as well
                let plunge = self.ctl.plunge(feed).unwrap_or(feed);
                let t = |e: &Emitter| {
                    // a post that writes drill elements whole (`drill`) does not write
                    // their plunges again
                    if e.shape == Shape::Drill && e.writes(Event::Drill) {
                        return String::new();
                    }
                    let expr = e.zexpr(to, xy).probe_text();
                    let vars = [
                        (Var::X, Value::Num(xy.x)),
                        (Var::Y, Value::Num(xy.y)),
                        (Var::Z, Value::Num(to)),
                        (Var::ZProbe, Value::Text(&expr)),
                        (Var::Feed, Value::Num(plunge)),
                    ];
                    e.text(Event::Plunge, &vars)
                };
                self.push(Kind::Drill, t, (th - to).abs(), plunge);
                self.to(Target::z(to));
            }
        }
    }

    pub(crate) fn sweep_xy(&mut self, from: P3, to: P3) {
        let d = from.dist(to);
        if !near(d, 0.0) {
            self.move_xy(to.x, to.y, d);
        }
    }

    #[allow(clippy::too_many_arguments)]
    pub(crate) fn safe_sweep(
        &mut self,
        from: P3,
        to: P3,
        th: f64,
        s: f64,
        feed: f64,
        backtrack: bool,
    ) {
        self.comment(2, || {
            format!(
                "SweepAndDrillSafelyFromTo {from} {to} s={} bt={}",
                F3(s),
                bt(backtrack)
            )
        });
        if from.xy().near(to.xy()) {
            self.drill_or_pull(from.xy(), from.z, to.z, th, feed);
        } else {
            self.drill_or_pull(from.xy(), from.z, s, th, feed);
            self.sweep_xy(from.xy().with_z(s), to);
            self.drill_or_pull(to.xy(), s, to.z, th, feed);
        }
        self.pos = to;
    }

    pub(crate) fn mill(
        &mut self,
        g: &Geom,
        from_z: f64,
        to_z: f64,
        th: f64,
        feed: f64,
        backtrack: bool,
    ) {
        self.drill_or_pull(self.pos.xy(), self.pos.z, from_z, th, feed);
        let (a, b) = (g.start(), g.end());
        match *g {
            Geom::Line { .. } => {
                self.comment(2, || {
                    format!(
                        "MillLine s={a} e={b} fr={} to={} bt={}",
                        F3(from_z),
                        F3(to_z),
                        bt(backtrack)
                    )
                });
            }
            Geom::Arc { c, r, a0, a1, .. } => {
                self.comment(2, || {
                    format!(
                        "MillArc l={c} r={} a0={} a1={} fr={} to={} p0={a} p1={b} bt={}",
                        F3(r),
                        F3(a0),
                        F3(a1),
                        F3(from_z),
                        F3(to_z),
                        bt(backtrack)
                    )
                });
            }
        }
        let n = self.split_count(g);
        if n <= 1 {
            self.mill_piece(g, from_z, to_z, feed);
        } else {
            // Z along the move as the whole move ramps it, each piece corrected at its start
            for (k, piece) in probe_split::pieces(g, n).iter().enumerate() {
                if self.full {
                    break;
                }
                let z = if k + 1 == n {
                    to_z
                } else {
                    from_z + (to_z - from_z) * (k + 1) as f64 / n as f64
                };
                let z0 = if k == 0 {
                    from_z
                } else {
                    from_z + (to_z - from_z) * k as f64 / n as f64
                };
                self.mill_piece(piece, z0, z, feed);
            }
            self.split.0 += 1;
            self.split.1 += n;
        }
        self.pos = b.with_z(to_z);
    }

    /// One line or arc along `g` from `from_z` to `to_z`, its Z corrected at `g`'s start
    /// (§12.4). An arc the post writes otherwise ([`Emitter::arc_form`]) goes in pieces.
    pub(crate) fn mill_piece(&mut self, g: &Geom, from_z: f64, to_z: f64, feed: f64) {
        if let Geom::Arc { .. } = g {
            let (n, as_lines) = self.arc_form(g);
            if n > 1 || as_lines {
                let pieces = probe_split::pieces(g, n);
                for (k, piece) in pieces.iter().enumerate() {
                    let z = if k + 1 == n {
                        to_z
                    } else {
                        from_z + (to_z - from_z) * (k + 1) as f64 / n as f64
                    };
                    if as_lines {
                        let line = Geom::Line {
                            a: piece.start(),
                            b: piece.end(),
                        };
                        self.mill_piece(&line, from_z, z, feed);
                    } else {
                        self.mill_piece_as_written(piece, z, feed);
                    }
                }
                return;
            }
        }
        self.mill_piece_as_written(g, to_z, feed);
    }

    /// How the post writes the arc `g`: in how many pieces, and as lines. `lines` (or a
    /// radius beyond `max_arc_radius`): chords within `chord_tolerance`; `r`: at most half a
    /// circle each (R cannot say more); `ij`: whole.
    pub(crate) fn arc_form(&mut self, g: &Geom) -> (usize, bool) {
        let Geom::Arc { r, .. } = *g else {
            return (1, false);
        };
        let f = &self.ctl.post.format;
        let sweep = g.sweep_deg().to_radians();
        let as_lines =
            f.arcs == millpath_post::ArcMode::Lines || f.max_arc_radius.is_some_and(|m| r > m);
        if as_lines {
            let tol = f.chord_tolerance.min(r);
            let step = 2.0 * (1.0 - tol / r).clamp(-1.0, 1.0).acos();
            let n = (sweep / step).ceil();
            if !(n.is_finite() && n <= probe_split::MAX_PIECES as f64) {
                let origin = self
                    .source
                    .and_then(|i| self.sources.get(i as usize).cloned())
                    .unwrap_or(Origin::Options);
                self.errors.push(Diagnostic::error(
                    Msg::PostCannot,
                    origin,
                    args![
                        self.ctl.post.name.clone(),
                        format!("this arc (r={}) in lines", F3(r)),
                        "chord_tolerance"
                    ],
                ));
                self.lost = true;
                return (1, false);
            }
            return ((n as usize).max(1), true);
        }
        if f.arcs == millpath_post::ArcMode::R && g.sweep_deg() > 180.0 - 1e-9 {
            return (2, false);
        }
        (1, false)
    }

    /// One `linear` or arc event along `g` to `to_z`, its Z corrected at `g`'s start.
    fn mill_piece_as_written(&mut self, g: &Geom, to_z: f64, feed: f64) {
        let (a, b) = (g.start(), g.end());
        match *g {
            Geom::Line { .. } => {
                let t = |e: &Emitter| {
                    let expr = e.zexpr(to_z, a).probe_text();
                    let vars = [
                        (Var::X, Value::Num(b.x)),
                        (Var::Y, Value::Num(b.y)),
                        (Var::Z, Value::Num(to_z)),
                        (Var::ZProbe, Value::Text(&expr)),
                        (Var::Feed, Value::Num(feed)),
                    ];
                    e.text(Event::Linear, &vars)
                };
                self.push(Kind::Mill, t, a.dist(b), feed);
                self.to(Target::xyz(b, to_z));
            }
            Geom::Arc { c, r, ccw, .. } => {
                let ij = (Value::Num(c.x - a.x), c.y - a.y);
                self.arc_move(b, c, r, ccw, ij, (to_z, a), feed, g.length());
            }
        }
    }

    /// An arc to `b` around `c` of radius `r`: `ij`, the centre's offsets as
    /// written (I a number, or the helix's whole `0`); `z`: its end height and the point
    /// whose probes correct it.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn arc_move(
        &mut self,
        b: P2,
        c: P2,
        r: f64,
        ccw: bool,
        (i, j): (Value<'static>, f64),
        (to_z, zxy): (f64, P2),
        feed: f64,
        len: f64,
    ) {
        let t = |e: &Emitter| {
            let expr = e.zexpr(to_z, zxy).probe_text();
            // R: negative beyond a half circle (the arc's length against the half's)
            let half = r * std::f64::consts::PI;
            let r_word = if len > half * (1.0 + 1e-9) { -r } else { r };
            let vars = [
                (Var::X, Value::Num(b.x)),
                (Var::Y, Value::Num(b.y)),
                (Var::Z, Value::Num(to_z)),
                (Var::ZProbe, Value::Text(&expr)),
                (Var::Feed, Value::Num(feed)),
                (Var::I, i.clone()),
                (Var::J, Value::Num(j)),
                (Var::R, Value::Num(r_word)),
                (Var::CenterX, Value::Num(c.x)),
                (Var::CenterY, Value::Num(c.y)),
            ];
            e.text(if ccw { Event::ArcCcw } else { Event::ArcCw }, &vars)
        };
        self.push(Kind::Mill, t, len, feed);
        self.to(Target::arc(b, to_z, c, ccw));
    }

    /// Pieces `g` is milled in: more than one only with drawn probes and `probe_split`
    /// outside the reference dialect. A move that would need more than
    /// [`probe_split::MAX_PIECES`] is an error at its element (and milled whole).
    fn split_count(&mut self, g: &Geom) -> usize {
        let Some(l) = self.ctl.probe_split else {
            return 1;
        };
        if self.probes.is_empty() || self.ctl.dialect == Dialect::Reference {
            return 1;
        }
        match probe_split::piece_count(g.length(), l) {
            Ok(n) => n,
            Err(n) => {
                let origin = self
                    .source
                    .and_then(|i| self.sources.get(i as usize).cloned())
                    .unwrap_or(Origin::Options);
                self.errors.push(Diagnostic::error(
                    Msg::ProbeSplitTooManyPieces,
                    origin,
                    args![
                        F3(g.length()),
                        fmt_num(l),
                        fmt_num(n),
                        probe_split::MAX_PIECES
                    ],
                ));
                self.lost = true;
                1
            }
        }
    }
}

/// A Z word's value, written straight into the line (no text of its own).
pub(crate) struct ZExpr<'p> {
    z: f64,
    xy: P2,
    probes: &'p [NamedProbe],
}

impl ZExpr<'_> {
    /// The expression comment after the Z value (`(=1.000+0.500*[#51-0.000]…)`), empty
    /// without probes: the post's `{z_probe}`.
    pub(crate) fn probe_text(&self) -> String {
        if self.probes.is_empty() {
            return String::new();
        }
        let whole = self.to_string();
        let z = F3(self.z).to_string();
        whole[z.len()..].to_string()
    }
}

impl fmt::Display for ZExpr<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let z = F3(self.z);
        if self.probes.is_empty() {
            return write!(f, "{z}");
        }
        let mut weights: Vec<(f64, usize)> = self
            .probes
            .iter()
            .enumerate()
            .map(|(i, p)| (1.0 / (p.placed.pos.dist(self.xy) + 0.001), i))
            .collect();
        // descending, ties keep tour order (stable sort)
        weights.sort_by(|a, b| b.0.partial_cmp(&a.0).unwrap_or(std::cmp::Ordering::Equal));
        weights.truncate(4);
        let sum: f64 = weights.iter().map(|w| w.0).sum();
        write!(f, "{z}(={z}")?;
        for (w, i) in weights {
            let p = &self.probes[i];
            write!(f, "+{}*[{}-{}]", F3(w / sum), p.name, F3(p.placed.height()))?;
        }
        f.write_str(")")
    }
}
