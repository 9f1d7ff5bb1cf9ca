//! The answers to editor questions.

use crate::{analyze, file_ref, workspace_files, Analysis, Pos, Workspace};
use millpath_core::build::traverse::traverse;
use millpath_core::diag::{Msg, Origin};
use millpath_core::emit::chain::pass_depths;
use millpath_core::emit::{generate_for, Controller, Output};
use millpath_core::front::drawing::{
    RawPath, RawSegment, SegKind, Style as CoreStyle, PATH_KEYS, PROBE_KEYS,
};
use millpath_core::params::{fmt_num, parse_number, ParamText};
use millpath_core::{Lang, Session};
use millpath_syntax::Style;
use millpath_syntax::{Element, Geometry, Item, Kind, PathBlock, PathItem};
use std::path::{Path, PathBuf};

/// A replacement of the byte range `start..end` of the document.
#[derive(Debug, Clone, PartialEq)]
pub struct TextEdit {
    pub start: usize,
    pub end: usize,
    pub text: String,
}

/// A place in some file: positions are 0-based lines and UTF-16 columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Location {
    pub path: PathBuf,
    pub start: Pos,
    pub end: Pos,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Hover {
    pub markdown: String,
    pub start: usize,
    pub end: usize,
}

fn de(a: &Analysis) -> bool {
    a.settings.settings.lang == Lang::De
}

/// The path block and element at a byte offset.
pub fn element_at(a: &Analysis, offset: usize) -> Option<(&PathBlock, &Element)> {
    a.ast.paths().find_map(|p| {
        p.elements()
            .find(|e| e.span.start <= offset && offset <= e.span.end)
            .map(|e| (p, e))
    })
}

fn object_index(a: &Analysis, el: &Element) -> Option<usize> {
    a.object_at.get(&el.span.start).copied()
}

fn raw_path<'a>(a: &'a Analysis, name: &str) -> Option<&'a RawPath> {
    a.paths.iter().find(|p| p.name == name)
}

/// Meaning, unit and default of a parameter letter.
pub fn param_doc(key: char, german: bool) -> Option<(&'static str, &'static str, &'static str)> {
    let en = match key {
        'A' => ("largest helix diameter", "mm", "4·O"),
        'B' => (
            "bottom: milling depth",
            "mm",
            "inherited from the path start",
        ),
        'C' => ("G81 depth (not used)", "", "none"),
        'D' => (
            "marking depth; top of support bars",
            "mm",
            "inherited from the path start",
        ),
        'E' => (
            "subpaths this path may embed (regular expression)",
            "",
            "the /e restrictions",
        ),
        'F' => (
            "feed for milling moves",
            "mm/min",
            "the machine feed (/f, millpath.toml)",
        ),
        'H' => ("extra height of a subpath or probe", "mm", "0"),
        'I' => (
            "infeed per pass; helix pitch",
            "mm",
            "inherited from the path start",
        ),
        'L' => ("z-probe label", "", "none"),
        'M' => (
            "material (must match between project and subpath)",
            "",
            "none",
        ),
        'N' => (
            "order at branch points (lower first)",
            "",
            "unnumbered: after numbered segments",
        ),
        'O' => ("bit diameter", "mm", "required"),
        'P' => ("support-bar length", "mm", "inherited from the path start"),
        'Q' => ("comment, written into the G-code", "", "none"),
        'R' => ("suffix of the output file names", "", "none"),
        'S' => (
            "sweep height",
            "mm",
            "top level: /s; subpaths and checks: T+O",
        ),
        'T' => ("top of the material (thickness)", "mm", "required"),
        'U' => (
            "smallest distance between support bars",
            "mm",
            "inherited from the path start",
        ),
        'W' => (
            "first depth of sweepless milling",
            "mm",
            "none (fast milling)",
        ),
        'Z' => ("probe feed", "mm/min", "the probe feed (/z), else the feed"),
        '>' => ("name of the embedded subpath", "", "required on sub lines"),
        '@' => (
            "use the start text of another path of this file",
            "",
            "none",
        ),
        ':' => (
            "variable: definition at the start, assignment on sub lines",
            "",
            "none",
        ),
        _ => return None,
    };
    if !german {
        return Some(en);
    }
    Some(match key {
        'A' => ("größter Helix-Durchmesser", "mm", "4·O"),
        'B' => ("Boden: Frästiefe", "mm", "vom Pfadanfang geerbt"),
        'C' => ("G81-Tiefe (nicht benutzt)", "", "keiner"),
        'D' => (
            "Markierungstiefe; Oberkante der Haltestege",
            "mm",
            "vom Pfadanfang geerbt",
        ),
        'E' => (
            "erlaubte Teilpfade (regulärer Ausdruck)",
            "",
            "die /e-Regeln",
        ),
        'F' => (
            "Vorschub der Fräsbewegungen",
            "mm/min",
            "Maschinenvorschub (/f, millpath.toml)",
        ),
        'H' => ("Zusatzhöhe eines Teilpfads oder Fühlpunkts", "mm", "0"),
        'I' => (
            "Zustellung je Durchgang; Helix-Steigung",
            "mm",
            "vom Pfadanfang geerbt",
        ),
        'L' => ("Name des Fühlpunkts", "", "keiner"),
        'M' => (
            "Material (muss bei Projekt und Teilpfad gleich sein)",
            "",
            "keiner",
        ),
        'N' => (
            "Reihenfolge an Verzweigungen (kleinere zuerst)",
            "",
            "ohne: nach nummerierten Segmenten",
        ),
        'O' => ("Fräserdurchmesser", "mm", "nötig"),
        'P' => ("Haltesteg-Länge", "mm", "vom Pfadanfang geerbt"),
        'Q' => ("Kommentar im G-Code", "", "keiner"),
        'R' => ("Zusatz der Ausgabe-Dateinamen", "", "keiner"),
        'S' => (
            "Leerfahrt-Höhe",
            "mm",
            "Hauptpfad: /s; Teilpfade und Prüfung: T+O",
        ),
        'T' => ("Materialoberkante (Dicke)", "mm", "nötig"),
        'U' => (
            "kleinster Abstand der Haltestege",
            "mm",
            "vom Pfadanfang geerbt",
        ),
        'W' => (
            "erste Tiefe beim leerfahrtlosen Fräsen",
            "mm",
            "keiner (schnelles Fräsen)",
        ),
        'Z' => (
            "Fühl-Vorschub",
            "mm/min",
            "Fühl-Vorschub (/z), sonst Vorschub",
        ),
        '>' => (
            "Name des eingebetteten Teilpfads",
            "",
            "nötig bei Teilpfad-Linien",
        ),
        '@' => (
            "Starttext eines anderen Pfads dieser Datei verwenden",
            "",
            "keiner",
        ),
        ':' => (
            "Variable: Definition am Start, Zuweisung an Teilpfad-Linien",
            "",
            "keiner",
        ),
        _ => en,
    })
}

