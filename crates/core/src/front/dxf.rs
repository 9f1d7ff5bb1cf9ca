//! The DXF front-end: entities → drawing model. Layers and path names, line types, circle
//! classification, and the geometric assignment of texts to elements (reference-input.md §1–§2).

use crate::args;
use crate::diag::{Diagnostic, Diags, EntityOrigin, FileRef, Msg, Origin};
use crate::front::drawing::{build_paths, DrawingFile, DrawnObject, Shape};
use crate::front::extended;
use crate::front::layer::{effective_layer, path_name_of_layer};
use crate::front::linetype_alias;
use crate::front::mtext::{mtext_plain, replace_percent_codes};
use crate::front::options::{FrontOptions, InputMode};
use crate::geom::{f3, near, normalize_angle, Geom, P2};
use crate::params::ParamText;
use millpath_dxf::{Drawing, Entity, EntityKind, Point3};
use std::sync::Arc;

/// OCS → WCS by the DXF arbitrary axis algorithm.
fn ocs_to_wcs(p: Point3, n: Point3) -> Point3 {
    if n[0] == 0.0 && n[1] == 0.0 && n[2] == 1.0 {
        return p;
    }
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len == 0.0 {
        return p;
    }
    let n = [n[0] / len, n[1] / len, n[2] / len];
    let ax = if n[0].abs() < 1.0 / 64.0 && n[1].abs() < 1.0 / 64.0 {
        cross([0.0, 1.0, 0.0], n)
    } else {
        cross([0.0, 0.0, 1.0], n)
    };
    let al = (ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]).sqrt();
    let ax = [ax[0] / al, ax[1] / al, ax[2] / al];
    let ay = cross(n, ax);
    [
        p[0] * ax[0] + p[1] * ay[0] + p[2] * n[0],
        p[0] * ax[1] + p[1] * ay[1] + p[2] * n[1],
        p[0] * ax[2] + p[1] * ay[2] + p[2] * n[2],
    ]
}

fn cross(a: Point3, b: Point3) -> Point3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

struct Obj<'a> {
    ent: &'a Entity,
    layer: &'a str,
    path: String,
    linetype: String,
    origin: Origin,
    shape: Shape,
    /// circle radius or arc data for overlap tests
    text: Option<ParamText>,
    candidate: bool,
}

struct Ctx<'a> {
    file: &'a Arc<FileRef>,
}

impl Ctx<'_> {
    fn origin(&self, e: &Entity, layer: &str, path: &str, pos: P2) -> Origin {
        Origin::Entity(Arc::new(EntityOrigin {
            file: self.file.clone(),
            line: e.line,
            handle: e.handle.clone(),
            layer: layer.to_string(),
            code_name: e.kind.code_name(),
            pos,
            path: path.to_string(),
        }))
    }
}

fn to2(p: Point3, origin: &Origin) -> Result<P2, Diagnostic> {
    if !near(p[2], 0.0) {
        return Err(Diagnostic::error(
            Msg::ZNotZero,
            origin.clone(),
            args![format!("({} {} {})", p[0], p[1], p[2])],
        ));
    }
    Ok(P2::new(p[0], p[1]))
}

