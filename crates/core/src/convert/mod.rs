//! Conversion both ways between drawn objects and the text language: `dxf2text` writes the
//! canonical text, `text2dxf` writes an AutoCAD 2000 DXF whose texts the reference's
//! assignment rule gives back to their own elements; `text2dxf --into` writes the paths into
//! an existing drawing and keeps the rest of it (`into.rs`).
//!
//! `dxf2text`, `text2dxf`, `fmt`. `dxf2text` writes a canonical order that ignores the drawing's
//! entity order: markers by kind then position, segments in traversal order, unreached ones by kind
//! and position; `text2dxf` plans the entities, `settle` moves texts the read-back assigns
//! elsewhere to `PATH~A` layers.

mod into;
mod keep;
pub use into::{
    kept_entities, kept_extended_geometry, overwrite_losses, text_into_dxf, IntoOutcome, Losses,
};

use crate::build::walk::walk;
use crate::diag::{Diags, FileRef};
use crate::front::drawing::{build_paths, DrawnObject, RawPath, Shape};
use crate::front::dxf::dxf_objects;
use crate::front::options::FrontOptions;
use crate::front::options::InputMode;
use crate::geom::{near, Geom};
use crate::load::names::Patterns;
use crate::params::parse_number;
use millpath_dxf::splice::{NewEntity, NewShape};
use millpath_dxf::writer::DxfWriter;
use millpath_syntax::ast::{Element, Geometry, Kind, Point, Spanned, Style};
use millpath_syntax::format;
use std::collections::BTreeMap;
use std::sync::Arc;

fn pt(p: crate::geom::P2) -> Point {
    Point { x: p.x, y: p.y }
}

/// The element kind of an object in the text language.
fn kind_of(o: &DrawnObject, path_o: Option<f64>) -> Kind {
    let lt = &*o.linetype;
    match &o.shape {
        Shape::Circle { r, .. } => {
            let r = *r;
            match lt {
                "PHANTOM" if near(r, 0.5) => Kind::Start,
                "PHANTOM" if near(r, 1.0) => Kind::End,
                "PHANTOM" if near(r, 0.75) => Kind::Turn,
                "PHANTOM" | "DASHDOT" if near(r, 3.0) => Kind::Probe,
                "DOT" if near(r, 3.0) => Kind::NoProbe,
                "CONTINUOUS" | "DIVIDE" | "BORDER" => {
                    let style = match lt {
                        "CONTINUOUS" => Style::Mill,
                        "DIVIDE" => Style::Mark,
                        _ => Style::Bars,
                    };
                    if path_o.is_some_and(|o| near(r, o / 2.0)) {
                        Kind::Drill(style)
                    } else {
                        Kind::Helix(style)
                    }
                }
                _ => Kind::Raw(lt.to_string()),
            }
        }
        Shape::Path(_) => match lt {
            "CONTINUOUS" => Kind::Mill,
            "DIVIDE" => Kind::Mark,
            "BORDER" => Kind::Bars,
            "DASHDOT" => Kind::Sub,
            "DASHED" => Kind::Sweep,
            "HIDDEN" => Kind::Move,
            "DOT" => Kind::Skip,
            _ => Kind::Raw(lt.to_string()),
        },
    }
}

fn geometry_of(o: &DrawnObject, kind: &Kind) -> Geometry {
    match &o.shape {
        Shape::Circle { c, r } => {
            if kind.marker_diameter().is_some() {
                Geometry::Point(pt(*c))
            } else {
                Geometry::Circle {
                    c: pt(*c),
                    d: 2.0 * r,
                }
            }
        }
        Shape::Path(Geom::Line { a, b }) => Geometry::Line(pt(*a), pt(*b)),
        Shape::Path(Geom::Arc { c, r, a0, a1, .. }) => Geometry::Arc {
            c: pt(*c),
            r: *r,
            a0: *a0,
            a1: *a1,
        },
    }
}

/// Where an object stands among a path's non-segments: markers first in a fixed order of
/// kinds, then everything else.
fn kind_rank(kind: &Kind) -> u8 {
    match kind {
        Kind::Start => 0,
        Kind::End => 1,
        Kind::Turn => 2,
        Kind::Probe => 3,
        Kind::NoProbe => 4,
        Kind::Drill(_) | Kind::Helix(_) => 5,
        Kind::Raw(_) => 7,
        _ => 6,
    }
}

