//! The extended input mode's geometry: polylines exploded into LINE/ARC, block references
//! resolved into model space (nested, scaled, rotated, mirrored, MINSERT arrays). Every
//! produced entity keeps the line and handle of the model-space entity it comes from, so
//! messages point at the polyline or INSERT in the file. ELLIPSE and SPLINE are refused,
//! never approximated; so are arcs that a non-uniform scale would turn into ellipses.
//!
//! The extended mode's geometry: polylines → LINE/ARC (bulges, exact centres), blocks resolved into
//! model space (nesting, scale, rotation, mirroring, arrays, layer `0`/`ByBlock` inheritance), each
//! result keeping its model-space entity's line; ELLIPSE/SPLINE and distorted arcs refused; depth ≤
//! 16 and ≤ 1,000,000 results.

use crate::extra::{Block, Extra, ExtraKind, Insert, Polyline};
use crate::{Drawing, Entity, EntityKind, Point3};

/// Nesting depth of blocks at most (a block that inserts itself stops here too).
pub const MAX_DEPTH: usize = 16;
/// Entities produced, plus block instances visited, at most per drawing.
pub const MAX_OUTPUT: usize = 1_000_000;

/// The model space with every polyline and block reference resolved.
#[derive(Debug, Clone, Default)]
pub struct Resolved {
    /// LINE/ARC/CIRCLE/TEXT/MTEXT only, in file order of their origin.
    pub entities: Vec<Entity>,
    /// What could not be resolved, in file order.
    pub refused: Vec<Refused>,
}

/// An entity the extended mode does not turn into lines and arcs.
#[derive(Debug, Clone, PartialEq)]
pub struct Refused {
    /// Line and handle of the model-space entity (the INSERT for block contents).
    pub line: usize,
    pub handle: String,
    pub layer: String,
    /// The refused entity's own type (`SPLINE`, also inside a block).
    pub code_name: &'static str,
    pub pos: Point3,
    pub reason: Reason,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Reason {
    /// ELLIPSE or SPLINE: a curve that would have to be approximated.
    Curve,
    /// A 3-D polyline, mesh or polyface, or an entity outside the XY plane.
    NotPlanar,
    /// An INSERT of a block the file does not define.
    UnknownBlock(String),
    /// Blocks nested deeper than [`MAX_DEPTH`] (or inserting themselves).
    TooDeep,
    /// More than [`MAX_OUTPUT`] entities.
    TooMany,
    /// A circle or arc under a non-uniform (or zero) scale.
    Distorted,
    /// A MINSERT with fewer than one row or column.
    BadArray,
    /// A coordinate, bulge, scale or angle that is NaN or infinite.
    NotFinite,
}

/// An affine map of the plane plus a Z scale and offset.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Affine {
    /// x' = m[0]x + m[1]y + m[4], y' = m[2]x + m[3]y + m[5]
    m: [f64; 6],
    zs: f64,
    z0: f64,
}

const IDENTITY: Affine = Affine {
    m: [1.0, 0.0, 0.0, 1.0, 0.0, 0.0],
    zs: 1.0,
    z0: 0.0,
};

/// x ↦ −x: an OCS with the normal (0, 0, −1) seen from +Z.
const MIRROR_X: Affine = Affine {
    m: [-1.0, 0.0, 0.0, 1.0, 0.0, 0.0],
    zs: -1.0,
    z0: 0.0,
};

impl Affine {
    fn apply(&self, p: Point3) -> Point3 {
        let m = &self.m;
        [
            m[0] * p[0] + m[1] * p[1] + m[4],
            m[2] * p[0] + m[3] * p[1] + m[5],
            self.zs * p[2] + self.z0,
        ]
    }

    /// The direction of a vector (no translation).
    fn apply_vec(&self, v: Point3) -> Point3 {
        let m = &self.m;
        [m[0] * v[0] + m[1] * v[1], m[2] * v[0] + m[3] * v[1], v[2]]
    }

    /// `self ∘ inner`: `inner` first.
    fn then_inner(&self, inner: &Affine) -> Affine {
        let (a, b) = (&self.m, &inner.m);
        Affine {
            m: [
                a[0] * b[0] + a[1] * b[2],
                a[0] * b[1] + a[1] * b[3],
                a[2] * b[0] + a[3] * b[2],
                a[2] * b[1] + a[3] * b[3],
                a[0] * b[4] + a[1] * b[5] + a[4],
                a[2] * b[4] + a[3] * b[5] + a[5],
            ],
            zs: self.zs * inner.zs,
            z0: self.zs * inner.z0 + self.z0,
        }
    }

