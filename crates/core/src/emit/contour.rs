//! The post's contour events: `contour_start` before each element (with its kind, path name,
//! whether a chain is closed, infeed, depth, feed and the ends of its first and last
//! segment in output coordinates) and `contour_end` after it. The built-in posts write
//! nothing for them; a post that does gets lines that are no moves (like comments). The
//! `drill` event (xcam's `B`) comes before a drill element that cuts.

use crate::emit::{Emitter, Frame};
use crate::front::drawing::Style;
use crate::geom::near;
use crate::model::{Drill, Element};
use millpath_post::{Event, Value, Var};

fn kind(e: &Element) -> &'static str {
    match e {
        Element::Chain(_) => "chain",
        Element::Drill(_) => "drill",
        Element::Helix(_) => "helix",
        Element::Sweep(_) => "sweep",
        Element::Subpath(_) => "subpath",
    }
}

impl Emitter<'_> {
    /// A line of the post that is no move (nothing in a dry run or for an empty template).
    pub(crate) fn event_line(&mut self, event: Event, vars: &[(Var, Value)]) {
        if !self.writes(event) {
            return;
        }
        let text = if self.dry {
            String::new()
        } else {
            self.text(event, vars)
        };
        let source = self.source.unwrap_or(crate::emit::NO_SOURCE);
        self.rec.comment(text, source);
    }

    pub(crate) fn contour_start(&mut self, fr: Frame, e: &Element) {
        if let Element::Drill(d) = e {
            self.drill_event(fr, d);
        }
        if !self.writes(Event::ContourStart) {
            return;
        }
        let h = fr.h;
        let (mut closed, mut infeed, mut depth, mut feed) = (false, None, None, None);
        let (mut first, mut last) = (None, None);
        let pick = |style: Style, b: Option<f64>, d: Option<f64>| match style {
            Style::Mark => d,
            _ => b,
        };
        match e {
            Element::Chain(c) => {
                if let (Some(a), Some(z)) = (c.segs.first(), c.segs.last()) {
                    let (s, t) = (fr.t.apply(a.geom.start()), fr.t.apply(z.geom.end()));
                    closed = near(s.dist(t), 0.0);
                    first = Some(s);
                    last = Some(t);
                    feed = Some(a.f);
                    depth = c
                        .segs
                        .iter()
                        .filter_map(|s| pick(s.style, s.b, s.d))
                        .reduce(f64::min);
                }
                infeed = c.i;
            }
            Element::Drill(d) => {
                first = Some(fr.t.apply(d.c));
                last = first;
                feed = Some(d.f);
                depth = pick(d.style, d.b, d.d);
            }
            Element::Helix(x) => {
                first = Some(fr.t.apply(x.c));
                last = first;
                feed = Some(x.f);
                infeed = x.i;
                depth = pick(x.style, x.b, x.d);
                closed = true;
            }
            Element::Sweep(_) | Element::Subpath(_) => {}
        }
        let top = h + fr.model.params.t;
        let count = match (infeed, depth) {
            (Some(i), Some(d)) if i > 0.0 => ((top - (h + d)) / i).ceil().clamp(1.0, 1e4) as i64,
            _ => 1,
        };
        let num = |v: Option<f64>| Value::Num(v.unwrap_or(0.0));
        let vars = [
            (Var::Element, Value::Text(kind(e))),
            (Var::Name, Value::Text(fr.model.name())),
            (Var::ClosedContour, Value::Int(closed as i64)),
            (Var::InfeedDepth, num(infeed)),
            (Var::InfeedCount, Value::Int(count)),
            (Var::Depth, Value::Num(h + depth.unwrap_or(0.0))),
            (Var::Feed, num(feed)),
            (Var::FirstX, num(first.map(|p| p.x))),
            (Var::FirstY, num(first.map(|p| p.y))),
            (Var::LastX, num(last.map(|p| p.x))),
            (Var::LastY, num(last.map(|p| p.y))),
        ];
        self.event_line(Event::ContourStart, &vars);
    }

    /// The post's `drill` event: a drill that cuts (its depth below the stock top), at its
    /// point, from the top down to its depth.
    fn drill_event(&mut self, fr: Frame, d: &Drill) {
        if !self.writes(Event::Drill) {
            return;
        }
        let Some(depth) = (match d.style {
            Style::Mark => d.d,
            _ => d.b,
        }) else {
            return;
        };
        let (top, bottom) = (fr.h + fr.model.params.t, fr.h + depth);
        if bottom > top || near(bottom, top) {
            return;
        }
        let c = fr.t.apply(d.c);
        let vars = [
            (Var::X, Value::Num(c.x)),
            (Var::Y, Value::Num(c.y)),
            (Var::Z, Value::Num(top)),
            (Var::Depth, Value::Num(bottom)),
            (Var::CutDepth, Value::Num(top - bottom)),
            (Var::Feed, Value::Num(d.f)),
        ];
        self.event_line(Event::Drill, &vars);
    }

    pub(crate) fn contour_end(&mut self, fr: Frame, e: &Element) {
        let vars = [
            (Var::Element, Value::Text(kind(e))),
            (Var::Name, Value::Text(fr.model.name())),
        ];
        self.event_line(Event::ContourEnd, &vars);
    }
}
