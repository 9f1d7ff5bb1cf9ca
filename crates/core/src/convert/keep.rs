//! What `text2dxf --into` keeps of the drawing's own paths, so that version control sees
//! only the paths that changed. A path whose canonical text is the one the drawing's own
//! `dxf2text` writes for it is unchanged: its entities stay byte for byte (handles, layers
//! with their `~` suffixes, MTEXT formatting, order). In a changed path, an element drawn
//! as before (same line type and shape) keeps its entity, and its text entity when the text
//! is the same; the rest is written again, on the layer the path's entities were on. In the
//! extended mode a changed path is written whole: its line type aliases (`Phantom`) and
//! polylines become the plain entities the reference reads.
//!
//! Paths are matched by the name their layer reads back as, ignoring case (as CAD layer
//! names do). Texts go only to elements of their own layer (reference-input.md §2.4), so a
//! path's entities read the same whatever happens to the other paths' entities.

use super::{
    front_options, layer_name, path_texts, paths_of, plan, settle, texts_match, Placement,
};
use crate::diag::{Diags, FileRef, Origin};
use crate::front::drawing::{DrawnObject, Shape};
use crate::front::dxf::dxf_objects;
use crate::front::layer::{effective_layer, path_name_of_layer, split_layer_suffix};
use crate::front::options::InputMode;
use crate::geom::Geom;
use crate::load::names::Patterns;
use millpath_dxf::splice::{Record, Target};
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet, VecDeque};
use std::sync::Arc;

/// The key of a path name as a layer reads it back: `_` → `.`, lower case.
pub(super) fn path_key(path: &str) -> String {
    path_name_of_layer(path).to_lowercase()
}

/// The key of the path an entity of `layer` belongs to.
pub(super) fn layer_key(layer: &str) -> String {
    path_key(effective_layer(layer))
}

/// A drawing's path objects as the front-end reads them; `None` when it cannot (then every
/// path is written, as a plain `--into` does).
pub(super) fn drawn_objects(
    target: &[u8],
    patterns: &Patterns,
    input: InputMode,
) -> Option<Vec<DrawnObject>> {
    let d = millpath_dxf::read_dxf(target).ok()?;
    let file = FileRef::new("into.dxf".into());
    let mut diags = Diags::default();
    dxf_objects(&d, &file, &front_options(patterns, input), &mut diags)
        .ok()
        .map(|o| o.0)
}

/// The canonical text of the paths of each key (usually one path).
pub(super) fn texts_by_key(
    objects: &[DrawnObject],
    patterns: &Patterns,
) -> BTreeMap<String, String> {
    let mut keyed: BTreeMap<String, String> = BTreeMap::new();
    for (path, block) in path_texts(objects, &paths_of(objects, patterns)) {
        keyed
            .entry(path_key(&layer_name(path, None)))
            .or_default()
            .push_str(&block);
    }
    keyed
}

/// The keys of the paths the text leaves as the drawing has them: the canonical text of
/// each path of that key is the same on both sides.
pub(super) fn unchanged_paths(
    drawn: &[DrawnObject],
    text: &[DrawnObject],
    patterns: &Patterns,
) -> BTreeSet<String> {
    let theirs = texts_by_key(text, patterns);
    texts_by_key(drawn, patterns)
        .into_iter()
        .filter(|(key, block)| theirs.get(key) == Some(block))
        .map(|(key, _)| key)
        .collect()
}

/// The drawing's own entities an element of a changed path keeps (by the line of their
/// `0` group).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct KeptElement {
    pub geometry: usize,
    /// Its text entity, when the text is the same.
    pub text: Option<usize>,
    /// The layer of the geometry entity, as the file spells it (a new text of the element
    /// goes there: texts go only to elements of their own layer).
    pub layer: String,
}

fn entity_line(o: &Origin) -> Option<usize> {
    match o {
        Origin::Entity(e) => Some(e.line),
        _ => None,
    }
}

