//! The diff of two versions of a drawing: per path, the elements added, removed, moved,
//! re-typed or with other parameters (`matching.rs`), and the effect on the compiled part.
//!
//! The effect is read from the compiler: both versions are compiled (`compiled.rs`) and each
//! element's moves compared. An element whose moves changed is reported, with the effective
//! parameters that changed on it (through inheritance, `@` references, `millpath.toml`),
//! grouped ("B -0,2 → -0,5 on 37 elements, from the path start"). An effective value that
//! changed on an element whose moves did not is no effect and is not reported.

use crate::compiled::{Compiled, MoveKey, Outcome};
use crate::matching::{match_elements, match_paths, Relation};
use crate::version::{Element, PathVersion, Version};
use millpath_core::params::parse_number;
use millpath_ide::Effective;
use std::collections::BTreeMap;
use std::path::Path;

/// What happened to an element.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum ChangeKind {
    Added,
    Removed,
    Moved,
    Retyped,
    /// Other parameter words as written.
    Params,
    /// Written as before; its moves changed (an inherited value, a neighbour, the order).
    Effect,
}

/// An effective value before and after.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ValueChange {
    pub key: char,
    pub old: Option<String>,
    pub new: Option<String>,
    /// Where the new value comes from (the old one's when the key is gone).
    pub source: String,
}

/// One changed element.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementChange {
    pub kind: ChangeKind,
    /// Its line in the old and the new canonical text (1-based).
    pub old_line: Option<usize>,
    pub new_line: Option<usize>,
    /// The element's line in the old and new text (trimmed).
    pub old_text: Option<String>,
    pub new_text: Option<String>,
    /// Its moves differ (always for added or removed elements that make moves).
    pub moves_changed: bool,
    /// Passes (distinct cutting depths) before and after.
    pub passes: (usize, usize),
    /// Effective values that changed (only on elements whose moves changed).
    pub values: Vec<ValueChange>,
}

/// Elements with the same effective value change from the same origin.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EffectGroup {
    pub key: char,
    pub old: Option<String>,
    pub new: Option<String>,
    pub source: String,
    pub count: usize,
}

/// What happened to a path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathStatus {
    Unchanged,
    Changed,
    Added,
    Removed,
    /// Under another name (most of its elements as before).
    Renamed,
}

/// The diff of one path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathDiff {
    /// The new name (the old one for a removed path).
    pub name: String,
    /// The old name when renamed.
    pub old_name: Option<String>,
    pub status: PathStatus,
    pub changes: Vec<ElementChange>,
    pub effects: Vec<EffectGroup>,
    /// Elements whose passes changed: (before, after) → count.
    pub passes: Vec<((usize, usize), usize)>,
    /// Elements of other files (embedded subpaths, `2001.mpath:7`) whose moves in this path
    /// changed; "" for moves of no element.
    pub elsewhere: Vec<String>,
    pub before: Option<Outcome>,
    pub after: Option<Outcome>,
}

impl PathDiff {
    /// The G-code's moves differ (or one side did not compile).
    pub fn gcode_changed(&self) -> bool {
        match (&self.before, &self.after) {
            (Some(a), Some(b)) => {
                a.error != b.error || a.gcode_digest != b.gcode_digest || a.moves != b.moves
            }
            (None, None) => false,
            _ => true,
        }
    }
}

/// The diff of two versions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Diff {
    pub paths: Vec<PathDiff>,
}

impl Diff {
    /// Anything changed (exit status 1).
    pub fn changed(&self) -> bool {
        self.paths.iter().any(|p| p.status != PathStatus::Unchanged)
    }
}

/// A version and the file it stands for (its folder holds its subpaths and `millpath.toml`).
pub struct Side<'a> {
    pub version: &'a Version,
    pub file: &'a Path,
    /// The files of the version's revision (a git commit) at their work-tree paths, read
    /// instead of the disk; `None`: the disk.
    pub files: Option<std::sync::Arc<millpath_core::MemFileSystem>>,
    /// Settings given by the caller (the command line's options) over the version's own
    /// `millpath.toml`, as an editor's settings are; `None`: the file's settings alone.
    pub options: Option<&'a crate::compiled::Options>,
}

