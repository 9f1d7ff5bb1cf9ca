//! A small, deterministic DXF writer for the entities the reader understands.
//!
//! It writes what path drawings need (LTYPE and LAYER tables, LINE, ARC, CIRCLE, TEXT,
//! MTEXT) as an AutoCAD 2000 (AC1015) ASCII file in code page 1252. Used for our own test
//! drawings and examples; the full CAD-compatible writer builds on it.
//!
//! Deterministic AutoCAD 2000 writer: tables, blocks, objects, line-type patterns; ezdxf audits it
//! clean.

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
        self.pair(1, escape_non_ascii(value));
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
        let mut value = escape_non_ascii(&lines.join("\\P"));
        if ends_with_escape(&value) {
            // readers decode an escape only when a character follows it (as the reference
            // does): an empty MTEXT group is that character and adds no text
            value.push_str("{}");
        }
        self.pair(1, value);
        self
    }

    /// The complete file text: an AutoCAD 2000 file with the tables, blocks and objects CAD
    /// programs expect (ezdxf audits it without errors or fixes).
    pub fn finish(&self) -> String {
        let mut o = Out::default();
        let mut next = self.next_handle.max(0x100) + 0x1000;
        let mut handle = || {
            next += 1;
            next
        };
        o.section("HEADER");
        o.var("$ACADVER", 1, "AC1015");
        o.var("$DWGCODEPAGE", 3, "ANSI_1252");
        o.var("$INSUNITS", 70, "4");
        o.var("$MEASUREMENT", 70, "1");
        o.var("$TEXTSIZE", 40, "2.5");
        // handles above every handle used in the file
        o.var(
            "$HANDSEED",
            5,
            &format!("{:X}", self.next_handle.max(0x100) + 0x2000),
        );
        o.endsec();
        o.section("CLASSES");
        o.endsec();
        o.section("TABLES");
        // VPORT
        o.table("VPORT", 0x8, 1);
        o.record("VPORT", 0x23, 0x8, "AcDbViewportTableRecord");
        o.pairs(&[
            (2, "*Active"),
            (70, "0"),
            (10, "0.0"),
            (20, "0.0"),
            (11, "1.0"),
            (21, "1.0"),
            (12, "100.0"),
            (22, "100.0"),
            (40, "300.0"),
            (41, "1.5"),
        ]);
        o.endtab();
        // LTYPE
        // the table spelling is what readers compare (CONTINUOUS ≠ Continuous for the
        // reference), so the drawing's own spelling replaces the standard one
        let mut lts: Vec<&str> = vec!["ByBlock", "ByLayer"];
        for lt in &self.linetypes {
            if !lts.iter().any(|l| l.eq_ignore_ascii_case(lt)) {
                lts.push(lt);
            }
        }
        let continuous = lts
            .iter()
            .find(|l| l.eq_ignore_ascii_case("continuous"))
            .copied()
            .unwrap_or("Continuous");
        if continuous == "Continuous" {
            lts.push("Continuous");
        }
        o.table("LTYPE", 0x5, lts.len());
        for lt in lts {
            let h = handle();
            o.record("LTYPE", h, 0x5, "AcDbLinetypeTableRecord");
            let (desc, pattern) = linetype_pattern(lt);
            o.pairs(&[(2, lt), (70, "0"), (3, desc), (72, "65")]);
            o.pair(73, pattern.len());
            o.pair(40, num(pattern.iter().map(|x: &f64| x.abs()).sum::<f64>()));
            for d in pattern {
                o.pair(49, num(d));
                o.pair(74, 0);
            }
        }
        o.endtab();
        // LAYER
        let mut layers: Vec<(&str, &str)> = vec![("0", continuous)];
        for (n, lt) in &self.layers {
            if n != "0" {
                layers.push((n, lt));
            }
        }
        o.table("LAYER", 0x2, layers.len());
        for (n, lt) in layers {
            let h = handle();
            o.record("LAYER", h, 0x2, "AcDbLayerTableRecord");
            o.pairs(&[(2, n), (70, "0"), (62, "7"), (6, lt), (370, "-3")]);
        }
        o.endtab();
        o.table("STYLE", 0x3, 1);
        o.record("STYLE", 0x29, 0x3, "AcDbTextStyleTableRecord");
        o.pairs(&[
            (2, "Standard"),
            (70, "0"),
            (40, "0.0"),
            (41, "1.0"),
            (50, "0.0"),
            (71, "0"),
            (42, "2.5"),
            (3, "txt"),
            (4, ""),
        ]);
        o.endtab();
        o.table("VIEW", 0x6, 0);
        o.endtab();
        o.table("UCS", 0x7, 0);
        o.endtab();
        o.table("APPID", 0x9, 1);
        o.record("APPID", 0x2A, 0x9, "AcDbRegAppTableRecord");
        o.pairs(&[(2, "ACAD"), (70, "0")]);
        o.endtab();
        o.table("DIMSTYLE", 0xA, 1);
        o.pair(100, "AcDbDimStyleTable");
        o.pairs(&[
            (0, "DIMSTYLE"),
            (105, "2B"),
            (330, "A"),
            (100, "AcDbSymbolTableRecord"),
            (100, "AcDbDimStyleTableRecord"),
            (2, "Standard"),
            (70, "0"),
        ]);
        o.endtab();
        o.table("BLOCK_RECORD", 0xB, 2);
        o.record(
            "BLOCK_RECORD",
            MODEL_SPACE_RECORD,
            0xB,
            "AcDbBlockTableRecord",
        );
        o.pairs(&[(2, "*Model_Space"), (340, "22")]);
        o.record("BLOCK_RECORD", 0x1B, 0xB, "AcDbBlockTableRecord");
        o.pairs(&[(2, "*Paper_Space"), (340, "1E")]);
        o.endtab();
        o.endsec();
        o.section("BLOCKS");
        for (name, rec, begin, end) in [
            ("*Model_Space", MODEL_SPACE_RECORD, 0x18, 0x19),
            ("*Paper_Space", 0x1B, 0x1C, 0x1D),
        ] {
            o.pair(0, "BLOCK");
            o.pair(5, format!("{begin:X}"));
            o.pair(330, format!("{rec:X}"));
            o.pairs(&[
                (100, "AcDbEntity"),
                (8, "0"),
                (100, "AcDbBlockBegin"),
                (2, name),
                (70, "0"),
                (10, "0.0"),
                (20, "0.0"),
                (30, "0.0"),
                (3, name),
                (1, ""),
            ]);
            o.pair(0, "ENDBLK");
            o.pair(5, format!("{end:X}"));
            o.pair(330, format!("{rec:X}"));
            o.pairs(&[(100, "AcDbEntity"), (8, "0"), (100, "AcDbBlockEnd")]);
        }
        o.endsec();
        o.section("ENTITIES");
        o.text.push_str(&self.entities);
        o.endsec();
        o.section("OBJECTS");
        o.pairs(&[
            (0, "DICTIONARY"),
            (5, "C"),
            (330, "0"),
            (100, "AcDbDictionary"),
            (281, "1"),
            (3, "ACAD_GROUP"),
            (350, "D"),
            (3, "ACAD_LAYOUT"),
            (350, "1A"),
        ]);
        o.pairs(&[
            (0, "DICTIONARY"),
            (5, "D"),
            (330, "C"),
            (100, "AcDbDictionary"),
            (281, "1"),
        ]);
        o.pairs(&[
            (0, "DICTIONARY"),
            (5, "1A"),
            (330, "C"),
            (100, "AcDbDictionary"),
            (281, "1"),
            (3, "Layout1"),
            (350, "1E"),
            (3, "Model"),
            (350, "22"),
        ]);
        for (h, name, rec, tab) in [
            ("22", "Model", MODEL_SPACE_RECORD, 0),
            ("1E", "Layout1", 0x1B, 1),
        ] {
            o.pairs(&[
                (0, "LAYOUT"),
                (5, h),
                (330, "1A"),
                (100, "AcDbPlotSettings"),
                (1, ""),
                (4, "A4"),
                (6, ""),
                (40, "0.0"),
                (41, "0.0"),
                (42, "0.0"),
                (43, "0.0"),
                (44, "297.0"),
                (45, "210.0"),
                (46, "0.0"),
                (47, "0.0"),
                (48, "0.0"),
                (49, "0.0"),
                (140, "0.0"),
                (141, "0.0"),
                (142, "1.0"),
                (143, "1.0"),
                (70, "688"),
                (72, "1"),
                (73, "0"),
                (74, "5"),
                (7, ""),
                (75, "16"),
                (147, "1.0"),
                (148, "0.0"),
                (149, "0.0"),
                (100, "AcDbLayout"),
                (1, name),
                (70, "1"),
            ]);
            o.pair(71, tab);
            o.pairs(&[
                (10, "0.0"),
                (20, "0.0"),
                (11, "297.0"),
                (21, "210.0"),
                (12, "0.0"),
                (22, "0.0"),
                (32, "0.0"),
                (14, "0.0"),
                (24, "0.0"),
                (34, "0.0"),
                (15, "0.0"),
                (25, "0.0"),
                (35, "0.0"),
                (146, "0.0"),
                (13, "0.0"),
                (23, "0.0"),
                (33, "0.0"),
                (16, "1.0"),
                (26, "0.0"),
                (36, "0.0"),
                (17, "0.0"),
                (27, "1.0"),
                (37, "0.0"),
                (76, "1"),
            ]);
            o.pair(330, format!("{rec:X}"));
        }
        o.endsec();
        o.pair(0, "EOF");
        o.text
    }
}

