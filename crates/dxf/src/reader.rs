//! The group-code reader: bytes → (code, value, line) pairs → sections → [`Drawing`].

use crate::decode::{decode_unicode_escapes, encoding_for};
use crate::{Drawing, DxfError, DxfErrorKind, Entity, EntityKind, MText, Point3, Text};
use encoding_rs::Encoding;

struct Pair<'a> {
    code: i32,
    value: &'a [u8],
    /// 1-based line of the group code.
    line: usize,
}

fn trim_eol(mut s: &[u8]) -> &[u8] {
    while let [rest @ .., b'\r' | b'\n'] = s {
        s = rest;
    }
    s
}

fn split_pairs(bytes: &[u8]) -> Result<Vec<Pair<'_>>, DxfError> {
    let mut lines = bytes.split(|&b| b == b'\n').map(trim_eol);
    let mut pairs = Vec::new();
    let mut line_no = 0usize;
    while let Some(code_line) = lines.next() {
        line_no += 1;
        let code_text = String::from_utf8_lossy(code_line);
        let code_trim = code_text.trim();
        if code_trim.is_empty() {
            // trailing empty lines at the end of the file are harmless
            if lines
                .clone()
                .all(|l| l.iter().all(|b| b.is_ascii_whitespace()))
            {
                break;
            }
            return Err(DxfError {
                line: line_no,
                kind: DxfErrorKind::BadGroupCode(String::new()),
            });
        }
        let code: i32 = code_trim.parse().map_err(|_| DxfError {
            line: line_no,
            kind: DxfErrorKind::BadGroupCode(code_trim.chars().take(40).collect()),
        })?;
        let Some(value) = lines.next() else {
            return Err(DxfError {
                line: line_no,
                kind: DxfErrorKind::Truncated,
            });
        };
        pairs.push(Pair {
            code,
            value,
            line: line_no,
        });
        line_no += 1;
    }
    Ok(pairs)
}

struct Ctx {
    enc: &'static Encoding,
}

impl Ctx {
    fn text(&self, p: &Pair) -> String {
        let (s, _, _) = self.enc.decode(p.value);
        decode_unicode_escapes(&s)
    }
}

fn raw_str(p: &Pair) -> String {
    String::from_utf8_lossy(p.value).trim().to_string()
}

fn num(p: &Pair) -> Result<f64, DxfError> {
    let s = raw_str(p);
    s.parse::<f64>().map_err(|_| DxfError {
        line: p.line + 1,
        kind: DxfErrorKind::BadNumber {
            code: p.code,
            value: s.chars().take(40).collect(),
        },
    })
}

fn int(p: &Pair) -> Result<i32, DxfError> {
    let s = raw_str(p);
    s.parse::<i32>()
        .or_else(|_| s.parse::<f64>().map(|f| f as i32))
        .map_err(|_| DxfError {
            line: p.line + 1,
            kind: DxfErrorKind::BadNumber {
                code: p.code,
                value: s.chars().take(40).collect(),
            },
        })
}

fn is(p: &Pair, code: i32, value: &str) -> bool {
    p.code == code && trim_ascii(p.value) == value.as_bytes()
}

fn trim_ascii(s: &[u8]) -> &[u8] {
    let start = s
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(s.len());
    let end = s
        .iter()
        .rposition(|b| !b.is_ascii_whitespace())
        .map_or(start, |e| e + 1);
    &s[start..end]
}