/// A total order of objects that ignores the drawing's entity order: kind, then position
/// (the shape's numbers), then line type and text.
fn canonical_cmp(a: &DrawnObject, b: &DrawnObject, path_o: Option<f64>) -> std::cmp::Ordering {
    fn numbers(s: &Shape) -> Vec<f64> {
        match s {
            Shape::Circle { c, r } => vec![c.x, c.y, *r],
            Shape::Path(Geom::Line { a, b }) => vec![a.x, a.y, b.x, b.y],
            Shape::Path(Geom::Arc { c, r, a0, a1, .. }) => vec![c.x, c.y, *r, *a0, *a1],
        }
    }
    let tokens = |o: &DrawnObject| {
        o.text
            .as_ref()
            .map(|t| t.tokens.clone())
            .unwrap_or_default()
    };
    kind_rank(&kind_of(a, path_o))
        .cmp(&kind_rank(&kind_of(b, path_o)))
        .then_with(|| {
            let (na, nb) = (numbers(&a.shape), numbers(&b.shape));
            na.len().cmp(&nb.len()).then_with(|| {
                na.iter()
                    .zip(&nb)
                    .map(|(x, y)| x.total_cmp(y))
                    .find(|o| o.is_ne())
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
        })
        .then_with(|| a.linetype.cmp(&b.linetype))
        .then_with(|| tokens(a).cmp(&tokens(b)))
}

/// The order of a path's objects in the text, the same for any entity order of the drawing
/// that compiles alike: markers and other non-segments in canonical order
/// ([`canonical_cmp`]), then the segments in traversal order; segments the traversal did
/// not reach follow in canonical order.
fn ordered(
    indices: &[usize],
    objects: &[DrawnObject],
    raw: Option<&RawPath>,
    path_o: Option<f64>,
) -> Vec<usize> {
    let canonical = |mut v: Vec<usize>| {
        v.sort_by(|&a, &b| canonical_cmp(&objects[a], &objects[b], path_o));
        v
    };
    let Some(raw) = raw else {
        return canonical(indices.to_vec());
    };
    // by object index: is a segment, was reached by the traversal (linear on large paths)
    let mut is_segment = vec![false; objects.len()];
    for s in &raw.segments {
        is_segment[s.object] = true;
    }
    let (segs, others): (Vec<usize>, Vec<usize>) = indices.iter().partition(|&&i| is_segment[i]);
    let mut out = canonical(others);
    let mut diags = Diags::default();
    let trav = match (&raw.start, &raw.end) {
        // the walk alone: the order warnings are the compiler's business
        (Some(s), Some(e)) => walk(raw, s.pos, e.pos, &mut diags).0,
        _ => Vec::new(),
    };
    let mut reached = vec![false; objects.len()];
    for s in trav.iter().filter(|s| !s.turn_back) {
        let o = raw.segments[s.index].object;
        if !std::mem::replace(&mut reached[o], true) {
            out.push(o);
        }
    }
    let rest: Vec<usize> = segs.into_iter().filter(|&o| !reached[o]).collect();
    out.extend(canonical(rest));
    out
}

fn front_options(patterns: &Patterns, input: InputMode) -> FrontOptions<'_> {
    FrontOptions {
        layer_pattern: &patterns.path_full,
        path_pattern: &patterns.path_cs,
        pattern_text: &patterns.path_text,
        debug: None,
        input,
    }
}

/// The canonical text of a drawing: paths sorted by name.
pub fn objects_to_text(objects: &[DrawnObject], paths: &[RawPath], header: Option<&str>) -> String {
    let mut out = String::new();
    if let Some(h) = header {
        for line in h.lines() {
            out.push_str(&format!("# {line}\n"));
        }
        out.push('\n');
    }
    let blocks: Vec<String> = path_texts(objects, paths).into_values().collect();
    out.push_str(&blocks.join("\n"));
    out
}

/// The canonical text of each path (`path NAME { … }`), by path name.
fn path_texts<'a>(objects: &'a [DrawnObject], paths: &[RawPath]) -> BTreeMap<&'a str, String> {
    let mut by_path: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for (i, o) in objects.iter().enumerate() {
        by_path.entry(&*o.path).or_default().push(i);
    }
    let mut texts = BTreeMap::new();
    for (name, indices) in by_path {
        let raw = paths.iter().find(|p| p.name == name);
        let path_o = raw
            .and_then(|r| r.start_text.as_ref())
            .and_then(|t| t.raw('O'))
            .and_then(parse_number);
        let mut out = format!(
            "path {} {{\n",
            millpath_syntax::lexer::quote_if_needed(name)
        );
        for i in ordered(&indices, objects, raw, path_o) {
            let o = &objects[i];
            let kind = kind_of(o, path_o);
            let geometry = geometry_of(o, &kind);
            let params = o
                .text
                .as_ref()
                .map(|t| {
                    t.tokens
                        .iter()
                        .map(|tok| Spanned::new(tok.clone(), 0..0))
                        .collect()
                })
                .unwrap_or_default();
            let el = Element {
                kind: Spanned::new(kind, 0..0),
                geometry: Spanned::new(geometry, 0..0),
                params,
                comment: None,
                span: 0..0,
            };
            out.push_str("  ");
            out.push_str(&format::element(&el));
            out.push('\n');
        }
        out.push_str("}\n");
        texts.insert(name, out);
    }
    texts
}