/// Diffs two versions; `compile`: also compile both and report the effect (without it the
/// diff is the written change only).
///
/// The two versions compile at once (one thread each), every path of a version in one go;
/// the effective values of all elements whose moves changed are then read with one
/// analysis per version, again both at once.
pub fn diff(old: Side, new: Side, compile: bool) -> Diff {
    let mut old_c = Compiled::new(old.version, old.file, old.files.clone());
    let mut new_c = Compiled::new(new.version, new.file, new.files.clone());
    if let Some(o) = old.options {
        old_c.set_options(o);
    }
    if let Some(o) = new.options {
        new_c.set_options(o);
    }
    let pairing = match_paths(old.version, new.version);
    // the same text read in the same place with the same files and settings: one compile
    let same = old.version.text == new.version.text
        && old_c.at == new_c.at
        && match (&old.files, &new.files) {
            (None, None) => true,
            (Some(a), Some(b)) => std::sync::Arc::ptr_eq(a, b),
            _ => false,
        }
        && match (old.options, new.options) {
            (None, None) => true,
            (Some(a), Some(b)) => std::ptr::eq(a, b),
            _ => false,
        };
    let (mut before, mut after) = if compile && same {
        let both = outcomes(&mut old_c, old.version);
        (both.clone(), both)
    } else if compile {
        both_sides(
            || outcomes(&mut old_c, old.version),
            || outcomes(&mut new_c, new.version),
        )
    } else {
        (
            vec![None; old.version.paths.len()],
            vec![None; new.version.paths.len()],
        )
    };
    let mut out = Diff::default();
    // (path, change, old offset, new offset) of the pairs whose moves changed
    let mut effect_pairs: Vec<(usize, usize, usize, usize)> = Vec::new();
    for &(i, j) in &pairing.both {
        let (po, pn) = (&old.version.paths[i], &new.version.paths[j]);
        let (d, pairs) = path_diff(
            (old.version, po, before[i].take()),
            (new.version, pn, after[j].take()),
        );
        let at = out.paths.len();
        effect_pairs.extend(pairs.into_iter().map(|(c, o, n)| (at, c, o, n)));
        out.paths.push(d);
    }
    let olds: Vec<usize> = effect_pairs.iter().map(|p| p.2).collect();
    let news: Vec<usize> = effect_pairs.iter().map(|p| p.3).collect();
    let (eff_old, eff_new) = both_sides(|| old_c.effective(&olds), || new_c.effective(&news));
    for (k, &(p, c, _, _)) in effect_pairs.iter().enumerate() {
        if let (Some(o), Some(n)) = (eff_old.get(k), eff_new.get(k)) {
            out.paths[p].changes[c].values = value_changes(o, n);
        }
    }
    for d in &mut out.paths {
        finish(d);
    }
    for &i in &pairing.removed {
        let p = &old.version.paths[i];
        out.paths
            .push(one_sided(old.version, p, before[i].take(), false));
    }
    for &j in &pairing.added {
        let p = &new.version.paths[j];
        out.paths
            .push(one_sided(new.version, p, after[j].take(), true));
    }
    out.paths.sort_by(|a, b| a.name.cmp(&b.name));
    out
}

/// Runs two jobs at once (the second on this thread); a panic in either goes on here.
fn both_sides<A: Send, B: Send>(
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    std::thread::scope(|s| {
        let first = s.spawn(a);
        let second = b();
        let first = first
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (first, second)
    })
}

/// The compiled outcome of every path of a version, by its index.
fn outcomes(c: &mut Compiled, v: &Version) -> Vec<Option<Outcome>> {
    v.paths.iter().map(|p| Some(c.outcome(&p.name))).collect()
}

/// The element's line (trimmed), found from its offset: as long as the line, not the text.
fn line_text(v: &Version, e: &Element) -> String {
    let text = v.text.as_str();
    let Some(before) = text.get(..e.offset) else {
        return String::new();
    };
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    let end = text[e.offset..]
        .find('\n')
        .map_or(text.len(), |i| e.offset + i);
    text[start..end].trim().to_string()
}

