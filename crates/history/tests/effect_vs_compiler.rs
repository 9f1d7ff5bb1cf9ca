//! The diff's effect report checked against the compiler: for every example and shared
//! drawing (`../shared`, skipped when absent) and seeded random mutations of parameters,
//! geometry, kinds and `millpath.toml`, both versions are compiled from disk (the toolpath
//! of each path, each move with its element) and the diff must agree:
//! - every element whose moves changed is reported changed;
//! - no element whose moves are identical is reported with a changed effective value, and
//!   none is reported as changed by its effect alone.

use millpath_core::diag::FileRef;
use millpath_core::load::names::Patterns;
use millpath_history::{diff, ChangeKind, Side, Version};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

type Moves = HashMap<usize, Vec<String>>;

/// The compiler's moves of one path of a file on disk, by the 1-based line of their element.
fn compiled_moves(file: &Path, path: &str) -> Moves {
    let ws = millpath_ide::Workspace::default();
    let mut out = Moves::new();
    let Ok(data) = millpath_ide::toolpath(&ws, file, Some(path)) else {
        return out;
    };
    let own = file.display().to_string();
    let sources = data["sources"].as_array().cloned().unwrap_or_default();
    for m in data["moves"].as_array().cloned().unwrap_or_default() {
        let Some(s) = m["source"].as_u64().and_then(|i| sources.get(i as usize)) else {
            continue;
        };
        if s["file"].as_str() != Some(own.as_str()) {
            continue;
        }
        let line = s["line"].as_u64().unwrap() as usize + 1;
        let key = format!(
            "{} {} {} {} {}",
            m["kind"], m["from"], m["to"], m["arc"], m["feed"]
        );
        out.entry(line).or_default().push(key);
    }
    out
}

/// A small seeded generator (no dependency for it).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self, n: usize) -> usize {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 33) as usize) % n.max(1)
    }
}

/// One mutation of a canonical text (or of the folder's millpath.toml); `None` when the
/// chosen one does not apply. Lines stay where they are.
fn mutate(text: &str, toml: &mut String, rng: &mut Lcg) -> Option<String> {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let elements: Vec<usize> = (0..lines.len())
        .filter(|&i| lines[i].starts_with("  ") && !lines[i].trim_start().starts_with('#'))
        .collect();
    let i = *elements.get(rng.next(elements.len()))?;
    let (body, comment) = match lines[i].find("  #") {
        Some(c) => (lines[i][..c].to_string(), lines[i][c..].to_string()),
        None => (lines[i].clone(), String::new()),
    };
    let word = regex::Regex::new(r" ([BDIOTSWF])(-?[0-9]+(?:,[0-9]+)?)(?: |$)").unwrap();
    let point = regex::Regex::new(r"\((-?[0-9.e-]+), (-?[0-9.e-]+)\)").unwrap();
    let body = match rng.next(6) {
        // a parameter value changed
        0 | 1 => {
            let c = word.captures(&body)?;
            let v: f64 = c[2].replace(',', ".").parse().ok()?;
            let d = [-0.3, 0.2, 0.5, 1.0][rng.next(4)];
            let new = format!(" {}{} ", &c[1], format!("{}", v + d).replace('.', ","));
            let m = c.get(0).unwrap();
            format!(
                "{}{}{}",
                &body[..m.start()],
                new.trim_end(),
                if m.as_str().ends_with(' ') { " " } else { "" }
            ) + &body[m.end()..]
        }
        // a parameter added
        2 => {
            let w = ["B-0,7", "D-0,1", "I0,5", "F222", "S12"][rng.next(5)];
            format!("{body} {w}")
        }
        // a point moved
        3 => {
            let c = point.captures(&body)?;
            let x: f64 = c[1].parse().ok()?;
            let m = c.get(0).unwrap();
            format!(
                "{}({}, {}){}",
                &body[..m.start()],
                x + 0.5,
                &c[2],
                &body[m.end()..]
            )
        }
        // another kind
        4 => {
            let pairs = [
                ("mill ", "mark "),
                ("mark ", "mill "),
                ("sweep ", "move "),
                ("drill ", "mark drill "),
            ];
            let t = body.trim_start();
            let (a, b) = pairs.iter().find(|(a, _)| t.starts_with(a))?;
            format!("  {b}{}", &t[a.len()..])
        }
        // the machine's feed in millpath.toml
        _ => {
            *toml = format!("{toml}\nfeed = 450\n").replace("feed = 300\n", "");
            body
        }
    };
    lines[i] = body + &comment;
    let mut out = lines.join("\n");
    out.push('\n');
    // canonical again (the diff reads both files as their canonical text)
    millpath_core::convert::format_text(&out, &FileRef::new("m.mpath".into())).ok()
}

/// A folder of drawings as canonical texts (DXF converted) with its millpath.toml.
struct Folder {
    files: Vec<(String, String)>,
    toml: String,
}

fn folder_of(dir: &Path, default_toml: &str) -> Folder {
    let patterns = Patterns::new(
        millpath_core::load::names::DEFAULT_PATH_PATTERN,
        millpath_core::load::names::DEFAULT_FILE_PATTERN,
    )
    .unwrap();
    let mut files = Vec::new();
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        let name = p.file_stem().unwrap().to_string_lossy().into_owned();
        let bytes = std::fs::read(&p).unwrap();
        let ext = p.extension().map(|e| e.to_ascii_lowercase());
        let text = if ext.as_deref() == Some("dxf".as_ref()) {
            let f = FileRef::new(p.clone());
            match millpath_core::convert::dxf_to_text(&bytes, &f, &patterns, Default::default()) {
                Ok((t, _)) => t,
                Err(_) => continue,
            }
        } else if ext.as_deref() == Some("mpath".as_ref()) {
            let f = FileRef::new(p.clone());
            millpath_core::convert::format_text(&String::from_utf8_lossy(&bytes), &f).unwrap()
        } else {
            continue;
        };
        files.push((format!("{name}.mpath"), text));
    }
    let toml =
        std::fs::read_to_string(dir.join("millpath.toml")).unwrap_or_else(|_| default_toml.into());
    Folder { files, toml }
}

