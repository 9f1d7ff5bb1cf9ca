//! The geometry entities the reference ignores: LWPOLYLINE, POLYLINE with its VERTEX/SEQEND
//! records, INSERT (block references, MINSERT arrays), and ELLIPSE/SPLINE (only detected).
//! They are read in every mode: the default mode warns about them, the extended mode
//! explodes them (`explode.rs`).

use crate::entity::Ctx;
use crate::tokens::{int, num, raw_str, Pair};
use crate::{DxfError, Entity, Point3};

/// One ignored geometry entity with its common properties.
#[derive(Debug, Clone, PartialEq)]
pub struct Extra {
    /// 1-based line of the `0` group that starts the entity.
    pub line: usize,
    pub handle: String,
    pub layer: String,
    /// Own line type (group 6), `None` = ByLayer.
    pub linetype: Option<String>,
    pub linetype_scale: f64,
    pub extrusion: Point3,
    pub kind: ExtraKind,
}

#[derive(Debug, Clone, PartialEq)]
pub enum ExtraKind {
    Polyline(Polyline),
    Insert(Insert),
    /// Centre (10/20/30): refused in the extended mode, never approximated.
    Ellipse(Point3),
    /// First control point (10/20/30): refused like ELLIPSE.
    Spline(Point3),
}

impl Extra {
    /// The DXF entity type name.
    pub fn code_name(&self) -> &'static str {
        match &self.kind {
            ExtraKind::Polyline(p) if p.lw => "LWPOLYLINE",
            ExtraKind::Polyline(_) => "POLYLINE",
            ExtraKind::Insert(_) => "INSERT",
            ExtraKind::Ellipse(_) => "ELLIPSE",
            ExtraKind::Spline(_) => "SPLINE",
        }
    }

    /// A point of the entity for messages: first vertex, insertion point or centre.
    pub fn position(&self) -> Point3 {
        match &self.kind {
            ExtraKind::Polyline(p) => p
                .vertices
                .first()
                .map_or([0.0, 0.0, p.elevation], |v| [v.x, v.y, p.elevation]),
            ExtraKind::Insert(i) => i.insert,
            ExtraKind::Ellipse(p) | ExtraKind::Spline(p) => *p,
        }
    }
}

/// A light-weight (LWPOLYLINE) or old-style 2-D/3-D POLYLINE.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Polyline {
    /// LWPOLYLINE (else POLYLINE).
    pub lw: bool,
    /// Flag 1 of group 70: the last vertex connects to the first.
    pub closed: bool,
    /// Flags 8/16/64 of a POLYLINE: 3-D polyline, mesh or polyface (not a plane outline).
    pub three_d: bool,
    /// Group 38 (LWPOLYLINE) or the Z of group 10 (POLYLINE): the plane's height in its OCS.
    pub elevation: f64,
    pub vertices: Vec<Vertex>,
}

/// A polyline vertex in the entity's OCS; widths are not kept (they do not change the path).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Vertex {
    pub x: f64,
    pub y: f64,
    /// Group 42: tan(¼ of the included angle) of the arc to the next vertex; 0 = straight,
    /// > 0 counter-clockwise.
    pub bulge: f64,
}

/// A block reference (INSERT; with rows or columns a MINSERT array).
#[derive(Debug, Clone, PartialEq)]
pub struct Insert {
    pub name: String,
    pub insert: Point3,
    /// Groups 41/42/43, 1 when absent.
    pub scale: Point3,
    /// Group 50, degrees.
    pub rotation: f64,
    /// Groups 70/71, 1 when absent.
    pub columns: i32,
    pub rows: i32,
    /// Groups 44/45.
    pub column_spacing: f64,
    pub row_spacing: f64,
}

/// A block definition of the BLOCKS section.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Block {
    /// Group 10/20/30 of the BLOCK record: the point that lands on the insertion point.
    pub base: Point3,
    /// LINE/ARC/CIRCLE/TEXT/MTEXT of the block, in file order.
    pub entities: Vec<Entity>,
    /// Polylines, nested inserts, ellipses and splines of the block.
    pub extra: Vec<Extra>,
}

/// Groups of the records that belong to the entity being read (a POLYLINE's VERTEX records,
/// an INSERT's ATTRIB records, both ended by SEQEND).
#[derive(Default)]
pub(crate) struct ExtraReader {
    pending: Option<Extra>,
}

impl ExtraReader {
    /// Takes the record when it belongs to an entity of this module (true), else leaves it to
    /// the caller (false). A record of another kind ends a pending POLYLINE first. A
    /// malformed entity is dropped with its error in `errors`.
    pub(crate) fn take(
        &mut self,
        ctx: &Ctx,
        kind: &str,
        rec: &[Pair],
        out: &mut Vec<Extra>,
        errors: &mut Vec<DxfError>,
    ) -> bool {
        self.try_take(ctx, kind, rec, out).unwrap_or_else(|e| {
            errors.push(e);
            true
        })
    }

    fn try_take(
        &mut self,
        ctx: &Ctx,
        kind: &str,
        rec: &[Pair],
        out: &mut Vec<Extra>,
    ) -> Result<bool, DxfError> {
        match kind {
            "VERTEX" => {
                if let Some(Extra {
                    kind: ExtraKind::Polyline(p),
                    ..
                }) = &mut self.pending
                {
                    if let Some(v) = vertex(rec)? {
                        p.vertices.push(v);
                    }
                }
                return Ok(true);
            }
            "ATTRIB" => return Ok(true),
            "SEQEND" => {
                self.finish(out);
                return Ok(true);
            }
            _ => self.finish(out),
        }
        let made = match kind {
            "LWPOLYLINE" => lwpolyline(ctx, rec)?,
            "POLYLINE" => {
                self.pending = polyline(ctx, rec)?;
                return Ok(true);
            }
            "INSERT" => insert(ctx, rec)?,
            "ELLIPSE" => curve(ctx, rec, ExtraKind::Ellipse)?,
            "SPLINE" => curve(ctx, rec, ExtraKind::Spline)?,
            _ => return Ok(false),
        };
        out.extend(made);
        Ok(true)
    }

