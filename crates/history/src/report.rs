//! The diff written out: human text, markdown (a pull-request comment, `$GITHUB_STEP_SUMMARY`)
//! and JSON, in English or German.
//!
//! Human text and markdown list at most [`LISTED`] changed elements per path (the JSON has
//! them all); the effect groups and the compiled figures always come whole.

use crate::compiled::Outcome;
use crate::diff::{ChangeKind, Diff, EffectGroup, ElementChange, PathDiff, PathStatus};
use millpath_core::Lang;
use serde_json::json;

/// Changed elements listed per path in human text and markdown.
pub const LISTED: usize = 50;

struct Words {
    unchanged: &'static str,
    changed: &'static str,
    added: &'static str,
    removed: &'static str,
    renamed_from: &'static str,
    moved: &'static str,
    retyped: &'static str,
    params: &'static str,
    effect: &'static str,
    line: &'static str,
    on: &'static str,
    elements: &'static str,
    element: &'static str,
    from: &'static str,
    passes: &'static str,
    more: &'static str,
    before: &'static str,
    after: &'static str,
    lowest_z: &'static str,
    length: &'static str,
    time: &'static str,
    moves: &'static str,
    gcode_changed: &'static str,
    gcode_same: &'static str,
    no_change: &'static str,
    not_compiled: &'static str,
    unset: &'static str,
    moves_only: &'static str,
    elsewhere: (&'static str, &'static str),
    no_element: &'static str,
}

const EN: Words = Words {
    unchanged: "unchanged",
    changed: "changed",
    added: "added",
    removed: "removed",
    renamed_from: "renamed from",
    moved: "moved",
    retyped: "re-typed",
    params: "parameters",
    effect: "effect",
    line: "line",
    on: "on",
    elements: "elements",
    element: "element",
    from: "from",
    passes: "passes",
    more: "more changed elements (see --format json)",
    before: "before",
    after: "after",
    lowest_z: "lowest Z",
    length: "milling length",
    time: "estimated time",
    moves: "moves",
    gcode_changed: "G-code changed",
    gcode_same: "G-code unchanged",
    no_change: "No change.",
    not_compiled: "does not compile",
    unset: "unset",
    moves_only: "its moves changed",
    elsewhere: ("moves of the embedded element", "changed"),
    no_element: "moves of no element changed",
};

const DE: Words = Words {
    unchanged: "unverändert",
    changed: "geändert",
    added: "hinzugefügt",
    removed: "entfernt",
    renamed_from: "umbenannt von",
    moved: "verschoben",
    retyped: "Art geändert",
    params: "Parameter",
    effect: "Wirkung",
    line: "Zeile",
    on: "auf",
    elements: "Elementen",
    element: "Element",
    from: "aus",
    passes: "Durchgänge",
    more: "weitere geänderte Elemente (siehe --format json)",
    before: "vorher",
    after: "nachher",
    lowest_z: "tiefstes Z",
    length: "Fräslänge",
    time: "geschätzte Zeit",
    moves: "Bewegungen",
    gcode_changed: "G-Code geändert",
    gcode_same: "G-Code unverändert",
    no_change: "Keine Änderung.",
    not_compiled: "lässt sich nicht übersetzen",
    unset: "nicht gesetzt",
    moves_only: "seine Bewegungen haben sich geändert",
    elsewhere: ("Bewegungen des eingebetteten Elements", "geändert"),
    no_element: "Bewegungen ohne Element geändert",
};

fn words(lang: Lang) -> &'static Words {
    match lang {
        Lang::En => &EN,
        Lang::De => &DE,
    }
}

fn status_word(w: &Words, p: &PathDiff) -> String {
    match p.status {
        PathStatus::Unchanged => w.unchanged.into(),
        PathStatus::Changed => w.changed.into(),
        PathStatus::Added => w.added.into(),
        PathStatus::Removed => w.removed.into(),
        PathStatus::Renamed => format!(
            "{} {}",
            w.renamed_from,
            p.old_name.as_deref().unwrap_or_default()
        ),
    }
}

fn kind_word(w: &Words, k: ChangeKind) -> &'static str {
    match k {
        ChangeKind::Added => w.added,
        ChangeKind::Removed => w.removed,
        ChangeKind::Moved => w.moved,
        ChangeKind::Retyped => w.retyped,
        ChangeKind::Params => w.params,
        ChangeKind::Effect => w.effect,
    }
}

