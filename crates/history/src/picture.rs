//! The visual diff: the moves of both versions of a path in one top view. A move both
//! versions make is grey; one only the old version makes red, only the new green; a move
//! whose X and Y stay but whose depth changed is drawn in the third colour (blue) on the
//! new side (its old twin not drawn red). The SVG is the picture (`--svg`, and `--png`
//! through the command line's rasteriser); the HTML page holds it with a toggle between
//! before, after and both, and both texts: clicking a move marks its element in the
//! version(s) it comes from.

use crate::compiled::MoveKey;
use crate::diff::{Diff, PathDiff};
use std::collections::HashMap;
use std::fmt::Write;

pub const REMOVED: &str = "#d62728";
pub const ADDED: &str = "#2ca02c";
pub const DEPTH: &str = "#1f5fd6";
pub const SAME: &str = "#9a9a9a";

/// How one drawn move differs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    Same,
    Removed,
    Added,
    Depth,
}

/// A move to draw: which version(s), its mark, its element's line in each.
struct Drawn<'a> {
    key: &'a MoveKey,
    mark: Mark,
    old_line: usize,
    new_line: usize,
}

fn xy(k: &MoveKey) -> [i64; 4] {
    [k.1[0], k.1[1], k.1[3], k.1[4]]
}

/// The moves of a path with their marks (rapids left out: they are no cut).
fn drawn(p: &PathDiff) -> Vec<Drawn<'_>> {
    static EMPTY: Vec<(MoveKey, usize)> = Vec::new();
    let old = p.before.as_ref().map_or(&EMPTY, |o| &o.sequence);
    let new = p.after.as_ref().map_or(&EMPTY, |o| &o.sequence);
    let cutting = |v: &'_ Vec<(MoveKey, usize)>| -> Vec<usize> {
        (0..v.len()).filter(|&i| v[i].0 .0 != "rapid").collect()
    };
    let (co, cn) = (cutting(old), cutting(new));
    // exact twins first, then twins in X and Y (a depth change)
    let mut waiting: HashMap<&MoveKey, Vec<usize>> = HashMap::new();
    for &i in co.iter().rev() {
        waiting.entry(&old[i].0).or_default().push(i);
    }
    let mut out = Vec::new();
    let mut old_used = vec![false; old.len()];
    let mut new_left = Vec::new();
    for &j in &cn {
        match waiting.get_mut(&new[j].0).and_then(Vec::pop) {
            Some(i) => {
                old_used[i] = true;
                out.push(Drawn {
                    key: &new[j].0,
                    mark: Mark::Same,
                    old_line: old[i].1,
                    new_line: new[j].1,
                });
            }
            None => new_left.push(j),
        }
    }
    let mut by_xy: HashMap<[i64; 4], Vec<usize>> = HashMap::new();
    for &i in co.iter().rev().filter(|&&i| !old_used[i]) {
        by_xy.entry(xy(&old[i].0)).or_default().push(i);
    }
    for j in new_left {
        match by_xy.get_mut(&xy(&new[j].0)).and_then(Vec::pop) {
            Some(i) => {
                old_used[i] = true;
                out.push(Drawn {
                    key: &new[j].0,
                    mark: Mark::Depth,
                    old_line: old[i].1,
                    new_line: new[j].1,
                });
            }
            None => out.push(Drawn {
                key: &new[j].0,
                mark: Mark::Added,
                old_line: 0,
                new_line: new[j].1,
            }),
        }
    }
    for &i in co.iter().filter(|&&i| !old_used[i]) {
        out.push(Drawn {
            key: &old[i].0,
            mark: Mark::Removed,
            old_line: old[i].1,
            new_line: 0,
        });
    }
    out
}

