//! The post's pass events, for a CAM format that names contours instead of moves
//! (`posts/xcam.toml`): a pass is a run of feed moves (plunges, lines and arcs) between
//! rapids; a drill element's plunges are not in one where the post writes drills whole
//! (`drill`). `pass_start` comes before its first move, at that move's start point;
//! `pass_end` before the next rapid (or the program's last retract), with the pass's lowest
//! Z. The G-code posts write nothing for them, and then nothing is tracked.

use crate::emit::pass_state::Open;
use crate::emit::{Emitter, Kind, Shape, Target};
use millpath_post::{Event, Value, Var};

impl Emitter<'_> {
    #[inline]
    fn writes_passes(&self) -> bool {
        self.writes(Event::PassStart) || self.writes(Event::PassEnd)
    }

    /// Before a move of `kind` at `feed` is recorded (the tool at `self.at`): opens a pass
    /// at a cutting move, closes one at any other move.
    #[inline]
    pub(crate) fn pass_before(&mut self, kind: Kind, feed: f64) {
        if !self.writes_passes() {
            return;
        }
        // plunges are cut too, but not a drill element's where the post writes drills whole
        let whole_drill = self.shape == Shape::Drill && self.writes(Event::Drill);
        let cutting = kind == Kind::Mill || (kind == Kind::Drill && !whole_drill);
        match (&self.passes.open, cutting) {
            (None, true) => {
                self.passes.count += 1;
                let number = self.passes.count;
                let at = self.at;
                self.passes.open = Some(Open {
                    number,
                    lowest: at.z,
                    feed,
                });
                let vars = [
                    (Var::X, Value::Num(at.x)),
                    (Var::Y, Value::Num(at.y)),
                    (Var::Z, Value::Num(at.z)),
                    (Var::Pass, Value::Int(number)),
                    (Var::Feed, Value::Num(feed)),
                ];
                self.event_line(Event::PassStart, &vars);
            }
            (Some(_), false) if kind != Kind::Comment => {
                let Some(open) = self.passes.open.take() else {
                    return;
                };
                let top = self.globals.stock_top;
                let vars = [
                    (Var::Pass, Value::Int(open.number)),
                    (Var::Depth, Value::Num(open.lowest)),
                    (Var::CutDepth, Value::Num(top - open.lowest)),
                    (Var::Feed, Value::Num(open.feed)),
                ];
                self.event_line(Event::PassEnd, &vars);
            }
            _ => {}
        }
    }

    /// Where the last move took the tool: the position a pass starts at, its lowest Z.
    #[inline]
    pub(crate) fn pass_moved(&mut self, t: &Target) {
        // only the pass events read where the tool is
        if !self.writes_passes() {
            return;
        }
        self.at = t.end(self.at);
        if let Some(open) = &mut self.passes.open {
            open.lowest = open.lowest.min(self.at.z);
        }
    }
}