/// Layer name of a path as CAD programs export it (`.` → `_`), with an optional
/// parameter-text suffix.
fn layer_name(path: &str, suffix: Option<&str>) -> String {
    let base = path.replace('.', "_");
    match suffix {
        Some(s) => format!("{base}~{s}"),
        None => base,
    }
}

/// `A`, `B`, … `Z`, `AA`, `AB`, …
fn suffix(mut n: usize) -> String {
    let mut s = Vec::new();
    loop {
        s.push((b'A' + (n % 26) as u8) as char);
        if n < 26 {
            break;
        }
        n = n / 26 - 1;
    }
    s.iter().rev().collect()
}

/// MTEXT escapes for a parameter text.
fn mtext_escape(s: &str) -> String {
    s.replace('\\', "\\\\")
        .replace('{', "\\{")
        .replace('}', "\\}")
}

const TEXT_HEIGHT: f64 = 0.35;

/// Where one object's entities go: their layer, and which of them are written (`--into`
/// keeps the drawing's own entities of an unchanged element).
struct Placement {
    layer: String,
    geometry: bool,
    text: bool,
}

/// The placement of object `i` with its parameter-text suffix.
type PlaceOf<'a> = &'a dyn Fn(usize, Option<&str>) -> Placement;

/// Every entity of each object written, on the layer `text2dxf` names.
fn written_whole(objects: &[DrawnObject]) -> impl Fn(usize, Option<&str>) -> Placement + '_ {
    |i, suffix| Placement {
        layer: layer_name(&objects[i].path, suffix),
        geometry: true,
        text: true,
    }
}

/// What a text's objects become in a drawing: the path layers (line type CONTINUOUS) and
/// the entities in the order they are written, placed as `place` says. Texts come after
/// the elements: circles' first, then arcs', then lines', so that circles win as the
/// assignment rule wants.
fn plan(
    objects: &[DrawnObject],
    suffixes: &[Option<String>],
    place: PlaceOf,
) -> (Vec<String>, Vec<NewEntity>) {
    let mut paths: Vec<&str> = objects.iter().map(|o| &*o.path).collect();
    paths.sort();
    paths.dedup();
    let layers = paths.iter().map(|p| layer_name(p, None)).collect();
    let mut entities = Vec::new();
    for (i, (o, suf)) in objects.iter().zip(suffixes).enumerate() {
        let at = place(i, suf.as_deref());
        if !at.geometry {
            continue;
        }
        let shape = match &o.shape {
            Shape::Circle { c, r } => NewShape::Circle {
                c: (c.x, c.y),
                r: *r,
            },
            Shape::Path(Geom::Line { a, b }) => NewShape::Line {
                a: (a.x, a.y),
                b: (b.x, b.y),
            },
            Shape::Path(Geom::Arc { c, r, a0, a1, .. }) => NewShape::Arc {
                c: (c.x, c.y),
                r: *r,
                a0: *a0,
                a1: *a1,
            },
        };
        entities.push(NewEntity {
            layer: at.layer,
            linetype: Some(o.linetype.to_string()),
            shape,
        });
    }
    for pass in 0..3 {
        for (i, (o, suf)) in objects.iter().zip(suffixes).enumerate() {
            let Some(t) = o.text.as_ref().filter(|t| !t.tokens.is_empty()) else {
                continue;
            };
            let (rank, at) = match &o.shape {
                Shape::Circle { c, .. } => (0, *c),
                Shape::Path(g @ Geom::Arc { .. }) => (1, g.sub(0.0, g.length() / 2.0).end()),
                Shape::Path(Geom::Line { a, b }) => (2, a.add(*b).scale(0.5)),
            };
            if rank != pass {
                continue;
            }
            let place = place(i, suf.as_deref());
            if !place.text {
                continue;
            }
            entities.push(NewEntity {
                layer: place.layer,
                linetype: None,
                shape: NewShape::Text {
                    at: (at.x, at.y),
                    height: TEXT_HEIGHT,
                    value: t.tokens.join(" "),
                },
            });
        }
    }
    (layers, entities)
}

