//! Hover: a parameter letter, a subpath name, or an element with its effective values.
//!
//! Hover: parameter letters, subpath names, elements with their value table and derived facts.

use crate::common::*;
use crate::param_doc::{allowed_in, param_doc};
use crate::provenance::{provenance, value, Row};
use crate::{Analysis, Workspace};
use millpath_core::emit::chain::pass_depths;
use millpath_core::params::fmt_num;
use millpath_syntax::{Element, Geometry, Kind};

#[derive(Debug, Clone, PartialEq)]
pub struct Hover {
    pub markdown: String,
    pub start: usize,
    pub end: usize,
}

/// Hover: a parameter letter, a subpath name, or an element with its effective values.
pub fn hover(a: &Analysis, ws: &Workspace, offset: usize) -> Option<Hover> {
    if let Some(p) = a
        .ast
        .paths()
        .find(|p| p.name.span.start <= offset && offset <= p.name.span.end)
    {
        return path_hover(a, ws, &p.name.value, p.name.span.clone());
    }
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
    // left-aligned columns: renderers centre the headers of `---` columns
    md.push_str(if german {
        "| Parameter | Wert | Herkunft |\n|:--|:--|:--|\n"
    } else {
        "| parameter | value | from |\n|:--|:--|:--|\n"
    });
    for r in &rows {
        md.push_str(&format!(
            "| {} | {} | {} |\n",
            cell(&r.key.to_string()),
            cell(&r.value),
            cell(&r.source)
        ));
    }
    // a blank line ends the table (a line right after it would become a row)
    md.push('\n');
    md.push_str(derived_facts(a, el, &rows, german).trim_start_matches('\n'));
    Some(Hover {
        markdown: md,
        start: el.kind.span.start,
        end: el.geometry.span.end,
    })
}

/// A path's name: its statistics as `millpath compile` writes them and the exact estimated
/// time (or why it cannot be compiled).
fn path_hover(
    a: &Analysis,
    ws: &Workspace,
    name: &str,
    span: std::ops::Range<usize>,
) -> Option<Hover> {
    let german = de(a);
    let pv = crate::preview::preview_of(a, ws, Some(name)).ok()?;
    let mut md = format!("**{}** `{name}`\n\n", if german { "Pfad" } else { "path" });
    if pv.gcode.is_empty() && !pv.errors.is_empty() {
        md.push_str(&pv.errors.join("\n\n"));
    } else {
        let model = match (a.settings.settings.machine().is_some(), german) {
            (true, false) => "LinuxCNC's planner with the `[machine]` limits",
            (true, true) => "LinuxCNC-Planer mit den `[machine]`-Grenzen",
            (false, false) => "the reference's length / F · 1.4",
            (false, true) => "Referenzformel Länge / F · 1,4",
        };
        md.push_str(&format!(
            "{}: **{}** ({model})\n\n```text\n{}\n```\n",
            if german {
                "Geschätzte Zeit"
            } else {
                "Estimated time"
            },
            pv.time,
            pv.stats.join("\n")
        ));
    }
    Some(Hover {
        markdown: md,
        start: span.start,
        end: span.end,
    })
}

/// A table cell: `|` would split it, a line break end the row.
fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace(['\n', '\r'], " ")
}

/// Pass depths, length and time of mill segments; size of circles.
pub(crate) fn derived_facts(a: &Analysis, el: &Element, rows: &[Row], german: bool) -> String {
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
            // the reference's estimate (length / F · 1.4), as h:mm:ss like every exact time
            let seconds = len * passes.len() as f64 / feed * 1.4 * 60.0;
            out.push_str(&format!(
                "\n{}: {} · {} {} mm · ca. {}",
                if german { "Durchgänge" } else { "passes" },
                list.join(", "),
                if german { "Länge" } else { "length" },
                millpath_core::geom::f3(len),
                millpath_core::emit::stats::hms(seconds)
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

pub(crate) fn subpath_hover(
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
