//! A CAD program re-saves a drawing with its entities in another order. Over every shared
//! drawing (skipped with a message when ../shared is absent), the examples and our own
//! fixtures, K re-saves with the ENTITIES section shuffled by a seeded generator:
//! - `dxf2text` is byte-identical whenever every path's G-code is (in a drawing with the
//!   warning the text shows the choice made, which may by chance give the same G-code);
//! - G-code that differs ⇒ the drawing has the order warning (MP118/MP120); no warning ⇒ every
//!   shuffle gives the same G-code.

use millpath_core::build::order_choice::{pin, pin_by_walking};
use millpath_core::build::walk::walk;
use millpath_core::convert::{dxf_to_text, text_to_dxf};
use millpath_core::diag::{FileRef, Lang};
use millpath_core::emit::{generate, Output};
use millpath_core::load::names::Patterns;
use millpath_core::{MemFileSystem, Msg, Session, Settings};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Re-saves per drawing; `MILLPATH_SHUFFLES=N` for a longer run.
fn shuffles() -> usize {
    std::env::var("MILLPATH_SHUFFLES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(12)
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// xorshift64*: a fixed, seeded sequence (no dependency, same on every platform).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The DXF with the entities of its ENTITIES section in another order. An entity is its
/// `0` group and everything up to the next `0`; VERTEX, SEQEND and ATTRIB stay with their owner.
fn shuffle_entities(dxf: &str, rng: &mut Rng) -> String {
    let lines: Vec<&str> = dxf.split_inclusive('\n').collect();
    let val = |i: usize| lines.get(i).map_or("", |l| l.trim());
    let mut i = 0;
    let mut begin = None;
    while i + 3 < lines.len() {
        if val(i) == "0" && val(i + 1) == "SECTION" && val(i + 2) == "2" && val(i + 3) == "ENTITIES"
        {
            begin = Some(i + 4);
            break;
        }
        i += 2;
    }
    let Some(begin) = begin else {
        return dxf.to_string();
    };
    let mut entities: Vec<Vec<&str>> = Vec::new();
    let mut j = begin;
    while j + 1 < lines.len() && !(val(j) == "0" && val(j + 1) == "ENDSEC") {
        let attached = matches!(val(j + 1), "VERTEX" | "SEQEND" | "ATTRIB");
        if val(j) == "0" && (!attached || entities.is_empty()) {
            entities.push(Vec::new());
        }
        let e = entities.last_mut().expect("an entity starts the section");
        e.push(lines[j]);
        e.push(lines[j + 1]);
        j += 2;
    }
    for k in (1..entities.len()).rev() {
        entities.swap(k, rng.below(k + 1));
    }
    let mut out: String = lines[..begin].concat();
    for e in entities {
        out.extend(e);
    }
    out.push_str(&lines[j..].concat());
    out
}

/// What a drawing compiles to: each path's G-code (or its failure), and whether the
/// order warning was reported.
fn compile(folder: &MemFileSystem, file: &Path) -> (BTreeMap<String, String>, bool) {
    let mut s = Session::new(Settings::default(), folder).unwrap();
    let names = s.load_file(file);
    let mut out = BTreeMap::new();
    for name in &names {
        pins_agree(&s, name);
    }
    for name in names {
        let text = match s.build_top(&name) {
            Err(d) => format!("abort {}", d.message(Lang::En)),
            Ok(None) => "none".to_string(),
            Ok(Some(model)) => match generate(&model, "f.dxf", "shuffle", 500.0, Lang::En) {
                Err(e) => format!("{:?}", e.iter().map(|d| d.msg).collect::<Vec<_>>()),
                Ok(g) => match g.output {
                    Output::Milling(m) => m,
                    Output::Probing {
                        probing,
                        z_txt,
                        clean,
                    } => format!("{probing}\u{0}{z_txt}\u{0}{clean}"),
                },
            },
        };
        out.insert(name, text);
    }
    let warned = s
        .diags
        .list
        .iter()
        .any(|d| matches!(d.msg, Msg::OrderDecides | Msg::OrderDecidesNoPin));
    (out, warned)
}

/// The pin the warning names (checked from what the walk recorded) is the one a second walk
/// with the pinned text confirms.
fn pins_agree(s: &Session, name: &str) {
    let Some(raw) = s.raw_path(name) else { return };
    let (Some(start), Some(end)) = (&raw.start, &raw.end) else {
        return;
    };
    let (steps, ties) = walk(&raw, start.pos, end.pos, &mut Default::default());
    for tie in &ties {
        assert_eq!(
            pin(&raw, tie),
            pin_by_walking(&raw, start.pos, end.pos, &steps, tie),
            "{name}: {tie:?}"
        );
    }
}

fn dxf2text(bytes: &[u8]) -> String {
    let s = Settings::default();
    let patterns = Patterns::new(&s.path_pattern, &s.file_pattern).unwrap();
    let file = FileRef::new("f.dxf".into());
    match dxf_to_text(bytes, &file, &patterns, millpath_core::InputMode::Reference) {
        Ok((t, _)) => t,
        Err(d) => format!("error {}", d.message(Lang::En)),
    }
}

/// (label, folder contents as a memory file system, the drawing's path in it).
fn drawings() -> Vec<(String, MemFileSystem, PathBuf)> {
    let mut out = Vec::new();
    let mut folder = |dir: &Path, label: &str| {
        let Ok(rd) = std::fs::read_dir(dir) else {
            return;
        };
        let mut fs = MemFileSystem::default();
        let mut mine = Vec::new();
        let mut files: Vec<PathBuf> = rd.map(|e| e.unwrap().path()).collect();
        files.sort();
        let s = Settings::default();
        let patterns = Patterns::new(&s.path_pattern, &s.file_pattern).unwrap();
        for p in files {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            let ext = p.extension().map(|e| e.to_string_lossy().to_lowercase());
            let bytes = std::fs::read(&p).unwrap();
            match ext.as_deref() {
                Some("dxf") => {
                    fs.add(PathBuf::from(&name), bytes);
                    mine.push(PathBuf::from(name));
                }
                Some("mpath") => {
                    // a text drawing as the DXF that text2dxf writes of it
                    let src = String::from_utf8(bytes).unwrap();
                    let f = FileRef::new(p.clone());
                    let dxf = text_to_dxf(&src, &f, &patterns).unwrap();
                    let stem = p.file_stem().unwrap().to_string_lossy().into_owned();
                    let n = PathBuf::from(format!("{stem}.dxf"));
                    fs.add(n.clone(), dxf.into_bytes());
                    mine.push(n);
                }
                _ => {}
            }
        }
        for m in mine {
            out.push((format!("{label}/{}", m.display()), fs.clone(), m));
        }
    };
    folder(&root().join("examples/plate"), "examples/plate");
    folder(&root().join("examples/text"), "examples/text");
    folder(
        &root().join("crates/core/tests/fixtures/order"),
        "fixtures/order",
    );
    let shared = root().join("../shared");
    if shared.join("conformance/fixtures").is_dir() {
        folder(&shared.join("conformance/fixtures"), "shared/fixtures");
        folder(&shared.join("samples"), "shared/samples");
    } else {
        eprintln!("../shared is absent: only the examples and our fixtures are shuffled");
    }
    out
}

#[test]
fn shuffled_resaves_keep_text_and_warn_where_order_decides() {
    let all = drawings();
    let shuffles = shuffles();
    assert!(all.len() >= 4, "{} drawings", all.len());
    let (mut text_diffs, mut gcode_diffs, mut unwarned, mut warned_count) = (0, 0, 0, 0);
    let mut text_diffs_warned = 0;
    let mut report = Vec::new();
    for (label, fs, file) in &all {
        let bytes = fs.files[file].clone();
        let original = String::from_utf8_lossy(&bytes).into_owned();
        let (gcode, warned) = compile(fs, file);
        let text = dxf2text(&bytes);
        warned_count += usize::from(warned);
        let mut seed = 0x9e37_79b9_7f4a_7c15u64 ^ (label.len() as u64 + 1);
        let mut differs = 0;
        for k in 0..shuffles {
            seed = seed.wrapping_add(k as u64 + 1);
            let mut rng = Rng(seed | 1);
            let shuffled = shuffle_entities(&original, &mut rng);
            let mut fs2 = fs.clone();
            fs2.add(file.clone(), shuffled.clone().into_bytes());
            let (g2, w2) = compile(&fs2, file);
            let t2 = dxf2text(shuffled.as_bytes());
            assert_eq!(
                warned, w2,
                "{label} shuffle {k}: the warning comes and goes"
            );
            if g2 != gcode {
                differs += 1;
                gcode_diffs += 1;
                if !warned {
                    unwarned += 1;
                    report.push(format!("{label} shuffle {k}: G-code differs, no warning"));
                }
            } else if t2 != text {
                // where the warning says the order decides, the text shows the choice made,
                // even when that choice happens to give the same G-code
                if warned {
                    text_diffs_warned += 1;
                } else {
                    text_diffs += 1;
                    report.push(format!(
                        "{label} shuffle {k}: text differs, G-code the same"
                    ));
                }
            }
        }
        eprintln!("{label}: {differs}/{shuffles} shuffles change the G-code; warning: {warned}");
    }
    eprintln!(
        "{} drawings × {shuffles} shuffles: {gcode_diffs} G-code diffs, {text_diffs} text diffs \
         where the G-code is the same (+ {text_diffs_warned} in warned drawings), {unwarned} \
         G-code diffs without warning; {warned_count} drawings warned",
        all.len()
    );
    assert!(report.is_empty(), "{report:#?}");
}