    fn det(&self) -> f64 {
        self.m[0] * self.m[3] - self.m[1] * self.m[2]
    }

    /// The scale factor when the map keeps circles circles (a similarity), else `None`.
    fn uniform_scale(&self) -> Option<f64> {
        let m = &self.m;
        let uniform = |m: [f64; 4]| {
            let (l1, l2) = (m[0] * m[0] + m[2] * m[2], m[1] * m[1] + m[3] * m[3]);
            let dot = m[0] * m[1] + m[2] * m[3];
            let tol = 1e-9 * l1.max(l2);
            ((l1 - l2).abs() <= tol && dot.abs() <= tol && l1 > 0.0).then(|| l1.sqrt())
        };
        let square = [m[0], m[1], m[2], m[3]];
        match uniform(square) {
            Some(s) => Some(s),
            // the squares of a huge (or tiny) scale overflow: a uniform scale of 1e300 is
            // still uniform (its coordinates are then out of range, which is the error)
            None => {
                let k = square.iter().fold(0.0f64, |k, v| k.max(v.abs()));
                (k.is_finite() && k > 0.0)
                    .then(|| uniform(square.map(|v| v / k)).map(|s| s * k))
                    .flatten()
            }
        }
    }

    /// Rotation of the X axis in degrees.
    fn rotation_deg(&self) -> f64 {
        self.m[2].atan2(self.m[0]).to_degrees()
    }

    fn finite(&self) -> bool {
        self.m.iter().all(|v| v.is_finite()) && self.zs.is_finite() && self.z0.is_finite()
    }

    fn translate(x: f64, y: f64, z: f64) -> Affine {
        Affine {
            m: [1.0, 0.0, 0.0, 1.0, x, y],
            zs: 1.0,
            z0: z,
        }
    }
}

/// sin and cos of an angle in degrees, exact for quarter turns (a block turned by 90° should
/// not move a point on an axis to -1e-15).
fn sin_cos_deg(deg: f64) -> (f64, f64) {
    let q = deg / 90.0;
    if q.fract() == 0.0 && q.abs() < 1e15 {
        return match (q as i64).rem_euclid(4) {
            0 => (0.0, 1.0),
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        };
    }
    deg.to_radians().sin_cos()
}

/// The placement of one block instance (INSERT, or one cell of a MINSERT array).
fn insert_map(i: &Insert, base: Point3, column: i32, row: i32) -> Affine {
    let (s, c) = sin_cos_deg(i.rotation);
    let (dx, dy) = (
        f64::from(column) * i.column_spacing,
        f64::from(row) * i.row_spacing,
    );
    let rot = Affine {
        m: [c, -s, s, c, 0.0, 0.0],
        zs: 1.0,
        z0: 0.0,
    };
    let scale = Affine {
        m: [i.scale[0], 0.0, 0.0, i.scale[1], 0.0, 0.0],
        zs: i.scale[2],
        z0: 0.0,
    };
    // insertion point, rotation, array offset (in the rotated frame), scale, base point
    Affine::translate(i.insert[0], i.insert[1], i.insert[2])
        .then_inner(&rot)
        .then_inner(&Affine::translate(dx, dy, 0.0))
        .then_inner(&scale)
        .then_inner(&Affine::translate(-base[0], -base[1], -base[2]))
}

/// Where the produced entities come from and what they inherit.
#[derive(Clone)]
struct Scope<'a> {
    /// The model-space entity (line, handle).
    line: usize,
    handle: &'a str,
    /// Inside a block: layer and line type of the INSERT, for layer `0` and `ByBlock`.
    inherit: Option<(String, Option<String>)>,
    map: Affine,
    depth: usize,
}

struct Out<'d> {
    d: &'d Drawing,
    resolved: Resolved,
    left: usize,
    /// Set by a depth or size overflow: the rest of that model-space entity is skipped.
    stop: bool,
}

/// Resolves the model space of a drawing.
pub fn resolve(d: &Drawing) -> Resolved {
    let mut out = Out {
        d,
        resolved: Resolved {
            entities: d.entities.clone(),
            refused: Vec::new(),
        },
        left: MAX_OUTPUT,
        stop: false,
    };
    for x in &d.extra {
        out.stop = false;
        let scope = Scope {
            line: x.line,
            handle: &x.handle,
            inherit: None,
            map: IDENTITY,
            depth: 0,
        };
        out.extra(x, &scope);
    }
    // produced entities carry their origin's line: a stable sort puts them in file order
    out.resolved.entities.sort_by_key(|e| e.line);
    out.resolved
}

