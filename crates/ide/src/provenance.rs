//! Effective values of an element and where each comes from (the rows of hover and inlay hints).
//!
//! Effective values of an element and where each comes from (§4.2 for display); chain starts
//! computed once per path and analysis.

use crate::common::*;
use crate::Analysis;
use millpath_core::build::traverse::traverse_in;
use millpath_core::build::traverse_memo::TraversalMemo;
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
    provenance_in(a, path, el, seg, &mut Inherited::default())
}

/// What the elements of one path take from its start or the defaults, per key: made once
/// per path and key, not per element (a path of 100,000 elements formats each once).
#[derive(Default)]
pub(crate) struct Inherited {
    rows: Vec<(char, Option<(String, String)>)>,
}

/// [`provenance`] with the rows of `path`'s elements taken from its start or the defaults
/// remembered in `inherited` (one per path).
pub(crate) fn provenance_in(
    a: &Analysis,
    path: &RawPath,
    el: &Element,
    seg: Option<&RawSegment>,
    inherited: &mut Inherited,
) -> Vec<Row> {
    let german = de(a);
    let own = seg.and_then(|s| s.text.as_deref()).or_else(|| {
        // markers and probes: their own text from the element line
        object_index(a, el).and_then(|i| a.objects[i].text.as_deref())
    });
    let own_src = || if german { "eigener Text" } else { "own text" }.to_string();
    let mut rows = Vec::new();
    let mut push = |key: char, value: String, source: String| rows.push(Row { key, value, source });
    let get = |t: Option<&ParamText>, k: char| t.and_then(|t| t.raw(k)).map(str::to_string);
    let chain_first = seg.and_then(|s| chain_first_segment(a, path, s));
    let is_start = matches!(el.kind.value, Kind::Start);
    let keys: &str = match &el.kind.value {
        Kind::Start => "TOMFSIBDWPUAZCER",
        Kind::Mill | Kind::Mark | Kind::Bars => "TOBDIWFPUS",
        Kind::Drill(_) | Kind::Helix(_) => "TOBDIFPUA",
        Kind::Sweep | Kind::Move | Kind::Skip => "TS",
        Kind::Sub => "TOMH",
        Kind::Probe => "THZ",
        _ => "",
    };
    for k in keys.chars() {
        if is_start {
            // the start's own words, else the defaults
            match get(path.start_text.as_ref(), k) {
                Some(v) => push(k, v, own_src()),
                None => {
                    if let Some((v, src)) = default_row(a, path, k) {
                        push(k, v, src)
                    }
                }
            }
            continue;
        }
        if let Some(v) = get(own, k) {
            push(k, v, own_src());
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
        let known = match inherited.rows.iter().position(|(key, _)| *key == k) {
            Some(i) => i,
            None => {
                inherited.rows.push((k, inherited_row(a, path, k)));
                inherited.rows.len() - 1
            }
        };
        if let Some((v, src)) = &inherited.rows[known].1 {
            push(k, v.clone(), src.clone());
        }
    }
    rows
}

/// What an element of `path` other than its start takes for key `k` from the start's text
/// or the defaults.
fn inherited_row(a: &Analysis, path: &RawPath, k: char) -> Option<(String, String)> {
    let german = de(a);
    if let Some(t) = path.start_text.as_ref() {
        if let Some(v) = t.raw(k) {
            let base = if german { "Pfadanfang" } else { "path start" };
            let src = match &path.at_ref {
                Some(r) => format!("{base} (@{r}, {})", line_of(t, german)),
                None => format!("{base} ({})", line_of(t, german)),
            };
            return Some((v.to_string(), src));
        }
    }
    default_row(a, path, k)
}

/// The default of key `k` where the path's start does not give it (F, S, A, Z).
fn default_row(a: &Analysis, path: &RawPath, k: char) -> Option<(String, String)> {
    let german = de(a);
    let lang = a.settings.settings.lang;
    let settings = &a.settings;
    let start = path.start_text.as_ref();
    // O and T of the start, for the defaults made of them
    let o = start.and_then(|t| t.raw('O')).and_then(parse_number);
    let t_ = start.and_then(|t| t.raw('T')).and_then(parse_number);
    match k {
        'F' => Some((
            fmt_num(settings.settings.feed),
            settings.feed.describe_in(lang),
        )),
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
            Some((
                fmt_num(settings.settings.sweep_height),
                format!("{} ({top}{sub})", settings.sweep_height.describe_in(lang)),
            ))
        }
        'A' => o.map(|o| (fmt_num(4.0 * o), "4·O".into())),
        'Z' => Some((
            fmt_num(settings.settings.probe_feed()),
            settings.probe_feed.describe_in(lang),
        )),
        _ => None,
    }
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
        // found without a copy of the name (asked once per element)
        match cache.get(path.name.as_str()) {
            Some(f) => f.clone(),
            None => cache
                .entry(path.name.clone())
                .or_insert_with(|| std::sync::Arc::new(chain_firsts(path, &a.traversals)))
                .clone(),
        }
    };
    firsts.get(&seg.object).map(|&f| &path.segments[f])
}

/// Segment object → index of the first segment of its mill chain, for a whole path (its
/// walk taken from the analysis's memo when a build walked it already).
pub(crate) fn chain_firsts(path: &RawPath, walks: &TraversalMemo) -> crate::FastMap<usize, usize> {
    let mut out = crate::FastMap::default();
    let (Some(start), Some(end)) = (path.start.as_ref(), path.end.as_ref()) else {
        return out;
    };
    let mut diags = millpath_core::Diags::default();
    let steps = traverse_in(Some(walks), path, start.pos, end.pos, &mut diags);
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
