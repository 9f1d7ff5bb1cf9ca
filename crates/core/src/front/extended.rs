//! The two ways of treating the geometry the reference ignores (polylines, blocks, ellipses,
//! splines): the default mode warns about each such entity that touches a path layer and
//! says how to include it; the extended mode (`--extended`, `input = "extended"`) resolves
//! it into lines and arcs (`millpath_dxf::explode`), refuses curves with an error, and
//! scales `$INSUNITS` drawings to millimetres.
//!
//! The reference mode's warning per ignored polyline/block/curve on a path layer (not printed by
//! `pathdxf2gcode`, as the reference is silent); the extended mode's resolution (`explode.rs`), its
//! refusals as located errors, `$INSUNITS` scaling.

use crate::args;
use crate::diag::{Diags, EntityOrigin, FileRef, Msg, Origin};
use crate::front::layer::{effective_layer, path_name_of_layer};
use crate::front::options::{FrontOptions, InputMode};
use crate::geom::P2;
use millpath_dxf::explode::{self, Reason};
use millpath_dxf::{Drawing, ExtraKind, Point3};
use std::collections::BTreeMap;
use std::sync::Arc;

/// The line types the compiler knows (by prefix, as `drawing::build_paths` compares them).
const KNOWN_LINE_TYPES: [&str; 7] = [
    "CONTINUOUS",
    "DIVIDE",
    "BORDER",
    "DASHDOT",
    "DASHED",
    "HIDDEN",
    "DOT",
];

/// In the reference mode, a line type that the extended mode would read (`Continuous`,
/// `ACAD_ISO02W100`, …): its "not supported" error (MP005) gets a note naming the mode and
/// what the name would be read as. Adds each note once.
pub fn hint_line_types(list: &mut [crate::diag::Diagnostic], mode: InputMode, lang: crate::Lang) {
    if mode == InputMode::Extended {
        return;
    }
    for d in list
        .iter_mut()
        .filter(|d| d.msg == Msg::LineTypeNotSupported && d.related.is_empty())
    {
        let Some(name) = d.args.first() else { continue };
        let read_as = crate::front::linetype_alias::canonical(name);
        if !KNOWN_LINE_TYPES.iter().any(|k| read_as.starts_with(k)) {
            continue;
        }
        let note = match lang {
            crate::Lang::En => format!(
                "the extended mode reads it as {read_as}: --extended, or input = \"extended\" in millpath.toml"
            ),
            crate::Lang::De => format!(
                "der erweiterte Modus liest sie als {read_as}: --extended oder input = \"extended\" in millpath.toml"
            ),
        };
        let origin = d.origin.clone();
        d.related.push(crate::diag::Related { origin, note });
    }
}

fn on_path_layer(layer: &str, opts: &FrontOptions) -> bool {
    opts.layer_pattern
        .is_match(&path_name_of_layer(effective_layer(layer)))
}

fn origin(
    file: &Arc<FileRef>,
    line: usize,
    handle: &str,
    layer: &str,
    code_name: &'static str,
    pos: Point3,
) -> Origin {
    let layer = effective_layer(layer);
    Origin::Entity(Arc::new(EntityOrigin {
        file: file.clone(),
        line,
        handle: handle.to_string(),
        layer: layer.to_string(),
        code_name,
        pos: P2::new(pos[0], pos[1]),
        path: path_name_of_layer(layer),
    }))
}

/// Default mode: one warning per ignored polyline, INSERT, ELLIPSE or SPLINE on a path layer
/// (an INSERT also when its block holds something on a path layer).
pub fn warn_ignored(d: &Drawing, file: &Arc<FileRef>, opts: &FrontOptions, diags: &mut Diags) {
    for x in &d.extra {
        let touches = on_path_layer(&x.layer, opts)
            || matches!(&x.kind, ExtraKind::Insert(i) if block_touches_paths(d, &i.name, opts, 0));
        if touches {
            let o = origin(
                file,
                x.line,
                &x.handle,
                &x.layer,
                x.code_name(),
                x.position(),
            );
            diags.push(crate::diag::Diagnostic::warning(
                Msg::IgnoredEntity,
                o,
                // the line makes each warning's text unique: identical texts are reported once
                args![x.code_name(), x.line],
            ));
        }
    }
}

fn block_touches_paths(d: &Drawing, name: &str, opts: &FrontOptions, depth: usize) -> bool {
    let Some(b) = d.blocks.get(name) else {
        return false;
    };
    if depth >= explode::MAX_DEPTH {
        return false;
    }
    b.entities.iter().any(|e| on_path_layer(&e.layer, opts))
        || b.extra.iter().any(|x| {
            on_path_layer(&x.layer, opts)
                || matches!(&x.kind, ExtraKind::Insert(i) if block_touches_paths(d, &i.name, opts, depth + 1))
        })
}

/// Extended mode: the drawing with polylines and blocks resolved into plain entities, in
/// millimetres; what cannot be resolved on a path layer is an error at its entity.
pub fn resolve(
    d: &Drawing,
    file: &Arc<FileRef>,
    opts: &FrontOptions,
    diags: &mut Diags,
) -> Drawing {
    let r = explode::resolve(d);
    for x in &r.refused {
        if !on_path_layer(&x.layer, opts) {
            continue;
        }
        let o = origin(file, x.line, &x.handle, &x.layer, x.code_name, x.pos);
        let name = x.code_name;
        let (msg, args) = match &x.reason {
            Reason::Curve => (Msg::CurveRefused, args![name]),
            Reason::NotPlanar => (Msg::NotPlanarRefused, args![name]),
            Reason::UnknownBlock(b) => (Msg::UnknownBlock, args![name, b]),
            Reason::TooDeep => (Msg::BlocksTooDeep, args![name, explode::MAX_DEPTH]),
            Reason::TooMany => (Msg::BlocksTooMany, args![name, explode::MAX_OUTPUT]),
            Reason::Distorted => (Msg::DistortedArc, args![name]),
            Reason::BadArray => (Msg::BadArray, args![name]),
            Reason::NotFinite => (Msg::NotFiniteGeometry, args![name]),
        };
        diags.error(msg, o, args);
    }
    let mut out = Drawing {
        version: d.version.clone(),
        codepage: d.codepage.clone(),
        text_size: d.text_size,
        layers: d.layers.clone(),
        linetypes: d.linetypes.clone(),
        entities: r.entities,
        ignored_entities: d.ignored_entities,
        insunits: d.insunits,
        extra: Vec::new(),
        blocks: BTreeMap::new(),
        extra_errors: Vec::new(),
    };
    for e in &d.extra_errors {
        diags.error(
            Msg::CannotLoadDxf,
            Origin::File(file.clone()),
            vec![
                file.path.display().to_string(),
                crate::diag::dxf_error_arg(e),
            ],
        );
    }
    if let Some(f) = d
        .insunits
        .and_then(millpath_dxf::units::millimetres_per_unit)
    {
        millpath_dxf::units::scale_entities(&mut out.entities, f);
        out.text_size *= f;
        diags.push(crate::diag::Diagnostic::warning(
            Msg::UnitsScaled,
            Origin::File(file.clone()),
            args![d.insunits.unwrap_or(0), f],
        ));
    }
    out
}
