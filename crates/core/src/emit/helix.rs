//! Helixes: semicircles down to the bottom, bars, pull-up and return to the centre (reference-output.md §9.2).

use crate::emit::{bounded_passes, missing, Emitter, Frame, Skip};
use crate::front::drawing::Style;
use crate::geom::{gt, le, Geom, Transform, F3, P2, P3};
use crate::model::*;
use millpath_post::Value;

impl Emitter<'_> {
    pub(crate) fn helix(&mut self, fr: Frame, hx: &Helix) -> Result<(), Skip> {
        let p = &fr.model.params;
        let h = fr.h;
        let c = fr.t.apply(hx.c);
        let th = h + p.t;
        let (key, depth) = if hx.style == Style::Mill {
            ("B", hx.b)
        } else {
            ("D", hx.d)
        };
        let bottom = h + depth.ok_or_else(|| missing(key, &hx.origin))?;
        let infeed = hx.i.ok_or_else(|| missing("I", &hx.origin))?;
        bounded_passes(th, bottom, infeed, &hx.origin)?;
        let r1 = hx.r - p.o / 2.0;
        self.drill_or_pull(self.pos.xy(), self.pos.z, th + p.o, th, hx.f);
        if let Some(q) = &hx.q {
            self.comment(4, || format!("Q:{q}"));
        }
        self.comment(2, || format!("MillHelix l={c} r={}", F3(hx.r)));
        self.move_xy(c.x, c.y - r1, r1);
        let (mut d, mut done) = (th, th);
        let mut z = self.pos.z;
        let half = r1 * std::f64::consts::PI;
        while gt(done, bottom) && !self.full {
            self.comment(4, || format!("MillSemiCircle l={}", F3(d)));
            let b1 = (d - infeed / 2.0).max(bottom);
            // the semicircles' centre is straight above or below their start: `I0`
            let (south, north) = (P2::new(c.x, c.y - r1), P2::new(c.x, c.y + r1));
            if !self.semicircle_in_pieces(c, r1, 270.0, z, b1, hx.f) {
                let ij = (Value::Int(0), r1);
                self.arc_move(north, c, r1, false, ij, (b1, c), hx.f, half);
            }
            let b0 = (b1 - infeed / 2.0).max(bottom);
            if !self.semicircle_in_pieces(c, r1, 90.0, b1, b0, hx.f) {
                let ij = (Value::Int(0), -r1);
                self.arc_move(south, c, r1, false, ij, (b0, c), hx.f, half);
            }
            z = b0;
            done = d;
            d -= infeed;
        }
        self.pos = P3 {
            x: c.x,
            y: c.y - r1,
            z,
        };
        if let (Style::Support, Some(pieces)) = (hx.style, &hx.bars) {
            let b = hx.b.ok_or_else(|| missing("B", &hx.origin))?;
            let dd = hx.d.ok_or_else(|| missing("D", &hx.origin))?;
            // the semicircles end at the circle's south point in output coordinates, where
            // the profile must begin: its pieces move with a subpath but do not turn with it
            // (deliberate difference: turned, the first arc began away from the tool, an arc
            // whose radius differs at its ends; found by fuzzing)
            let shift = Transform {
                from_start: hx.c,
                from_end: hx.c,
                to_start: c,
                to_end: c,
                angle: 0.0,
            };
            let pieces: Vec<Geom> = pieces.iter().map(|g| g.transform(&shift)).collect();
            while gt(done, h + b) && !self.full {
                let z = (done - infeed).max(h + b);
                // deliberate difference: bar depths are raised by h like everything else
                self.profile(&pieces, true, z, h + b, h + dd, th, hx.f, false);
                done = z;
            }
        }
        if le(hx.r, p.o) {
            self.move_xy(c.x, c.y, r1);
            self.pos = c.with_z(self.pos.z);
        } else {
            // deliberate difference: the pull-up height is raised by h as well
            let s = h + p.s;
            self.rapid_z_len(done, s, c, s - done);
            self.move_xy(c.x, c.y, r1);
            self.pos = c.with_z(s);
        }
        Ok(())
    }
}

impl Emitter<'_> {
    /// A clockwise half circle of the helix from angle `from_deg` where the post writes such
    /// an arc in pieces or as lines (`arc_form`): milled so, `true`; else `false` (the caller
    /// writes it whole, as the reference does).
    fn semicircle_in_pieces(
        &mut self,
        c: P2,
        r: f64,
        from_deg: f64,
        z0: f64,
        z1: f64,
        feed: f64,
    ) -> bool {
        let semi = Geom::Arc {
            c,
            r,
            a0: from_deg,
            a1: from_deg + 180.0,
            ccw: false,
        };
        let (n, as_lines) = self.arc_form(&semi);
        if n > 1 || as_lines {
            self.mill_piece(&semi, z0, z1, feed);
            return true;
        }
        false
    }
}