/// Owner of model-space entities.
const MODEL_SPACE_RECORD: u32 = 0x17;

/// Descriptions and dash patterns (drawing units) of the line types path drawings use.
pub(crate) fn linetype_pattern(lt: &str) -> (&'static str, Vec<f64>) {
    match lt.to_ascii_uppercase().as_str() {
        "DASHED" => ("Dashed __ __ __", vec![0.5, -0.25]),
        "HIDDEN" => ("Hidden _ _ _", vec![0.25, -0.125]),
        "DASHDOT" => ("Dash dot __ . __ .", vec![0.5, -0.25, 0.0, -0.25]),
        "DOT" => ("Dot . . . .", vec![0.0, -0.25]),
        "DIVIDE" => (
            "Divide __ . . __ . .",
            vec![0.5, -0.25, 0.0, -0.25, 0.0, -0.25],
        ),
        "BORDER" => (
            "Border __ __ . __ __ .",
            vec![0.5, -0.25, 0.5, -0.25, 0.0, -0.25],
        ),
        "CENTER" => ("Center ____ _ ____ _", vec![1.25, -0.25, 0.25, -0.25]),
        "PHANTOM" => (
            "Phantom ______  __  __",
            vec![1.25, -0.25, 0.25, -0.25, 0.25, -0.25],
        ),
        _ => ("Solid line", vec![]),
    }
}