fn write_folder(dir: &Path, f: &Folder, changed: Option<(usize, &str)>, toml: &str) {
    std::fs::create_dir_all(dir).unwrap();
    for (k, (name, text)) in f.files.iter().enumerate() {
        let t = match changed {
            Some((c, t)) if c == k => t,
            _ => text,
        };
        std::fs::write(dir.join(name), t).unwrap();
    }
    std::fs::write(dir.join("millpath.toml"), toml).unwrap();
}

/// Checks the diff of one mutation against the compiler; returns the number of elements
/// whose moves changed.
fn check(tmp: &Path, f: &Folder, k: usize, new_text: &str, new_toml: &str, what: &str) -> usize {
    let (old_dir, new_dir) = (tmp.join("old"), tmp.join("new"));
    let _ = std::fs::remove_dir_all(&old_dir);
    let _ = std::fs::remove_dir_all(&new_dir);
    write_folder(&old_dir, f, None, &f.toml);
    write_folder(&new_dir, f, Some((k, new_text)), new_toml);
    let name = &f.files[k].0;
    let (old_file, new_file) = (old_dir.join(name), new_dir.join(name));
    let old = Version::of_text(f.files[k].1.clone());
    let new = Version::of_text(new_text.to_string());
    let d = diff(
        Side {
            version: &old,
            file: &old_file,
            files: None,
            options: None,
        },
        Side {
            version: &new,
            file: &new_file,
            files: None,
            options: None,
        },
        true,
    );
    let mut changed_elements = 0;
    for p in &old.paths {
        let Some(pd) = d.paths.iter().find(|x| x.name == p.name) else {
            continue;
        };
        let (mo, mn) = (
            compiled_moves(&old_file, &p.name),
            compiled_moves(&new_file, &p.name),
        );
        let empty = Vec::new();
        // every element (same line in both texts) whose moves changed is reported
        for e in &p.elements {
            let (a, b) = (
                mo.get(&e.line).unwrap_or(&empty),
                mn.get(&e.line).unwrap_or(&empty),
            );
            if a != b {
                changed_elements += 1;
                assert!(
                    pd.changes
                        .iter()
                        .any(|c| c.old_line == Some(e.line) || c.new_line == Some(e.line)),
                    "{what}: {} line {} changed its moves and is not reported:\n{}",
                    p.name,
                    e.line,
                    new_text
                );
            }
        }
        // no element with the same moves is reported with a changed effective value
        for c in &pd.changes {
            let (Some(lo), Some(ln)) = (c.old_line, c.new_line) else {
                continue;
            };
            let same = mo.get(&lo).unwrap_or(&empty) == mn.get(&ln).unwrap_or(&empty);
            if same {
                assert!(
                    c.values.is_empty() && c.kind != ChangeKind::Effect,
                    "{what}: {} line {lo}→{ln} has the same moves but is reported {:?} with {:?}",
                    p.name,
                    c.kind,
                    c.values
                );
            }
        }
    }
    changed_elements
}

fn run_over(dir: &Path, default_toml: &str, mutations: usize, seed: u64) -> (usize, usize) {
    let f = folder_of(dir, default_toml);
    let tmp = tempfile::tempdir().unwrap();
    let mut rng = Lcg(seed);
    let (mut tried, mut with_effect) = (0, 0);
    for k in 0..f.files.len() {
        for m in 0..mutations {
            let mut toml = f.toml.clone();
            let Some(new_text) = mutate(&f.files[k].1, &mut toml, &mut rng) else {
                continue;
            };
            let what = format!("{} #{m} (seed {seed})", f.files[k].0);
            tried += 1;
            if check(tmp.path(), &f, k, &new_text, &toml, &what) > 0 {
                with_effect += 1;
            }
        }
    }
    (tried, with_effect)
}

const TOML: &str = "feed = 300\nsweep_speed = 1000\nsweep_height = 10\nprobe_feed = 50\n";

#[test]
fn examples_mutated() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let (mut tried, mut effect) = (0, 0);
    for (sub, seed) in [("text", 1u64), ("plate", 2)] {
        let (t, e) = run_over(&root.join(sub), TOML, 12, seed);
        tried += t;
        effect += e;
    }
    eprintln!("examples: {tried} mutations, {effect} changed moves");
    // the check is not empty: mutations ran and many of them reached the G-code
    assert!(tried >= 20 && effect >= 5, "{tried} {effect}");
}

#[test]
fn shared_drawings_mutated() {
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared");
    if !shared.is_dir() {
        eprintln!("skipped: ../shared is not there");
        return;
    }
    let (mut tried, mut effect) = (0, 0);
    for (sub, seed) in [("samples", 3u64), ("conformance/fixtures", 4)] {
        let (t, e) = run_over(&shared.join(sub), TOML, 3, seed);
        tried += t;
        effect += e;
    }
    eprintln!("shared drawings: {tried} mutations, {effect} changed moves");
    assert!(tried >= 40 && effect >= 10, "{tried} {effect}");
}
