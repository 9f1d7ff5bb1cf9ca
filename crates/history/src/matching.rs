//! Pairs the paths and elements of two versions of a drawing.
//!
//! Paths pair by name; a removed and an added path whose elements are mostly the same (at
//! least half of the larger one, by kind, geometry and parameters) are a rename. Elements of
//! a path pair in four rounds, each over what the rounds before left:
//! 1. the same kind, geometry and parameter words: unchanged, wherever they stand in the
//!    text (a CAD re-save that reorders the entities changes nothing);
//! 2. the same kind and geometry: the parameters changed;
//! 3. the same geometry, another kind: re-typed;
//! 4. the same kind, shape and parameters, other geometry: moved (the nearest first).
//!
//! Geometry compares to 1e-6 mm (the drawing's tolerance is far coarser, a re-save's float
//! noise far finer); a line compares without its direction, angles modulo 360°. Every round
//! is linear in the number of elements except the nearest-first pairing of round 4, which
//! is bounded ([`NEAREST_LIMIT`]) and pairs in position order beyond it.

use crate::version::{Element, PathVersion, Version};
use millpath_syntax::{Geometry, Kind};
use std::collections::HashMap;

/// Round 4 pairs a group nearest-first while old × new candidates stay below this (the
/// distances are all computed); larger groups pair in the order of their positions.
pub const NEAREST_LIMIT: usize = 250_000;

/// How a matched element changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Relation {
    /// Kind, geometry and parameters as before.
    Same,
    /// The same kind and geometry, other parameter words.
    Params,
    /// The same geometry, another kind (the parameters may differ too).
    Retyped,
    /// The same kind and parameters, the geometry shifted or reshaped.
    Moved,
}

/// An element of the old version paired with one of the new.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ElementMatch {
    /// Index into the old path's elements.
    pub old: usize,
    /// Index into the new path's elements.
    pub new: usize,
    pub relation: Relation,
}

/// The pairing of two element lists.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Pairing {
    /// In the order of the new elements.
    pub pairs: Vec<ElementMatch>,
    /// Old elements without a partner (ascending).
    pub removed: Vec<usize>,
    /// New elements without a partner (ascending).
    pub added: Vec<usize>,
}

impl Pairing {
    /// Nothing changed (possibly reordered).
    pub fn unchanged(&self) -> bool {
        self.removed.is_empty()
            && self.added.is_empty()
            && self.pairs.iter().all(|p| p.relation == Relation::Same)
    }
}

/// The pairing of two versions' paths.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PathPairing {
    /// (old index, new index) into `Version::paths`: same name, or renamed when the names
    /// differ.
    pub both: Vec<(usize, usize)>,
    /// Old paths without a partner.
    pub removed: Vec<usize>,
    /// New paths without a partner.
    pub added: Vec<usize>,
}

/// Geometry to 1e-6 mm, as an exact key.
type GeomKey = (u8, [i64; 5]);

fn q(v: f64) -> i64 {
    // NaN and ±inf never come out of the parser; saturate whatever else does
    (v * 1e6).round() as i64
}

fn angle(a: f64) -> i64 {
    q(a.rem_euclid(360.0)) % q(360.0)
}

/// The exact key of a geometry (lines without direction).
pub fn geometry_key(g: &Geometry) -> GeomKey {
    match *g {
        Geometry::Point(p) => (0, [q(p.x), q(p.y), 0, 0, 0]),
        Geometry::Line(a, b) => {
            let (a, b) = ((q(a.x), q(a.y)), (q(b.x), q(b.y)));
            let (a, b) = if a <= b { (a, b) } else { (b, a) };
            (1, [a.0, a.1, b.0, b.1, 0])
        }
        Geometry::Arc { c, r, a0, a1 } => (2, [q(c.x), q(c.y), q(r), angle(a0), angle(a1)]),
        Geometry::Circle { c, d } => (3, [q(c.x), q(c.y), q(d), 0, 0]),
    }
}