/// Reads a DXF file (ASCII, R12 to current versions).
pub fn read_dxf(bytes: &[u8]) -> Result<Drawing, DxfError> {
    if bytes.starts_with(b"AutoCAD Binary DXF") {
        return Err(DxfError {
            line: 0,
            kind: DxfErrorKind::Binary,
        });
    }
    let pairs = split_pairs(bytes)?;
    // Sections: (name, first pair index after the name, index of ENDSEC).
    let mut sections: Vec<(String, usize, usize)> = Vec::new();
    let mut i = 0;
    while i < pairs.len() {
        if is(&pairs[i], 0, "SECTION") {
            let name = pairs
                .get(i + 1)
                .filter(|p| p.code == 2)
                .map(raw_str)
                .unwrap_or_default();
            let start = i + 2;
            let mut j = start;
            while j < pairs.len() && !is(&pairs[j], 0, "ENDSEC") {
                if is(&pairs[j], 0, "SECTION") || is(&pairs[j], 0, "EOF") {
                    break;
                }
                j += 1;
            }
            if j >= pairs.len() || !is(&pairs[j], 0, "ENDSEC") {
                let line = pairs.get(j).or(pairs.last()).map_or(0, |p| p.line);
                return Err(DxfError {
                    line,
                    kind: DxfErrorKind::Truncated,
                });
            }
            sections.push((name, start, j));
            i = j + 1;
        } else if is(&pairs[i], 0, "EOF") {
            break;
        } else {
            i += 1;
        }
    }
    if sections.is_empty() {
        return Err(DxfError {
            line: pairs.first().map_or(1, |p| p.line),
            kind: DxfErrorKind::NotDxf,
        });
    }

    let mut drawing = Drawing {
        text_size: 2.5,
        ..Default::default()
    };
    // Header first: it decides the string decoding.
    for (name, s, e) in &sections {
        if name == "HEADER" {
            read_header(&pairs[*s..*e], &mut drawing)?;
        }
    }
    let ctx = Ctx {
        enc: encoding_for(&drawing.version, &drawing.codepage),
    };
    for (name, s, e) in &sections {
        match name.as_str() {
            "TABLES" => read_tables(&ctx, &pairs[*s..*e], &mut drawing),
            "ENTITIES" => read_entities(&ctx, &pairs[*s..*e], &mut drawing)?,
            _ => {}
        }
    }
    Ok(drawing)
}

fn read_header(pairs: &[Pair], d: &mut Drawing) -> Result<(), DxfError> {
    let mut var = String::new();
    for p in pairs {
        match p.code {
            9 => var = raw_str(p),
            1 if var == "$ACADVER" => d.version = raw_str(p),
            3 if var == "$DWGCODEPAGE" => d.codepage = raw_str(p),
            40 if var == "$TEXTSIZE" => d.text_size = num(p)?,
            _ => {}
        }
    }
    Ok(())
}

/// Splits a section body into records, each starting at a `0` group.
fn records<'p, 'a>(pairs: &'p [Pair<'a>]) -> impl Iterator<Item = &'p [Pair<'a>]> {
    let mut i = 0;
    std::iter::from_fn(move || {
        while i < pairs.len() && pairs[i].code != 0 {
            i += 1;
        }
        if i >= pairs.len() {
            return None;
        }
        let start = i;
        i += 1;
        while i < pairs.len() && pairs[i].code != 0 {
            i += 1;
        }
        Some(&pairs[start..i])
    })
}

fn read_tables(ctx: &Ctx, pairs: &[Pair], d: &mut Drawing) {
    for rec in records(pairs) {
        let kind = raw_str(&rec[0]);
        match kind.as_str() {
            "LTYPE" => {
                if let Some(p) = rec.iter().find(|p| p.code == 2) {
                    d.linetypes.push(ctx.text(p));
                }
            }
            "LAYER" => {
                let name = rec.iter().find(|p| p.code == 2).map(|p| ctx.text(p));
                let lt = rec.iter().find(|p| p.code == 6).map(|p| ctx.text(p));
                if let Some(name) = name {
                    d.layers
                        .insert(name, lt.unwrap_or_else(|| "Continuous".to_string()));
                }
            }
            _ => {}
        }
    }
}

fn read_entities(ctx: &Ctx, pairs: &[Pair], d: &mut Drawing) -> Result<(), DxfError> {
    for rec in records(pairs) {
        let kind = raw_str(&rec[0]);
        if !matches!(kind.as_str(), "LINE" | "ARC" | "CIRCLE" | "TEXT" | "MTEXT") {
            if !matches!(kind.as_str(), "VERTEX" | "SEQEND" | "ATTRIB") {
                d.ignored_entities += 1;
            }
            continue;
        }
        if let Some(e) = read_entity(ctx, &kind, rec)? {
            d.entities.push(e);
        }
    }
    Ok(())
}

fn set(pt: &mut Point3, axis: usize, p: &Pair) -> Result<(), DxfError> {
    pt[axis] = num(p)?;
    Ok(())
}

