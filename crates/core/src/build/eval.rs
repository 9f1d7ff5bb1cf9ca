//! Parameter values of one build, interpolated with its variables, and the origin of a
//! message moved to where on the drawing it applies.

use crate::diag::Origin;
use crate::geom::P2;
use crate::params::{parse_number, ParamText, Vars};

/// Where a build is: its subpath depth, and whether it is the top-level path.
pub(crate) struct BuildCtx {
    pub(crate) depth: usize,
    pub(crate) top: bool,
}

/// Parameter values of one build, interpolated with its variables.
pub(crate) struct Eval<'v> {
    pub(crate) vars: &'v Vars,
}

impl Eval<'_> {
    pub(crate) fn string(&self, t: Option<&ParamText>, key: char) -> Option<String> {
        let raw = t?.raw(key)?;
        Some(
            self.vars
                .interpolate(raw)
                .unwrap_or_else(|_| raw.to_string()),
        )
    }
    pub(crate) fn num(&self, t: Option<&ParamText>, key: char) -> Option<f64> {
        parse_number(&self.string(t, key)?)
    }
}

/// The same origin with another reported position.
pub(crate) fn with_pos(o: &Origin, pos: P2) -> Origin {
    match o {
        Origin::Entity(e) => {
            let mut e = e.clone();
            std::sync::Arc::make_mut(&mut e).pos = pos;
            Origin::Entity(e)
        }
        o => o.clone(),
    }
}
