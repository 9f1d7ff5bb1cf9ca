//! Code lenses: the statistics of each path, with the preview as command.

use crate::preview::preview_of;
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
            let title = match preview_of(a, ws, Some(&p.name.value)) {
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
            Lens {
                offset: p.span.start,
                title: format!("▶ G-code · {title}{}", placeholders.unwrap_or("")),
                path: p.name.value.clone(),
            }
        })
        .collect()
}
