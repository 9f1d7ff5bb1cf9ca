//! Building the validated model of a path: traversal, chains and elements with their
//! effective parameters, validation, support bars and subpath connection
//! (reference-input.md §4–§6).
//!
//! `build_top`/`build`: elements from the traversal, chains (reference-input.md §5.3), drills,
//! helixes, sweeps, embeddings, probes.

pub mod bars;
mod candidates;
pub mod connect;
pub(crate) mod eval;
pub mod order_choice;
pub mod params;
pub mod traverse;
pub mod traverse_memo;
pub mod validate;
pub mod walk;

use crate::args;
use crate::build::bars::support_bars;
use crate::build::eval::{BuildCtx, Eval};
use crate::build::traverse::traverse_in;
use crate::build::walk::{turn_back_kind, Step};
use crate::diag::{Diagnostic, Msg, Origin};
use crate::front::drawing::{
    RawPath, SegKind, Shape, Style, SweepKind, PATH_KEYS, PATH_KEYS_HEIGHTMAP, PROBE_KEYS,
};
use crate::geom::{absnear, f3, gt, le, Geom, Transform};
use crate::load::session::{Abort, Session};
use crate::model::*;
use crate::params::{check_values, fmt_num, Vars};
use std::sync::Arc;

impl Session<'_> {
    /// Builds (or fetches) the model of a top-level path.
    pub fn build_top(&mut self, name: &str) -> Result<Option<Arc<Model>>, Abort> {
        let vars = if self.settings.check {
            let defs = self
                .raw
                .get(name)
                .and_then(|r| r.start_text.as_ref().map(|t| t.vars.clone()))
                .unwrap_or_default();
            match check_values(&defs) {
                Ok(v) => v,
                Err((msg, a)) => {
                    let origin = self.raw.get(name).map_or(Origin::Input, |r| r.origin());
                    let inner = Diagnostic::error(msg, origin.clone(), a);
                    self.diags.error(
                        Msg::VariableDefinitionError,
                        origin,
                        args![inner.message(self.lang())],
                    );
                    Vars::default()
                }
            }
        } else {
            Vars::default()
        };
        self.build(
            name,
            &vars,
            &BuildCtx {
                depth: 0,
                top: true,
            },
        )
    }

    pub(crate) fn build(
        &mut self,
        name: &str,
        vars: &Vars,
        cx: &BuildCtx,
    ) -> Result<Option<Arc<Model>>, Abort> {
        let key = (name.to_string(), vars.clone());
        if let Some(m) = self.models.get(&key) {
            return Ok(m.clone());
        }
        let Some(raw) = self.raw.get(name).cloned() else {
            return Ok(None);
        };
        let model = self.build_model(raw, vars, cx)?;
        self.models.insert(key, model.clone());
        Ok(model)
    }

    pub(crate) fn build_model(
        &mut self,
        raw: Arc<RawPath>,
        vars: &Vars,
        cx: &BuildCtx,
    ) -> Result<Option<Arc<Model>>, Abort> {
        // its syntax errors are reported; what follows from them would only mislead
        if raw.broken {
            return Ok(None);
        }
        let errors_before = self.diags.errors_reported();
        // 1. markers
        let (Some(start), Some(end)) = (raw.start.clone(), raw.end.clone()) else {
            if raw.start.is_none() {
                self.diags.error(Msg::StartMissing, raw.origin(), vec![]);
            }
            if raw.end.is_none() {
                self.diags.error(Msg::EndMissing, raw.origin(), vec![]);
            }
            return Ok(None);
        };
        // 2. traversal
        let trav = traverse_in(self.traversals, &raw, start.pos, end.pos, &mut self.diags);
        let ev = Eval { vars };
        self.check_self_references(&raw, vars);
        // 4. path parameters
        let params = self.path_params(&raw, &ev, cx);
        let path_text = raw.start_text.as_ref();
        if let Some(t) = path_text {
            let keys = if self.settings.dialect == crate::Dialect::Reference {
                PATH_KEYS
            } else {
                PATH_KEYS_HEIGHTMAP
            };
            self.check_text(t, keys, &raw.start_origin(), &ev);
        }
        self.validate(&raw.start_origin(), &params, path_text, &ev, true);

        // 3. chains and elements
        let mut chain: Option<Chain> = None;
        let mut subpaths = Vec::new();
        // a step of a chain: a milled line or arc
        let chained = |step: &Step| {
            let seg = &raw.segments[step.index];
            let kind = if step.turn_back {
                turn_back_kind(seg.kind)
            } else {
                seg.kind
            };
            matches!((kind, &seg.shape), (SegKind::Mill(_), Shape::Path(_)))
        };
        // the elements counted first (a chain is one): the list is not copied as it grows
        let mut in_chain = false;
        let count = trav
            .iter()
            .filter(|step| {
                let starts = !(in_chain && chained(step));
                in_chain = chained(step);
                starts
            })
            .count();
        let mut elements = Vec::with_capacity(count);
        for (k, step) in trav.iter().enumerate() {
            let seg = &raw.segments[step.index];
            let geom = match &seg.shape {
                Shape::Path(g) => Some(if step.reversed { g.reversed() } else { *g }),
                Shape::Circle { .. } => None,
            };
            let kind = if step.turn_back {
                turn_back_kind(seg.kind)
            } else {
                seg.kind
            };
            if let (SegKind::Mill(style), Some(g)) = (kind, geom) {
                let first = chain.is_none();
                if first {
                    let (i, w) = self.chain_params(seg, &params, &ev);
                    // its length at once: a chain of a million segments is not copied as
                    // it grows
                    let run = trav[k..].iter().take_while(|s| chained(s)).count();
                    chain = Some(Chain {
                        segs: Vec::with_capacity(run),
                        i,
                        w,
                        origin: seg.origin.clone(),
                    });
                }
                let cs = self.chain_seg(seg, style, g, &params, &ev, first)?;
                if let Some(c) = chain.as_mut() {
                    c.segs.push(cs);
                }
                continue;
            }
            if let Some(c) = chain.take() {
                elements.push(Element::Chain(c));
            }
            let text = if step.turn_back {
                None
            } else {
                seg.text.as_deref()
            };
            match (kind, &seg.shape) {
                (SegKind::Drill(style), Shape::Circle { c, .. }) => {
                    if let Some(t) = text {
                        self.check_text(t, kind.allowed_keys(), &seg.origin, &ev);
                    }
                    elements.push(Element::Drill(Drill {
                        c: *c,
                        style,
                        f: ev.num(text, 'F').unwrap_or(params.f),
                        b: ev.num(text, 'B').or(params.b),
                        d: ev.num(text, 'D').or(params.d),
                        q: ev.string(text, 'Q'),
                        origin: seg.origin.clone(),
                    }));
                    self.validate_child(&seg.origin, text, &params, &ev);
                }
                (SegKind::Helix(style), Shape::Circle { c, r }) => {
                    if let Some(t) = text {
                        self.check_text(t, kind.allowed_keys(), &seg.origin, &ev);
                    }
                    if gt(2.0 * r, params.a) {
                        self.diags.error(
                            Msg::HelixTooLarge,
                            seg.origin.clone(),
                            args![f3(2.0 * r), fmt_num(params.a)],
                        );
                    }
                    let b = ev.num(text, 'B').or(params.b);
                    let d = ev.num(text, 'D').or(params.d);
                    let bars = if style == Style::Support {
                        let circle = Geom::Arc {
                            c: *c,
                            r: r - params.o / 2.0,
                            a0: 270.0,
                            a1: 270.0 * (1.0 + 1e-6),
                            ccw: false,
                        };
                        let p = ev.num(text, 'P').or(params.p);
                        let u = ev.num(text, 'U').or(params.u);
                        support_bars(&circle, params.o, p, u, b, d, &seg.origin)?
                    } else {
                        None
                    };
                    elements.push(Element::Helix(Helix {
                        c: *c,
                        r: *r,
                        style,
                        f: ev.num(text, 'F').unwrap_or(params.f),
                        b,
                        d,
                        i: ev.num(text, 'I').or(params.i),
                        q: ev.string(text, 'Q'),
                        bars,
                        origin: seg.origin.clone(),
                    }));
                    self.validate_child(&seg.origin, text, &params, &ev);
                }
                (SegKind::Sweep(sk), _) => {
                    let g = geom.unwrap_or(Geom::Line {
                        a: seg.shape.start(),
                        b: seg.shape.end(),
                    });
                    let text = if sk == SweepKind::Dashed { text } else { None };
                    if let Some(t) = text {
                        self.check_text(t, kind.allowed_keys(), &seg.origin, &ev);
                    }
                    let s = ev.num(text, 'S').unwrap_or(params.s);
                    if text.is_some_and(|t| t.has('S')) && le(s, params.t) {
                        self.diags.error(
                            Msg::SNotAboveT,
                            seg.origin.clone(),
                            args![fmt_num(s), fmt_num(params.t)],
                        );
                    }
                    elements.push(Element::Sweep(Sweep {
                        a: g.start(),
                        b: g.end(),
                        s,
                        bt: !step.turn_back && seg.backtrack(),
                        origin: seg.origin.clone(),
                    }));
                }
                (SegKind::Subpath, _) => {
                    let g = geom.unwrap_or(Geom::Line {
                        a: seg.shape.start(),
                        b: seg.shape.end(),
                    });
                    if let Some(t) = text {
                        self.check_text(t, kind.allowed_keys(), &seg.origin, &ev);
                    }
                    subpaths.push((elements.len(), step.index));
                    elements.push(Element::Subpath(Embedding {
                        a: g.start(),
                        b: g.end(),
                        h: ev.num(text, 'H').unwrap_or(0.0),
                        target: None,
                        origin: seg.origin.clone(),
                    }));
                }
                _ => {}
            }
        }
        if let Some(c) = chain.take() {
            elements.push(Element::Chain(c));
        }

        // probes
        let mut probes = Vec::new();
        for p in &raw.probes {
            let text = p.text.as_ref();
            if let Some(t) = text {
                self.check_text(t, PROBE_KEYS, &p.origin, &ev);
            }
            probes.push(Probe {
                center: p.center,
                t: ev.num(text, 'T').unwrap_or(params.t),
                h: ev.num(text, 'H').unwrap_or(0.0),
                l: ev.string(text, 'L'),
                z: ev.num(text, 'Z').unwrap_or(params.z),
                origin: p.origin.clone(),
            });
        }

        // 5. subpaths
        for (ei, si) in subpaths {
            let seg = &raw.segments[si];
            let target = self.connect(&raw, seg, &params, &ev, cx)?;
            if let Element::Subpath(emb) = &mut elements[ei] {
                if let Some(t) = &target {
                    let size = emb.a.dist(emb.b);
                    let tsize = t.start.dist(t.end);
                    if !absnear(size, tsize, 1e-3) {
                        let d = Diagnostic::error(
                            Msg::SizeMismatch,
                            emb.origin.clone(),
                            args![f3(size), t.label(), f3(tsize)],
                        )
                        .with_related(t.raw.start_origin(), "start of the referenced path");
                        self.diags.push(d);
                    } else if Transform::between(t.start, t.end, emb.a, emb.b).is_none() {
                        self.diags
                            .error(Msg::CannotPlace, emb.origin.clone(), args![t.label()]);
                    }
                }
                emb.target = target;
            }
        }

        let embeds_errors = elements.iter().any(|e| match e {
            Element::Subpath(emb) => emb.target.as_ref().is_some_and(|t| t.has_errors),
            _ => false,
        });
        Ok(Some(Arc::new(Model {
            // not its segments: a drawing released after building is then freed
            raw: Arc::new(raw.head()),
            vars: vars.clone(),
            start: start.pos,
            end: end.pos,
            params,
            elements,
            probes,
            has_errors: embeds_errors || self.diags.errors_reported() > errors_before,
        })))
    }
}