/// The elements of a DXF drawing's path layers with their assigned texts (stage one of the
/// DXF front-end: entities, line types, text assignment). `Err` aborts the file.
pub fn dxf_objects(
    d: &Drawing,
    file: &Arc<FileRef>,
    opts: &FrontOptions,
    diags: &mut Diags,
) -> Result<(Vec<DrawnObject>, Vec<String>), Diagnostic> {
    let ctx = Ctx { file };
    let resolved;
    let d = match opts.input {
        InputMode::Reference => {
            extended::warn_ignored(d, file, opts, diags);
            d
        }
        InputMode::Extended => {
            resolved = extended::resolve(d, file, opts, diags);
            &resolved
        }
    };
    let table_lt = |name: &str| -> String {
        d.linetypes
            .iter()
            .find(|l| l.eq_ignore_ascii_case(name))
            .cloned()
            .unwrap_or_else(|| name.to_string())
    };
    let effective_lt = |e: &Entity, layer_lt: &str| -> String {
        match &e.linetype {
            Some(lt) if lt.eq_ignore_ascii_case("bylayer") => {}
            Some(lt) if lt.eq_ignore_ascii_case("byblock") => return "ByBlock".into(),
            Some(lt) => return table_lt(lt),
            None => {}
        }
        layer_lt.to_string()
    };
    // What an entity's layer gives, worked out once per layer name (entities share few layers).
    struct OnLayer<'d> {
        layer: &'d str,
        path: String,
        /// `None` unless the path name matches the pattern; else the layer's line type.
        linetype: Option<String>,
    }
    let mut layer_index: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    let mut on_layers: Vec<OnLayer> = Vec::new();
    // consecutive entities mostly share their layer: no hashing for those
    let mut last: Option<(&str, usize)> = None;

    // 1. elements (circles, lines, arcs) and texts on path layers
    let mut objs: Vec<Obj> = Vec::new();
    let mut texts: Vec<(&Entity, &str, String)> = Vec::new();
    for e in &d.entities {
        let i = match last {
            Some((name, i)) if name == e.layer => i,
            _ => {
                let i = *layer_index.entry(e.layer.as_str()).or_insert_with(|| {
                    let layer = effective_layer(&e.layer);
                    let path = path_name_of_layer(layer);
                    let linetype = opts.layer_pattern.is_match(&path).then(|| {
                        d.layers
                            .get(layer)
                            .map_or_else(|| "Continuous".into(), |lt| table_lt(lt))
                    });
                    on_layers.push(OnLayer {
                        layer,
                        path,
                        linetype,
                    });
                    on_layers.len() - 1
                });
                last = Some((e.layer.as_str(), i));
                i
            }
        };
        let on = &on_layers[i];
        let Some(layer_lt) = &on.linetype else {
            continue;
        };
        let (layer, path) = (on.layer, on.path.clone());
        let linetype = match opts.input {
            InputMode::Reference => effective_lt(e, layer_lt),
            InputMode::Extended => linetype_alias::canonical(&effective_lt(e, layer_lt)),
        };
        let (shape, pos) = match &e.kind {
            EntityKind::Text(_) | EntityKind::MText(_) => {
                texts.push((e, layer, path));
                continue;
            }
            EntityKind::Line { start, end } => {
                let o = ctx.origin(e, layer, &path, P2::new(start[0], start[1]));
                let (a, b) = (to2(*start, &o)?, to2(*end, &o)?);
                (Shape::Path(Geom::Line { a, b }), a)
            }
            EntityKind::Circle { center, radius } => {
                let c3 = ocs_to_wcs(*center, e.extrusion);
                let o = ctx.origin(e, layer, &path, P2::new(c3[0], c3[1]));
                let c = to2(c3, &o)?;
                if *radius <= 0.0 {
                    return Err(Diagnostic::error(Msg::BadRadius, o, args![radius]));
                }
                (Shape::Circle { c, r: *radius }, c)
            }
            EntityKind::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => {
                let c3 = ocs_to_wcs(*center, e.extrusion);
                let o = ctx.origin(e, layer, &path, P2::new(c3[0], c3[1]));
                let c = to2(c3, &o)?;
                if *radius <= 0.0 {
                    return Err(Diagnostic::error(Msg::BadRadius, o, args![radius]));
                }
                let g = Geom::Arc {
                    c,
                    r: *radius,
                    a0: normalize_angle(*start_angle),
                    a1: normalize_angle(*end_angle),
                    ccw: true,
                };
                (Shape::Path(g), g.start())
            }
        };
        let origin = ctx.origin(e, layer, &path, pos);
        let candidate = crate::front::drawing::takes_text(&linetype, &shape);
        objs.push(Obj {
            ent: e,
            layer,
            path,
            linetype,
            origin,
            shape,
            text: None,
            candidate,
        });
    }

    // 2. texts → elements: TEXT first, then MTEXT, each in file order
    let mut debug = Vec::new();
    let mut assigned: Vec<(usize, String, P2, f64)> = Vec::new();
    let mut taken_by: Vec<Option<TakenBy>> = vec![None; objs.len()];
    let ordered: Vec<_> = texts
        .iter()
        .filter(|(e, _, _)| matches!(e.kind, EntityKind::Text(_)))
        .chain(
            texts
                .iter()
                .filter(|(e, _, _)| matches!(e.kind, EntityKind::MText(_))),
        )
        .collect();
    for (e, layer, path) in ordered {
        let Some((value, raw, centre, radius, pos)) = search_circle(e, d.text_size) else {
            let raw = match &e.kind {
                EntityKind::Text(t) => t.value.clone(),
                EntityKind::MText(m) => m.value.clone(),
                _ => String::new(),
            };
            let pos = text_position(e);
            diags.error(Msg::TextAnchor, ctx.origin(e, layer, path, pos), args![raw]);
            continue;
        };
        let _ = raw;
        let origin = ctx.origin(e, layer, path, pos);
        let mtext = matches!(e.kind, EntityKind::MText(_));
        let free = |_: usize, o: &Obj| o.candidate && o.text.is_none() && o.layer == *layer;
        match find_overlap(&objs, centre, radius, free) {
            None => diags.error(
                Msg::NoOverlap,
                origin,
                args![value, centre, f3(2.0 * radius)],
            ),
            Some(idx) => {
                // the file order decides where a text of the same kind came first (all TEXT
                // goes before all MTEXT, whatever the order)
                let unless_same_kind = |i: usize, o: &Obj| {
                    o.candidate
                        && o.layer == *layer
                        && taken_by[i]
                            .as_ref()
                            .is_none_or(|t: &TakenBy| t.mtext == mtext)
                };
                let first = find_overlap(&objs, centre, radius, unless_same_kind)
                    .and_then(|best| taken_by[best].as_ref().filter(|_| best != idx))
                    .filter(|t| t.value.trim() != value.trim());
                if let Some(t) = first {
                    diags.push(Diagnostic::warning(
                        Msg::TextTakenFirst,
                        origin.clone(),
                        args![value, t.value],
                    ));
                }
                taken_by[idx] = Some(TakenBy {
                    mtext,
                    value: value.clone(),
                });
                let pt = ParamText::parse(&value, origin)?;
                objs[idx].text = Some(pt);
                assigned.push((idx, value, centre, radius));
            }
        }
    }
    if let Some(re) = opts.debug {
        for (idx, value, centre, radius) in &assigned {
            if re.is_match(value) {
                debug.push(String::new());
                debug.push("Object".into());
                debug.push(format!("   {}", describe(&objs[*idx])));
                debug.push(format!(
                    "has assigned text ''{}' @ {} d={}'",
                    value,
                    centre,
                    f3(2.0 * radius)
                ));
            }
        }
        debug.push(String::new());
    }

    let mut names = crate::front::drawing::SharedNames::default();
    let objects: Vec<DrawnObject> = objs
        .into_iter()
        .map(|o| DrawnObject {
            path: names.get(&o.path),
            linetype: names.get(&o.linetype),
            shape: o.shape,
            text: o.text.map(Box::new),
            origin: o.origin,
        })
        .collect();
    Ok((objects, debug))
}

