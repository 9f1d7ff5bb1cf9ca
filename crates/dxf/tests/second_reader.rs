//! The `dxf` crate (crates.io) as a second reader: on every shared drawing and on ours, it
//! sees the same model-space entities (type, layer, own line type, in file order), the same
//! layers with their line types and the same LTYPE names as our reader. MTEXT values are
//! compared too: where they differ, the crate must have lost the end of the value from a
//! paragraph break on; the test counts those. The finding: the crate returns many MTEXT values
//! without their end from a paragraph break `\P` on (`M3x40\PO2\PT3\PI1,5\PB-0,2\PD2,5` comes
//! back without `\PD2,5`, 54 of 256 values in the shared drawings): parameters would be lost,
//! so it is no candidate for reading path drawings.

use millpath_dxf::{read_dxf, EntityKind};
use std::path::{Path, PathBuf};

/// (entity type, layer, own line type) of one entity.
type Seen = (String, String, String);

/// Entities, layers (name, line type), LTYPE names, MTEXT values.
type View = (Vec<Seen>, Vec<(String, String)>, Vec<String>, Vec<String>);

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn drawings() -> Vec<PathBuf> {
    let mut dirs = vec![
        repo().join("examples/plate"),
        repo().join("tests/extended/drawings/cad"),
        repo().join("tests/extended/freecad"),
    ];
    let shared = repo().join("../shared");
    if shared.join("conformance/fixtures").is_dir() {
        dirs.push(shared.join("conformance/fixtures"));
        dirs.push(shared.join("samples"));
    } else {
        eprintln!("../shared is absent: comparing our own drawings only");
    }
    let mut files = Vec::new();
    for d in dirs {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dxf")) {
                files.push(p);
            }
        }
    }
    files.sort();
    files
}

/// A drawing our writer makes (what text2dxf writes), with every entity kind it writes.
fn written() -> String {
    let mut w = millpath_dxf::writer::DxfWriter::new();
    w.layer("1234_1P", "CONTINUOUS")
        .layer("1234_1P~A", "DASHED");
    w.line("1234_1P", Some("PHANTOM"), (0.0, 0.0), (10.0, 0.0))
        .circle("1234_1P", None, (0.0, 0.0), 0.5)
        .arc("1234_1P~A", Some("DASHED"), (5.0, 5.0), 2.0, 0.0, 90.0)
        .text("1234_1P", (1.0, 1.0), 0.35, "O2 T3")
        .mtext("1234_1P", (2.0, 2.0), 0.35, &["M10x3", "B-0,2"]);
    w.finish()
}

fn lt(name: Option<&str>) -> String {
    name.unwrap_or("BYLAYER").to_ascii_uppercase()
}

fn ours(bytes: &[u8]) -> View {
    let d = read_dxf(bytes).unwrap();
    let mut ents: Vec<(usize, Seen)> = d
        .entities
        .iter()
        .map(|e| {
            let kind = e.kind.code_name().to_string();
            (e.line, (kind, e.layer.clone(), lt(e.linetype.as_deref())))
        })
        .collect();
    ents.extend(d.extra.iter().map(|x| {
        let seen = (
            x.code_name().to_string(),
            x.layer.clone(),
            lt(x.linetype.as_deref()),
        );
        (x.line, seen)
    }));
    ents.sort_by_key(|(l, _)| *l);
    let layers = d
        .layers
        .iter()
        .map(|(n, l)| (n.clone(), l.to_ascii_uppercase()))
        .collect();
    let mtexts = d
        .entities
        .iter()
        .filter_map(|e| match &e.kind {
            EntityKind::MText(m) => Some(m.value.clone()),
            _ => None,
        })
        .collect();
    (
        ents.into_iter().map(|(_, s)| s).collect(),
        layers,
        d.linetypes,
        mtexts,
    )
}