fn read_entity(ctx: &Ctx, kind: &str, rec: &[Pair]) -> Result<Option<Entity>, DxfError> {
    let mut handle = String::new();
    let mut layer = "0".to_string();
    let mut linetype = None;
    let mut linetype_scale = 1.0;
    let mut extrusion = [0.0, 0.0, 1.0];
    let mut p10 = [0.0; 3];
    let mut p11 = [0.0; 3];
    let mut has11 = false;
    let mut r40 = 0.0;
    let mut a50: Option<f64> = None;
    let mut a51 = 0.0;
    let (mut i71, mut i72, mut i73): (Option<i32>, i32, i32) = (None, 0, 0);
    let mut text = String::new();
    let mut paper_space = false;
    for p in &rec[1..] {
        match p.code {
            5 => handle = raw_str(p),
            8 => layer = ctx.text(p),
            6 => linetype = Some(ctx.text(p)),
            48 => linetype_scale = num(p)?,
            67 => paper_space = int(p)? == 1,
            10 => set(&mut p10, 0, p)?,
            20 => set(&mut p10, 1, p)?,
            30 => set(&mut p10, 2, p)?,
            11 => {
                has11 = true;
                set(&mut p11, 0, p)?
            }
            21 => set(&mut p11, 1, p)?,
            31 => set(&mut p11, 2, p)?,
            210 => set(&mut extrusion, 0, p)?,
            220 => set(&mut extrusion, 1, p)?,
            230 => set(&mut extrusion, 2, p)?,
            40 => r40 = num(p)?,
            50 => a50 = Some(num(p)?),
            51 => a51 = num(p)?,
            71 => i71 = Some(int(p)?),
            72 => i72 = int(p)?,
            73 => i73 = int(p)?,
            1 | 3 if kind == "MTEXT" => text.push_str(&ctx.text(p)),
            1 if kind == "TEXT" => text = ctx.text(p),
            _ => {}
        }
    }
    if paper_space {
        return Ok(None);
    }
    let kind = match kind {
        "LINE" => EntityKind::Line {
            start: p10,
            end: p11,
        },
        "CIRCLE" => EntityKind::Circle {
            center: p10,
            radius: r40,
        },
        "ARC" => EntityKind::Arc {
            center: p10,
            radius: r40,
            start_angle: a50.unwrap_or(0.0),
            end_angle: a51,
        },
        "TEXT" => EntityKind::Text(Text {
            value: text,
            first: p10,
            second: has11.then_some(p11),
            height: r40,
            rotation: a50.unwrap_or(0.0),
            generation: i71.unwrap_or(0),
            halign: i72,
            valign: i73,
        }),
        _ => EntityKind::MText(MText {
            value: text,
            insert: p10,
            height: r40,
            attachment: i71.unwrap_or(1),
            rotation: a50,
            direction: has11.then_some(p11),
        }),
    };
    Ok(Some(Entity {
        line: rec[0].line,
        handle,
        layer,
        linetype,
        linetype_scale,
        extrusion,
        kind,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dxf(body: &str) -> String {
        format!(
            "  0\nSECTION\n  2\nHEADER\n  9\n$ACADVER\n  1\nAC1015\n  9\n$DWGCODEPAGE\n  3\nANSI_1252\n  0\nENDSEC\n  0\nSECTION\n  2\nTABLES\n  0\nTABLE\n  2\nLAYER\n  0\nLAYER\n  2\nP1\n  6\nDASHED\n  0\nENDTAB\n  0\nENDSEC\n  0\nSECTION\n  2\nENTITIES\n{body}  0\nENDSEC\n  0\nEOF\n"
        )
    }

    #[test]
    fn reads_entities_with_line_numbers() {
        let src = dxf("  0\nLINE\n  5\nA1\n  8\nP1\n 10\n1.5\n 20\n2\n 30\n0\n 11\n3\n 21\n4\n 31\n0\n  0\nPOINT\n  8\nP1\n  0\nMTEXT\n  8\nP1\n  3\nAB\n  1\nC\\PD\n 71\n7\n");
        let d = read_dxf(src.as_bytes()).unwrap();
        assert_eq!(d.version, "AC1015");
        assert_eq!(d.layers.get("P1").map(String::as_str), Some("DASHED"));
        assert_eq!(d.entities.len(), 2);
        assert_eq!(d.ignored_entities, 1);
        let e = &d.entities[0];
        assert_eq!(e.handle, "A1");
        assert_eq!(
            e.kind,
            EntityKind::Line {
                start: [1.5, 2.0, 0.0],
                end: [3.0, 4.0, 0.0]
            }
        );
        assert_eq!(src.lines().nth(e.line - 1).unwrap().trim(), "0");
        assert_eq!(src.lines().nth(e.line).unwrap(), "LINE");
        match &d.entities[1].kind {
            EntityKind::MText(m) => {
                assert_eq!(m.value, "ABC\\PD");
                assert_eq!(m.attachment, 7);
            }
            k => panic!("unexpected {k:?}"),
        }
    }

    #[test]
    fn code_page_1252_is_decoded() {
        let mut bytes = dxf("  0\nTEXT\n  8\nP1\n  1\nGr\u{1}n\n").into_bytes();
        let pos = bytes.iter().position(|&b| b == 1).unwrap();
        bytes[pos] = 0xFC; // ü in windows-1252
        let d = read_dxf(&bytes).unwrap();
        match &d.entities[0].kind {
            EntityKind::Text(t) => assert_eq!(t.value, "Grün"),
            k => panic!("unexpected {k:?}"),
        }
    }

    #[test]
    fn truncated_and_malformed_files_report_lines() {
        let src = dxf("  0\nLINE\n  8\nP1\n 10\n1.5\n");
        let cut = &src[..src.find(" 10\n1.5").unwrap() + 4];
        let err = read_dxf(cut.as_bytes()).unwrap_err();
        assert_eq!(err.kind, DxfErrorKind::Truncated);
        assert!(err.line > 20);
        let bad = dxf("  0\nLINE\n  8\nP1\n 10\nabc\n");
        let err = read_dxf(bad.as_bytes()).unwrap_err();
        assert!(
            matches!(err.kind, DxfErrorKind::BadNumber { code: 10, .. }),
            "{err:?}"
        );
        assert_eq!(bad.lines().nth(err.line - 1), Some("abc"));
        let err = read_dxf(b"hello\nworld\n").unwrap_err();
        assert!(matches!(err.kind, DxfErrorKind::BadGroupCode(_)));
        assert!(read_dxf(b"").is_err());
        assert_eq!(
            read_dxf(b"AutoCAD Binary DXF\r\n\x1a\0").unwrap_err().kind,
            DxfErrorKind::Binary
        );
    }

    #[test]
    fn r12_files_without_handles_or_subclasses() {
        let src = "  0\nSECTION\n  2\nHEADER\n  9\n$ACADVER\n  1\nAC1009\n  0\nENDSEC\n  0\nSECTION\n  2\nTABLES\n  0\nTABLE\n  2\nLAYER\n  0\nLAYER\n  2\n1000_1P\n 70\n0\n 62\n7\n  6\nCONTINUOUS\n  0\nENDTAB\n  0\nENDSEC\n  0\nSECTION\n  2\nBLOCKS\n  0\nBLOCK\n  8\n0\n  0\nLINE\n  8\n1000_1P\n 10\n5\n 20\n5\n 11\n6\n 21\n6\n  0\nENDBLK\n  0\nENDSEC\n  0\nSECTION\n  2\nENTITIES\n  0\nCIRCLE\n  8\n1000_1P\n  6\nPHANTOM\n 10\n1.0\n 20\n2.0\n 30\n0.0\n 40\n0.5\n  0\nARC\n  8\n1000_1P\n 10\n0\n 20\n0\n 40\n3\n 50\n0\n 51\n90\n  0\nENDSEC\n  0\nEOF\n";
        let d = read_dxf(src.as_bytes()).unwrap();
        assert_eq!(d.version, "AC1009");
        // entities of blocks are not model space
        assert_eq!(d.entities.len(), 2);
        assert_eq!(d.entities[0].handle, "");
        assert_eq!(
            d.entities[0].kind,
            EntityKind::Circle {
                center: [1.0, 2.0, 0.0],
                radius: 0.5
            }
        );
        assert_eq!(
            d.entities[1].kind,
            EntityKind::Arc {
                center: [0.0, 0.0, 0.0],
                radius: 3.0,
                start_angle: 0.0,
                end_angle: 90.0
            }
        );
    }

    #[test]
    fn paper_space_entities_are_skipped() {
        let d =
            read_dxf(dxf("  0\nLINE\n  8\nP1\n 67\n1\n  0\nCIRCLE\n  8\nP1\n 40\n2\n").as_bytes())
                .unwrap();
        assert_eq!(d.entities.len(), 1);
        assert_eq!(d.entities[0].kind.code_name(), "CIRCLE");
    }
}