/// Converts a parsed DXF drawing into the drawing model. `Err` aborts the file (it then
/// contributes no paths); other problems are recorded in `diags`.
pub fn dxf_to_drawing(
    d: &Drawing,
    file: &Arc<FileRef>,
    opts: &FrontOptions,
    diags: &mut Diags,
) -> Result<DrawingFile, Diagnostic> {
    let (objects, debug) = dxf_objects(d, file, opts, diags)?;
    let paths = build_paths(&objects, file, opts.path_pattern, opts.pattern_text, diags)?;
    Ok(DrawingFile {
        paths,
        debug,
        version: d.version.clone(),
    })
}

fn describe(o: &Obj) -> String {
    let head = format!(
        "{} LAYER={} CODENAME={} TYPE={} LINETYPE={}%{} ",
        o.ent.kind.code_name(),
        o.layer,
        o.ent.kind.code_name(),
        o.ent.kind.code_name(),
        o.linetype,
        o.ent.linetype_scale
    );
    match (&o.ent.kind, &o.shape) {
        (EntityKind::Line { start, end }, _) => format!(
            "{head}From=[{} {} {}] To=[{} {} {}]",
            f3(start[0]),
            f3(start[1]),
            f3(start[2]),
            f3(end[0]),
            f3(end[1]),
            f3(end[2])
        ),
        (EntityKind::Arc { .. }, Shape::Path(Geom::Arc { c, r, a0, a1, .. })) => {
            format!(
                "{head}Center=[{} {} 0.000] Dia={} Start={}° End={}°",
                f3(c.x),
                f3(c.y),
                f3(2.0 * r),
                f3(*a0),
                f3(*a1)
            )
        }
        (_, Shape::Circle { c, r }) => format!(
            "{head}Center=[{} {} 0.000] Dia={}",
            f3(c.x),
            f3(c.y),
            f3(2.0 * r)
        ),
        _ => head,
    }
}