/// A number as the drawings write it in the language (decimal comma in German).
fn num(v: f64, decimals: usize, lang: Lang) -> String {
    let s = format!("{v:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    let s = if s == "-0" { "0".to_string() } else { s };
    match lang {
        Lang::En => s,
        Lang::De => s.replace('.', ","),
    }
}

fn value(w: &Words, v: &Option<String>) -> String {
    v.clone().unwrap_or_else(|| format!("({})", w.unset))
}

/// "B -0,2 → -0,5 on 37 elements, from path start (line 2)"
fn effect_line(w: &Words, g: &EffectGroup) -> String {
    let what = if g.count == 1 { w.element } else { w.elements };
    format!(
        "{} {} → {} {} {} {what}, {} {}",
        g.key,
        value(w, &g.old),
        value(w, &g.new),
        w.on,
        g.count,
        w.from,
        g.source
    )
}

/// "mill (0, 0) -> (10, 0)  B-0,2 → mill (0, 0) -> (10, 0)  B-0,5"
fn change_line(w: &Words, c: &ElementChange) -> String {
    let lines = match (c.old_line, c.new_line) {
        (Some(a), Some(b)) if a == b => format!("{} {a}", w.line),
        (Some(a), Some(b)) => format!("{} {a} → {b}", w.line),
        (Some(a), None) | (None, Some(a)) => format!("{} {a}", w.line),
        (None, None) => String::new(),
    };
    let text = match (&c.old_text, &c.new_text) {
        (Some(a), Some(b)) if a == b => a.clone(),
        (Some(a), Some(b)) => format!("{a}  →  {b}"),
        (Some(a), None) | (None, Some(a)) => a.clone(),
        (None, None) => String::new(),
    };
    let mut out = format!("{} ({lines}): {text}", kind_word(w, c.kind));
    if c.kind == ChangeKind::Effect && c.values.is_empty() {
        out.push_str(&format!(" ({})", w.moves_only));
    }
    out
}

fn outcome_parts(w: &Words, o: &Option<Outcome>, lang: Lang) -> Vec<String> {
    match o {
        None => vec!["—".into(); 4],
        Some(o) if o.error.is_some() => {
            vec![w.not_compiled.into(), "—".into(), "—".into(), "—".into()]
        }
        Some(o) => vec![
            num(o.lowest_z, 3, lang),
            format!("{} mm", num(o.milling_length, 0, lang)),
            millpath_core::emit::stats::hms(o.seconds),
            o.moves.to_string(),
        ],
    }
}

fn elsewhere_line(w: &Words, label: &str) -> String {
    if label.is_empty() {
        w.no_element.to_string()
    } else {
        format!("{} {label} {}", w.elsewhere.0, w.elsewhere.1)
    }
}

fn figure_rows(w: &Words, p: &PathDiff, lang: Lang) -> Vec<(&'static str, String, String)> {
    let (b, a) = (
        outcome_parts(w, &p.before, lang),
        outcome_parts(w, &p.after, lang),
    );
    [w.lowest_z, w.length, w.time, w.moves]
        .into_iter()
        .zip(b.into_iter().zip(a))
        .map(|(l, (b, a))| (l, b, a))
        .collect()
}

fn compiled(p: &PathDiff) -> bool {
    p.before.is_some() || p.after.is_some()
}

/// The human text.
pub fn human(d: &Diff, title: &str, lang: Lang) -> String {
    let w = words(lang);
    let mut out = format!("{title}\n");
    if !d.changed() {
        out.push_str(&format!("  {}\n", w.no_change));
        return out;
    }
    for p in d.paths.iter().filter(|p| p.status != PathStatus::Unchanged) {
        out.push_str(&format!("  {}: {}\n", p.name, status_word(w, p)));
        if matches!(p.status, PathStatus::Changed | PathStatus::Renamed) {
            for c in p.changes.iter().take(LISTED) {
                out.push_str(&format!("    {}\n", change_line(w, c)));
            }
            if p.changes.len() > LISTED {
                out.push_str(&format!("    … {} {}\n", p.changes.len() - LISTED, w.more));
            }
        } else {
            out.push_str(&format!("    {} {}\n", p.changes.len(), w.elements));
        }
        for e in &p.elsewhere {
            out.push_str(&format!("    {}: {}\n", w.effect, elsewhere_line(w, e)));
        }
        for g in &p.effects {
            out.push_str(&format!("    {}: {}\n", w.effect, effect_line(w, g)));
        }
        for ((a, b), n) in &p.passes {
            let what = if *n == 1 { w.element } else { w.elements };
            out.push_str(&format!(
                "    {}: {a} → {b} {} {n} {what}\n",
                w.passes, w.on
            ));
        }
        if compiled(p) {
            let rows = figure_rows(w, p, lang);
            let figures: Vec<String> = rows
                .iter()
                .map(|(l, b, a)| {
                    if b == a {
                        format!("{l} {a}")
                    } else {
                        format!("{l} {b} → {a}")
                    }
                })
                .collect();
            let g = if p.gcode_changed() {
                w.gcode_changed
            } else {
                w.gcode_same
            };
            out.push_str(&format!("    {}; {g}\n", figures.join("; ")));
        }
    }
    out
}

/// Markdown for a pull-request comment or `$GITHUB_STEP_SUMMARY`.
pub fn markdown(d: &Diff, title: &str, lang: Lang) -> String {
    let w = words(lang);
    let mut out = format!("### {title}\n\n");
    if !d.changed() {
        out.push_str(&format!("{}\n", w.no_change));
        return out;
    }
    for p in d.paths.iter().filter(|p| p.status != PathStatus::Unchanged) {
        out.push_str(&format!("#### `{}`: {}\n\n", p.name, status_word(w, p)));
        if compiled(p) {
            out.push_str(&format!(
                "| | {} | {} |\n|---|---:|---:|\n",
                w.before, w.after
            ));
            for (l, b, a) in figure_rows(w, p, lang) {
                let a = if a != b { format!("**{a}**") } else { a };
                out.push_str(&format!("| {l} | {b} | {a} |\n"));
            }
            let g = if p.gcode_changed() {
                w.gcode_changed
            } else {
                w.gcode_same
            };
            out.push_str(&format!("\n{g}.\n\n"));
        }
        for e in &p.elsewhere {
            out.push_str(&format!("- {}: {}\n", w.effect, elsewhere_line(w, e)));
        }
        for g in &p.effects {
            out.push_str(&format!(
                "- {}: {}\n",
                w.effect,
                effect_line(w, g).replace('|', "\\|")
            ));
        }
        for ((a, b), n) in &p.passes {
            let what = if *n == 1 { w.element } else { w.elements };
            out.push_str(&format!("- {}: {a} → {b} {} {n} {what}\n", w.passes, w.on));
        }
        if matches!(p.status, PathStatus::Changed | PathStatus::Renamed) {
            for c in p.changes.iter().take(LISTED) {
                out.push_str(&format!("- {}\n", change_line(w, c).replace('`', "'")));
            }
            if p.changes.len() > LISTED {
                out.push_str(&format!("- … {} {}\n", p.changes.len() - LISTED, w.more));
            }
        } else {
            out.push_str(&format!("- {} {}\n", p.changes.len(), w.elements));
        }
        out.push('\n');
    }
    out
}

fn outcome_json(o: &Option<Outcome>) -> serde_json::Value {
    match o {
        None => serde_json::Value::Null,
        Some(o) => json!({
            "error": o.error,
            "lowest_z": o.lowest_z,
            "milling_length": (o.milling_length * 1000.0).round() / 1000.0,
            "seconds": (o.seconds * 1000.0).round() / 1000.0,
            "moves": o.moves,
        }),
    }
}

fn kind_json(k: ChangeKind) -> &'static str {
    match k {
        ChangeKind::Added => "added",
        ChangeKind::Removed => "removed",
        ChangeKind::Moved => "moved",
        ChangeKind::Retyped => "retyped",
        ChangeKind::Params => "params",
        ChangeKind::Effect => "effect",
    }
}