/// A representative point of a geometry (for "nearest" and position order).
fn centre(g: &Geometry) -> (f64, f64) {
    match *g {
        Geometry::Point(p) => (p.x, p.y),
        Geometry::Line(a, b) => ((a.x + b.x) / 2.0, (a.y + b.y) / 2.0),
        Geometry::Arc { c, r, a0, a1 } => {
            let mut sweep = a1 - a0;
            if sweep <= 0.0 {
                sweep += 360.0;
            }
            let mid = (a0 + sweep / 2.0).to_radians();
            (c.x + r * mid.cos(), c.y + r * mid.sin())
        }
        Geometry::Circle { c, .. } => (c.x, c.y),
    }
}

/// Pairs the elements of two versions of a path (see the module comment).
pub fn match_elements(old: &[Element], new: &[Element]) -> Pairing {
    let mut old_left: Vec<bool> = vec![true; old.len()];
    let mut new_partner: Vec<Option<(usize, Relation)>> = vec![None; new.len()];
    type Keyed<'a> = Box<dyn Fn(&'a Element) -> Vec<u8> + 'a>;
    let full: Keyed = Box::new(|e| key_bytes(Some(&e.kind), Some(&e.geometry), Some(&e.params)));
    let shape: Keyed = Box::new(|e| key_bytes(Some(&e.kind), Some(&e.geometry), None));
    let geometry: Keyed = Box::new(|e| key_bytes(None, Some(&e.geometry), None));
    for (key, relation) in [
        (full, Relation::Same),
        (shape, Relation::Params),
        (geometry, Relation::Retyped),
    ] {
        let mut waiting: HashMap<Vec<u8>, Vec<usize>> = HashMap::new();
        for (i, e) in old.iter().enumerate().rev().filter(|(i, _)| old_left[*i]) {
            waiting.entry(key(e)).or_default().push(i);
        }
        for (j, e) in new.iter().enumerate() {
            if new_partner[j].is_some() {
                continue;
            }
            if let Some(i) = waiting.get_mut(&key(e)).and_then(Vec::pop) {
                old_left[i] = false;
                new_partner[j] = Some((i, relation));
            }
        }
    }
    pair_moved(old, new, &mut old_left, &mut new_partner);
    let mut pairs = Vec::new();
    let mut added = Vec::new();
    for (j, p) in new_partner.iter().enumerate() {
        match p {
            Some((i, relation)) => pairs.push(ElementMatch {
                old: *i,
                new: j,
                relation: *relation,
            }),
            None => added.push(j),
        }
    }
    let removed = (0..old.len()).filter(|&i| old_left[i]).collect();
    Pairing {
        pairs,
        removed,
        added,
    }
}

