//! Support-bar pieces along a line, arc or helix circle (reference-output.md §8.1).

use crate::args;
use crate::diag::{Diagnostic, Msg, Origin};
use crate::geom::Geom;
use crate::load::session::Abort;

/// Bars along one element: far beyond any real part, a bound on what a hostile drawing allocates.
const MAX_BARS: f64 = 10_000.0;

/// Support-bar pieces along a geometry (reference-output.md §8.1); `None` when it is too short.
pub(crate) fn support_bars(
    g: &Geom,
    o: f64,
    p: Option<f64>,
    u: Option<f64>,
    b: Option<f64>,
    d: Option<f64>,
    origin: &Origin,
) -> Result<Option<Vec<Geom>>, Abort> {
    let need = |v: Option<f64>, k: &str| {
        v.ok_or_else(|| Diagnostic::error(Msg::ValueMissing, origin.clone(), args![k]))
    };
    let p = need(p, "P")?;
    let u = need(u, "U")?;
    let b = need(b, "B")?;
    let d = need(d, "D")?;
    let len = g.length();
    let n = (len / (u + p)).floor();
    if n.is_nan() || n < 1.0 || !n.is_finite() {
        return Ok(None);
    }
    if n > MAX_BARS {
        return Err(Diagnostic::error(
            Msg::TooManyBars,
            origin.clone(),
            args![n, MAX_BARS],
        ));
    }
    let delta = d - b;
    let i = delta.min(p / 2.0);
    let v = len / n - p - 2.0 * i;
    let e = p / 2.0 + o / 2.0;
    let w = v - o;
    let bar = p + o;
    let step = 2.0 * i + v + p;
    let mut pieces = vec![g.sub(0.0, e)];
    for k in 0..(n as usize - 1) {
        let s = e + k as f64 * step;
        pieces.push(g.sub(s, s + i));
        pieces.push(g.sub(s + i, s + i + w));
        pieces.push(g.sub(s + i + w, s + 2.0 * i + w));
        pieces.push(g.sub(s + 2.0 * i + w, s + 2.0 * i + w + bar));
    }
    let t = len - e - 2.0 * i - w;
    pieces.push(g.sub(t, t + i));
    pieces.push(g.sub(t + i, t + i + w));
    pieces.push(g.sub(t + i + w, t + 2.0 * i + w));
    pieces.push(g.sub(t + 2.0 * i + w, len));
    Ok(Some(pieces))
}
