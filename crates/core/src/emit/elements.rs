//! Subpath embeddings (reference-output.md §11), sweep elements (§10) and drills (§9.1).

use crate::args;
use crate::diag::{Diagnostic, Msg};
use crate::emit::{missing, Emitter, Frame, Skip};
use crate::front::drawing::Style;
use crate::model::*;

impl Emitter<'_> {
    pub(crate) fn subpath(&mut self, fr: Frame, emb: &Embedding) {
        let Some(target) = &emb.target else { return };
        let Some(t) = sub_transform(target, emb, &fr.t) else {
            return;
        };
        let label = format!("{} t={}", target.label(), t.describe());
        self.comment(2, || format!("START Subpath {label}"));
        self.emit_model(Frame {
            model: target,
            t,
            h: fr.h + emb.h,
        });
        self.comment(2, || format!("END Subpath {label}"));
    }

    pub(crate) fn sweep(&mut self, fr: Frame, s: &Sweep) -> Result<(), Skip> {
        let (a, b) = (fr.t.apply(s.a), fr.t.apply(s.b));
        if self.lost {
            self.pos = a.with_z(self.pos.z);
            self.lost = false;
        } else if !self.pos.xy().assert_near(a) {
            return Err(Diagnostic::error(
                Msg::NotNear,
                s.origin.clone(),
                args![a, self.pos.xy()],
            ));
        }
        let p = &fr.model.params;
        let height = fr.h + s.s;
        self.safe_sweep(self.pos, b.with_z(height), fr.h + p.t, height, p.f, s.bt);
        Ok(())
    }

    pub(crate) fn drill(&mut self, fr: Frame, d: &Drill) -> Result<(), Skip> {
        let p = &fr.model.params;
        let c = fr.t.apply(d.c);
        let (key, depth) = if d.style == Style::Mark {
            ("D", d.d)
        } else {
            ("B", d.b)
        };
        let depth = depth.ok_or_else(|| missing(key, &d.origin))?;
        self.comment(2, || format!("Drill l={c}"));
        if let Some(q) = &d.q {
            self.comment(4, || format!("Q:{q}"));
        }
        self.drill_or_pull(c, self.pos.z, fr.h + depth, fr.h + p.t, d.f);
        self.pos.z = fr.h + depth;
        Ok(())
    }
}
