//! `$INSUNITS`: the drawing's unit. The reference ignores it (every number is taken as
//! millimetres); the extended mode scales other units to millimetres.

use crate::{Entity, EntityKind};

/// Millimetres per drawing unit for the `$INSUNITS` codes that name a length other than the
/// millimetre; `None` for unitless (0), millimetres (4) and unknown codes (kept as they are).
pub fn millimetres_per_unit(insunits: i32) -> Option<f64> {
    Some(match insunits {
        1 => 25.4,        // inch
        2 => 304.8,       // foot
        3 => 1_609_344.0, // mile
        5 => 10.0,        // centimetre
        6 => 1000.0,      // metre
        7 => 1_000_000.0, // kilometre
        8 => 25.4e-6,     // microinch
        9 => 0.0254,      // mil
        10 => 914.4,      // yard
        11 => 1e-7,       // ångström
        12 => 1e-6,       // nanometre
        13 => 1e-3,       // micrometre
        14 => 100.0,      // decimetre
        _ => return None,
    })
}

/// Multiplies every length of the entities (points, radii, text heights) by `factor`.
pub fn scale_entities(entities: &mut [Entity], factor: f64) {
    let s = |p: &mut [f64; 3]| p.iter_mut().for_each(|v| *v *= factor);
    for e in entities {
        match &mut e.kind {
            EntityKind::Line { start, end } => {
                s(start);
                s(end);
            }
            EntityKind::Circle { center, radius } | EntityKind::Arc { center, radius, .. } => {
                s(center);
                *radius *= factor;
            }
            EntityKind::Text(t) => {
                s(&mut t.first);
                if let Some(p) = &mut t.second {
                    s(p);
                }
                t.height *= factor;
            }
            EntityKind::MText(m) => {
                s(&mut m.insert);
                m.height *= factor;
            }
        }
    }
}
