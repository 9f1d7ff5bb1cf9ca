//! A small, deterministic DXF writer for the entities the reader understands.
//!
//! It writes what path drawings need (LTYPE and LAYER tables, LINE, ARC, CIRCLE, TEXT,
//! MTEXT) as an AutoCAD 2000 (AC1015) ASCII file in code page 1252. Used for our own test
//! drawings and examples; the full CAD-compatible writer builds on it.

use std::fmt::Write;

/// Builder of one drawing.
#[derive(Debug, Default, Clone)]
pub struct DxfWriter {
    layers: Vec<(String, String)>,
    linetypes: Vec<String>,
    entities: String,
    next_handle: u32,
}

/// Numbers in their shortest exact decimal form (no float noise).
pub fn num(v: f64) -> String {
    let s = format!("{v}");
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") {
        s
    } else {
        format!("{s}.0")
    }
}

impl DxfWriter {
    pub fn new() -> Self {
        DxfWriter {
            next_handle: 0x100,
            ..Default::default()
        }
    }

    /// Declares a layer with its line type (declared line types get LTYPE entries).
    pub fn layer(&mut self, name: &str, linetype: &str) -> &mut Self {
        self.use_linetype(linetype);
        if !self.layers.iter().any(|(n, _)| n == name) {
            self.layers.push((name.to_string(), linetype.to_string()));
        }
        self
    }

    fn use_linetype(&mut self, lt: &str) {
        if !lt.eq_ignore_ascii_case("bylayer") && !self.linetypes.iter().any(|l| l == lt) {
            self.linetypes.push(lt.to_string());
        }
    }

    fn head(&mut self, kind: &str, layer: &str, linetype: Option<&str>) {
        if !self.layers.iter().any(|(n, _)| n == layer) {
            self.layer(layer, "CONTINUOUS");
        }
        let h = self.next_handle;
        self.next_handle += 1;
        let _ = write!(
            self.entities,
            "  0\n{kind}\n  5\n{h:X}\n100\nAcDbEntity\n  8\n{layer}\n"
        );
        if let Some(lt) = linetype {
            self.use_linetype(lt);
            let _ = write!(self.entities, "  6\n{lt}\n");
        }
    }

    fn pair(&mut self, code: i32, value: impl std::fmt::Display) {
        let _ = write!(self.entities, "{code:>3}\n{value}\n");
    }

    pub fn line(
        &mut self,
        layer: &str,
        linetype: Option<&str>,
        a: (f64, f64),
        b: (f64, f64),
    ) -> &mut Self {
        self.head("LINE", layer, linetype);
        self.pair(100, "AcDbLine");
        for (c, v) in [
            (10, a.0),
            (20, a.1),
            (30, 0.0),
            (11, b.0),
            (21, b.1),
            (31, 0.0),
        ] {
            self.pair(c, num(v));
        }
        self
    }

    pub fn circle(
        &mut self,
        layer: &str,
        linetype: Option<&str>,
        c: (f64, f64),
        r: f64,
    ) -> &mut Self {
        self.head("CIRCLE", layer, linetype);
        self.pair(100, "AcDbCircle");
        for (code, v) in [(10, c.0), (20, c.1), (30, 0.0), (40, r)] {
            self.pair(code, num(v));
        }
        self
    }

    /// A counter-clockwise arc from `a0` to `a1` degrees.
    pub fn arc(
        &mut self,
        layer: &str,
        linetype: Option<&str>,
        c: (f64, f64),
        r: f64,
        a0: f64,
        a1: f64,
    ) -> &mut Self {
        self.head("ARC", layer, linetype);
        self.pair(100, "AcDbCircle");
        for (code, v) in [(10, c.0), (20, c.1), (30, 0.0), (40, r)] {
            self.pair(code, num(v));
        }
        self.pair(100, "AcDbArc");
        self.pair(50, num(a0));
        self.pair(51, num(a1));
        self
    }

