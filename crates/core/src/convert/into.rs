//! `text2dxf --into`: the paths of a text written into an existing drawing, which keeps
//! everything else; and what a plain `text2dxf` over an existing drawing would destroy.
//!
//! The path layers are the layers the compiler reads as paths (the path-name pattern) and
//! the layers of the paths the text defines. On them the entities the front-end reads as
//! path objects are replaced (LINE, ARC, CIRCLE, TEXT, MTEXT; in the extended mode also
//! polylines and block references, which `dxf2text --extended` turned into elements);
//! every other entity, layer, block, table entry and header value stays.

use super::{front_options, layer_name, plan, settle, text_objects};
use crate::diag::{FileRef, Lang};
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

/// `text2dxf --into`: the drawing `target` with the paths of the text in place of its path
/// objects. A target that is no readable DXF is a located error; nothing is half-written
/// because the result is returned whole.
pub fn text_into_dxf(
    src: &str,
    file: &Arc<FileRef>,
    patterns: &Patterns,
    target: &[u8],
    target_file: &Arc<FileRef>,
    input: InputMode,
) -> Result<Vec<u8>, Vec<Diagnostic>> {
    let objects = text_objects(src, file)?;
    let t = scan(target).map_err(|e| vec![load_error(target_file, e)])?;
    let paths: Vec<String> = objects.iter().map(|o| o.path.to_string()).collect();
    let layers = PathLayers::new(patterns, &paths);
    let remove = |r: &Record| layers.replaces(r, input);
    Ok(settle(&objects, patterns, &|suffixes| {
        t.splice(&remove, &plan(&objects, suffixes).1)
    }))
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