/// The SVG path data of a move in drawing units (Y up, flipped by the caller's transform).
/// A plunge (no X/Y travel: a drill) is a small ring of radius `dot`.
fn path_data(k: &MoveKey, dot: f64) -> String {
    let f = |v: i64| v as f64 / 1000.0;
    let (x0, y0, x1, y1) = (f(k.1[0]), f(k.1[1]), f(k.1[3]), f(k.1[4]));
    if k.2.is_none() && k.1[0] == k.1[3] && k.1[1] == k.1[4] {
        return format!(
            "M{} {y0}A{dot} {dot} 0 1 0 {} {y0}A{dot} {dot} 0 1 0 {} {y0}",
            x0 - dot,
            x0 + dot,
            x0 - dot
        );
    }
    match k.2 {
        Some((cx, cy, ccw)) => {
            let r = (x0 - f(cx)).hypot(y0 - f(cy));
            if (x0 - x1).abs() < 1e-9 && (y0 - y1).abs() < 1e-9 {
                // a full circle: two halves
                let (mx, my) = (2.0 * f(cx) - x0, 2.0 * f(cy) - y0);
                format!(
                    "M{x0} {y0}A{r} {r} 0 0 {s} {mx} {my}A{r} {r} 0 0 {s} {x0} {y0}",
                    s = u8::from(ccw)
                )
            } else {
                let a0 = (y0 - f(cy)).atan2(x0 - f(cx));
                let a1 = (y1 - f(cy)).atan2(x1 - f(cx));
                let mut sweep = if ccw { a1 - a0 } else { a0 - a1 };
                if sweep <= 0.0 {
                    sweep += std::f64::consts::TAU;
                }
                let large = u8::from(sweep > std::f64::consts::PI);
                format!("M{x0} {y0}A{r} {r} 0 {large} {} {x1} {y1}", u8::from(ccw))
            }
        }
        None => format!("M{x0} {y0}L{x1} {y1}"),
    }
}

/// Bounds of every drawn move (min x, min y, max x, max y).
fn bounds(moves: &[Drawn]) -> (f64, f64, f64, f64) {
    let mut b = (
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    );
    for m in moves {
        for (x, y) in [(m.key.1[0], m.key.1[1]), (m.key.1[3], m.key.1[4])] {
            let (x, y) = (x as f64 / 1000.0, y as f64 / 1000.0);
            b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
        }
        if let Some((cx, cy, _)) = m.key.2 {
            let r = ((m.key.1[0] - cx) as f64).hypot((m.key.1[1] - cy) as f64) / 1000.0;
            let (cx, cy) = (cx as f64 / 1000.0, cy as f64 / 1000.0);
            b = (
                b.0.min(cx - r),
                b.1.min(cy - r),
                b.2.max(cx + r),
                b.3.max(cy + r),
            );
        }
    }
    if !b.0.is_finite() {
        b = (0.0, 0.0, 1.0, 1.0);
    }
    b
}

fn colour(m: Mark) -> &'static str {
    match m {
        Mark::Same => SAME,
        Mark::Removed => REMOVED,
        Mark::Added => ADDED,
        Mark::Depth => DEPTH,
    }
}

fn class(m: Mark) -> &'static str {
    match m {
        Mark::Same => "same",
        Mark::Removed => "removed",
        Mark::Added => "added",
        Mark::Depth => "depth",
    }
}