impl Out<'_> {
    /// Records a refusal once per model-space entity, type and reason (a block inserted a
    /// thousand times gives one message); overflows stop the entity.
    fn refuse(
        &mut self,
        scope: &Scope,
        layer: &str,
        code_name: &'static str,
        pos: Point3,
        reason: Reason,
    ) {
        self.stop |= matches!(reason, Reason::TooDeep | Reason::TooMany);
        let seen = self
            .resolved
            .refused
            .iter()
            .rev()
            .any(|r| r.line == scope.line && r.code_name == code_name && r.reason == reason);
        if seen {
            return;
        }
        self.resolved.refused.push(Refused {
            line: scope.line,
            handle: scope.handle.to_string(),
            layer: layer.to_string(),
            code_name,
            pos: scope.map.apply(pos),
            reason,
        });
    }

    /// Layer and line type after block inheritance (`0` and `ByBlock` take the INSERT's).
    fn inherited(
        &self,
        scope: &Scope,
        layer: &str,
        lt: &Option<String>,
    ) -> (String, Option<String>) {
        match &scope.inherit {
            None => (layer.to_string(), lt.clone()),
            Some((il, ilt)) => {
                let layer = if layer == "0" {
                    il.clone()
                } else {
                    layer.to_string()
                };
                let lt = match lt {
                    Some(t) if t.eq_ignore_ascii_case("byblock") => {
                        Some(ilt.clone().unwrap_or_else(|| {
                            self.d
                                .layers
                                .get(il)
                                .cloned()
                                .unwrap_or_else(|| "Continuous".into())
                        }))
                    }
                    other => other.clone(),
                };
                (layer, lt)
            }
        }
    }

    /// The map of an entity's own OCS (normal ±Z only), or `None` outside the XY plane.
    fn ocs(scope: &Scope, extrusion: Point3) -> Option<Affine> {
        let [x, y, z] = extrusion;
        let flat = x.abs() < 1e-12 && y.abs() < 1e-12;
        match () {
            _ if flat && z > 0.0 => Some(scope.map),
            _ if flat && z < 0.0 => Some(scope.map.then_inner(&MIRROR_X)),
            _ => None,
        }
    }

    fn push(&mut self, e: Entity) -> bool {
        if self.left == 0 {
            return false;
        }
        self.left -= 1;
        self.resolved.entities.push(e);
        true
    }

    fn extra(&mut self, x: &Extra, scope: &Scope) {
        if self.left == 0 || self.stop {
            return;
        }
        let (layer, lt) = self.inherited(scope, &x.layer, &x.linetype);
        let pos = x.position();
        let Some(map) = Self::ocs(scope, x.extrusion) else {
            self.refuse(scope, &layer, x.code_name(), pos, Reason::NotPlanar);
            return;
        };
        match &x.kind {
            ExtraKind::Ellipse(_) | ExtraKind::Spline(_) => {
                self.refuse(scope, &layer, x.code_name(), pos, Reason::Curve)
            }
            ExtraKind::Polyline(p) if p.three_d => {
                self.refuse(scope, &layer, x.code_name(), pos, Reason::NotPlanar)
            }
            ExtraKind::Polyline(p) => {
                let template = Entity {
                    line: scope.line,
                    handle: scope.handle.to_string(),
                    layer,
                    linetype: lt,
                    linetype_scale: x.linetype_scale,
                    extrusion: [0.0, 0.0, 1.0],
                    kind: EntityKind::Line {
                        start: [0.0; 3],
                        end: [0.0; 3],
                    },
                };
                self.polyline(p, &template, map, scope, x.code_name());
            }
            ExtraKind::Insert(i) => self.insert(x, i, layer, lt, map, scope),
        }
    }

    fn polyline(
        &mut self,
        p: &Polyline,
        template: &Entity,
        map: Affine,
        scope: &Scope,
        code: &'static str,
    ) {
        let n = p.vertices.len();
        let finite = p.elevation.is_finite()
            && p.vertices
                .iter()
                .all(|v| v.x.is_finite() && v.y.is_finite() && v.bulge.is_finite());
        if !finite {
            let first = p.vertices.first().map_or([0.0; 3], |v| [v.x, v.y, 0.0]);
            self.refuse(scope, &template.layer, code, first, Reason::NotFinite);
            return;
        }
        let segments = if p.closed { n } else { n.saturating_sub(1) };
        let z = p.elevation;
        for k in 0..segments {
            let (v0, v1) = (p.vertices[k], p.vertices[(k + 1) % n]);
            let (p0, p1) = ([v0.x, v0.y, z], [v1.x, v1.y, z]);
            if p0 == p1 {
                continue;
            }
            let kind = match bulge_arc(p0, p1, v0.bulge) {
                None => EntityKind::Line { start: p0, end: p1 },
                // a bulge like 1e300 overflows: refused, never milled as some other arc
                Some((c, r, _, _)) if !(r.is_finite() && c.iter().all(|v| v.is_finite())) => {
                    self.refuse(scope, &template.layer, code, p0, Reason::NotFinite);
                    continue;
                }
                Some((center, radius, start_angle, end_angle)) => EntityKind::Arc {
                    center,
                    radius,
                    start_angle,
                    end_angle,
                },
            };
            let local = Entity {
                kind,
                ..template.clone()
            };
            if !self.place(local, map, scope, code) {
                return;
            }
        }
    }

    fn insert(
        &mut self,
        x: &Extra,
        i: &Insert,
        layer: String,
        lt: Option<String>,
        map: Affine,
        scope: &Scope,
    ) {
        let code = x.code_name();
        let Some(block) = self.d.blocks.get(&i.name) else {
            self.refuse(
                scope,
                &layer,
                code,
                i.insert,
                Reason::UnknownBlock(i.name.clone()),
            );
            return;
        };
        if scope.depth >= MAX_DEPTH {
            self.refuse(scope, &layer, code, i.insert, Reason::TooDeep);
            return;
        }
        if i.columns < 1 || i.rows < 1 {
            self.refuse(scope, &layer, code, i.insert, Reason::BadArray);
            return;
        }
        let numbers = [i.rotation, i.column_spacing, i.row_spacing]
            .into_iter()
            .chain(i.insert)
            .chain(i.scale)
            .chain(block.base);
        if numbers.into_iter().any(|v| !v.is_finite()) {
            self.refuse(scope, &layer, code, i.insert, Reason::NotFinite);
            return;
        }
        for row in 0..i.rows {
            for column in 0..i.columns {
                if self.stop {
                    return;
                }
                if self.left == 0 {
                    self.refuse(scope, &layer, code, i.insert, Reason::TooMany);
                    return;
                }
                self.left -= 1;
                let inner = Scope {
                    line: scope.line,
                    handle: scope.handle,
                    inherit: Some((layer.clone(), lt.clone())),
                    map: map.then_inner(&insert_map(i, block.base, column, row)),
                    depth: scope.depth + 1,
                };
                self.block(block, &inner);
            }
        }
    }

    fn block(&mut self, block: &Block, scope: &Scope) {
        for e in &block.entities {
            if self.stop {
                return;
            }
            let (layer, linetype) = self.inherited(scope, &e.layer, &e.linetype);
            let Some(map) = Self::ocs(scope, e.extrusion) else {
                self.refuse(
                    scope,
                    &layer,
                    e.kind.code_name(),
                    [0.0; 3],
                    Reason::NotPlanar,
                );
                continue;
            };
            let local = Entity {
                line: scope.line,
                handle: scope.handle.to_string(),
                layer,
                linetype,
                extrusion: [0.0, 0.0, 1.0],
                ..e.clone()
            };
            if !self.place(local, map, scope, e.kind.code_name()) {
                return;
            }
        }
        for x in &block.extra {
            self.extra(x, scope);
        }
    }

    /// Maps one entity given in local coordinates; false when the output budget is spent.
    fn place(&mut self, mut e: Entity, map: Affine, scope: &Scope, code: &'static str) -> bool {
        if !map.finite() {
            self.refuse(scope, &e.layer, code, [0.0; 3], Reason::NotFinite);
            return true;
        }
        let mirrored = map.det() < 0.0;
        e.kind = match e.kind {
            EntityKind::Line { start, end } => EntityKind::Line {
                start: map.apply(start),
                end: map.apply(end),
            },
            EntityKind::Circle { center, radius } => match map.uniform_scale() {
                Some(s) => EntityKind::Circle {
                    center: map.apply(center),
                    radius: radius * s,
                },
                None => {
                    self.refuse(scope, &e.layer, code, center, Reason::Distorted);
                    return true;
                }
            },
            EntityKind::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => {
                let Some(s) = map.uniform_scale() else {
                    self.refuse(scope, &e.layer, code, center, Reason::Distorted);
                    return true;
                };
                let c = map.apply(center);
                let angle = |a: f64| {
                    let (sin, cos) = a.to_radians().sin_cos();
                    let v = map.apply_vec([cos, sin, 0.0]);
                    whole_degree(v[1].atan2(v[0]).to_degrees())
                };
                let (a0, a1) = (angle(start_angle), angle(end_angle));
                // a mirror turns the counter-clockwise arc around: it now runs from a1 to a0
                let (start_angle, end_angle) = if mirrored { (a1, a0) } else { (a0, a1) };
                EntityKind::Arc {
                    center: c,
                    radius: radius * s,
                    start_angle,
                    end_angle,
                }
            }
            EntityKind::Text(mut t) => {
                let s = map
                    .uniform_scale()
                    .unwrap_or_else(|| map.det().abs().sqrt());
                t.first = map.apply(t.first);
                t.second = t.second.map(|p| map.apply(p));
                t.height *= s;
                t.rotation += map.rotation_deg();
                EntityKind::Text(t)
            }
            EntityKind::MText(mut m) => {
                let s = map
                    .uniform_scale()
                    .unwrap_or_else(|| map.det().abs().sqrt());
                m.insert = map.apply(m.insert);
                m.height *= s;
                m.rotation = m.rotation.map(|r| r + map.rotation_deg());
                m.direction = m.direction.map(|v| map.apply_vec(v));
                EntityKind::MText(m)
            }
        };
        let layer = e.layer.clone();
        if !self.push(e) {
            self.refuse(scope, &layer, code, [0.0; 3], Reason::TooMany);
            return false;
        }
        true
    }
}

