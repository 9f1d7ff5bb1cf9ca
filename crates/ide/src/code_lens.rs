//! Code lenses: the statistics of each path, with the preview as command.

use crate::preview::preview_of;
use crate::{Analysis, Workspace};

#[derive(Debug, Clone, PartialEq)]
pub struct Lens {
    pub offset: usize,
    pub title: String,
    pub path: String,
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
