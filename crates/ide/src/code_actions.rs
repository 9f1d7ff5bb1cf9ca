//! Quick fixes for diagnostics.

use crate::common::*;
use crate::Analysis;
use millpath_core::build::traverse::traverse;
use millpath_core::diag::{Msg, Origin};
use millpath_core::params::fmt_num;
use millpath_syntax::{Geometry, Kind, PathBlock};

#[derive(Debug, Clone, PartialEq)]
pub struct Action {
    pub title: String,
    pub edits: Vec<TextEdit>,
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
        let (ds, de_) = (ds as usize, de_ as usize);
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
                let title = if de(a) {
                    format!(
                        "{value} am Anfang von {} ergänzen (dann den richtigen Wert eintragen)",
                        block.name.value
                    )
                } else {
                    format!(
                        "Add {value} at the start of {} (then set the real value)",
                        block.name.value
                    )
                };
                out.push(Action {
                    title,
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
                        title: if de(a) {
                            "Die Werte von B und D tauschen"
                        } else {
                            "Swap the values of B and D"
                        }
                        .into(),
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
                let title = if de(a) {
                    format!(
                        "Das Sackgassen-Ende mit einer Wendemarke bei ({}, {}) schließen",
                        pos.0, pos.1
                    )
                } else {
                    format!(
                        "Close the dead end with a turn marker at ({}, {})",
                        pos.0, pos.1
                    )
                };
                out.push(Action {
                    title,
                    edits: vec![TextEdit {
                        start: line_end,
                        end: line_end,
                        text: format!("{indent}turn ({}, {})\n", pos.0, pos.1),
                    }],
                });
                out.extend(sweep_to_end(block, &pos, line_end, de(a)));
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
                out.extend(sweep_to_end(
                    block,
                    &(fmt_num(p.x), fmt_num(p.y)),
                    line_end,
                    de(a),
                ));
            }
            Msg::OrderDecidesText => out.extend(pin_order(a, ds, d.args.get(1))),
            _ => {}
        }
    }
    out
}

/// "Pin the choice with N9997": the element's N value set to the one the warning checked.
fn pin_order(a: &Analysis, at: usize, pin: Option<&String>) -> Option<Action> {
    let pin = pin.filter(|p| p.len() > 1 && p.starts_with('N'))?;
    let (_, el) = element_at(a, at)?;
    let edit = match el.params.iter().find(|p| p.value.starts_with('N')) {
        Some(n) => TextEdit {
            start: n.span.start,
            end: n.span.end,
            text: pin.clone(),
        },
        None => {
            let end = el
                .params
                .last()
                .map_or(el.geometry.span.end, |p| p.span.end);
            let sep = if el.params.is_empty() { "  " } else { " " };
            TextEdit {
                start: end,
                end,
                text: format!("{sep}{pin}"),
            }
        }
    };
    Some(Action {
        title: if de(a) {
            format!("Die Wahl mit {pin} festlegen (unabhängig von der Reihenfolge der Zeilen)")
        } else {
            format!("Pin the choice with {pin} (independent of the order of the lines)")
        },
        edits: vec![edit],
    })
}

/// "Add a sweep from (x, y) to the end marker", inserted at `at`.
pub(crate) fn sweep_to_end(
    block: &PathBlock,
    from: &(String, String),
    at: usize,
    german: bool,
) -> Option<Action> {
    let end_marker = block
        .elements()
        .find(|e| matches!(e.kind.value, Kind::End))?;
    let Geometry::Point(e) = end_marker.geometry.value else {
        return None;
    };
    Some(Action {
        title: if german {
            format!(
                "Eine Leerfahrt von ({}, {}) zur Ende-Markierung ergänzen",
                from.0, from.1
            )
        } else {
            format!(
                "Add a sweep from ({}, {}) to the end marker",
                from.0, from.1
            )
        },
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
pub(crate) fn parse_point(s: &str) -> Option<(String, String)> {
    let inner = s.trim().strip_prefix('[')?.strip_suffix(']')?;
    let (x, y) = inner.split_once(' ')?;
    let clean = |v: &str| -> Option<String> { Some(fmt_num(v.parse::<f64>().ok()?)) };
    Some((clean(x)?, clean(y)?))
}
