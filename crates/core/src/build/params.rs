//! Effective parameters of a path, a chain and a chain segment, and the checks of a parameter text (reference-input.md §4.1–§4.2).

use crate::args;
use crate::build::bars::support_bars;
use crate::build::eval::{BuildCtx, Eval};
use crate::diag::{Diagnostic, Diags, Msg, Origin};
use crate::front::drawing::{RawPath, RawSegment, Style, CHAIN_KEYS, HEIGHTMAP_KEY, PATH_KEYS};
use crate::geom::{le, Geom};
use crate::load::session::{Abort, Session};
use crate::model::*;
use crate::params::{fmt_num, parse_number_checked, NumberError, ParamText, MAX_MAGNITUDE};
use crate::probe::heightmap::MIN_STEP;

impl Session<'_> {
    pub(crate) fn path_params(&mut self, raw: &RawPath, ev: &Eval, cx: &BuildCtx) -> PathParams {
        let t_ = raw.start_text.as_ref();
        let missing = |key: &str, diags: &mut Diags| {
            diags.error(Msg::ValueMissing, raw.start_origin(), args![key]);
            f64::NAN
        };
        let t = match ev.num(t_, 'T') {
            Some(v) => v,
            None => missing("T", &mut self.diags),
        };
        let o = match ev.num(t_, 'O') {
            Some(v) => v,
            None => missing("O", &mut self.diags),
        };
        let s = ev.num(t_, 'S').unwrap_or(
            if cx.top && (!self.settings.check || self.settings.check_sweep_height) {
                self.settings.sweep_height
            } else {
                t + o
            },
        );
        PathParams {
            f: ev.num(t_, 'F').unwrap_or(self.settings.feed),
            t,
            o,
            s,
            a: ev.num(t_, 'A').unwrap_or(4.0 * o),
            z: ev.num(t_, 'Z').unwrap_or(self.settings.probe_feed()),
            v: self.settings.sweep_speed,
            b: ev.num(t_, 'B'),
            d: ev.num(t_, 'D'),
            i: ev.num(t_, 'I'),
            w: ev.num(t_, 'W'),
            p: ev.num(t_, 'P'),
            u: ev.num(t_, 'U'),
            c: ev.num(t_, 'C').map(|c| c.trunc() as i64),
            m: ev.string(t_, 'M'),
            e: ev.string(t_, 'E'),
            r: ev.string(t_, 'R').unwrap_or_default(),
            heightmap: self.drawn_heightmap(raw, ev),
        }
    }

    /// `K` of the start text (not in the reference dialect, where it is unsupported):
    /// `K<step>` or `K<step>+<margin>`, decimal commas allowed; anything else an error at
    /// the start text.
    fn drawn_heightmap(&mut self, raw: &RawPath, ev: &Eval) -> Option<DrawnHeightmap> {
        if self.settings.dialect == crate::Dialect::Reference {
            return None;
        }
        let v = ev.string(raw.start_text.as_ref(), HEIGHTMAP_KEY)?;
        let parsed = parse_drawn_heightmap(&v);
        if parsed.is_none() {
            self.diags.error(
                Msg::HeightmapKeyBad,
                raw.start_origin(),
                args![v, fmt_num(MIN_STEP)],
            );
        }
        parsed
    }

    pub(crate) fn chain_params(
        &mut self,
        first: &RawSegment,
        params: &PathParams,
        ev: &Eval,
    ) -> (Option<f64>, Option<f64>) {
        let text = first.text.as_deref();
        if let Some(t) = text {
            for (k, _) in &t.params {
                if !CHAIN_KEYS.contains(*k) {
                    let d = unsupported(*k, CHAIN_KEYS, t, &first.origin, self.settings.lang);
                    self.diags.push(d);
                }
            }
        }
        let i = ev.num(text, 'I').or(params.i);
        let w = ev.num(text, 'W').or(params.w);
        if text.is_some_and(|t| t.has('I')) && i.is_some_and(|i| le(i, 0.0)) {
            self.diags.error(
                Msg::MustBePositive,
                first.origin.clone(),
                args!["I", fmt_num(i.unwrap_or(0.0))],
            );
        }
        if text.is_some_and(|t| t.has('W')) && w.is_some_and(|w| le(w, 0.0)) {
            self.diags.error(
                Msg::MustBePositive,
                first.origin.clone(),
                args!["W", fmt_num(w.unwrap_or(0.0))],
            );
        }
        if let Some(c) = ev.num(text, 'C') {
            if c.trunc() <= 0.0 {
                self.diags.error(
                    Msg::MustBePositive,
                    first.origin.clone(),
                    args!["C", fmt_num(c.trunc())],
                );
            }
        }
        (i, w)
    }

    pub(crate) fn chain_seg(
        &mut self,
        seg: &RawSegment,
        style: Style,
        geom: Geom,
        params: &PathParams,
        ev: &Eval,
        _first: bool,
    ) -> Result<ChainSeg, Abort> {
        let text = seg.text.as_deref();
        if let Some(t) = text {
            self.check_text(t, seg.kind.allowed_keys(), &seg.origin, ev);
            if t.has('S') {
                let s = ev.num(text, 'S').unwrap_or(params.s);
                if le(s, params.t) {
                    self.diags.error(
                        Msg::SNotAboveT,
                        seg.origin.clone(),
                        args![fmt_num(s), fmt_num(params.t)],
                    );
                }
            }
        }
        self.validate_child(&seg.origin, text, params, ev);
        let b = ev.num(text, 'B').or(params.b);
        let d = ev.num(text, 'D').or(params.d);
        let bars = if style == Style::Support {
            let p = ev.num(text, 'P').or(params.p);
            let u = ev.num(text, 'U').or(params.u);
            support_bars(&geom, params.o, p, u, b, d, &seg.origin)?
        } else {
            None
        };
        Ok(ChainSeg {
            geom,
            style,
            f: ev.num(text, 'F').unwrap_or(params.f),
            b,
            d,
            q: ev.string(text, 'Q').map(String::into_boxed_str),
            bt: seg.backtrack(),
            bars: bars.map(Vec::into_boxed_slice),
            origin: seg.origin.clone(),
        })
    }

    /// Unsupported keys and values that are not numbers.
    pub(crate) fn check_text(&mut self, t: &ParamText, allowed: &str, origin: &Origin, ev: &Eval) {
        for (k, raw) in &t.params {
            if !allowed.contains(*k) {
                let d = unsupported(*k, allowed, t, origin, self.settings.lang);
                self.diags.push(d);
                continue;
            }
            if "ABCDFHIOPSTUWZ".contains(*k) {
                let v = ev.vars.interpolate(raw).unwrap_or_else(|_| raw.clone());
                match parse_number_checked(&v) {
                    Ok(_) => {}
                    Err(NumberError::NotANumber) => self.diags.push(Diagnostic::warning(
                        Msg::NotANumber,
                        origin.clone(),
                        args![k, v],
                    )),
                    // an error, not a warning: ignoring it would mill with another value
                    Err(NumberError::NotFinite) => {
                        self.diags
                            .error(Msg::NumberNotFinite, origin.clone(), args![k, v])
                    }
                    Err(NumberError::OutOfRange) => self.diags.error(
                        Msg::NumberOutOfRange,
                        origin.clone(),
                        args![k, v, MAX_MAGNITUDE],
                    ),
                }
            }
            if *k == 'N' && raw.trim().parse::<i64>().is_err() {
                self.diags.push(Diagnostic::warning(
                    Msg::NotANumber,
                    origin.clone(),
                    args![k, raw],
                ));
            }
        }
    }
}