/// A new drawing of the objects (AutoCAD 2000, [`DxfWriter`]).
fn write_dxf(objects: &[DrawnObject], suffixes: &[Option<String>]) -> String {
    let (layers, entities) = plan(objects, suffixes, &written_whole(objects));
    let mut w = DxfWriter::new();
    for l in &layers {
        w.layer(l, "CONTINUOUS");
    }
    for e in &entities {
        let (layer, lt) = (e.layer.as_str(), e.linetype.as_deref());
        match &e.shape {
            NewShape::Circle { c, r } => w.circle(layer, lt, *c, *r),
            NewShape::Line { a, b } => w.line(layer, lt, *a, *b),
            NewShape::Arc { c, r, a0, a1 } => w.arc(layer, lt, *c, *r, *a0, *a1),
            NewShape::Text { at, height, value } => {
                w.mtext(layer, *at, *height, &[&mtext_escape(value)])
            }
        };
    }
    w.finish()
}

pub(super) fn texts_match(
    a: Option<&crate::params::ParamText>,
    b: Option<&crate::params::ParamText>,
) -> bool {
    let toks = |t: Option<&crate::params::ParamText>| {
        t.as_ref().map(|t| t.tokens.clone()).unwrap_or_default()
    };
    toks(a) == toks(b)
}

/// Writes objects as a DXF file. Elements whose text would be assigned to another element
/// are moved to their own parameter-text layer (`PATH~A`, …), checked by reading back.
pub fn objects_to_dxf(objects: &[DrawnObject], patterns: &Patterns) -> String {
    let in_order: Vec<usize> = (0..objects.len()).collect();
    settle(objects, patterns, &|_| true, &|suffixes| {
        (write_dxf(objects, suffixes), in_order.clone())
    })
}

/// A drawing of objects with the given parameter-text suffixes, and the order in which the
/// objects read back from it (indexes into the objects).
type Render<'a, T> = &'a dyn Fn(&[Option<String>]) -> (T, Vec<usize>);

/// The drawing `render` makes of the objects, with parameter-text layers for the elements
/// whose text the read-back assigns elsewhere (at most eight rounds). `ours` chooses, by
/// path, the read-back objects that are `objects` (a drawing may hold other paths too);
/// `render` also says in which order they read back (indexes into `objects`).
fn settle<T: AsRef<[u8]>>(
    objects: &[DrawnObject],
    patterns: &Patterns,
    ours: &dyn Fn(&str) -> bool,
    render: Render<T>,
) -> T {
    let mut suffixes: Vec<Option<String>> = vec![None; objects.len()];
    let mut next = 0usize;
    let file = FileRef::new("check.dxf".into());
    for _ in 0..8 {
        let (out, order) = render(&suffixes);
        let Ok(d) = millpath_dxf::read_dxf(out.as_ref()) else {
            return out;
        };
        // our own writing has lines and arcs only
        let opts = front_options(patterns, InputMode::Reference);
        let mut diags = Diags::default();
        let Ok((back, _)) = dxf_objects(&d, &file, &opts, &mut diags) else {
            return out;
        };
        let back: Vec<&DrawnObject> = back.iter().filter(|b| ours(&b.path)).collect();
        // where each object reads back
        let mut at = vec![None; objects.len()];
        for (j, &i) in order.iter().enumerate() {
            if let Some(a) = at.get_mut(i) {
                *a = Some(j);
            }
        }
        let mut changed = false;
        for (i, o) in objects.iter().enumerate() {
            let ok = at[i]
                .and_then(|j| back.get(j))
                .is_some_and(|b| texts_match(b.text.as_deref(), o.text.as_deref()));
            if !ok && suffixes[i].is_none() {
                suffixes[i] = Some(suffix(next));
                next += 1;
                changed = true;
            }
        }
        if !changed {
            return out;
        }
    }
    render(&suffixes).0
}