/// The JSON (keys in English whatever the language; sources in the run's language).
pub fn json(d: &Diff, old: &str, new: &str) -> serde_json::Value {
    let paths: Vec<serde_json::Value> = d
        .paths
        .iter()
        .map(|p| {
            json!({
                "name": p.name,
                "old_name": p.old_name,
                "status": match p.status {
                    PathStatus::Unchanged => "unchanged",
                    PathStatus::Changed => "changed",
                    PathStatus::Added => "added",
                    PathStatus::Removed => "removed",
                    PathStatus::Renamed => "renamed",
                },
                "elements": p.changes.iter().map(|c| json!({
                    "change": kind_json(c.kind),
                    "old_line": c.old_line,
                    "new_line": c.new_line,
                    "old": c.old_text,
                    "new": c.new_text,
                    "moves_changed": c.moves_changed,
                    "passes": [c.passes.0, c.passes.1],
                    "values": c.values.iter().map(|v| json!({
                        "key": v.key.to_string(), "old": v.old, "new": v.new, "source": v.source,
                    })).collect::<Vec<_>>(),
                })).collect::<Vec<_>>(),
                "effects": p.effects.iter().map(|g| json!({
                    "key": g.key.to_string(), "old": g.old, "new": g.new, "source": g.source, "count": g.count,
                })).collect::<Vec<_>>(),
                "elsewhere": p.elsewhere,
                "passes": p.passes.iter().map(|((a, b), n)| json!({"before": a, "after": b, "count": n})).collect::<Vec<_>>(),
                "before": outcome_json(&p.before),
                "after": outcome_json(&p.after),
                "gcode_changed": p.gcode_changed(),
            })
        })
        .collect();
    json!({ "old": old, "new": new, "changed": d.changed(), "paths": paths })
}