/// A path only one version has.
fn one_sided(v: &Version, p: &PathVersion, outcome: Option<Outcome>, added: bool) -> PathDiff {
    let changes = p
        .elements
        .iter()
        .map(|e| {
            let (line, text) = (Some(e.line), Some(line_text(v, e)));
            let moves = outcome
                .as_ref()
                .map_or(0, |o| o.by_line.get(&e.line).map_or(0, Vec::len));
            let passes = outcome
                .as_ref()
                .map_or(0, |o| passes_of(o.by_line.get(&e.line)));
            ElementChange {
                kind: if added {
                    ChangeKind::Added
                } else {
                    ChangeKind::Removed
                },
                old_line: if added { None } else { line },
                new_line: if added { line } else { None },
                old_text: if added { None } else { text.clone() },
                new_text: if added { text } else { None },
                moves_changed: moves > 0,
                passes: if added { (0, passes) } else { (passes, 0) },
                values: Vec::new(),
            }
        })
        .collect();
    let (before, after) = if added {
        (None, outcome)
    } else {
        (outcome, None)
    };
    PathDiff {
        name: p.name.clone(),
        old_name: None,
        status: if added {
            PathStatus::Added
        } else {
            PathStatus::Removed
        },
        changes,
        effects: Vec::new(),
        passes: Vec::new(),
        elsewhere: Vec::new(),
        before,
        after,
    }
}

/// Passes of an element: its distinct cutting depths (Z of level cutting moves, else of
/// every cutting move's end).
pub fn passes_of(moves: Option<&Vec<MoveKey>>) -> usize {
    let Some(moves) = moves else { return 0 };
    let cutting = || moves.iter().filter(|m| m.0 != "rapid");
    let mut level: Vec<i64> = cutting()
        .filter(|m| m.1[2] == m.1[5])
        .map(|m| m.1[5])
        .collect();
    if level.is_empty() {
        level = cutting().map(|m| m.1[5]).collect();
    }
    level.sort_unstable();
    level.dedup();
    level.len()
}

type SideData<'a> = (&'a Version, &'a PathVersion, Option<Outcome>);

/// The diff of a path both versions have, without the effective values and what is counted
/// from them ([`finish`]); with (change, old offset, new offset) of the pairs whose moves
/// changed, whose effective values are to be compared.
fn path_diff(old: SideData, new: SideData) -> (PathDiff, Vec<(usize, usize, usize)>) {
    let (vo, po, before) = old;
    let (vn, pn, after) = new;
    let pairing = match_elements(&po.elements, &pn.elements);
    let empty = Vec::new();
    let mut changes = Vec::new();
    // pairs whose moves changed: their effective values are compared
    let mut effect_pairs = Vec::new();
    for m in &pairing.pairs {
        let (eo, en) = (&po.elements[m.old], &pn.elements[m.new]);
        let (mo, mn) = (moves_of(&before, eo.line), moves_of(&after, en.line));
        let moves_changed = mo.unwrap_or(&empty) != mn.unwrap_or(&empty);
        let kind = match m.relation {
            Relation::Same if !moves_changed => continue,
            Relation::Same => ChangeKind::Effect,
            Relation::Params => ChangeKind::Params,
            Relation::Retyped => ChangeKind::Retyped,
            Relation::Moved => ChangeKind::Moved,
        };
        if moves_changed {
            effect_pairs.push((changes.len(), eo.offset, en.offset));
        }
        changes.push(ElementChange {
            kind,
            old_line: Some(eo.line),
            new_line: Some(en.line),
            old_text: Some(line_text(vo, eo)),
            new_text: Some(line_text(vn, en)),
            moves_changed,
            passes: (passes_of(mo), passes_of(mn)),
            values: Vec::new(),
        });
    }
    for &i in &pairing.removed {
        let e = &po.elements[i];
        let mo = moves_of(&before, e.line);
        changes.push(ElementChange {
            kind: ChangeKind::Removed,
            old_line: Some(e.line),
            new_line: None,
            old_text: Some(line_text(vo, e)),
            new_text: None,
            moves_changed: mo.is_some_and(|m| !m.is_empty()),
            passes: (passes_of(mo), 0),
            values: Vec::new(),
        });
    }
    for &j in &pairing.added {
        let e = &pn.elements[j];
        let mn = moves_of(&after, e.line);
        changes.push(ElementChange {
            kind: ChangeKind::Added,
            old_line: None,
            new_line: Some(e.line),
            old_text: None,
            new_text: Some(line_text(vn, e)),
            moves_changed: mn.is_some_and(|m| !m.is_empty()),
            passes: (0, passes_of(mn)),
            values: Vec::new(),
        });
    }
    let renamed = po.name != pn.name;
    let no_moves = std::collections::BTreeMap::new();
    let (eo, en) = (
        before.as_ref().map_or(&no_moves, |o| &o.elsewhere),
        after.as_ref().map_or(&no_moves, |o| &o.elsewhere),
    );
    let elsewhere: Vec<String> = eo
        .keys()
        .chain(en.keys())
        .filter(|k| eo.get(*k) != en.get(*k))
        .cloned()
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    let d = PathDiff {
        name: pn.name.clone(),
        old_name: renamed.then(|| po.name.clone()),
        status: PathStatus::Unchanged,
        changes,
        effects: Vec::new(),
        passes: Vec::new(),
        elsewhere,
        before,
        after,
    };
    (d, effect_pairs)
}