/// Path building for conversions (errors are the compiler's business, not the converter's).
pub fn paths_of(objects: &[DrawnObject], patterns: &Patterns) -> Vec<RawPath> {
    let mut diags = Diags::default();
    let file: Arc<FileRef> = FileRef::new("convert".into());
    build_paths(
        objects,
        &file,
        &patterns.path_cs,
        &patterns.path_text,
        &mut diags,
    )
    .unwrap_or_default()
}

/// `dxf2text`: a DXF file → canonical text. Problems of the drawing that lose information
/// (texts that belong to no element, …) come back as diagnostics beside the text. In the
/// extended mode polylines and blocks become plain elements (the language has neither).
pub fn dxf_to_text(
    bytes: &[u8],
    file: &Arc<FileRef>,
    patterns: &Patterns,
    input: InputMode,
) -> Result<(String, Vec<crate::Diagnostic>), crate::Diagnostic> {
    let d = millpath_dxf::read_dxf(bytes).map_err(|e| {
        crate::Diagnostic::error(
            crate::Msg::CannotLoadDxf,
            crate::Origin::File(file.clone()),
            vec![
                file.path.display().to_string(),
                crate::diag::dxf_error_arg(&e),
            ],
        )
    })?;
    let opts = front_options(patterns, input);
    let mut diags = Diags::default();
    let (objects, _) = dxf_objects(&d, file, &opts, &mut diags)?;
    let paths = paths_of(&objects, patterns);
    Ok((objects_to_text(&objects, &paths, None), diags.list))
}

/// `text2dxf`: text → DXF. Syntax errors refuse the conversion (nothing half-converted).
pub fn text_to_dxf(
    src: &str,
    file: &Arc<FileRef>,
    patterns: &Patterns,
) -> Result<String, Vec<crate::Diagnostic>> {
    Ok(objects_to_dxf(&text_objects(src, file)?, patterns))
}

/// The drawn objects of a text; syntax errors refuse it.
fn text_objects(
    src: &str,
    file: &Arc<FileRef>,
) -> Result<Vec<DrawnObject>, Vec<crate::Diagnostic>> {
    let mut diags = Diags::default();
    let objects = crate::front::text::text_objects(src, file, &mut diags)
        .map_err(|d| vec![d])?
        .objects;
    if diags.has_errors() {
        return Err(diags.list);
    }
    Ok(objects)
}

/// `fmt`: the canonical form of a text file; `Err` with the syntax errors when it does not parse.
pub fn format_text(src: &str, file: &Arc<FileRef>) -> Result<String, Vec<crate::Diagnostic>> {
    format_text_parsed(src, file).map(|(text, _)| text)
}

/// [`format_text`] with the tree of `src` it parsed (a caller whose `src` is canonical
/// already has the tree of the result without a second parse).
pub fn format_text_parsed(
    src: &str,
    file: &Arc<FileRef>,
) -> Result<(String, millpath_syntax::File), Vec<crate::Diagnostic>> {
    let (ast, errors) = millpath_syntax::parse(src);
    if !errors.is_empty() {
        return Err(errors
            .into_iter()
            .map(|e| {
                let origin = crate::front::text::span_origin(src, file, &e.span);
                crate::front::text::syntax_diagnostic(e, origin)
            })
            .collect());
    }
    // the file's own line ends (a CRLF checkout stays CRLF)
    let crlf = crate::load::text_file::LineEnds::of(src).written_crlf();
    let text = crate::load::text_file::with_line_ends(millpath_syntax::format(&ast, src), crlf);
    Ok((text, ast))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suffixes() {
        assert_eq!(suffix(0), "A");
        assert_eq!(suffix(25), "Z");
        assert_eq!(suffix(26), "AA");
        assert_eq!(suffix(27), "AB");
    }
}