    /// A centred single-line TEXT.
    pub fn text(&mut self, layer: &str, at: (f64, f64), height: f64, value: &str) -> &mut Self {
        self.head("TEXT", layer, None);
        self.pair(100, "AcDbText");
        for (code, v) in [(10, at.0), (20, at.1), (30, 0.0), (40, height)] {
            self.pair(code, num(v));
        }
        self.pair(1, value);
        self.pair(72, 1);
        for (code, v) in [(11, at.0), (21, at.1), (31, 0.0)] {
            self.pair(code, num(v));
        }
        self.pair(100, "AcDbText");
        self.pair(73, 2);
        self
    }

    /// A centred MTEXT; lines are joined with `\P`.
    pub fn mtext(&mut self, layer: &str, at: (f64, f64), height: f64, lines: &[&str]) -> &mut Self {
        self.head("MTEXT", layer, None);
        self.pair(100, "AcDbMText");
        for (code, v) in [(10, at.0), (20, at.1), (30, 0.0), (40, height)] {
            self.pair(code, num(v));
        }
        self.pair(71, 5);
        self.pair(72, 1);
        self.pair(1, lines.join("\\P"));
        self
    }

    /// The complete file text.
    pub fn finish(&self) -> String {
        let mut s = String::new();
        s.push_str("  0\nSECTION\n  2\nHEADER\n  9\n$ACADVER\n  1\nAC1015\n  9\n$DWGCODEPAGE\n  3\nANSI_1252\n  9\n$TEXTSIZE\n 40\n2.5\n  0\nENDSEC\n");
        s.push_str("  0\nSECTION\n  2\nTABLES\n  0\nTABLE\n  2\nLTYPE\n 70\n");
        let _ = writeln!(s, "{}", self.linetypes.len());
        for lt in &self.linetypes {
            let _ = write!(
                s,
                "  0\nLTYPE\n  2\n{lt}\n 70\n0\n  3\n{lt}\n 72\n65\n 73\n0\n 40\n0.0\n"
            );
        }
        s.push_str("  0\nENDTAB\n  0\nTABLE\n  2\nLAYER\n 70\n");
        let _ = writeln!(s, "{}", self.layers.len());
        for (name, lt) in &self.layers {
            let _ = write!(s, "  0\nLAYER\n  2\n{name}\n 70\n0\n 62\n7\n  6\n{lt}\n");
        }
        s.push_str("  0\nENDTAB\n  0\nENDSEC\n  0\nSECTION\n  2\nENTITIES\n");
        s.push_str(&self.entities);
        s.push_str("  0\nENDSEC\n  0\nEOF\n");
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{read_dxf, EntityKind};

    #[test]
    fn written_files_read_back() {
        let mut w = DxfWriter::new();
        w.layer("1234_1P", "CONTINUOUS")
            .circle("1234_1P", Some("PHANTOM"), (0.0, 0.0), 0.5)
            .line("1234_1P", None, (0.0, 0.0), (10.5, 0.0))
            .arc("1234_1P", Some("DASHED"), (0.0, 0.0), 2.0, 0.0, 90.0)
            .text("1234_1P", (1.0, 1.0), 1.0, "B1")
            .mtext("1234_1P", (0.0, 1.0), 1.0, &["T2", "O2"]);
        let text = w.finish();
        let d = read_dxf(text.as_bytes()).unwrap();
        assert_eq!(d.entities.len(), 5);
        assert_eq!(
            d.layers.get("1234_1P").map(String::as_str),
            Some("CONTINUOUS")
        );
        assert!(
            d.linetypes.contains(&"PHANTOM".to_string())
                && d.linetypes.contains(&"DASHED".to_string())
        );
        assert_eq!(
            d.entities[1].kind,
            EntityKind::Line {
                start: [0.0, 0.0, 0.0],
                end: [10.5, 0.0, 0.0]
            }
        );
        assert_eq!(d.entities[0].linetype.as_deref(), Some("PHANTOM"));
        match &d.entities[4].kind {
            EntityKind::MText(m) => assert_eq!(m.value, "T2\\PO2"),
            k => panic!("{k:?}"),
        }
        // deterministic
        assert_eq!(text, w.finish());
        assert_eq!(num(0.1), "0.1");
        assert_eq!(num(3.0), "3.0");
    }
}