/// CAD programs store arcs by whole-degree angles more often than not: an angle rebuilt
/// within 1e-9° of a whole degree is taken as that degree, so the arc ends where the
/// original did (the rebuilt angle is off in its last bits only).
fn whole_degree(a: f64) -> f64 {
    if (a - a.round()).abs() < 1e-9 {
        a.round()
    } else {
        a
    }
}

/// The arc of a polyline segment from `p0` to `p1` with a bulge: `(centre, radius, start
/// angle, end angle)` counter-clockwise in degrees, or `None` for a straight segment.
fn bulge_arc(p0: Point3, p1: Point3, bulge: f64) -> Option<(Point3, f64, f64, f64)> {
    if bulge.abs() < 1e-12 {
        return None;
    }
    let (dx, dy) = (p1[0] - p0[0], p1[1] - p0[1]);
    // with θ = 4·atan(bulge) the centre lies (chord/2)·cot(θ/2) left of the chord's middle
    // (right for a clockwise arc), and cot(θ/2) = (1 − bulge²)/(2·bulge): no trigonometry,
    // so an arc whose points were written from whole numbers gets its centre back exactly
    let k = (1.0 - bulge * bulge) / (4.0 * bulge);
    let center = [
        (p0[0] + p1[0]) / 2.0 - dy * k,
        (p0[1] + p1[1]) / 2.0 + dx * k,
        p0[2],
    ];
    let radius = (p0[0] - center[0]).hypot(p0[1] - center[1]);
    let angle = |p: Point3| whole_degree((p[1] - center[1]).atan2(p[0] - center[0]).to_degrees());
    let (a0, a1) = (angle(p0), angle(p1));
    Some(if bulge > 0.0 {
        (center, radius, a0, a1)
    } else {
        (center, radius, a1, a0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn bulges_give_the_arcs_they_describe() {
        // a half circle counter-clockwise from (1,0) to (-1,0) around the origin
        let (c, r, a0, a1) = bulge_arc([1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], 1.0).unwrap();
        assert!(close(c[0], 0.0) && close(c[1], 0.0) && close(r, 1.0));
        assert!(close(a0, 0.0) && close(a1, 180.0));
        // clockwise quarter from (0,1) to (1,0): the same arc as counter-clockwise 0°..90°
        let b = (std::f64::consts::FRAC_PI_2 / 4.0).tan();
        let (c, r, a0, a1) = bulge_arc([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], -b).unwrap();
        assert!(close(c[0], 0.0) && close(c[1], 0.0) && close(r, 1.0));
        assert!(close(a0, 0.0) && close(a1, 90.0), "{a0} {a1}");
        assert!(bulge_arc([0.0; 3], [1.0, 0.0, 0.0], 0.0).is_none());
    }

    fn drawing(entities: &str) -> Drawing {
        let src = format!(
            "  0\nSECTION\n  2\nBLOCKS\n  0\nBLOCK\n  2\nB\n 10\n0\n 20\n0\n  0\nLINE\n  8\n0\n 10\n0\n 20\n0\n 11\n1\n 21\n0\n  0\nENDBLK\n  0\nENDSEC\n  0\nSECTION\n  2\nENTITIES\n{entities}  0\nENDSEC\n  0\nEOF\n"
        );
        crate::read_dxf(src.as_bytes()).unwrap()
    }

    #[test]
    fn huge_arrays_stop_at_the_output_bound() {
        let d = drawing("  0\nINSERT\n  8\nP\n  2\nB\n 70\n100000\n 71\n100000\n 44\n2\n 45\n2\n");
        let r = resolve(&d);
        assert!(r.entities.len() <= MAX_OUTPUT);
        assert_eq!(r.refused.len(), 1);
        assert_eq!(r.refused[0].reason, Reason::TooMany);
        // a 2 × 3 array: six lines, the last one at column 1, row 2
        let r = resolve(&drawing(
            "  0\nINSERT\n  8\nP\n  2\nB\n 70\n2\n 71\n3\n 44\n10\n 45\n5\n",
        ));
        assert_eq!(r.entities.len(), 6);
        assert!(
            matches!(r.entities[5].kind, EntityKind::Line { start, .. } if start == [10.0, 10.0, 0.0])
        );
        assert_eq!(r.entities[5].layer, "P");
        // negative counts, unknown blocks, NaN scales: refused, nothing produced
        for bad in [" 70\n-3\n", " 41\nnan\n"] {
            let r = resolve(&drawing(&format!("  0\nINSERT\n  8\nP\n  2\nB\n{bad}")));
            assert!(
                r.entities.is_empty() && r.refused.len() == 1,
                "{bad}: {r:?}"
            );
        }
        let r = resolve(&drawing("  0\nINSERT\n  8\nP\n  2\nNONE\n"));
        assert_eq!(r.refused[0].reason, Reason::UnknownBlock("NONE".into()));
    }

    #[test]
    fn malformed_polylines_do_not_cost_the_reference_mode_the_file() {
        let d = drawing("  0\nLWPOLYLINE\n  8\nP\n 10\nabc\n  0\nLINE\n  8\nP\n");
        assert_eq!(d.entities.len(), 1);
        assert!(d.extra.is_empty());
        assert_eq!(d.extra_errors.len(), 1);
        assert!(d.extra_errors[0].to_string().contains("'abc'"));
        // and bulges that overflow are refused, not milled as some other arc
        let d = drawing("  0\nLWPOLYLINE\n  8\nP\n 10\n0\n 20\n0\n 42\n1e300\n 10\n1\n 20\n0\n");
        let r = resolve(&d);
        assert!(r.entities.is_empty());
        assert_eq!(r.refused[0].reason, Reason::NotFinite);
    }

    #[test]
    fn mirrored_arcs_keep_their_points() {
        let i = Insert {
            name: "B".into(),
            insert: [10.0, 0.0, 0.0],
            scale: [-2.0, 2.0, 1.0],
            rotation: 90.0,
            columns: 1,
            rows: 1,
            column_spacing: 0.0,
            row_spacing: 0.0,
        };
        let m = insert_map(&i, [0.0; 3], 0, 0);
        assert!(m.det() < 0.0);
        assert!(close(m.uniform_scale().unwrap(), 2.0));
        // (1,0) scaled to (-2,0), turned 90° to (0,-2), moved to (10,-2)
        let p = m.apply([1.0, 0.0, 0.0]);
        assert!(close(p[0], 10.0) && close(p[1], -2.0), "{p:?}");
        let stretched = Insert {
            scale: [1.0, 2.0, 1.0],
            ..i.clone()
        };
        assert!(insert_map(&stretched, [0.0; 3], 0, 0)
            .uniform_scale()
            .is_none());
        // squares that overflow or underflow: uniform all the same, stretched all the same
        for k in [1e300, -1e300, 1e-300] {
            let huge = Insert {
                scale: [k, k, 1.0],
                ..i.clone()
            };
            let s = insert_map(&huge, [0.0; 3], 0, 0).uniform_scale();
            assert!(s.is_some_and(|s| close(s / k.abs(), 1.0)), "{k}: {s:?}");
            let stretched = Insert {
                scale: [k, 2.0 * k, 1.0],
                ..i.clone()
            };
            assert!(insert_map(&stretched, [0.0; 3], 0, 0)
                .uniform_scale()
                .is_none());
        }
    }
}