/// Round 4: the same kind, shape and parameters at another place, nearest first.
fn pair_moved(
    old: &[Element],
    new: &[Element],
    old_left: &mut [bool],
    new_partner: &mut [Option<(usize, Relation)>],
) {
    let group = |e: &Element| {
        let mut k = key_bytes(Some(&e.kind), None, Some(&e.params));
        k.push(geometry_key(&e.geometry).0);
        k
    };
    let mut groups: HashMap<Vec<u8>, (Vec<usize>, Vec<usize>)> = HashMap::new();
    for (i, e) in old.iter().enumerate().filter(|(i, _)| old_left[*i]) {
        groups.entry(group(e)).or_default().0.push(i);
    }
    for (j, e) in new
        .iter()
        .enumerate()
        .filter(|(j, _)| new_partner[*j].is_none())
    {
        if let Some(g) = groups.get_mut(&group(e)) {
            g.1.push(j);
        }
    }
    let mut groups: Vec<(Vec<usize>, Vec<usize>)> = groups.into_values().collect();
    // a fixed order: the result does not depend on the hash
    groups.sort();
    for (olds, news) in groups {
        if olds.is_empty() || news.is_empty() {
            continue;
        }
        let found: Vec<(usize, usize)> = if olds.len().saturating_mul(news.len()) <= NEAREST_LIMIT {
            let mut cand = Vec::with_capacity(olds.len() * news.len());
            for &i in &olds {
                let a = centre(&old[i].geometry);
                for &j in &news {
                    let b = centre(&new[j].geometry);
                    cand.push(((a.0 - b.0).hypot(a.1 - b.1), i, j));
                }
            }
            cand.sort_by(|x, y| x.0.total_cmp(&y.0).then((x.1, x.2).cmp(&(y.1, y.2))));
            let mut used_old = std::collections::HashSet::new();
            let mut used_new = std::collections::HashSet::new();
            let mut out = Vec::new();
            for (_, i, j) in cand {
                if !used_old.contains(&i) && !used_new.contains(&j) {
                    used_old.insert(i);
                    used_new.insert(j);
                    out.push((i, j));
                }
            }
            out
        } else {
            let by_pos = |v: &[usize], els: &[Element]| {
                let mut v = v.to_vec();
                v.sort_by(|&a, &b| {
                    let (pa, pb) = (centre(&els[a].geometry), centre(&els[b].geometry));
                    pa.0.total_cmp(&pb.0).then(pa.1.total_cmp(&pb.1))
                });
                v
            };
            by_pos(&olds, old)
                .into_iter()
                .zip(by_pos(&news, new))
                .collect()
        };
        for (i, j) in found {
            old_left[i] = false;
            new_partner[j] = Some((i, Relation::Moved));
        }
    }
}

/// An exact key of the chosen parts of an element.
fn key_bytes(
    kind: Option<&Kind>,
    geometry: Option<&Geometry>,
    params: Option<&[String]>,
) -> Vec<u8> {
    let mut k = Vec::new();
    if let Some(kind) = kind {
        k.extend_from_slice(kind.words().as_bytes());
        k.push(0);
    }
    if let Some(g) = geometry {
        let (tag, nums) = geometry_key(g);
        k.push(tag);
        for n in nums {
            k.extend_from_slice(&n.to_le_bytes());
        }
    }
    if let Some(params) = params {
        for p in params {
            k.extend_from_slice(p.as_bytes());
            k.push(0);
        }
    }
    k
}

/// Pairs the paths of two versions: by name, then removed and added paths that share at
/// least half of their elements (the larger path's count) as renames.
pub fn match_paths(old: &Version, new: &Version) -> PathPairing {
    let mut out = PathPairing::default();
    let mut new_used = vec![false; new.paths.len()];
    let mut removed = Vec::new();
    for (i, p) in old.paths.iter().enumerate() {
        match new.paths.iter().position(|q| q.name == p.name) {
            Some(j) => {
                new_used[j] = true;
                out.both.push((i, j));
            }
            None => removed.push(i),
        }
    }
    let mut added: Vec<usize> = (0..new.paths.len()).filter(|&j| !new_used[j]).collect();
    for i in removed {
        let best = added
            .iter()
            .map(|&j| (shared(&old.paths[i], &new.paths[j]), j))
            .filter(|&(s, j)| {
                2 * s >= old.paths[i].elements.len().max(new.paths[j].elements.len()) && s > 0
            })
            .max_by_key(|&(s, j)| (s, std::cmp::Reverse(j)));
        match best {
            Some((_, j)) => {
                added.retain(|&a| a != j);
                out.both.push((i, j));
            }
            None => out.removed.push(i),
        }
    }
    out.both.sort_by_key(|&(_, j)| j);
    out.added = added;
    out
}

