//! `text2dxf --into`: the paths of a text written into an existing drawing, which keeps
//! everything else; and what a plain `text2dxf` over an existing drawing would destroy.
//!
//! The path layers are the layers the compiler reads as paths (the path-name pattern) and
//! the layers of the paths the text defines. On them the entities the front-end reads as
//! path objects are replaced (LINE, ARC, CIRCLE, TEXT, MTEXT; in the extended mode also
//! polylines and block references, which `dxf2text --extended` turned into elements);
//! every other entity, layer, block, table entry and header value stays.
//!
//! `text2dxf --into` through `dxf::splice` on the path layers (the pattern's and the text's), and
//! `overwrite_losses`: what a plain `text2dxf` would destroy in an existing drawing.

use super::keep::{drawn_objects, layer_key, path_key, unchanged_paths, write_changed};
use super::{front_options, layer_name, text_objects, texts_match};
use crate::diag::{FileRef, Lang};
use crate::front::drawing::DrawnObject;
use crate::front::layer::{effective_layer, path_name_of_layer};
use crate::front::options::InputMode;
use crate::load::names::Patterns;
use crate::{Diagnostic, Msg, Origin};
use millpath_dxf::splice::{scan, Record, Target};
use millpath_dxf::DxfError;
use std::collections::BTreeMap;
use std::sync::Arc;

/// Entity types that are path objects on a path layer.
fn replaced_kind(kind: &str, input: InputMode) -> bool {
    matches!(kind, "LINE" | "ARC" | "CIRCLE" | "TEXT" | "MTEXT")
        || (input == InputMode::Extended && matches!(kind, "LWPOLYLINE" | "POLYLINE" | "INSERT"))
}

/// Which layers hold paths: the pattern's and the text's own (CAD layer names ignore case).
struct PathLayers<'a> {
    patterns: &'a Patterns,
    /// Path names of the text, as a layer name reads back, in lower case.
    own: Vec<String>,
}

impl PathLayers<'_> {
    fn new<'a>(patterns: &'a Patterns, text_paths: &[String]) -> PathLayers<'a> {
        let own = text_paths
            .iter()
            .map(|p| path_name_of_layer(&layer_name(p, None)).to_lowercase())
            .collect();
        PathLayers { patterns, own }
    }

    fn contains(&self, layer: &str) -> bool {
        let path = path_name_of_layer(effective_layer(layer));
        let opts = front_options(self.patterns, InputMode::Reference);
        opts.layer_pattern.is_match(&path) || self.own.contains(&path.to_lowercase())
    }

    /// An entity the paths of the text replace.
    fn replaces(&self, r: &Record, input: InputMode) -> bool {
        !r.paper && replaced_kind(&r.kind, input) && self.contains(&r.layer)
    }
}

fn load_error(file: &Arc<FileRef>, e: DxfError) -> Diagnostic {
    Diagnostic::error(
        Msg::CannotLoadDxf,
        Origin::File(file.clone()),
        vec![
            file.path.display().to_string(),
            crate::diag::dxf_error_arg(&e),
        ],
    )
}

/// What `text2dxf --into` makes of the drawing.
#[derive(Debug, Clone, PartialEq)]
pub enum IntoOutcome {
    /// The drawing with the paths of the text in place of its path objects.
    Written(Vec<u8>),
    /// The drawing's path objects read back exactly as those the text would write (same
    /// paths, order, shapes, line types and texts): the file is left as it is, byte for byte,
    /// so version control sees no change.
    Unchanged,
}