    /// Ends a POLYLINE that has no SEQEND (end of the section).
    pub(crate) fn finish(&mut self, out: &mut Vec<Extra>) {
        out.extend(self.pending.take());
    }
}

/// The common groups of an entity; `None` for paper space.
fn common(ctx: &Ctx, rec: &[Pair], kind: ExtraKind) -> Result<Option<Extra>, DxfError> {
    let mut e = Extra {
        line: rec[0].line,
        handle: String::new(),
        layer: "0".into(),
        linetype: None,
        linetype_scale: 1.0,
        extrusion: [0.0, 0.0, 1.0],
        kind,
    };
    for p in &rec[1..] {
        match p.code {
            5 => e.handle = raw_str(p.value).into_owned(),
            8 => e.layer = ctx.text(p),
            6 => e.linetype = Some(ctx.text(p)),
            48 => e.linetype_scale = num(p)?,
            67 if int(p)? == 1 => return Ok(None),
            210 => e.extrusion[0] = num(p)?,
            220 => e.extrusion[1] = num(p)?,
            230 => e.extrusion[2] = num(p)?,
            _ => {}
        }
    }
    Ok(Some(e))
}

/// ELLIPSE or SPLINE: only where it is (the first 10/20/30).
fn curve(
    ctx: &Ctx,
    rec: &[Pair],
    make: fn(Point3) -> ExtraKind,
) -> Result<Option<Extra>, DxfError> {
    let mut at = [0.0; 3];
    for (axis, code) in [10, 20, 30].into_iter().enumerate() {
        if let Some(p) = rec.iter().find(|p| p.code == code) {
            at[axis] = num(p)?;
        }
    }
    common(ctx, rec, make(at))
}

fn lwpolyline(ctx: &Ctx, rec: &[Pair]) -> Result<Option<Extra>, DxfError> {
    let Some(mut e) = common(ctx, rec, ExtraKind::Polyline(Polyline::default()))? else {
        return Ok(None);
    };
    let mut pl = Polyline {
        lw: true,
        ..Polyline::default()
    };
    for p in &rec[1..] {
        match p.code {
            70 => pl.closed = int(p)? & 1 != 0,
            38 => pl.elevation = num(p)?,
            // every 10 starts a vertex; 20 and 42 belong to the last one
            10 => pl.vertices.push(Vertex {
                x: num(p)?,
                ..Vertex::default()
            }),
            20 => {
                if let Some(v) = pl.vertices.last_mut() {
                    v.y = num(p)?;
                }
            }
            42 => {
                if let Some(v) = pl.vertices.last_mut() {
                    v.bulge = num(p)?;
                }
            }
            _ => {}
        }
    }
    e.kind = ExtraKind::Polyline(pl);
    Ok(Some(e))
}

fn polyline(ctx: &Ctx, rec: &[Pair]) -> Result<Option<Extra>, DxfError> {
    let Some(mut e) = common(ctx, rec, ExtraKind::Polyline(Polyline::default()))? else {
        return Ok(None);
    };
    let mut pl = Polyline::default();
    for p in &rec[1..] {
        match p.code {
            70 => {
                let f = int(p)?;
                pl.closed = f & 1 != 0;
                pl.three_d = f & (8 | 16 | 64) != 0;
            }
            30 => pl.elevation = num(p)?,
            _ => {}
        }
    }
    e.kind = ExtraKind::Polyline(pl);
    Ok(Some(e))
}

/// A VERTEX record; `None` for spline frame control points (flag 16), which are not on the
/// curve.
fn vertex(rec: &[Pair]) -> Result<Option<Vertex>, DxfError> {
    let mut v = Vertex::default();
    for p in &rec[1..] {
        match p.code {
            10 => v.x = num(p)?,
            20 => v.y = num(p)?,
            42 => v.bulge = num(p)?,
            70 if int(p)? & 16 != 0 => return Ok(None),
            _ => {}
        }
    }
    Ok(Some(v))
}

fn insert(ctx: &Ctx, rec: &[Pair]) -> Result<Option<Extra>, DxfError> {
    let Some(mut e) = common(ctx, rec, ExtraKind::Ellipse([0.0; 3]))? else {
        return Ok(None);
    };
    let mut i = Insert {
        name: String::new(),
        insert: [0.0; 3],
        scale: [1.0; 3],
        rotation: 0.0,
        columns: 1,
        rows: 1,
        column_spacing: 0.0,
        row_spacing: 0.0,
    };
    for p in &rec[1..] {
        match p.code {
            2 => i.name = ctx.text(p),
            10 => i.insert[0] = num(p)?,
            20 => i.insert[1] = num(p)?,
            30 => i.insert[2] = num(p)?,
            41 => i.scale[0] = num(p)?,
            42 => i.scale[1] = num(p)?,
            43 => i.scale[2] = num(p)?,
            50 => i.rotation = num(p)?,
            70 => i.columns = int(p)?,
            71 => i.rows = int(p)?,
            44 => i.column_spacing = num(p)?,
            45 => i.row_spacing = num(p)?,
            _ => {}
        }
    }
    e.kind = ExtraKind::Insert(i);
    Ok(Some(e))
}