fn theirs(path: &Path) -> Result<View, String> {
    use dxf::entities::EntityType as T;
    let d = dxf::Drawing::load_file(path).map_err(|e| e.to_string())?;
    let mut ents = Vec::new();
    let mut mtexts = Vec::new();
    for e in d.entities() {
        if e.common.is_in_paper_space {
            continue;
        }
        let kind = match &e.specific {
            T::Line(_) => "LINE",
            T::Arc(_) => "ARC",
            T::Circle(_) => "CIRCLE",
            T::Text(_) => "TEXT",
            T::MText(m) => {
                mtexts.push(m.extended_text.concat() + &m.text);
                "MTEXT"
            }
            T::LwPolyline(_) => "LWPOLYLINE",
            T::Polyline(_) => "POLYLINE",
            T::Insert(_) => "INSERT",
            T::Ellipse(_) => "ELLIPSE",
            T::Spline(_) => "SPLINE",
            _ => continue,
        };
        ents.push((
            kind.to_string(),
            e.common.layer.clone(),
            lt(Some(&e.common.line_type_name)),
        ));
    }
    let mut layers: Vec<(String, String)> = d
        .layers()
        .map(|l| (l.name.clone(), l.line_type_name.to_ascii_uppercase()))
        .collect();
    layers.sort();
    let linetypes = d.line_types().map(|l| l.name.clone()).collect();
    Ok((ents, layers, linetypes, mtexts))
}

#[test]
fn the_dxf_crate_sees_what_our_reader_sees() {
    let dir = std::env::temp_dir().join(format!("millpath-second-reader-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ours_written = dir.join("written.dxf");
    std::fs::write(&ours_written, written()).unwrap();
    let mut files = drawings();
    files.push(ours_written);
    let (mut compared, mut mtexts, mut mtext_cut) = (0, 0, 0);
    let mut problems = Vec::new();
    for f in &files {
        let name = f.file_name().unwrap().to_string_lossy().into_owned();
        let (e1, l1, t1, m1) = ours(&std::fs::read(f).unwrap());
        let (e2, l2, t2, m2) = match theirs(f) {
            Ok(x) => x,
            Err(e) => {
                problems.push(format!("{name}: the dxf crate cannot read it: {e}"));
                continue;
            }
        };
        if e1 != e2 {
            let at = e1.iter().zip(&e2).position(|(a, b)| a != b);
            problems.push(format!(
                "{name}: entities differ ({} vs {}), first at {at:?}: {:?} vs {:?}",
                e1.len(),
                e2.len(),
                at.and_then(|i| e1.get(i)),
                at.and_then(|i| e2.get(i))
            ));
        }
        // the crate adds the layer 0 and the line types that entities or layers name when
        // the tables lack them (BYLAYER, Standard, …): compared are the table entries
        let l2: Vec<_> = l2
            .into_iter()
            .filter(|(n, _)| n != "0" || l1.iter().any(|(m, _)| m == "0"))
            .collect();
        let t2: Vec<_> = t2.into_iter().filter(|t| t1.contains(t)).collect();
        let t1: Vec<_> = {
            let mut seen = Vec::new();
            for t in t1 {
                if !seen.contains(&t) {
                    seen.push(t);
                }
            }
            seen
        };
        if l1 != l2 {
            problems.push(format!("{name}: layers differ: {l1:?} vs {l2:?}"));
        }
        if t1 != t2 {
            problems.push(format!("{name}: line types differ: {t1:?} vs {t2:?}"));
        }
        if m1.len() != m2.len() {
            problems.push(format!("{name}: {} vs {} MTEXT", m1.len(), m2.len()));
        }
        for (a, b) in m1.iter().zip(&m2) {
            mtexts += 1;
            if a != b {
                // the known finding: the crate loses the end of the value from a `\P`
                // (paragraph break) on; anything else is a difference
                if a.starts_with(b.as_str()) && a[b.len()..].starts_with("\\P") {
                    mtext_cut += 1;
                } else {
                    problems.push(format!("{name}: MTEXT {a:?} vs {b:?}"));
                }
            }
        }
        compared += 1;
    }
    let _ = std::fs::remove_dir_all(&dir);
    eprintln!(
        "{} drawings, {compared} compared, {mtexts} MTEXT values, {mtext_cut} differ",
        files.len()
    );
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
