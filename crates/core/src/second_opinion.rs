//! A second opinion on every program `compile` writes: the independent G-code checker
//! (`millpath-verify`, which knows nothing of this compiler) simulates the program against a
//! stock model, and each finding comes back located at the element that wrote the line.

use crate::args;
use crate::diag::{Diagnostic, Lang, Msg, Origin};
use crate::model::{Element, Model};
use millpath_verify::{verify, Dialect, Options, Severity};

/// The material top, tool diameter and deepest drawn depth the checker needs. Subpaths raised
/// by H lift the top: the stock's top is the highest of them (nothing above it is material).
pub fn stock_of(model: &Model) -> (f64, f64, Option<f64>) {
    fn walk(m: &Model, h: f64, depth: usize, top: &mut f64, bottom: &mut Option<f64>) {
        *top = top.max(h + m.params.t);
        let mut depths: Vec<Option<f64>> = Vec::new();
        for e in &m.elements {
            match e {
                Element::Chain(c) => c.segs.iter().for_each(|s| depths.extend([s.b, s.d])),
                Element::Drill(d) => depths.extend([d.b, d.d]),
                Element::Helix(x) => depths.extend([x.b, x.d]),
                Element::Subpath(emb) => {
                    if let (Some(t), true) = (&emb.target, depth < 10) {
                        walk(t, h + emb.h, depth + 1, top, bottom);
                    }
                }
                Element::Sweep(_) => {}
            }
        }
        for z in depths.into_iter().flatten().map(|v| h + v) {
            *bottom = Some(bottom.map_or(z, |b| b.min(z)));
        }
    }
    let (mut top, mut bottom) = (model.params.t, None);
    walk(model, 0.0, 0, &mut top, &mut bottom);
    (top, model.params.o, bottom)
}

/// Checks one written program; findings become diagnostics at the element of their line
/// (warnings: the reference dialect must stay byte-identical, so nothing is refused here).
pub fn review(
    program: &str,
    model: &Model,
    line_sources: &[Option<Origin>],
    lang: Lang,
) -> Vec<Diagnostic> {
    let (top, tool, bottom) = stock_of(model);
    let report = verify(
        program,
        &Options {
            dialect: Dialect::Reference,
            top: Some(top),
            tool: Some(tool),
            bottom,
            ..Options::default()
        },
    );
    let vlang = match lang {
        Lang::En => millpath_verify::Lang::En,
        Lang::De => millpath_verify::Lang::De,
    };
    report
        .findings
        .iter()
        .filter(|f| f.severity != Severity::Note)
        .map(|f| {
            let origin = f
                .line
                .and_then(|l| line_sources.get(l.wrapping_sub(1)).cloned().flatten())
                .unwrap_or_else(|| model.raw.start_origin());
            Diagnostic::warning(
                Msg::SecondOpinion,
                origin,
                args![f.line.unwrap_or(0), f.text, f.message(vlang)],
            )
        })
        .collect()
}