/// Where a key is allowed, as element kinds.
fn allowed_in(key: char) -> Vec<&'static str> {
    let mut v = Vec::new();
    if PATH_KEYS.contains(key) || key == '@' {
        v.push("start");
    }
    for (name, kind) in [
        ("mill/mark/bars", SegKind::Mill(CoreStyle::Mill)),
        (
            "sweep",
            SegKind::Sweep(millpath_core::front::drawing::SweepKind::Dashed),
        ),
        ("drill", SegKind::Drill(CoreStyle::Mill)),
        ("helix", SegKind::Helix(CoreStyle::Support)),
        ("sub", SegKind::Subpath),
    ] {
        if kind.allowed_keys().contains(key) {
            v.push(name);
        }
    }
    if PROBE_KEYS.contains(key) {
        v.push("probe");
    }
    v
}

/// The keys that make sense on an element of this kind.
fn keys_for(kind: &Kind) -> &'static str {
    match kind {
        Kind::Start => "ABCDEFIMOPRSTUWZ@:",
        Kind::Mill | Kind::Mark | Kind::Bars => "BCDFINPQSUW",
        Kind::Sweep => "NS",
        Kind::Sub => "HMNOT>:",
        Kind::Probe => "HLTZ",
        Kind::Drill(Style::Mark) => "CDFQ",
        Kind::Drill(_) => "BCFQ",
        Kind::Helix(Style::Mill) => "BFIQ",
        Kind::Helix(Style::Mark) => "DFIQ",
        Kind::Helix(Style::Bars) => "BDFIPQU",
        _ => "",
    }
}

struct Row {
    key: char,
    value: String,
    source: String,
}

fn line_of(t: &ParamText) -> String {
    match &t.origin {
        Origin::Span { line, .. } => format!("line {line}"),
        o => o.context(),
    }
}

