//! What a model says about the stock: its top, the tool and the lowest drawn depth. The
//! stock comment of the real dialects (`emit/dialect.rs`) and the second opinion
//! (`second_opinion.rs`) read the same figures from here.

use crate::front::drawing::Style;
use crate::model::{Element, Model};

/// The material top, tool diameter and deepest drawn depth the checker needs. The checker's
/// stock is one block, but a subpath's H moves its material top (T + H): every part of the
/// program comes down to its own top, so the block's top is the lowest of them. A block as
/// high as the highest would put the rest's approaches "into material" and refuse valid
/// programs (found by fuzzing); above a raised part the block is air, as it is above any cut.
pub fn stock_of(model: &Model) -> (f64, f64, Option<f64>) {
    fn lowest_top(m: &Model, h: f64, depth: usize) -> f64 {
        m.elements
            .iter()
            .filter_map(|e| match e {
                Element::Subpath(emb) if depth < 10 => emb
                    .target
                    .as_ref()
                    .map(|t| lowest_top(t, h + emb.h, depth + 1)),
                _ => None,
            })
            .fold(h + m.params.t, f64::min)
    }
    (
        lowest_top(model, 0.0, 0),
        model.params.o,
        lowest_depth(model, 0.0, 0),
    )
}

/// The lowest Z a model's elements ask for (`h` + B or D), subpaths with their H included.
pub fn lowest_depth(model: &Model, h: f64, depth: usize) -> Option<f64> {
    let pick = |style: Style, b: Option<f64>, d: Option<f64>| match style {
        Style::Mark => d,
        Style::Mill | Style::Support => b,
    };
    let mut lowest: Option<f64> = None;
    let mut take = |z: Option<f64>| {
        if let Some(z) = z {
            lowest = Some(lowest.map_or(z, |l: f64| l.min(z)));
        }
    };
    for e in &model.elements {
        match e {
            Element::Chain(c) => c
                .segs
                .iter()
                .for_each(|s| take(pick(s.style, s.b, s.d).map(|z| h + z))),
            Element::Drill(d) => take(pick(d.style, d.b, d.d).map(|z| h + z)),
            Element::Helix(x) => {
                let z = match (x.style, &x.bars) {
                    (Style::Support, None) => x.d,
                    (style, _) => pick(style, x.b, x.d),
                };
                take(z.map(|z| h + z));
            }
            Element::Subpath(emb) => {
                if let (Some(t), true) = (&emb.target, depth < 10) {
                    take(lowest_depth(t, h + emb.h, depth + 1));
                }
            }
            Element::Sweep(_) => {}
        }
    }
    lowest
}