/// `<step>` or `<step>+<margin>` (mm, decimal comma allowed): finite, step ≥ `MIN_STEP`,
/// margin ≥ 0; `None` otherwise.
pub(crate) fn parse_drawn_heightmap(v: &str) -> Option<DrawnHeightmap> {
    let (step, margin) = match v.split_once('+') {
        Some((s, m)) => (s, Some(m)),
        None => (v, None),
    };
    let num = |s: &str| parse_number_checked(s).ok();
    let step = num(step).filter(|s| *s >= MIN_STEP)?;
    let margin = match margin {
        Some(m) => Some(num(m).filter(|m| *m >= 0.0)?),
        None => None,
    };
    Some(DrawnHeightmap { step, margin })
}

/// `<CODE> @ [x y]` of a text, used in "Unsupported" messages.
pub(crate) fn text_context(t: &ParamText) -> String {
    match &t.origin {
        Origin::Entity(e) => format!("{} @ {}", e.code_name, e.pos),
        o => o.context(),
    }
}

/// The reference's "Unsupported K value" with a hint for people beside it (the `****` line
/// stays the reference's): the capital letter meant, or the keys allowed at this element.
fn unsupported(
    k: char,
    allowed: &str,
    t: &crate::params::ParamText,
    origin: &crate::diag::Origin,
    lang: crate::Lang,
) -> Diagnostic {
    let upper = k.to_uppercase().next().unwrap_or(k);
    let de = lang == crate::Lang::De;
    let hint = if k == HEIGHTMAP_KEY && allowed == PATH_KEYS {
        // the key exists, but not in PathDxf2GCode's programs
        if de {
            "K (eine Höhenkarte) braucht den Dialekt linuxcnc oder grbl".to_string()
        } else {
            "K (a height map) needs the linuxcnc or grbl dialect".to_string()
        }
    } else if upper != k && allowed.contains(upper) {
        if de {
            format!("{upper} gemeint? (Schlüssel sind Großbuchstaben)")
        } else {
            format!("did you mean {upper}? (keys are capital letters)")
        }
    } else {
        let mut keys: Vec<String> = allowed.chars().map(String::from).collect();
        keys.sort();
        let keys = keys.join(" ");
        if de {
            format!("hier erlaubte Schlüssel: {keys}")
        } else {
            format!("keys allowed here: {keys}")
        }
    };
    Diagnostic::error(Msg::Unsupported, origin.clone(), args![k, text_context(t)])
        .with_related(origin.clone(), hint)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::FileRef;

    #[test]
    fn an_unsupported_key_says_which_would_do() {
        let origin = Origin::File(FileRef::new("a.mpath".into()));
        let t = ParamText::parse("b1 X2", origin.clone()).unwrap();
        let d = unsupported('b', CHAIN_KEYS, &t, &origin, crate::Lang::En);
        assert_eq!(d.message(crate::Lang::En), "Unsupported b value; a.mpath");
        assert_eq!(
            d.related[0].note,
            "did you mean B? (keys are capital letters)"
        );
        let d = unsupported('X', CHAIN_KEYS, &t, &origin, crate::Lang::De);
        assert_eq!(
            d.related[0].note,
            "hier erlaubte Schlüssel: B C D F I N Q S W"
        );
        assert_eq!(
            d.reference_line(crate::Lang::En),
            "**** a.mpath: Unsupported X value; a.mpath"
        );
    }
}
