//! Range checks of parameter values (reference-input.md §4.3) and self-referencing variables.

use crate::args;
use crate::build::eval::Eval;
use crate::diag::{Diags, Msg, Origin};
use crate::front::drawing::RawPath;
use crate::geom::{ge, le};
use crate::load::session::Session;
use crate::model::*;
use crate::params::{feed_too_small, fmt_num, ParamText, Vars};

impl Session<'_> {
    pub(crate) fn check_self_references(&mut self, raw: &RawPath, vars: &Vars) {
        for (name, value) in &vars.0 {
            if vars.interpolate(&format!("={name}")).is_err() {
                self.diags
                    .error(Msg::SelfReference, raw.start_origin(), args![name, value]);
            }
        }
    }

    /// Range checks of a path (§4.3, all values) .
    pub(crate) fn validate(
        &mut self,
        origin: &Origin,
        p: &PathParams,
        _text: Option<&ParamText>,
        _ev: &Eval,
        _path: bool,
    ) {
        let d = &mut self.diags;
        let pos = |d: &mut Diags, key: &str, v: f64| {
            if le(v, 0.0) {
                d.error(Msg::MustBePositive, origin.clone(), args![key, fmt_num(v)]);
            }
        };
        pos(d, "F", p.f);
        for (key, v) in [("F", p.f), ("Z", p.z)] {
            if let Some(e) = feed_too_small(key, v, origin) {
                d.push(e);
            }
        }
        if let Some(i) = p.i {
            pos(d, "I", i);
        }
        if let Some(c) = p.c {
            if c <= 0 {
                d.error(Msg::MustBePositive, origin.clone(), args!["C", c]);
            }
        }
        pos(d, "V", p.v);
        pos(d, "O", p.o);
        pos(d, "T", p.t);
        if le(p.s, p.t) {
            d.error(
                Msg::SNotAboveT,
                origin.clone(),
                args![fmt_num(p.s), fmt_num(p.t)],
            );
        }
        if let Some(b) = p.b {
            if ge(b, p.t) {
                d.error(
                    Msg::BAboveT,
                    origin.clone(),
                    args![fmt_num(b), fmt_num(p.t)],
                );
            }
        }
        if let Some(dd) = p.d {
            if ge(dd, p.t) {
                d.error(
                    Msg::DAboveT,
                    origin.clone(),
                    args![fmt_num(dd), fmt_num(p.t)],
                );
            }
        }
        pos(d, "A", p.a);
        if let Some(w) = p.w {
            pos(d, "W", w);
        }
        if let (Some(b), Some(dd)) = (p.b, p.d) {
            if ge(b, dd) {
                d.error(
                    Msg::DNotAboveB,
                    origin.clone(),
                    args![fmt_num(dd), fmt_num(b)],
                );
            }
        }
        if let Some(pp) = p.p {
            pos(d, "P", pp);
        }
        if let Some(u) = p.u {
            pos(d, "U", u);
        }
    }

    /// Range checks of an element's own values against the path's T.
    pub(crate) fn validate_child(
        &mut self,
        origin: &Origin,
        text: Option<&ParamText>,
        p: &PathParams,
        ev: &Eval,
    ) {
        let Some(t) = text else { return };
        if let Some(f) = ev.num(text, 'F') {
            if le(f, 0.0) {
                self.diags
                    .error(Msg::MustBePositive, origin.clone(), args!["F", fmt_num(f)]);
            }
            if let Some(e) = feed_too_small("F", f, origin) {
                self.diags.push(e);
            }
        }
        if t.has('I') {
            if let Some(i) = ev.num(text, 'I').filter(|i| le(*i, 0.0)) {
                self.diags
                    .error(Msg::MustBePositive, origin.clone(), args!["I", fmt_num(i)]);
            }
        }
        if let Some(b) = ev.num(text, 'B') {
            if ge(b, p.t) {
                self.diags.error(
                    Msg::BAboveT,
                    origin.clone(),
                    args![fmt_num(b), fmt_num(p.t)],
                );
            }
        }
        if let Some(d) = ev.num(text, 'D') {
            if ge(d, p.t) {
                self.diags.error(
                    Msg::DAboveT,
                    origin.clone(),
                    args![fmt_num(d), fmt_num(p.t)],
                );
            }
        }
    }
}