/// The top view of every compiled path of the diff as one SVG (paths side by side in
/// drawing coordinates would overlap: each path gets its own panel, stacked).
pub fn svg(d: &Diff) -> String {
    let panels: Vec<(&PathDiff, Vec<Drawn>)> = d.paths.iter().map(|p| (p, drawn(p))).collect();
    let width = 800.0;
    let mut body = String::new();
    let mut y_at = 0.0;
    for (pi, (p, moves)) in panels.iter().enumerate() {
        let (x0, y0, x1, y1) = bounds(moves);
        let (w, h) = ((x1 - x0).max(1.0), (y1 - y0).max(1.0));
        let margin = 0.05 * w.max(h);
        let scale = (width - 20.0) / (w + 2.0 * margin);
        let ph = (h + 2.0 * margin) * scale;
        let stroke = (1.5 / scale).max(1e-3);
        let _ = write!(
            body,
            r#"<g data-path="{name}" transform="translate(10 {ty}) scale({scale} {neg}) translate({tx} {ty2})">"#,
            name = p.name,
            ty = y_at + 10.0 + ph,
            neg = -scale,
            tx = -(x0 - margin),
            ty2 = -(y0 - margin),
        );
        // grey below, the changes above
        let mut order: Vec<&Drawn> = moves.iter().collect();
        order.sort_by_key(|m| m.mark != Mark::Same);
        for (mi, m) in order.iter().enumerate() {
            let _ = write!(
                body,
                r#"<path id="m{pi}-{mi}" class="{c}" d="{d}" stroke="{col}" stroke-width="{sw}" fill="none" data-old-line="{ol}" data-new-line="{nl}" data-path="{name}"/>"#,
                c = class(m.mark),
                d = path_data(m.key, 4.0 * stroke),
                col = colour(m.mark),
                sw = if m.mark == Mark::Same {
                    stroke
                } else {
                    2.0 * stroke
                },
                ol = m.old_line,
                nl = m.new_line,
                name = p.name,
            );
        }
        body.push_str("</g>");
        y_at += ph + 20.0;
    }
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{h}" viewBox="0 0 {width} {h}"><rect width="100%" height="100%" fill="white"/>{body}</svg>"#,
        h = (y_at + 10.0).max(20.0)
    )
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn listing(id: &str, title: &str, text: &str) -> String {
    let mut out = format!(
        r#"<div class="text" id="{id}"><h3>{}</h3><pre>"#,
        escape(title)
    );
    for (i, l) in text.lines().enumerate() {
        let _ = writeln!(
            out,
            r#"<span id="{id}-{n}" class="line">{n:>5}  {}</span>"#,
            escape(l),
            n = i + 1
        );
    }
    out.push_str("</pre></div>");
    out
}

/// The standalone page: the picture with the toggle, both texts, the click.
pub fn html(d: &Diff, title: &str, old: (&str, &str), new: (&str, &str), german: bool) -> String {
    let (before, after, both) = if german {
        ("vorher", "nachher", "beides")
    } else {
        ("before", "after", "both")
    };
    let legend = if german {
        "rot: entfernt · grün: hinzugefügt · blau: andere Tiefe · grau: unverändert"
    } else {
        "red: removed · green: added · blue: changed depth · grey: unchanged"
    };
    format!(
        r#"<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>{t}</title>
<style>
body {{ font-family: sans-serif; margin: 1em; }}
#view .hidden {{ display: none; }}
#view path {{ cursor: pointer; pointer-events: all; }}
#texts {{ display: flex; gap: 1em; }}
.text {{ flex: 1; overflow: auto; max-height: 40em; }}
.line {{ display: block; white-space: pre; }}
.line.selected {{ background: #ffe98a; }}
button.on {{ font-weight: bold; }}
</style></head><body>
<h2>{t}</h2>
<div id="toggle"><button id="show-before">{before}</button> <button id="show-after">{after}</button> <button id="show-both" class="on">{both}</button> <span>{legend}</span></div>
<div id="view">{svg}</div>
<div id="texts">{lo}{ln}</div>
<script>
const view = document.getElementById('view');
function show(which) {{
  for (const p of view.querySelectorAll('path')) {{
    // a depth change stands at the same place in both versions
    const c = p.classList.contains('added') ? 'added' : p.classList.contains('removed') ? 'removed' : '';
    p.classList.toggle('hidden', which === 'before' ? c === 'added' : which === 'after' ? c === 'removed' : false);
  }}
  for (const b of document.querySelectorAll('#toggle button')) b.classList.toggle('on', b.id === 'show-' + which);
}}
for (const w of ['before', 'after', 'both']) document.getElementById('show-' + w).onclick = () => show(w);
function select(side, line) {{
  for (const s of document.querySelectorAll('#' + side + ' .selected')) s.classList.remove('selected');
  const el = document.getElementById(side + '-' + line);
  if (el) {{ el.classList.add('selected'); el.scrollIntoView({{block: 'center'}}); }}
}}
view.addEventListener('click', e => {{
  const p = e.target.closest('path');
  if (!p) return;
  select('old', p.dataset.oldLine);
  select('new', p.dataset.newLine);
}});
</script></body></html>
"#,
        t = escape(title),
        svg = svg(d),
        lo = listing("old", old.0, old.1),
        ln = listing("new", new.0, new.1),
    )
}
