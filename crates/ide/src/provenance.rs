//! Effective values of an element and where each comes from (the rows of hover and inlay hints).
//!
//! Effective values of an element and where each comes from (§4.2 for display); chain starts
//! computed once per path and analysis.

use crate::common::*;
use crate::Analysis;
use millpath_core::build::traverse::traverse;
use millpath_core::diag::Origin;
use millpath_core::front::drawing::{RawPath, RawSegment, SegKind};
use millpath_core::params::{fmt_num, parse_number, ParamText};
use millpath_syntax::{Element, Kind};

pub(crate) struct Row {
    pub key: char,
    pub value: String,
    pub source: String,
}

/// Where a parameter text is: its line in a text file, its entity's line and layer in a DXF.
pub(crate) fn line_of(t: &ParamText, german: bool) -> String {
    let word = if german { "Zeile" } else { "line" };
    match &t.origin {
        Origin::Span { line, .. } => format!("{word} {line}"),
        Origin::Entity(e) => format!(
            "{word} {}, {} {}",
            e.line,
            if german { "Layer" } else { "layer" },
            e.layer
        ),
        o => o.context(),
    }
}

/// Effective values of an element and where each comes from.
pub(crate) fn provenance(
    a: &Analysis,
    path: &RawPath,
    el: &Element,
    seg: Option<&RawSegment>,
) -> Vec<Row> {
    let german = de(a);
    let lang = a.settings.settings.lang;
    let own = seg.and_then(|s| s.text.as_deref()).or_else(|| {
        // markers and probes: their own text from the element line
        object_index(a, el).and_then(|i| a.objects[i].text.as_deref())
    });
    let start = path.start_text.as_ref();
    // the start's text is one for every key it gives: its label made once
    let start_label = std::cell::OnceCell::new();
    let start_src = |t: &ParamText| {
        start_label
            .get_or_init(|| {
                let base = if german { "Pfadanfang" } else { "path start" };
                match &path.at_ref {
                    Some(r) => format!("{base} (@{r}, {})", line_of(t, german)),
                    None => format!("{base} ({})", line_of(t, german)),
                }
            })
            .clone()
    };
    let own_src = if german { "eigener Text" } else { "own text" }.to_string();
    let mut rows = Vec::new();
    let mut push = |key: char, value: String, source: String| rows.push(Row { key, value, source });
    let get = |t: Option<&ParamText>, k: char| t.and_then(|t| t.raw(k)).map(str::to_string);
    let chain_first = seg.and_then(|s| chain_first_segment(a, path, s));
    let is_start = matches!(el.kind.value, Kind::Start);
    let keys: Vec<char> = match &el.kind.value {
        Kind::Start => "TOMFSIBDWPUAZCER".chars().collect(),
        Kind::Mill | Kind::Mark | Kind::Bars => "TOBDIWFPUS".chars().collect(),
        Kind::Drill(_) | Kind::Helix(_) => "TOBDIFPUA".chars().collect(),
        Kind::Sweep | Kind::Move | Kind::Skip => "TS".chars().collect(),
        Kind::Sub => "TOMH".chars().collect(),
        Kind::Probe => "THZ".chars().collect(),
        _ => Vec::new(),
    };
    let settings = &a.settings;
    // O and T of the start, for the defaults made of them (read once, not per key)
    let o = start.and_then(|t| t.raw('O')).and_then(parse_number);
    let t_ = start.and_then(|t| t.raw('T')).and_then(parse_number);
    for k in keys {
        if !is_start {
            if let Some(v) = get(own, k) {
                push(k, v, own_src.clone());
                continue;
            }
            // the chain takes I and W (and N, C) from its first segment
            if "IW".contains(k) && matches!(el.kind.value, Kind::Mill | Kind::Mark | Kind::Bars) {
                if let Some(first) = chain_first.filter(|f| !std::ptr::eq(*f, seg.unwrap_or(f))) {
                    if let Some(v) = get(first.text.as_deref(), k) {
                        let src = if german {
                            "erstes Segment der Kette"
                        } else {
                            "chain's first segment"
                        };
                        push(
                            k,
                            v,
                            format!(
                                "{src} ({})",
                                first
                                    .text
                                    .as_ref()
                                    .map(|t| line_of(t, german))
                                    .unwrap_or_default()
                            ),
                        );
                        continue;
                    }
                }
            }
            if k == 'H' {
                push(
                    k,
                    "0".into(),
                    if german { "Standard" } else { "default" }.into(),
                );
                continue;
            }
        }
        if let Some(t) = start {
            if let Some(v) = get(Some(t), k) {
                let src = if is_start {
                    own_src.clone()
                } else {
                    start_src(t)
                };
                push(k, v, src);
                continue;
            }
        }
        match k {
            'F' => push(
                k,
                fmt_num(settings.settings.feed),
                settings.feed.describe_in(lang),
            ),
            'S' => {
                // top level: the machine's sweep height; embedded or checked: T+O
                let sub = match (t_, o) {
                    (Some(t), Some(o)) if german => {
                        format!("; T+O = {} eingebettet oder geprüft", fmt_num(t + o))
                    }
                    (Some(t), Some(o)) => {
                        format!("; T+O = {} when embedded or checked", fmt_num(t + o))
                    }
                    _ => String::new(),
                };
                let top = if german { "Hauptpfad" } else { "top level" };
                push(
                    k,
                    fmt_num(settings.settings.sweep_height),
                    format!("{} ({top}{sub})", settings.sweep_height.describe_in(lang)),
                );
            }
            'A' => {
                if let Some(o) = o {
                    push(k, fmt_num(4.0 * o), "4·O".into())
                }
            }
            'Z' => push(
                k,
                fmt_num(settings.settings.probe_feed()),
                settings.probe_feed.describe_in(lang),
            ),
            _ => {}
        }
    }
    rows
}

/// The first segment of the chain a mill segment belongs to (in traversal order). The
/// traversal of a path is made once per analysis (not per element).
pub(crate) fn chain_first_segment<'p>(
    a: &Analysis,
    path: &'p RawPath,
    seg: &RawSegment,
) -> Option<&'p RawSegment> {
    let firsts = {
        let mut cache = a.chain_first.lock().ok()?;
        cache
            .entry(path.name.clone())
            .or_insert_with(|| std::sync::Arc::new(chain_firsts(path)))
            .clone()
    };
    firsts.get(&seg.object).map(|&f| &path.segments[f])
}

/// Segment object → index of the first segment of its mill chain, for a whole path.
pub(crate) fn chain_firsts(path: &RawPath) -> std::collections::HashMap<usize, usize> {
    let mut out = std::collections::HashMap::new();
    let (Some(start), Some(end)) = (path.start.as_ref(), path.end.as_ref()) else {
        return out;
    };
    let mut diags = millpath_core::Diags::default();
    let steps = traverse(path, start.pos, end.pos, &mut diags);
    let mut first: Option<usize> = None;
    for st in &steps {
        let s = &path.segments[st.index];
        if matches!(s.kind, SegKind::Mill(_)) {
            let f = *first.get_or_insert(st.index);
            out.entry(s.object).or_insert(f);
        } else {
            first = None;
        }
    }
    out
}

pub(crate) fn value(rows: &[Row], k: char) -> Option<f64> {
    rows.iter()
        .find(|r| r.key == k)
        .and_then(|r| parse_number(&r.value))
}