/// Sorts a path's changes (their effective values filled in), groups the effects and the
/// pass counts, and sets its status.
fn finish(d: &mut PathDiff) {
    d.changes
        .sort_by_key(|c| (c.new_line.or(c.old_line), c.old_line, c.kind));
    let mut groups: BTreeMap<(char, Option<String>, Option<String>, String), usize> =
        BTreeMap::new();
    let mut passes: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for c in &d.changes {
        for v in &c.values {
            *groups
                .entry((v.key, v.old.clone(), v.new.clone(), v.source.clone()))
                .or_default() += 1;
        }
        if c.passes.0 != c.passes.1 && c.old_line.is_some() && c.new_line.is_some() {
            *passes.entry(c.passes).or_default() += 1;
        }
    }
    let mut effects: Vec<EffectGroup> = groups
        .into_iter()
        .map(|((key, old, new, source), count)| EffectGroup {
            key,
            old,
            new,
            source,
            count,
        })
        .collect();
    effects.sort_by(|a, b| b.count.cmp(&a.count).then(a.key.cmp(&b.key)));
    d.effects = effects;
    d.passes = passes.into_iter().collect();
    d.status = if d.old_name.is_some() {
        PathStatus::Renamed
    } else if !d.changes.is_empty() || !d.elsewhere.is_empty() || d.gcode_changed() {
        PathStatus::Changed
    } else {
        PathStatus::Unchanged
    };
}

fn moves_of(o: &Option<Outcome>, line: usize) -> Option<&Vec<MoveKey>> {
    o.as_ref().and_then(|o| o.by_line.get(&line))
}

/// Whether two written values are the same (numbers compare as numbers: `-0,2` = `-0.2`).
fn same_value(a: &str, b: &str) -> bool {
    if a == b {
        return true;
    }
    match (parse_number(a), parse_number(b)) {
        (Some(x), Some(y)) => x == y,
        _ => a == b,
    }
}

/// The effective values that differ between two elements.
fn value_changes(old: &[Effective], new: &[Effective]) -> Vec<ValueChange> {
    let mut keys: Vec<char> = old.iter().chain(new).map(|e| e.key).collect();
    keys.sort_unstable();
    keys.dedup();
    keys.into_iter()
        .filter_map(|k| {
            let o = old.iter().find(|e| e.key == k);
            let n = new.iter().find(|e| e.key == k);
            let same = match (o, n) {
                (Some(o), Some(n)) => same_value(&o.value, &n.value),
                (None, None) => true,
                _ => false,
            };
            (!same).then(|| ValueChange {
                key: k,
                old: o.map(|e| e.value.clone()),
                new: n.map(|e| e.value.clone()),
                source: n.or(o).map(|e| e.source.clone()).unwrap_or_default(),
            })
        })
        .collect()
}
