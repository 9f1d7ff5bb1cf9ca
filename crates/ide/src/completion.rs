//! Completion: element kinds, parameter letters, subpath names.

use crate::common::*;
use crate::param_doc::{keys_for, param_doc};
use crate::symbols::workspace_symbols;
use crate::{Analysis, Workspace};
use millpath_syntax::Kind;

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
    // a quoted text (`"` is a trigger character for post names in millpath.toml)
    if word.starts_with('"') {
        return Vec::new();
    }
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
            return Kind::ALL
                .iter()
                .map(|k| Completion {
                    label: k.words(),
                    detail: "element".into(),
                    insert: format!("{} ", k.words()),
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
        // C (the G81 depth) is accepted for old drawings but has no effect: not offered
        .filter(|k| *k != 'C')
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