fn text_position(e: &Entity) -> P2 {
    match &e.kind {
        EntityKind::Text(t) => P2::new(t.first[0], t.first[1]),
        EntityKind::MText(m) => P2::new(m.insert[0], m.insert[1]),
        _ => P2::default(),
    }
}

/// The text value for parameters, its raw value, the search-circle centre and radius, and the
/// text position; `None` when the anchor/rotation rules reject the text.
fn search_circle(e: &Entity, default_height: f64) -> Option<(String, String, P2, f64, P2)> {
    match &e.kind {
        EntityKind::Text(t) => {
            let centred = t.halign == 1 && t.valign == 2;
            let top_left = t.halign == 0 && t.valign == 3;
            let baseline = t.halign == 0 && t.valign == 0;
            if !(centred || top_left || baseline) || t.generation & 6 != 0 {
                return None;
            }
            if !centred && !near(normalize_angle(t.rotation), 0.0) {
                return None;
            }
            let p3 = if baseline {
                t.first
            } else {
                t.second.unwrap_or(t.first)
            };
            let p3 = ocs_to_wcs(p3, e.extrusion);
            let pos = P2::new(p3[0], p3[1]);
            let h = if t.height <= 0.0 {
                default_height
            } else {
                t.height
            };
            let n = t.value.chars().count() as f64;
            let w = 0.6 * h * n;
            let off = if centred {
                P2::default()
            } else if top_left {
                P2::new(w / 2.0, -h / 2.0)
            } else {
                P2::new(w / 2.0, h / 2.0)
            };
            let r = 0.5 * (w * w + h * h).sqrt();
            Some((
                replace_percent_codes(&t.value),
                t.value.clone(),
                pos.add(off),
                r,
                pos,
            ))
        }
        EntityKind::MText(m) => {
            let att = m.attachment;
            if !matches!(att, 1 | 5 | 7) {
                return None;
            }
            let rot = match (m.rotation, m.direction) {
                (Some(r), _) => r,
                (None, Some(d)) => d[1].atan2(d[0]).to_degrees(),
                (None, None) => 0.0,
            };
            let rot = normalize_angle(rot);
            if att != 5 && !((0.0..=1.0).contains(&rot) || (359.0..=361.0).contains(&rot)) {
                return None;
            }
            let plain = mtext_plain(&m.value);
            let lines: Vec<&str> = plain.split('\n').collect();
            // every line but the last keeps its CR and so counts one character more
            let n = lines.iter().map(|l| l.chars().count()).max().unwrap_or(0) as f64;
            let count = lines.len() as f64;
            let h = m.height;
            let w = 0.6 * h * n;
            let hh = h * count;
            let off = match att {
                5 => P2::default(),
                1 => P2::new(w / 2.0, -hh / 2.0),
                _ => P2::new(w / 2.0, hh / 2.0),
            };
            let r = (0.5 * (w * w + hh * hh).sqrt()).min(0.7 * hh);
            let pos = P2::new(m.insert[0], m.insert[1]);
            Some((
                replace_percent_codes(&plain),
                m.value.clone(),
                pos.add(off),
                r,
                pos,
            ))
        }
        _ => None,
    }
}