/// How many elements two paths have in common (kind, geometry and parameters).
fn shared(a: &PathVersion, b: &PathVersion) -> usize {
    let mut counts: HashMap<Vec<u8>, usize> = HashMap::new();
    for e in &a.elements {
        *counts
            .entry(key_bytes(Some(&e.kind), Some(&e.geometry), Some(&e.params)))
            .or_default() += 1;
    }
    b.elements
        .iter()
        .filter(|e| {
            let k = key_bytes(Some(&e.kind), Some(&e.geometry), Some(&e.params));
            counts.get_mut(&k).is_some_and(|c| {
                let had = *c > 0;
                *c = c.saturating_sub(1);
                had
            })
        })
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path(text: &str) -> Vec<Element> {
        Version::of_text(format!("path 2001.1P {{\n{text}}}\n")).paths[0]
            .elements
            .clone()
    }

    fn relations(p: &Pairing) -> Vec<(usize, usize, Relation)> {
        p.pairs.iter().map(|m| (m.old, m.new, m.relation)).collect()
    }

    #[test]
    fn a_reordered_path_is_no_change() {
        let a = path("  start (0, 0)  T3 O2\n  end (30, 0)\n  mill (0, 0) -> (30, 0)\n");
        let b = path("  end (30, 0)\n  mill (30, 0) -> (0, 0)\n  start (0, 0)  T3 O2\n");
        let p = match_elements(&a, &b);
        assert!(p.unchanged(), "{p:?}");
        assert_eq!(
            relations(&p),
            vec![
                (1, 0, Relation::Same),
                (2, 1, Relation::Same),
                (0, 2, Relation::Same)
            ]
        );
    }

    #[test]
    fn params_retyped_moved_added_removed() {
        let a = path(concat!(
            "  mill (0, 0) -> (10, 0)  B-0,2\n",
            "  mark (10, 0) -> (20, 0)\n",
            "  drill (5, 5) d2\n",
            "  sweep (20, 0) -> (30, 0)\n",
        ));
        let b = path(concat!(
            "  mill (0, 0) -> (10, 0)  B-0,5\n",
            "  mill (10, 0) -> (20, 0)\n",
            "  drill (6, 5) d2\n",
            "  helix (40, 40) d8\n",
        ));
        let p = match_elements(&a, &b);
        assert_eq!(
            relations(&p),
            vec![
                (0, 0, Relation::Params),
                (1, 1, Relation::Retyped),
                (2, 2, Relation::Moved)
            ]
        );
        assert_eq!((p.removed.clone(), p.added.clone()), (vec![3], vec![3]));
    }

    #[test]
    fn moved_pairs_nearest_first() {
        let a = path("  drill (0, 0) d2\n  drill (100, 0) d2\n");
        let b = path("  drill (101, 0) d2\n  drill (1, 0) d2\n");
        let p = match_elements(&a, &b);
        assert_eq!(
            relations(&p),
            vec![(1, 0, Relation::Moved), (0, 1, Relation::Moved)]
        );
    }

    #[test]
    fn large_groups_pair_by_position_in_bounded_time() {
        let n = 2000;
        let a: String = (0..n).map(|i| format!("  drill ({i}, 0) d2\n")).collect();
        let b: String = (0..n).map(|i| format!("  drill ({i}, 1) d2\n")).collect();
        let p = match_elements(&path(&a), &path(&b));
        assert_eq!(p.pairs.len(), n);
        assert!(p
            .pairs
            .iter()
            .all(|m| m.old == m.new && m.relation == Relation::Moved));
    }

    #[test]
    fn paths_by_name_and_renames() {
        let old = Version::of_text(
            "path 2001.1P {\n  start (0, 0)\n  end (1, 0)\n}\npath 2002.1P {\n  drill (9, 9) d2\n}\n".into(),
        );
        let new = Version::of_text(
            "path 2001.1P {\n  start (0, 0)\n}\npath 2003.1P {\n  drill (9, 9) d2\n}\npath 2004.1P {\n  end (1, 0)\n}\n".into(),
        );
        let p = match_paths(&old, &new);
        assert_eq!(p.both, vec![(0, 0), (1, 1)]);
        assert!(p.removed.is_empty());
        assert_eq!(p.added, vec![2]);
    }
}
