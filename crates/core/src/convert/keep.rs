//! What `text2dxf --into` keeps of the drawing's own paths, so that version control sees
//! only the paths that changed. A path whose canonical text is the one the drawing's own
//! `dxf2text` writes for it is unchanged: its entities stay byte for byte (handles, layers
//! with their `~` suffixes, MTEXT formatting, order). A changed path is written again, on
//! the layer its entities were on.
//!
//! Paths are matched by the name their layer reads back as, ignoring case (as CAD layer
//! names do). Texts go only to elements of their own layer (reference-input.md §2.4), so a
//! path's entities read the same whatever happens to the other paths' entities.

use super::{front_options, layer_name, path_texts, paths_of};
use crate::diag::{Diags, FileRef};
use crate::front::drawing::DrawnObject;
use crate::front::dxf::dxf_objects;
use crate::front::layer::{effective_layer, path_name_of_layer};
use crate::front::options::InputMode;
use crate::load::names::Patterns;
use millpath_dxf::splice::Record;
use std::collections::{BTreeMap, BTreeSet};

/// The key of a path name as a layer reads it back: `_` → `.`, lower case.
pub(super) fn path_key(path: &str) -> String {
    path_name_of_layer(path).to_lowercase()
}

/// The key of the path an entity of `layer` belongs to.
pub(super) fn layer_key(layer: &str) -> String {
    path_key(effective_layer(layer))
}

/// The keys of the paths the text leaves as the drawing has them: the canonical text of
/// each path of that key (usually one) is the same on both sides. Empty when the drawing's
/// paths cannot be read (then every path is written, as a plain `--into` does).
pub(super) fn unchanged_paths(
    target: &[u8],
    text: &[DrawnObject],
    patterns: &Patterns,
    input: InputMode,
) -> BTreeSet<String> {
    let Ok(d) = millpath_dxf::read_dxf(target) else {
        return BTreeSet::new();
    };
    let file = FileRef::new("into.dxf".into());
    let mut diags = Diags::default();
    let Ok((drawn, _)) = dxf_objects(&d, &file, &front_options(patterns, input), &mut diags) else {
        return BTreeSet::new();
    };
    let by_key = |objects: &[DrawnObject]| -> BTreeMap<String, String> {
        let mut keyed: BTreeMap<String, String> = BTreeMap::new();
        for (path, block) in path_texts(objects, &paths_of(objects, patterns)) {
            keyed
                .entry(path_key(&layer_name(path, None)))
                .or_default()
                .push_str(&block);
        }
        keyed
    };
    let (ours, theirs) = (by_key(&drawn), by_key(text));
    ours.into_iter()
        .filter(|(key, block)| theirs.get(key) == Some(block))
        .map(|(key, _)| key)
        .collect()
}

/// The layer each path's entities were on, by path key: the first layer without a `~`
/// suffix among `records`, else the base of the first suffixed one, spelt as the file
/// spells it.
pub(super) fn old_layers<'r>(
    records: impl Iterator<Item = &'r Record>,
) -> BTreeMap<String, String> {
    let mut plain: BTreeMap<String, String> = BTreeMap::new();
    let mut suffixed: BTreeMap<String, String> = BTreeMap::new();
    for r in records {
        let layer = effective_layer(&r.layer);
        let (base, is_suffixed) = split_suffix(layer);
        let first = if is_suffixed {
            &mut suffixed
        } else {
            &mut plain
        };
        first
            .entry(path_key(base))
            .or_insert_with(|| base.to_string());
    }
    for (key, base) in suffixed {
        plain.entry(key).or_insert(base);
    }
    plain
}

/// A layer's base and whether it had a `~letters` suffix (as `path_name_of_layer` reads it).
fn split_suffix(layer: &str) -> (&str, bool) {
    match layer.rfind('~') {
        Some(p)
            if p + 1 < layer.len() && layer[p + 1..].chars().all(|c| c.is_ascii_alphabetic()) =>
        {
            (&layer[..p], true)
        }
        _ => (layer, false),
    }
}

/// The layer a changed path's entity goes on: the path's old layer where it reads back as
/// the same path name (exactly, case included), else the layer `text2dxf` names.
pub(super) fn layer_of(path: &str, suffix: Option<&str>, old: &BTreeMap<String, String>) -> String {
    let own = layer_name(path, None);
    let base = old
        .get(&path_key(&own))
        .filter(|b| path_name_of_layer(b) == path_name_of_layer(&own))
        .map_or(own.clone(), |b| b.clone());
    match suffix {
        Some(s) => format!("{base}~{s}"),
        None => base,
    }
}
