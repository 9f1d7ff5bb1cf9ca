//! Code lenses: the statistics of each path, with the preview as command.
//!
//! One lens per path: its statistics (marked when placeholder machine settings are in use), the
//! preview as command; `code_lenses_until` stops when asked (a cancelled request).

use crate::preview::preview_of_until;
use crate::{Analysis, Workspace};

#[derive(Debug, Clone, PartialEq)]
pub struct Lens {
    pub offset: usize,
    pub title: String,
    pub path: String,
}

/// One lens per path: its statistics, with the preview as command. Without the machine
/// settings `millpath compile` asks for, the statistics come from the placeholders (F150,
/// S15): the lens says so instead of showing them as real.
pub fn code_lenses(a: &Analysis, ws: &Workspace) -> Vec<Lens> {
    code_lenses_until(a, ws, &|| false).unwrap_or_default()
}

/// [`code_lenses`] that gives up (`None`) when `stop()` turns true, inside the compile of
/// each path's statistics too (a cancelled request stops its work).
pub fn code_lenses_until(
    a: &Analysis,
    ws: &Workspace,
    stop: &dyn Fn() -> bool,
) -> Option<Vec<Lens>> {
    let placeholders = (!a.settings.missing_machine().is_empty()).then(|| {
        if crate::common::de(a) {
            " · ⚠ Maschinenwerte fehlen (Platzhalter)"
        } else {
            " · ⚠ machine settings missing (placeholders)"
        }
    });
    a.ast
        .paths()
        .map(|p| {
            let title = match preview_of_until(a, ws, Some(&p.name.value), stop)? {
                Ok(pv) if pv.gcode.is_empty() && !pv.errors.is_empty() => pv.errors.join("; "),
                Ok(pv) => pv
                    .stats
                    .iter()
                    .map(|s| s.split_whitespace().collect::<Vec<_>>().join(" "))
                    .take(4)
                    .chain([format!("⏱ {}", pv.time)])
                    .collect::<Vec<_>>()
                    .join(" · "),
                Err(e) => e,
            };
            Some(Lens {
                offset: p.span.start,
                title: format!("▶ G-code · {title}{}", placeholders.unwrap_or("")),
                path: p.name.value.clone(),
            })
        })
        .collect()
}