/// `text2dxf --into`: the drawing `target` with the paths of the text in place of its path
/// objects. A path the text leaves as the drawing has it keeps its entities byte for byte;
/// a changed one keeps those of its unchanged elements, the rest is written on its old
/// layer (`keep.rs`). A target that is no readable DXF
/// is a located error; nothing is half-written because the result is returned whole. The
/// objects of paths the text does not define would be deleted: refused naming them
/// ([`Msg::IntoWouldDeletePaths`]) unless `delete_missing`.
pub fn text_into_dxf(
    src: &str,
    file: &Arc<FileRef>,
    patterns: &Patterns,
    target: &[u8],
    target_file: &Arc<FileRef>,
    input: InputMode,
    delete_missing: bool,
) -> Result<IntoOutcome, Vec<Diagnostic>> {
    let objects = text_objects(src, file)?;
    let t = scan(target).map_err(|e| vec![load_error(target_file, e)])?;
    let paths: Vec<String> = objects.iter().map(|o| o.path.to_string()).collect();
    let layers = PathLayers::new(patterns, &paths);
    let drawn = drawn_objects(target, patterns, input);
    let unchanged = unchanged_paths(drawn.as_deref().unwrap_or_default(), &objects, patterns);
    let remove =
        |r: &Record| layers.replaces(r, input) && !unchanged.contains(&layer_key(&r.layer));
    let missing = missing_paths(&t, &layers, input);
    if !missing.is_empty() && !delete_missing {
        return Err(vec![Diagnostic::error(
            Msg::IntoWouldDeletePaths,
            Origin::File(target_file.clone()),
            vec![
                target_file.path.display().to_string(),
                missing.join(", "),
                file.path.display().to_string(),
            ],
        )]);
    }
    let changed: Vec<DrawnObject> = objects
        .iter()
        .filter(|o| !unchanged.contains(&path_key(&layer_name(&o.path, None))))
        .cloned()
        .collect();
    if changed.is_empty() && missing.is_empty() {
        return Ok(IntoOutcome::Unchanged);
    }
    let ours = |path: &str| !unchanged.contains(&path_key(path));
    let out = write_changed(
        &t,
        &changed,
        drawn.as_deref().unwrap_or_default(),
        &remove,
        &ours,
        patterns,
        input,
    );
    let all_read = paths.iter().all(|p| {
        let layer = path_name_of_layer(&layer_name(p, None));
        front_options(patterns, input)
            .layer_pattern
            .is_match(&layer)
    });
    // a path the pattern does not read is no object of either file: compared, it would hide
    // the text's changes to it
    let written = || drawn_objects(&out, patterns, input);
    if all_read && drawn.is_some_and(|a| written().is_some_and(|b| same_path_objects(&a, &b))) {
        return Ok(IntoOutcome::Unchanged);
    }
    Ok(IntoOutcome::Written(out))
}

/// The paths whose objects `--into` would take out of `t` and the text does not define:
/// each once, spelt as its first layer, in name order.
fn missing_paths(t: &Target, layers: &PathLayers, input: InputMode) -> Vec<String> {
    let mut names: BTreeMap<String, String> = BTreeMap::new();
    for r in t.entities().iter().filter(|r| layers.replaces(r, input)) {
        let path = path_name_of_layer(effective_layer(&r.layer));
        let key = path.to_lowercase();
        if !layers.own.contains(&key) {
            names.entry(key).or_insert(path);
        }
    }
    names.into_values().collect()
}

/// Whether two drawings hold the same path objects, in the same order (the order breaks
/// ties of the traversal): path, line type, shape and the text each element is given. Their
/// other entities are no business of the compiler.
fn same_path_objects(a: &[DrawnObject], b: &[DrawnObject]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(x, y)| {
            x.path == y.path
                && x.linetype == y.linetype
                && x.shape == y.shape
                && texts_match(x.text.as_deref(), y.text.as_deref())
        })
}

/// The entities `--into` keeps in `target` when writing the paths named `paths` (the
/// drawing's other content): layer, type and the entity's bytes. `Err` when it is no DXF.
pub fn kept_entities(
    target: &[u8],
    paths: &[String],
    patterns: &Patterns,
    input: InputMode,
) -> Result<Vec<(String, String, Vec<u8>)>, DxfError> {
    let t = scan(target)?;
    let layers = PathLayers::new(patterns, paths);
    Ok(t.entities()
        .iter()
        .filter(|r| !layers.replaces(r, input))
        .map(|r| (r.layer.clone(), r.kind.clone(), t.bytes_of(r).to_vec()))
        .collect())
}

/// What `--into` without the extended mode keeps on the path layers of `target` that the
/// extended mode replaces: polylines and block references. A text from `dxf2text
/// --extended` holds them as elements, so kept they would be drawn twice.
pub fn kept_extended_geometry(
    target: &[u8],
    src: &str,
    file: &Arc<FileRef>,
    patterns: &Patterns,
) -> Losses {
    let mut kept = Losses::default();
    let Ok(t) = scan(target) else {
        return kept;
    };
    let paths: Vec<String> = text_objects(src, file)
        .map(|o| o.into_iter().map(|o| o.path.to_string()).collect())
        .unwrap_or_default();
    let layers = PathLayers::new(patterns, &paths);
    let extended_only = |r: &&Record| {
        layers.replaces(r, InputMode::Extended) && !layers.replaces(r, InputMode::Reference)
    };
    for r in t.entities().iter().filter(extended_only) {
        *kept
            .entities
            .entry(r.layer.clone())
            .or_default()
            .entry(r.kind.clone())
            .or_default() += 1;
    }
    kept
}