/// Group-code output helper.
#[derive(Default)]
struct Out {
    text: String,
}

impl Out {
    fn pair(&mut self, code: i32, value: impl std::fmt::Display) {
        let _ = write!(self.text, "{code:>3}\n{value}\n");
    }
    fn pairs(&mut self, p: &[(i32, &str)]) {
        for (c, v) in p {
            self.pair(*c, v);
        }
    }
    fn section(&mut self, name: &str) {
        self.pair(0, "SECTION");
        self.pair(2, name);
    }
    fn endsec(&mut self) {
        self.pair(0, "ENDSEC");
    }
    fn var(&mut self, name: &str, code: i32, value: &str) {
        self.pair(9, name);
        self.pair(code, value);
    }
    fn table(&mut self, name: &str, handle: u32, count: usize) {
        self.pair(0, "TABLE");
        self.pair(2, name);
        self.pair(5, format!("{handle:X}"));
        self.pair(330, 0);
        self.pair(100, "AcDbSymbolTable");
        self.pair(70, count);
    }
    fn endtab(&mut self) {
        self.pair(0, "ENDTAB");
    }
    fn record(&mut self, kind: &str, handle: u32, owner: u32, subclass: &str) {
        self.pair(0, kind);
        self.pair(5, format!("{handle:X}"));
        self.pair(330, format!("{owner:X}"));
        self.pair(100, "AcDbSymbolTableRecord");
        self.pair(100, subclass);
    }
}

/// A text value for the file's code page (`ANSI_1252`, whose files readers decode byte by
/// byte): characters beyond ASCII as `\U+XXXX` escapes, as AutoCAD writes them. Characters
/// beyond the Basic Multilingual Plane have no such escape and stay as they are.
fn escape_non_ascii(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        let code = u32::from(c);
        if c.is_ascii() || code > 0xFFFF {
            out.push(c);
        } else {
            let _ = write!(out, "\\U+{code:04X}");
        }
    }
    out
}

/// Whether a value ends with a `\U+XXXX` escape.
fn ends_with_escape(s: &str) -> bool {
    let b = s.as_bytes();
    b.len() >= 7 && {
        let tail = &b[b.len() - 7..];
        tail[0] == b'\\'
            && tail[1] == b'U'
            && tail[2] == b'+'
            && tail[3..].iter().all(u8::is_ascii_hexdigit)
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
