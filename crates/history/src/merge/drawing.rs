//! The merge of three versions of a drawing: each read as canonical text (`dxf2text`), the
//! texts merged (`super::merge_texts`), the merged paths written into *our* drawing
//! (`text2dxf --into`, deleting the paths the merge deleted) so that our other layers,
//! blocks and dimensions stay. What the text cannot hold is compared on its own: other
//! content changed on their side is a conflict that names it, never lost.

use super::{broken_paths_at, merge_texts, TextMerge};
use millpath_core::convert::{dxf_to_text, kept_entities, text_into_dxf, IntoOutcome};
use millpath_core::diag::FileRef;
use millpath_core::load::names::Patterns;
use millpath_core::{Diagnostic, InputMode, Settings};
use std::collections::BTreeMap;
use std::sync::Arc;

/// One version of the drawing: its bytes and the name messages give it.
pub struct Version<'a> {
    pub bytes: &'a [u8],
    pub file: Arc<FileRef>,
}

/// Per layer and entity type, how many entities their side added (positive) or removed
/// (negative) among the content that is not paths.
pub type OtherChanges = BTreeMap<(String, String), i64>;

/// What merging drawings gives.
#[derive(Debug)]
pub enum DrawingMerge {
    /// Merged: our drawing's new bytes, `None` when it stays as it is.
    Merged(Option<Vec<u8>>),
    /// Conflicts: the merged text with markers, what their side changed outside the
    /// paths, and the paths the merge would make fail to compile.
    Conflict {
        text: TextMerge,
        other: OtherChanges,
        broken: Vec<String>,
    },
}

/// The canonical text of a version; an empty file (git's base of an add/add) has no paths.
pub fn text_of(v: &Version, patterns: &Patterns, input: InputMode) -> Result<String, Diagnostic> {
    if v.bytes.is_empty() {
        return Ok(String::new());
    }
    dxf_to_text(v.bytes, &v.file, patterns, input).map(|(text, _)| text)
}

/// The merged drawing of `ours` and `theirs` with their common `base`; `at`: where the
/// drawing's text stands for the compile check (its `.mpath` twin in the work tree, see
/// [`broken_paths_at`]).
pub fn merge_drawings(
    base: &Version,
    ours: &Version,
    theirs: &Version,
    patterns: &Patterns,
    input: InputMode,
    settings: &Settings,
    at: Option<&std::path::Path>,
) -> Result<DrawingMerge, Vec<Diagnostic>> {
    let texts = [base, ours, theirs].map(|v| text_of(v, patterns, input));
    let [b, o, t] = texts;
    let (b, o, t) = (b.map_err(one)?, o.map_err(one)?, t.map_err(one)?);
    let other = other_changes(base, ours, theirs, [&b, &o, &t], patterns, input)?;
    let text = merge_texts(&b, &o, &t);
    let broken = if text.conflicts.is_empty() {
        broken_paths_at(&o, &t, &text.text, settings, at)
    } else {
        Vec::new()
    };
    if !text.conflicts.is_empty() || !other.is_empty() || !broken.is_empty() {
        return Ok(DrawingMerge::Conflict {
            text,
            other,
            broken,
        });
    }
    let merged_file = FileRef::new(ours.file.path.with_extension("merge.mpath"));
    match text_into_dxf(
        &text.text,
        &merged_file,
        patterns,
        ours.bytes,
        &ours.file,
        input,
        true,
    )? {
        IntoOutcome::Unchanged => Ok(DrawingMerge::Merged(None)),
        IntoOutcome::Written(bytes) => Ok(DrawingMerge::Merged(Some(bytes))),
    }
}

fn one(d: Diagnostic) -> Vec<Diagnostic> {
    vec![d]
}

/// What their side changed in the content that is not paths, where ours did not make the
/// same change: empty when theirs kept the base's (or made ours).
fn other_changes(
    base: &Version,
    ours: &Version,
    theirs: &Version,
    texts: [&str; 3],
    patterns: &Patterns,
    input: InputMode,
) -> Result<OtherChanges, Vec<Diagnostic>> {
    let content = |v: &Version, text: &str| -> Result<Vec<(String, String, String)>, Diagnostic> {
        if v.bytes.is_empty() {
            return Ok(Vec::new());
        }
        let (file, _) = millpath_syntax::parse(text);
        let paths: Vec<String> = file.paths().map(|p| p.name.value.clone()).collect();
        let kept = kept_entities(v.bytes, &paths, patterns, input).map_err(|e| {
            Diagnostic::error(
                millpath_core::Msg::CannotLoadDxf,
                millpath_core::Origin::File(v.file.clone()),
                vec![
                    v.file.path.display().to_string(),
                    millpath_core::diag::dxf_error_arg(&e),
                ],
            )
        })?;
        let mut list: Vec<(String, String, String)> = kept
            .into_iter()
            .map(|(layer, kind, bytes)| (layer, kind, normalized(&bytes)))
            .collect();
        list.sort();
        Ok(list)
    };
    let b = content(base, texts[0]).map_err(one)?;
    let o = content(ours, texts[1]).map_err(one)?;
    let t = content(theirs, texts[2]).map_err(one)?;
    let mut changes = OtherChanges::new();
    if t == b || t == o {
        return Ok(changes);
    }
    for (layer, kind, _) in &t {
        *changes.entry((layer.clone(), kind.clone())).or_default() += 1;
    }
    for (layer, kind, _) in &b {
        *changes.entry((layer.clone(), kind.clone())).or_default() -= 1;
    }
    // the same count of another content: changed in place
    // a multiset difference by counts: linear in the drawing's entities
    let mut count: std::collections::HashMap<&(String, String, String), i64> =
        std::collections::HashMap::new();
    t.iter().for_each(|e| *count.entry(e).or_default() += 1);
    b.iter().for_each(|e| *count.entry(e).or_default() -= 1);
    let changed_in_place: Vec<(String, String)> = count
        .into_iter()
        .filter(|(_, n)| *n != 0)
        .map(|((l, k, _), _)| (l.clone(), k.clone()))
        .collect();
    changes.retain(|_, n| *n != 0);
    for key in changed_in_place {
        changes.entry(key).or_insert(0);
    }
    Ok(changes)
}

/// An entity's content without what a CAD program renumbers when it saves (the handle and
/// the pointers to other objects) and with numbers in one spelling.
fn normalized(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes);
    let lines: Vec<&str> = text.lines().map(str::trim).collect();
    let mut out = String::new();
    for pair in lines.chunks(2) {
        let [code, value] = pair else { continue };
        if matches!(*code, "5" | "105" | "330" | "340" | "350" | "360") {
            continue;
        }
        let value = match value.parse::<f64>() {
            Ok(v) if v.is_finite() => format!("{v}"),
            _ => value.to_string(),
        };
        out.push_str(code);
        out.push('=');
        out.push_str(&value);
        out.push('\n');
    }
    out
}