/// Which text took an element.
#[derive(Debug, Clone)]
struct TakenBy {
    mtext: bool,
    value: String,
}

/// The element a text belongs to (§2.4), among those `free` lets in (given index and
/// element): any overlapping circle beats any arc beats any line; of equally near ones the
/// first in the file.
fn find_overlap(
    objs: &[Obj],
    c: P2,
    radius: f64,
    free: impl Fn(usize, &Obj) -> bool,
) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (i, o) in objs.iter().enumerate() {
        if let (true, Shape::Circle { c: cc, r }) = (free(i, o), &o.shape) {
            let d = c.dist(*cc);
            if d < radius + r && best.is_none_or(|(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
    }
    if best.is_some() {
        return best.map(|b| b.0);
    }
    for (i, o) in objs.iter().enumerate() {
        if let (
            true,
            Shape::Path(Geom::Arc {
                c: ac, r, a0, a1, ..
            }),
        ) = (free(i, o), &o.shape)
        {
            let v = c.sub(*ac);
            let mut ang = v.y.atan2(v.x);
            if ang < 0.0 {
                ang += 2.0 * std::f64::consts::PI;
            }
            let (s, e) = (a0.to_radians(), a1.to_radians());
            let inside = if s < e {
                s <= ang && ang <= e
            } else {
                ang >= s || ang <= e
            };
            let d = if inside {
                (v.len() - r).abs()
            } else {
                f64::INFINITY
            };
            if d <= radius && best.is_none_or(|(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
    }
    if best.is_some() {
        return best.map(|b| b.0);
    }
    for (i, o) in objs.iter().enumerate() {
        if let (true, Shape::Path(Geom::Line { a, b })) = (free(i, o), &o.shape) {
            let d = b.sub(*a);
            let len = d.len();
            if len == 0.0 {
                continue;
            }
            let u = d.scale(1.0 / len);
            let proj = c.sub(*a).dot(u);
            if !(0.0..=len).contains(&proj) {
                continue;
            }
            let perp = c.dist(a.add(u.scale(proj)));
            if perp >= radius {
                continue;
            }
            // the reference compares overlapping lines with this distorted metric
            let t = d.dot(c.sub(*a));
            let metric = c.dist(a.add(d.scale(t)));
            if best.is_none_or(|(_, bd)| metric < bd) {
                best = Some((i, metric));
            }
        }
    }
    best.map(|b| b.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layer_names() {
        assert_eq!(path_name_of_layer("8999_1P"), "8999.1P");
        assert_eq!(path_name_of_layer("2916_2P~A"), "2916.2P");
        assert_eq!(path_name_of_layer("8999_16P~REVERSE"), "8999.16P");
        assert_eq!(path_name_of_layer("8999___"), "8999...");
        assert_eq!(path_name_of_layer("a~1"), "a~1");
    }

    #[test]
    fn extrusion_minus_z_mirrors_x() {
        let p = ocs_to_wcs([1.0, 2.0, 0.0], [0.0, 0.0, -1.0]);
        assert!((p[0] + 1.0).abs() < 1e-12 && (p[1] - 2.0).abs() < 1e-12);
    }
}