/// Effective values of an element and where each comes from.
fn provenance(a: &Analysis, path: &RawPath, el: &Element, seg: Option<&RawSegment>) -> Vec<Row> {
    let german = de(a);
    let own = seg.and_then(|s| s.text.as_ref()).or_else(|| {
        // markers and probes: their own text from the element line
        object_index(a, el).and_then(|i| a.objects[i].text.as_ref())
    });
    let start = path.start_text.as_ref();
    let start_src = |t: &ParamText| {
        let base = if german { "Pfadanfang" } else { "path start" };
        match &path.at_ref {
            Some(r) => format!("{base} (@{r}, {})", line_of(t)),
            None => format!("{base} ({})", line_of(t)),
        }
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
    for k in keys {
        if !is_start {
            if let Some(v) = get(own, k) {
                push(k, v, own_src.clone());
                continue;
            }
            // the chain takes I and W (and N, C) from its first segment
            if "IW".contains(k) && matches!(el.kind.value, Kind::Mill | Kind::Mark | Kind::Bars) {
                if let Some(first) = chain_first.filter(|f| !std::ptr::eq(*f, seg.unwrap_or(f))) {
                    if let Some(v) = get(first.text.as_ref(), k) {
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
                                first.text.as_ref().map(line_of).unwrap_or_default()
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
        let o = start.and_then(|t| t.raw('O')).and_then(parse_number);
        let t_ = start.and_then(|t| t.raw('T')).and_then(parse_number);
        match k {
            'F' => push(k, fmt_num(settings.settings.feed), settings.feed.describe()),
            'S' => {
                // top level: the machine's sweep height; embedded or checked: T+O
                let sub = match (t_, o) {
                    (Some(t), Some(o)) => {
                        format!("; T+O = {} when embedded or checked", fmt_num(t + o))
                    }
                    _ => String::new(),
                };
                push(
                    k,
                    fmt_num(settings.settings.sweep_height),
                    format!("{} (top level{sub})", settings.sweep_height.describe()),
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
                settings.probe_feed.describe(),
            ),
            _ => {}
        }
    }
    rows
}

/// The first segment of the chain a mill segment belongs to (in traversal order). The
/// traversal of a path is made once per analysis (not per element).
fn chain_first_segment<'p>(
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
fn chain_firsts(path: &RawPath) -> std::collections::HashMap<usize, usize> {
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

fn segment_of<'a>(a: &'a Analysis, el: &Element) -> Option<(&'a RawPath, Option<&'a RawSegment>)> {
    let i = object_index(a, el)?;
    let path = raw_path(a, &a.objects[i].path)?;
    Some((path, path.segments.iter().find(|s| s.object == i)))
}

/// Hover: a parameter letter, a subpath name, or an element with its effective values.
pub fn hover(a: &Analysis, ws: &Workspace, offset: usize) -> Option<Hover> {
    let (_, el) = element_at(a, offset)?;
    let german = de(a);
    if let Some(p) = el
        .params
        .iter()
        .find(|p| p.span.start <= offset && offset <= p.span.end)
    {
        let key = p.value.chars().next()?;
        if key == '>' && offset > p.span.start {
            return subpath_hover(a, ws, &p.value[1..], p.span.clone());
        }
        let (meaning, unit, default) = param_doc(key, german)?;
        let mut md = format!("**{key}** — {meaning}");
        if !unit.is_empty() {
            md.push_str(&format!(" ({unit})"));
        }
        md.push_str(&format!(
            "\n\n{}: {default}",
            if german { "Standard" } else { "Default" }
        ));
        md.push_str(&format!(
            "\n\n{}: {}",
            if german { "Erlaubt bei" } else { "Allowed at" },
            allowed_in(key).join(", ")
        ));
        return Some(Hover {
            markdown: md,
            start: p.span.start,
            end: p.span.start + key.len_utf8(),
        });
    }
    let (path, seg) = segment_of(a, el)?;
    let rows = provenance(a, path, el, seg);
    let mut md = format!(
        "**{}** — {} `{}`\n\n",
        el.kind.value.words(),
        if german { "Pfad" } else { "path" },
        path.name
    );
    md.push_str(if german {
        "| Wert | | Herkunft |\n|---|---|---|\n"
    } else {
        "| value | | from |\n|---|---|---|\n"
    });
    for r in &rows {
        md.push_str(&format!("| {} | {} | {} |\n", r.key, r.value, r.source));
    }
    md.push_str(&derived_facts(a, el, &rows, german));
    Some(Hover {
        markdown: md,
        start: el.kind.span.start,
        end: el.geometry.span.end,
    })
}

fn value(rows: &[Row], k: char) -> Option<f64> {
    rows.iter()
        .find(|r| r.key == k)
        .and_then(|r| parse_number(&r.value))
}

/// Pass depths, length and time of mill segments; size of circles.
fn derived_facts(a: &Analysis, el: &Element, rows: &[Row], german: bool) -> String {
    let feed = value(rows, 'F').unwrap_or(a.settings.settings.feed);
    let length = match el.geometry.value {
        Geometry::Line(p, q) => Some(((q.x - p.x).powi(2) + (q.y - p.y).powi(2)).sqrt()),
        Geometry::Arc { r, a0, a1, .. } => {
            Some(r * millpath_core::geom::normalize_angle(a1 - a0).to_radians())
        }
        _ => None,
    };
    let mut out = String::new();
    if let (Some(len), true) = (
        length,
        matches!(el.kind.value, Kind::Mill | Kind::Mark | Kind::Bars),
    ) {
        let t = value(rows, 'T');
        let i = value(rows, 'I');
        let bottom = if matches!(el.kind.value, Kind::Mark) {
            value(rows, 'D')
        } else {
            value(rows, 'B')
        };
        if let (Some(t), Some(i), Some(b)) = (t, i, bottom) {
            let first = value(rows, 'W').unwrap_or(t - i);
            let passes = pass_depths(first, b, i);
            let list: Vec<String> = passes.iter().map(|z| millpath_core::geom::f3(*z)).collect();
            let minutes = len * passes.len() as f64 / feed * 1.4;
            out.push_str(&format!(
                "\n{}: {} · {} {} mm · ca. {:.1} min",
                if german { "Durchgänge" } else { "passes" },
                list.join(", "),
                if german { "Länge" } else { "length" },
                millpath_core::geom::f3(len),
                minutes
            ));
        }
    } else if let Some(len) = length {
        out.push_str(&format!(
            "\n{} {} mm",
            if german { "Länge" } else { "length" },
            millpath_core::geom::f3(len)
        ));
    }
    if let Geometry::Circle { d, .. } = el.geometry.value {
        out.push_str(&format!("\nØ {} mm", fmt_num(d)));
    }
    out
}

fn lookup(ws: &Workspace, from: &Path, name: &str) -> Option<std::sync::Arc<RawPath>> {
    let fs = ws.fs();
    let settings = ws.settings_for(from).settings;
    let mut session = Session::new(settings, &fs).ok()?;
    session.load_file(from);
    session.lookup(name, from)
}

fn subpath_hover(
    a: &Analysis,
    ws: &Workspace,
    target: &str,
    span: std::ops::Range<usize>,
) -> Option<Hover> {
    let german = de(a);
    let Some(raw) = lookup(ws, &a.path, target) else {
        let md = if german {
            format!("Teilpfad `{target}` nicht gefunden")
        } else {
            format!("subpath `{target}` not found")
        };
        return Some(Hover {
            markdown: md,
            start: span.start,
            end: span.end,
        });
    };
    let t = raw.start_text.as_ref();
    let get = |k: char| t.and_then(|t| t.raw(k)).unwrap_or("–").to_string();
    let size = match (&raw.start, &raw.end) {
        (Some(s), Some(e)) => millpath_core::geom::f3(s.pos.dist(e.pos)),
        _ => "–".into(),
    };
    let md = format!(
        "**{}** — {}\n\nT {} · O {} · M {} · {} {size} mm",
        raw.name,
        raw.file.path.display(),
        get('T'),
        get('O'),
        get('M'),
        if german { "Länge" } else { "size" }
    );
    Some(Hover {
        markdown: md,
        start: span.start,
        end: span.end,
    })
}

/// The G-code of one path as `millpath compile` writes it.
#[derive(Debug, Clone, PartialEq)]
pub struct Preview {
    pub path: String,
    /// `_Milling.gcode`, or `_Clean.gcode` when the path has probes.
    pub gcode: String,
    pub probing: Option<String>,
    pub z_txt: Option<String>,
    /// The five statistics lines.
    pub stats: Vec<String>,
    /// Errors that would stop `millpath compile` from writing the files.
    pub errors: Vec<String>,
}

/// A path built as `millpath compile` builds it, with the errors of the build.
struct TopModel {
    model: std::sync::Arc<millpath_core::model::Model>,
    lang: Lang,
    sweep_speed: f64,
    controller: Controller,
    errors: Vec<String>,
}

/// Builds `name` (default: the first path of the file) with the file's settings.
fn top_model(ws: &Workspace, path: &Path, name: Option<&str>) -> Result<TopModel, String> {
    let ds = ws.settings_for(path);
    let missing = ds.missing_message();
    let lang = ds.settings.lang;
    let sweep_speed = ds.settings.sweep_speed;
    let controller = Controller::of(&ds.settings);
    let fs = ws.fs();
    let joined = |e: &[millpath_core::Diagnostic]| {
        e.iter()
            .map(|d| d.message(lang))
            .collect::<Vec<_>>()
            .join("; ")
    };
    let mut session = Session::new(ds.settings, &fs).map_err(|e| joined(&e))?;
    let names = session.load_file(path);
    let name = match name {
        Some(n) => n.to_string(),
        None => names.first().cloned().ok_or("no path in this file")?,
    };
    match session.build_top(&name) {
        Ok(Some(model)) => Ok(TopModel {
            model,
            lang,
            sweep_speed,
            controller,
            // not silent: `millpath compile` would refuse without them
            errors: missing
                .into_iter()
                .chain(messages(&session, lang))
                .collect(),
        }),
        Ok(None) => Err(format!(
            "path {name} cannot be built: {}",
            messages(&session, lang).join("; ")
        )),
        Err(abort) => Err(abort.message(lang)),
    }
}

/// Preview of `name` (default: the first path of the document).
pub fn preview(ws: &Workspace, path: &Path, name: Option<&str>) -> Result<Preview, String> {
    let TopModel {
        model,
        lang,
        sweep_speed,
        controller,
        errors,
    } = top_model(ws, path, name)?;
    let name = model.name().to_string();
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let g = generate_for(
        &model,
        &file_name,
        &millpath_core::banner(),
        sweep_speed,
        lang,
        &controller,
    )
    .map_err(|e| {
        e.iter()
            .map(|d| d.message(lang))
            .collect::<Vec<_>>()
            .join("; ")
    })?;
    let stats = g.stats.lines(lang).to_vec();
    Ok(match g.output {
        Output::Milling(gcode) => Preview {
            path: name,
            gcode,
            probing: None,
            z_txt: None,
            stats,
            errors,
        },
        Output::Probing {
            probing,
            z_txt,
            clean,
        } => Preview {
            path: name,
            gcode: clean,
            probing: Some(probing),
            z_txt: Some(z_txt),
            stats,
            errors,
        },
    })
}

fn messages(session: &Session, lang: Lang) -> Vec<String> {
    session
        .diags
        .list
        .iter()
        .filter(|d| d.severity == millpath_core::Severity::Error)
        .map(|d| d.reference_line(lang))
        .collect()
}

/// An inlay hint after the byte offset.
#[derive(Debug, Clone, PartialEq)]
pub struct Hint {
    pub offset: usize,
    pub label: String,
}

/// Inherited depths (B, D, I) shown after elements that do not set them.
pub fn inlay_hints(a: &Analysis) -> Vec<Hint> {
    inlay_hints_in(a, 0, usize::MAX)
}

/// Inlay hints of the elements overlapping the byte range `start..end`: the cost is that of
/// those elements (plus one traversal per path, made once per analysis).
pub fn inlay_hints_in(a: &Analysis, start: usize, end: usize) -> Vec<Hint> {
    let mut out = Vec::new();
    for p in a.ast.paths() {
        if p.span.end < start || p.span.start > end {
            continue;
        }
        for el in p.elements() {
            if el.span.end < start || el.span.start > end {
                continue;
            }
            let keys: &[char] = match el.kind.value {
                Kind::Mill | Kind::Bars | Kind::Drill(Style::Mill) | Kind::Helix(Style::Mill) => {
                    &['B']
                }
                Kind::Mark | Kind::Drill(Style::Mark) | Kind::Helix(Style::Mark) => &['D'],
                Kind::Helix(Style::Bars) => &['B', 'D'],
                _ => continue,
            };
            let Some((path, seg)) = segment_of(a, el) else {
                continue;
            };
            let rows = provenance(a, path, el, seg);
            let mut parts = Vec::new();
            for k in keys {
                let own = el.params.iter().any(|p| p.value.starts_with(*k));
                if let (false, Some(r)) = (own, rows.iter().find(|r| r.key == *k)) {
                    parts.push(format!("{k}{}", r.value));
                }
            }
            if !parts.is_empty() {
                out.push(Hint {
                    offset: el.geometry.span.end,
                    label: format!("⇐ {}", parts.join(" ")),
                });
            }
        }
    }
    out
}

fn location_of(ws: &Workspace, raw: &RawPath) -> Location {
    let origin = raw.start_origin();
    match origin {
        Origin::Span {
            file, start, end, ..
        } => {
            let text = ws.text(&file.path).unwrap_or_default();
            let idx = ws.line_index(&text);
            Location {
                path: file.path.clone(),
                start: idx.pos(start),
                end: idx.pos(end),
            }
        }
        Origin::Entity(e) => {
            let line = e.line.saturating_sub(1) as u32;
            Location {
                path: e.file.path.clone(),
                start: Pos { line, col: 0 },
                end: Pos { line, col: 0 },
            }
        }
        o => {
            let path = o.file().map(|f| f.path.clone()).unwrap_or_default();
            Location {
                path,
                start: Pos { line: 0, col: 0 },
                end: Pos { line: 0, col: 0 },
            }
        }
    }
}

/// The subpath name at an offset: `>NAME` parameters and `path NAME` headers.
fn name_at(a: &Analysis, offset: usize) -> Option<String> {
    if let Some((_, el)) = element_at(a, offset) {
        let p = el
            .params
            .iter()
            .find(|p| p.span.start <= offset && offset <= p.span.end && p.value.starts_with('>'))?;
        return Some(p.value[1..].to_string());
    }
    a.ast
        .paths()
        .find(|p| p.name.span.start <= offset && offset <= p.name.span.end)
        .map(|p| p.name.value.clone())
}

/// Go to definition of a subpath name.
pub fn definition(a: &Analysis, ws: &Workspace, offset: usize) -> Vec<Location> {
    let Some(name) = name_at(a, offset) else {
        return Vec::new();
    };
    lookup(ws, &a.path, &name)
        .map(|raw| vec![location_of(ws, &raw)])
        .unwrap_or_default()
}

/// Every embedding of a path name in the workspace (text and DXF files).
pub fn references(a: &Analysis, ws: &Workspace, offset: usize) -> Vec<Location> {
    let Some(name) = name_at(a, offset) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for f in workspace_files(ws) {
        let fref = file_ref(&f);
        let objects = if millpath_core::load::fs::is_text_file(&f) {
            let Some(text) = ws.text(&f) else { continue };
            let mut d = millpath_core::Diags::default();
            millpath_core::front::text::text_objects(&text, &fref, &mut d)
                .map(|t| t.objects)
                .unwrap_or_default()
        } else {
            let Ok(bytes) = std::fs::read(&f) else {
                continue;
            };
            let Ok(dxf) = millpath_dxf::read_dxf(&bytes) else {
                continue;
            };
            let s = ws.settings_for(&f).settings;
            let Ok(p) =
                millpath_core::load::names::Patterns::shared(&s.path_pattern, &s.file_pattern)
            else {
                continue;
            };
            let opts = millpath_core::front::dxf::FrontOptions {
                layer_pattern: &p.path_full,
                path_pattern: &p.path_cs,
                pattern_text: &p.path_text,
                debug: None,
                input: s.input,
            };
            let mut d = millpath_core::Diags::default();
            millpath_core::front::dxf::dxf_objects(&dxf, &fref, &opts, &mut d)
                .map(|x| x.0)
                .unwrap_or_default()
        };
        for o in objects {
            let Some(t) = &o.text else { continue };
            if t.raw('>') != Some(name.as_str()) {
                continue;
            }
            match &t.origin {
                Origin::Span { start, end, .. } => {
                    let text = ws.text(&f).unwrap_or_default();
                    let idx = ws.line_index(&text);
                    out.push(Location {
                        path: f.clone(),
                        start: idx.pos(*start),
                        end: idx.pos(*end),
                    });
                }
                Origin::Entity(e) => {
                    let line = e.line.saturating_sub(1) as u32;
                    out.push(Location {
                        path: f.clone(),
                        start: Pos { line, col: 0 },
                        end: Pos { line, col: 0 },
                    });
                }
                _ => {}
            }
        }
    }
    out
}

#[derive(Debug, Clone, PartialEq)]
pub struct Symbol {
    pub name: String,
    pub detail: String,
    /// `true` for paths, `false` for elements.
    pub is_path: bool,
    pub start: usize,
    pub end: usize,
    pub children: Vec<Symbol>,
}

pub fn document_symbols(a: &Analysis) -> Vec<Symbol> {
    a.ast
        .paths()
        .map(|p| Symbol {
            name: p.name.value.clone(),
            detail: format!("{} elements", p.elements().count()),
            is_path: true,
            start: p.span.start,
            end: p.span.end,
            children: p
                .elements()
                .map(|e| Symbol {
                    name: format!(
                        "{} {}",
                        e.kind.value.words(),
                        millpath_syntax::format::geometry(&e.geometry.value)
                    ),
                    detail: e
                        .params
                        .iter()
                        .map(|p| p.value.as_str())
                        .collect::<Vec<_>>()
                        .join(" "),
                    is_path: false,
                    start: e.span.start,
                    end: e.span.end,
                    children: Vec::new(),
                })
                .collect(),
        })
        .collect()
}

/// Paths of every workspace file whose name contains `query` (case-insensitive).
pub fn workspace_symbols(ws: &Workspace, query: &str) -> Vec<(String, Location)> {
    let q = query.to_lowercase();
    let mut out = Vec::new();
    for f in workspace_files(ws) {
        let fs = ws.fs();
        let Ok(mut session) = Session::new(ws.settings_for(&f).settings, &fs) else {
            continue;
        };
        for name in session.load_file(&f) {
            if name.to_lowercase().contains(&q) {
                if let Some(raw) = session.raw_path(&name) {
                    out.push((name, location_of(ws, &raw)));
                }
            }
        }
    }
    out
}

#[derive(Debug, Clone, PartialEq)]
pub struct Completion {
    pub label: String,
    pub detail: String,
    pub insert: String,
}

/// Parameter letters valid for the element (not yet given), subpath names after `>`, element
/// kinds at the start of a line.
pub fn completion(a: &Analysis, ws: &Workspace, offset: usize) -> Vec<Completion> {
    let german = de(a);
    let line_start = a.src[..offset.min(a.src.len())]
        .rfind('\n')
        .map_or(0, |p| p + 1);
    let before = &a.src[line_start..offset.min(a.src.len())];
    let word = before.rsplit(char::is_whitespace).next().unwrap_or("");
    if let Some(prefix) = word.strip_prefix('>') {
        let mut names: Vec<String> = workspace_symbols(ws, prefix)
            .into_iter()
            .map(|(n, _)| n)
            .collect();
        names.sort();
        names.dedup();
        return names
            .into_iter()
            .map(|n| Completion {
                label: n.clone(),
                detail: "subpath".into(),
                insert: n,
            })
            .collect();
    }
    if before.trim().is_empty() || !before.trim_start().contains(' ') && !before.contains('(') {
        let inside = a
            .ast
            .paths()
            .any(|p| p.span.start < offset && offset <= p.span.end);
        if inside {
            return [
                "start",
                "end",
                "turn",
                "probe",
                "noprobe",
                "mill",
                "mark",
                "bars",
                "sub",
                "sweep",
                "move",
                "skip",
                "drill",
                "helix",
                "mark drill",
                "mark helix",
                "bars helix",
            ]
            .iter()
            .map(|k| Completion {
                label: k.to_string(),
                detail: "element".into(),
                insert: format!("{k} "),
            })
            .collect();
        }
        return vec![Completion {
            label: "path".into(),
            detail: "path block".into(),
            insert: "path ".into(),
        }];
    }
    let Some((_, el)) = element_at(a, offset.saturating_sub(1)).or_else(|| element_at(a, offset))
    else {
        return Vec::new();
    };
    if offset < el.geometry.span.end || !word.is_empty() && word.len() > 1 {
        return Vec::new();
    }
    keys_for(&el.kind.value)
        .chars()
        .filter(|k| *k == ':' || !el.params.iter().any(|p| p.value.starts_with(*k)))
        .filter_map(|k| {
            let (meaning, unit, _) = param_doc(k, german)?;
            Some(Completion {
                label: k.to_string(),
                detail: if unit.is_empty() {
                    meaning.to_string()
                } else {
                    format!("{meaning} ({unit})")
                },
                insert: k.to_string(),
            })
        })
        .collect()
}

/// The canonical form of the document, when it parses.
pub fn format(a: &Analysis) -> Option<String> {
    millpath_core::convert::format_text(&a.src, &file_ref(&a.path)).ok()
}

#[derive(Debug, Clone, PartialEq)]
pub struct Action {
    pub title: String,
    pub edits: Vec<TextEdit>,
}

fn start_element<'a>(a: &'a Analysis, path_name: &str) -> Option<&'a Element> {
    a.ast
        .paths()
        .filter(|p| p.name.value == path_name)
        .flat_map(|p| p.elements())
        .find(|e| matches!(e.kind.value, Kind::Start))
}

fn path_at(a: &Analysis, offset: usize) -> Option<&PathBlock> {
    a.ast
        .paths()
        .find(|p| p.span.start <= offset && offset <= p.span.end)
}

/// Quick fixes for the diagnostics in `start..end`.
pub fn code_actions(a: &Analysis, start: usize, end: usize) -> Vec<Action> {
    let mut out = Vec::new();
    for d in &a.diagnostics {
        let Origin::Span {
            start: ds,
            end: de_,
            ..
        } = d.origin
        else {
            continue;
        };
        if de_ < start || ds > end {
            continue;
        }
        let Some(block) = path_at(a, ds) else {
            continue;
        };
        match d.msg {
            Msg::ValueMissing
                if d.args
                    .first()
                    .is_some_and(|k| k.len() == 1 && "BDIOTMPU".contains(k.as_str())) =>
            {
                let key = &d.args[0];
                let Some(st) = start_element(a, &block.name.value) else {
                    continue;
                };
                let at = st
                    .params
                    .last()
                    .map_or(st.geometry.span.end, |p| p.span.end);
                let sep = if st.params.is_empty() { "  " } else { " " };
                let placeholder = if key == "M" { "M?" } else { "0" };
                let value = if key == "M" {
                    placeholder.to_string()
                } else {
                    format!("{key}{placeholder}")
                };
                out.push(Action {
                    title: format!(
                        "Add {value} at the start of {} (then set the real value)",
                        block.name.value
                    ),
                    edits: vec![TextEdit {
                        start: at,
                        end: at,
                        text: format!("{sep}{value}"),
                    }],
                });
            }
            Msg::DNotAboveB => {
                let Some(st) = start_element(a, &block.name.value) else {
                    continue;
                };
                let b = st.params.iter().find(|p| p.value.starts_with('B'));
                let dd = st.params.iter().find(|p| p.value.starts_with('D'));
                if let (Some(b), Some(dd)) = (b, dd) {
                    out.push(Action {
                        title: "Swap the values of B and D".into(),
                        edits: vec![
                            TextEdit {
                                start: b.span.start,
                                end: b.span.end,
                                text: format!("B{}", &dd.value[1..]),
                            },
                            TextEdit {
                                start: dd.span.start,
                                end: dd.span.end,
                                text: format!("D{}", &b.value[1..]),
                            },
                        ],
                    });
                }
            }
            Msg::NoMoreSegments => {
                let Some(pos) = d.args.first().and_then(|p| parse_point(p)) else {
                    continue;
                };
                let line_end = a.src[ds..].find('\n').map_or(a.src.len(), |p| ds + p + 1);
                let indent = "  ";
                out.push(Action {
                    title: format!(
                        "Close the dead end with a turn marker at ({}, {})",
                        pos.0, pos.1
                    ),
                    edits: vec![TextEdit {
                        start: line_end,
                        end: line_end,
                        text: format!("{indent}turn ({}, {})\n", pos.0, pos.1),
                    }],
                });
                out.extend(sweep_to_end(block, &pos, line_end));
            }
            Msg::EndNotAtLast => {
                // the walk ended somewhere else: sweep from there to the end marker
                let Some(path) = raw_path(a, &block.name.value) else {
                    continue;
                };
                let (Some(st), Some(en)) = (&path.start, &path.end) else {
                    continue;
                };
                let mut diags = millpath_core::Diags::default();
                let steps = traverse(path, st.pos, en.pos, &mut diags);
                let Some(last) = steps.last() else { continue };
                let sh = &path.segments[last.index].shape;
                let p = if last.reversed { sh.start() } else { sh.end() };
                let line_end = a.src[ds..].find('\n').map_or(a.src.len(), |x| ds + x + 1);
                out.extend(sweep_to_end(block, &(fmt_num(p.x), fmt_num(p.y)), line_end));
            }
            _ => {}
        }
    }
    out
}

/// "Add a sweep from (x, y) to the end marker", inserted at `at`.
fn sweep_to_end(block: &PathBlock, from: &(String, String), at: usize) -> Option<Action> {
    let end_marker = block
        .elements()
        .find(|e| matches!(e.kind.value, Kind::End))?;
    let Geometry::Point(e) = end_marker.geometry.value else {
        return None;
    };
    Some(Action {
        title: format!(
            "Add a sweep from ({}, {}) to the end marker",
            from.0, from.1
        ),
        edits: vec![TextEdit {
            start: at,
            end: at,
            text: format!(
                "  sweep ({}, {}) -> ({}, {})\n",
                from.0,
                from.1,
                fmt_num(e.x),
                fmt_num(e.y)
            ),
        }],
    })
}

/// `[x y]` as printed in messages → the drawing's coordinates (3 decimals).
fn parse_point(s: &str) -> Option<(String, String)> {
    let inner = s.trim().strip_prefix('[')?.strip_suffix(']')?;
    let (x, y) = inner.split_once(' ')?;
    let clean = |v: &str| -> Option<String> { Some(fmt_num(v.parse::<f64>().ok()?)) };
    Some((clean(x)?, clean(y)?))
}

/// Semantic token types, in the order of the legend.
pub const TOKEN_TYPES: &[&str] = &[
    "keyword", "number", "property", "string", "comment", "type", "operator",
];

#[derive(Debug, Clone, PartialEq)]
pub struct SemToken {
    pub start: usize,
    pub end: usize,
    pub kind: u32,
}

pub fn semantic_tokens(a: &Analysis) -> Vec<SemToken> {
    let mut out = Vec::new();
    let push = |out: &mut Vec<SemToken>, start: usize, end: usize, kind: u32| {
        if end > start {
            out.push(SemToken { start, end, kind });
        }
    };
    for item in &a.ast.items {
        match item {
            Item::Comment(c) => push(&mut out, c.span.start, c.span.end, 4),
            Item::Path(p) => {
                push(&mut out, p.span.start, p.span.start + 4, 0);
                push(&mut out, p.name.span.start, p.name.span.end, 5);
                if let Some(c) = &p.comment {
                    push(&mut out, c.span.start, c.span.end, 4);
                }
                for pi in &p.items {
                    match pi {
                        PathItem::Comment(c) => push(&mut out, c.span.start, c.span.end, 4),
                        PathItem::Element(e) => {
                            push(&mut out, e.kind.span.start, e.kind.span.end, 0);
                            // numbers of the geometry
                            let g = &a.src[e.geometry.span.clone()];
                            let mut i = 0;
                            let bytes = g.as_bytes();
                            while i < bytes.len() {
                                let c = bytes[i] as char;
                                if c.is_ascii_digit()
                                    || ((c == '-' || c == '.')
                                        && i + 1 < bytes.len()
                                        && (bytes[i + 1] as char).is_ascii_digit())
                                {
                                    let s = i;
                                    while i < bytes.len()
                                        && ((bytes[i] as char).is_ascii_digit()
                                            || matches!(bytes[i], b'.' | b'-' | b'e' | b'E' | b'+'))
                                    {
                                        i += 1;
                                    }
                                    push(
                                        &mut out,
                                        e.geometry.span.start + s,
                                        e.geometry.span.start + i,
                                        1,
                                    );
                                } else if g[i..].starts_with("->") {
                                    push(
                                        &mut out,
                                        e.geometry.span.start + i,
                                        e.geometry.span.start + i + 2,
                                        6,
                                    );
                                    i += 2;
                                } else {
                                    i += 1;
                                }
                            }
                            for p in &e.params {
                                let k = p.value.chars().next().map_or(1, char::len_utf8);
                                push(&mut out, p.span.start, p.span.start + k, 2);
                                push(&mut out, p.span.start + k, p.span.end, 3);
                            }
                            if let Some(c) = &e.comment {
                                push(&mut out, c.span.start, c.span.end, 4);
                            }
                        }
                        _ => {}
                    }
                }
            }
            _ => {}
        }
    }
    out.sort_by_key(|t| t.start);
    out
}

#[derive(Debug, Clone, PartialEq)]
pub struct Lens {
    pub offset: usize,
    pub title: String,
    pub path: String,
}

/// [`preview`] computed once per analysis: `ws` must be the workspace `a` was made from.
pub fn preview_of(a: &Analysis, ws: &Workspace, name: Option<&str>) -> Result<Preview, String> {
    let key = name.map(str::to_string);
    if let Some(p) = a.previews.lock().ok().and_then(|c| c.get(&key).cloned()) {
        return p;
    }
    let p = preview(ws, &a.path, name);
    if let Ok(mut c) = a.previews.lock() {
        c.insert(key, p.clone());
    }
    p
}

/// One lens per path: its statistics, with the preview as command.
pub fn code_lenses(a: &Analysis, ws: &Workspace) -> Vec<Lens> {
    a.ast
        .paths()
        .map(|p| {
            let title = match preview_of(a, ws, Some(&p.name.value)) {
                Ok(pv) => pv
                    .stats
                    .iter()
                    .map(|s| s.split_whitespace().collect::<Vec<_>>().join(" "))
                    .take(4)
                    .collect::<Vec<_>>()
                    .join(" · "),
                Err(e) => e,
            };
            Lens {
                offset: p.span.start,
                title: format!("▶ G-code · {title}"),
                path: p.name.value.clone(),
            }
        })
        .collect()
}

/// Re-analyses a document (convenience for tests and the server).
pub fn reanalyze(ws: &Workspace, path: &Path) -> Analysis {
    analyze(ws, path)
}

/// The toolpath of a path as JSON for the toolpath view: moves with kind, start, end, depth,
/// arc and source element; probes; bounds.
pub fn toolpath(
    ws: &Workspace,
    path: &Path,
    name: Option<&str>,
) -> Result<serde_json::Value, String> {
    use serde_json::json;
    let TopModel { model, lang, .. } = top_model(ws, path, name)?;
    let name = model.name().to_string();
    let tp = millpath_core::emit::toolpath(&model).map_err(|e| {
        e.iter()
            .map(|d| d.message(lang))
            .collect::<Vec<_>>()
            .join("; ")
    })?;
    let mut texts: std::collections::HashMap<PathBuf, crate::LineIndex> =
        std::collections::HashMap::new();
    let mut source_json = |o: &Origin| -> serde_json::Value {
        match o {
            Origin::Span {
                file, start, line, ..
            } => {
                let idx = texts
                    .entry(file.path.clone())
                    .or_insert_with(|| ws.line_index(&ws.text(&file.path).unwrap_or_default()));
                let p = idx.pos(*start);
                let text = ws
                    .text(&file.path)
                    .and_then(|t| t.lines().nth(p.line as usize).map(|l| l.trim().to_string()))
                    .unwrap_or_default();
                json!({ "file": file.path.display().to_string(), "line": line - 1, "character": p.col, "label": format!("{}:{line}", file.name), "text": text })
            }
            Origin::Entity(e) => json!({
                "file": e.file.path.display().to_string(), "line": e.line.saturating_sub(1), "character": 0,
                "label": format!("{}:{}", e.file.name, e.line), "text": format!("{} on layer {} at {}", e.code_name, e.layer, e.pos),
            }),
            o => {
                json!({ "file": o.file().map(|f| f.path.display().to_string()), "line": 0, "character": 0, "label": o.context(), "text": "" })
            }
        }
    };
    let (mut minx, mut miny, mut maxx, mut maxy) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut minz, mut maxz) = (f64::INFINITY, f64::NEG_INFINITY);
    let moves: Vec<serde_json::Value> = tp
        .moves
        .iter()
        .map(|m| {
            for p in [m.from, m.to] {
                minx = minx.min(p.x);
                miny = miny.min(p.y);
                maxx = maxx.max(p.x);
                maxy = maxy.max(p.y);
            }
            if let Some((c, _)) = m.arc {
                let r = c.dist(m.to.xy());
                minx = minx.min(c.x - r);
                miny = miny.min(c.y - r);
                maxx = maxx.max(c.x + r);
                maxy = maxy.max(c.y + r);
            }
            if m.kind != "rapid" {
                minz = minz.min(m.to.z);
                maxz = maxz.max(m.to.z);
            }
            json!({
                "kind": m.kind,
                "from": [m.from.x, m.from.y, m.from.z],
                "to": [m.to.x, m.to.y, m.to.z],
                "depth": m.to.z,
                "arc": m.arc.map(|(c, ccw)| json!({ "cx": c.x, "cy": c.y, "ccw": ccw })),
                "source": m.source.as_ref().map(&mut source_json),
            })
        })
        .collect();
    let probes: Vec<serde_json::Value> = tp
        .probes
        .iter()
        .map(|(n, p)| json!({ "name": n, "x": p.x, "y": p.y }))
        .collect();
    if !minz.is_finite() {
        minz = 0.0;
        maxz = 0.0;
    }
    Ok(json!({
        "path": name,
        "file": path.display().to_string(),
        "moves": moves,
        "probes": probes,
        "bounds": { "minX": minx, "minY": miny, "maxX": maxx, "maxY": maxy, "minZ": minz, "maxZ": maxz },
    }))
}

/// The toolpath view as a standalone HTML page (the page of `editors/toolpath` with the data
/// embedded).
pub fn toolpath_html(data: &serde_json::Value) -> String {
    const PAGE: &str = include_str!("../../../editors/toolpath/toolpath.html");
    const SLOT: &str = r#"<script id="toolpath-data" type="application/json">null</script>"#;
    let json = data.to_string().replace("</", "<\\/");
    PAGE.replacen(
        SLOT,
        &format!(r#"<script id="toolpath-data" type="application/json">{json}</script>"#),
        1,
    )
}

/// The toolpath as a standalone SVG (top view; cuts coloured by depth, rapid moves dashed,
/// probes as circles).
pub fn toolpath_svg(data: &serde_json::Value) -> String {
    use std::fmt::Write;
    let b = &data["bounds"];
    let f = |v: &serde_json::Value| v.as_f64().unwrap_or(0.0);
    let (minx, miny, maxx, maxy, minz, maxz) = (
        f(&b["minX"]),
        f(&b["minY"]),
        f(&b["maxX"]),
        f(&b["maxY"]),
        f(&b["minZ"]),
        f(&b["maxZ"]),
    );
    let (w, h) = ((maxx - minx).max(1.0), (maxy - miny).max(1.0));
    let pad = w.max(h) * 0.05 + 2.0;
    let colour = |z: f64| {
        let t = if maxz > minz {
            ((maxz - z) / (maxz - minz)).clamp(0.0, 1.0)
        } else {
            1.0
        };
        format!("hsl({:.0},80%,45%)", 220.0 - 220.0 * t)
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{} {} {} {}" width="{:.0}mm" height="{:.0}mm">"#,
        minx - pad,
        -(maxy + pad),
        w + 2.0 * pad,
        h + 2.0 * pad,
        w + 2.0 * pad,
        h + 2.0 * pad
    );
    let _ = writeln!(
        s,
        r#"<g transform="scale(1,-1)" fill="none" stroke-linecap="round">"#
    );
    let stroke = (w.max(h) / 400.0).max(0.05);
    for m in data["moves"].as_array().into_iter().flatten() {
        let kind = m["kind"].as_str().unwrap_or("");
        let (fx, fy) = (f(&m["from"][0]), f(&m["from"][1]));
        let (tx, ty) = (f(&m["to"][0]), f(&m["to"][1]));
        let style = if kind == "rapid" {
            format!(
                r##"stroke="#888" stroke-width="{}" stroke-dasharray="{} {}""##,
                stroke / 2.0,
                stroke * 3.0,
                stroke * 3.0
            )
        } else {
            format!(
                r#"stroke="{}" stroke-width="{stroke}""#,
                colour(f(&m["depth"]))
            )
        };
        if (tx - fx).hypot(ty - fy) < 1e-9 {
            if kind != "rapid" {
                let _ = writeln!(
                    s,
                    r#"<circle cx="{tx}" cy="{ty}" r="{}" {style}/>"#,
                    stroke * 1.5
                );
            }
        } else if m["arc"].is_object() {
            let (cx, cy) = (f(&m["arc"]["cx"]), f(&m["arc"]["cy"]));
            let ccw = m["arc"]["ccw"].as_bool().unwrap_or(true);
            let r = (fx - cx).hypot(fy - cy);
            let (a0, a1) = ((fy - cy).atan2(fx - cx), (ty - cy).atan2(tx - cx));
            let mut sweep = if ccw { a1 - a0 } else { a0 - a1 };
            while sweep <= 1e-9 {
                sweep += std::f64::consts::TAU;
            }
            let large = u8::from(sweep > std::f64::consts::PI);
            let _ = writeln!(
                s,
                r#"<path d="M{fx} {fy} A{r} {r} 0 {large} {} {tx} {ty}" {style}/>"#,
                u8::from(ccw)
            );
        } else {
            let _ = writeln!(
                s,
                r#"<line x1="{fx}" y1="{fy}" x2="{tx}" y2="{ty}" {style}/>"#
            );
        }
    }
    for p in data["probes"].as_array().into_iter().flatten() {
        let _ = writeln!(
            s,
            r##"<circle cx="{}" cy="{}" r="3" stroke="#0a7d3a" stroke-width="{stroke}"/>"##,
            f(&p["x"]),
            f(&p["y"])
        );
    }
    s.push_str("</g>\n</svg>\n");
    s
}