/// Exact numbers of a shape, for finding the same element.
fn shape_bits(s: &Shape) -> Vec<u64> {
    let v = match s {
        Shape::Circle { c, r } => vec![c.x, c.y, *r],
        Shape::Path(Geom::Line { a, b }) => vec![a.x, a.y, b.x, b.y],
        Shape::Path(Geom::Arc {
            c, r, a0, a1, ccw, ..
        }) => vec![c.x, c.y, *r, *a0, *a1, f64::from(u8::from(*ccw))],
    };
    v.into_iter().map(f64::to_bits).collect()
}

/// For each object of `text`, the entities of the drawing's element it keeps: an element of
/// the drawing with the same path, line type and shape whose entity is a LINE, ARC or
/// CIRCLE of its own (an exploded polyline's parts are not), each used once.
pub(super) fn kept_elements(
    drawn: &[DrawnObject],
    text: &[DrawnObject],
    records: &[Record],
) -> Vec<Option<KeptElement>> {
    let by_line: HashMap<usize, &Record> = records.iter().map(|r| (r.line, r)).collect();
    let mut per_line: HashMap<usize, usize> = HashMap::new();
    for o in drawn {
        if let Some(l) = entity_line(&o.origin) {
            *per_line.entry(l).or_default() += 1;
        }
    }
    type Key = (String, Arc<str>, Vec<u64>);
    let key =
        |o: &DrawnObject| -> Key { (path_key(&o.path), o.linetype.clone(), shape_bits(&o.shape)) };
    let mut candidates: HashMap<Key, VecDeque<&DrawnObject>> = HashMap::new();
    for o in drawn {
        let own = entity_line(&o.origin)
            .filter(|l| per_line.get(l) == Some(&1))
            .and_then(|l| by_line.get(&l))
            .is_some_and(|r| matches!(r.kind.as_str(), "LINE" | "ARC" | "CIRCLE"));
        if own {
            candidates.entry(key(o)).or_default().push_back(o);
        }
    }
    text.iter()
        .map(|o| {
            let old = candidates.get_mut(&key(o))?.pop_front()?;
            let geometry = entity_line(&old.origin)?;
            let text = old
                .text
                .as_ref()
                .filter(|_| texts_match(old.text.as_deref(), o.text.as_deref()))
                .and_then(|t| entity_line(&t.origin))
                .filter(|l| {
                    by_line
                        .get(l)
                        .is_some_and(|r| matches!(r.kind.as_str(), "TEXT" | "MTEXT"))
                });
            Some(KeptElement {
                geometry,
                text,
                layer: by_line.get(&geometry)?.layer.clone(),
            })
        })
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
        let (base, is_suffixed) = split_layer_suffix(layer);
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

/// The drawing `t` with the objects of the changed paths written in place of the entities
/// `remove` chooses, keeping the entities of their unchanged elements ([`kept_elements`]).
/// `ours` chooses the changed paths by name. Where the kept entities would not read back
/// as the text says (a new text taken by a kept element, …), the changed paths are written
/// whole instead.
pub(super) fn write_changed(
    t: &Target,
    changed: &[DrawnObject],
    drawn: &[DrawnObject],
    remove: &dyn Fn(&Record) -> bool,
    ours: &dyn Fn(&str) -> bool,
    patterns: &Patterns,
    input: InputMode,
) -> Vec<u8> {
    let old = old_layers(t.entities().iter().filter(|r| remove(r)));
    let write = |keeps: &[Option<KeptElement>]| {
        settle(changed, patterns, ours, &|suffixes| {
            // an element given a parameter-text layer is written again
            let kept = |i: usize| keeps[i].as_ref().filter(|_| suffixes[i].is_none());
            let lines: HashSet<usize> = (0..changed.len())
                .filter_map(kept)
                .flat_map(|k| std::iter::once(k.geometry).chain(k.text))
                .collect();
            let remove = |r: &Record| remove(r) && !lines.contains(&r.line);
            let place = |i: usize, suffix: Option<&str>| match kept(i) {
                Some(k) => Placement {
                    layer: k.layer.clone(),
                    geometry: false,
                    text: k.text.is_none(),
                },
                None => Placement {
                    layer: layer_of(&changed[i].path, suffix, &old),
                    geometry: true,
                    text: true,
                },
            };
            // read back: the kept elements where they stand, then the written ones
            let mut order: Vec<usize> = (0..changed.len()).filter(|&i| kept(i).is_some()).collect();
            order.sort_by_key(|&i| kept(i).map(|k| k.geometry));
            order.extend((0..changed.len()).filter(|&i| kept(i).is_none()));
            (t.splice(&remove, &plan(changed, suffixes, &place).1), order)
        })
    };
    let keeps = match input {
        InputMode::Reference => kept_elements(drawn, changed, t.entities()),
        InputMode::Extended => vec![None; changed.len()],
    };
    if keeps.iter().any(Option::is_some) {
        let out = write(&keeps);
        let wanted = texts_by_key(changed, patterns);
        let written = drawn_objects(&out, patterns, input).unwrap_or_default();
        let mut got = texts_by_key(&written, patterns);
        got.retain(|k, _| wanted.contains_key(k));
        if got == wanted {
            return out;
        }
    }
    write(&vec![None; changed.len()])
}

#[cfg(test)]
mod tests {
    use super::super::{text_into_dxf, text_to_dxf, IntoOutcome};
    use crate::diag::FileRef;
    use crate::front::options::InputMode;
    use crate::load::names::{Patterns, DEFAULT_FILE_PATTERN, DEFAULT_PATH_PATTERN};
    use millpath_dxf::splice::scan;

    const TWO: &str = "path 8998.1P {
  start (0, 0)  M3 O2 T3 I1,5 B-0,2
  end (60, 0)
  mill (0, 0) -> (30, 0)  B-0,3
  mill (30, 0) -> (60, 0)
}

path 8998.2P {
  start (0, 20)  M3 O2 T3 I1,5 B-0,2
  end (40, 20)
  mill (0, 20) -> (20, 20)  B-0,3
  mill (20, 20) -> (40, 20)
}
";

    /// `(layer, kind, bytes)` of every entity.
    fn entities(dxf: &[u8]) -> Vec<(String, String, Vec<u8>)> {
        let t = scan(dxf).unwrap();
        t.entities()
            .iter()
            .map(|r| (r.layer.clone(), r.kind.clone(), t.bytes_of(r).to_vec()))
            .collect()
    }

    #[test]
    fn only_the_edited_element_is_written_again() {
        let patterns = Patterns::new(DEFAULT_PATH_PATTERN, DEFAULT_FILE_PATTERN).unwrap();
        let file = FileRef::new("two.mpath".into());
        let dxf = text_to_dxf(TWO, &file, &patterns).unwrap().into_bytes();
        let target = FileRef::new("two.dxf".into());
        let into = |text: &str| {
            text_into_dxf(
                text,
                &file,
                &patterns,
                &dxf,
                &target,
                InputMode::Reference,
                false,
            )
            .unwrap()
        };
        assert_eq!(into(TWO), IntoOutcome::Unchanged);
        let edited = TWO.replace("(20, 20)  B-0,3", "(20, 20)  B-0,5");
        let IntoOutcome::Written(out) = into(&edited) else {
            panic!("the edit was not written");
        };
        let (before, after) = (entities(&dxf), entities(&out));
        let gone: Vec<_> = before.iter().filter(|e| !after.contains(e)).collect();
        let new: Vec<_> = after.iter().filter(|e| !before.contains(e)).collect();
        // the one text entity: its old bytes out, the new in, on the path's layer
        assert_eq!(gone.len(), 1, "{gone:?}");
        assert_eq!(new.len(), 1, "{new:?}");
        assert_eq!((&gone[0].0[..], &gone[0].1[..]), ("8998_2P", "MTEXT"));
        assert_eq!((&new[0].0[..], &new[0].1[..]), ("8998_2P", "MTEXT"));
        assert!(String::from_utf8_lossy(&new[0].2).contains("B-0,5"));
        // and it reads back as the edited text
        let (text, _) =
            super::super::dxf_to_text(&out, &target, &patterns, InputMode::Reference).unwrap();
        assert_eq!(text, edited);
    }
}