/// What a plain `text2dxf` would destroy in an existing drawing: everything `--into` keeps.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct Losses {
    /// Layer → entity type → count, for the entities that are no path objects.
    pub entities: BTreeMap<String, BTreeMap<String, usize>>,
    /// Blocks other than the model and paper space blocks.
    pub blocks: Vec<String>,
    /// Layers of the LAYER table without entities that are no path layers (`0` and
    /// `Defpoints` left out: every drawing has them).
    pub empty_layers: Vec<String>,
}

impl Losses {
    pub fn is_empty(&self) -> bool {
        self.entities.is_empty() && self.blocks.is_empty() && self.empty_layers.is_empty()
    }

    /// `layer BEMASSUNG (2 INSERT), layer STANDARD (29 LINE, 3 MTEXT), blocks D1, D2, …`.
    pub fn describe(&self, lang: Lang) -> String {
        let (layer, blocks, empty) = match lang {
            Lang::En => ("layer", "blocks", "empty layers"),
            Lang::De => ("Layer", "Blöcke", "leere Layer"),
        };
        let mut parts: Vec<String> = self
            .entities
            .iter()
            .map(|(l, kinds)| {
                let k: Vec<String> = kinds.iter().map(|(k, n)| format!("{n} {k}")).collect();
                format!("{layer} {l} ({})", k.join(", "))
            })
            .collect();
        if !self.blocks.is_empty() {
            parts.push(format!("{blocks} {}", short_list(&self.blocks, lang)));
        }
        if !self.empty_layers.is_empty() {
            parts.push(format!(
                "{} {empty} ({})",
                self.empty_layers.len(),
                short_list(&self.empty_layers, lang)
            ));
        }
        parts.join(", ")
    }
}

/// At most six names, then how many more.
fn short_list(names: &[String], lang: Lang) -> String {
    const MAX: usize = 6;
    let mut s = names
        .iter()
        .take(MAX)
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    if names.len() > MAX {
        let more = names.len() - MAX;
        s.push_str(&match lang {
            Lang::En => format!(" and {more} more"),
            Lang::De => format!(" und {more} weitere"),
        });
    }
    s
}

/// What overwriting the drawing `existing` with the paths of the text `src` would lose.
/// `Err` when `existing` is no DXF this reader can read (then it is not ours to overwrite
/// either).
pub fn overwrite_losses(
    existing: &[u8],
    src: &str,
    file: &Arc<FileRef>,
    patterns: &Patterns,
    input: InputMode,
) -> Result<Losses, DxfError> {
    let t: Target = scan(existing)?;
    // a text that does not parse is refused before anything is written; its paths do not
    // matter then
    let paths: Vec<String> = text_objects(src, file)
        .map(|o| o.into_iter().map(|o| o.path.to_string()).collect())
        .unwrap_or_default();
    let layers = PathLayers::new(patterns, &paths);
    let mut losses = Losses::default();
    for r in t.entities().iter().filter(|r| !layers.replaces(r, input)) {
        *losses
            .entities
            .entry(r.layer.clone())
            .or_default()
            .entry(r.kind.clone())
            .or_default() += 1;
    }
    losses.blocks = t
        .block_names()
        .iter()
        .filter(|b| {
            let b = b.to_ascii_lowercase();
            !b.starts_with("*model_space") && !b.starts_with("*paper_space")
        })
        .cloned()
        .collect();
    let used: Vec<&str> = t.entities().iter().map(|r| r.layer.as_str()).collect();
    losses.empty_layers = t
        .layer_names()
        .into_iter()
        .filter(|l| {
            !l.eq_ignore_ascii_case("0")
                && !l.eq_ignore_ascii_case("defpoints")
                && !layers.contains(l)
                && !used.iter().any(|u| u.eq_ignore_ascii_case(l))
        })
        .map(str::to_string)
        .collect();
    Ok(losses)
}
