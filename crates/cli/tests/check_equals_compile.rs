//! `check` is `compile` without writing: over every shared drawing, the examples and
//! mutations of them (renamed and lowercase layers, empty and cut files, broken parameter
//! texts, missing subpaths, a deleted end marker, a feed that rounds to 0), both report the
//! same diagnostics and exit with the same status. The allowed difference is the library:
//! `compile` takes one path per file (MP061, or it stops at the first path that aborts), while
//! `check` checks every path of a file, so there compile's other errors must be among check's;
//! and a path that defines variables, which compile gives no values (it warns so) and check its
//! check values (reference-input.md §6.2).

mod common;

use millpath_core::Msg;
use std::path::{Path, PathBuf};

/// The diagnostics' first lines (`error[MP…]: …`), sorted: the severity, code and message
/// of each. What compile says about the files it writes or removes (an older output of a
/// drawing that failed) is no diagnostic of the drawing: check writes nothing.
fn heads(text: &str) -> Vec<String> {
    let about_files = [
        Msg::StaleOutputRemoved.code(),
        Msg::OutputSetRestored.code(),
        Msg::CannotWrite.code(),
    ];
    let mut v: Vec<String> = text
        .lines()
        .filter(|l| {
            let l = l.trim_start();
            (l.starts_with("error[") || l.starts_with("warning["))
                && l.contains("MP")
                && !about_files.iter().any(|c| l.contains(&format!("[{c}]")))
        })
        .map(|l| l.trim().to_string())
        .collect();
    v.sort();
    v.dedup();
    v
}

struct Run {
    status: i32,
    heads: Vec<String>,
    /// `---- Checking …` lines: the paths check checked.
    checked: usize,
}

fn run(dir: &Path, args: &[&str]) -> Run {
    let (status, text) = common::status_and_text(dir, args);
    Run {
        status,
        heads: heads(&text),
        checked: text
            .lines()
            .filter(|l| l.starts_with("---- Checking"))
            .count(),
    }
}

/// Path-layer names of a DXF (values of group code 8 that look like `1234_5P`, suffix kept).
fn path_layers(dxf: &str) -> Vec<String> {
    let lines: Vec<&str> = dxf.lines().collect();
    let mut names = Vec::new();
    for pair in lines.chunks(2) {
        if let [code, value] = pair {
            let v = value.trim();
            let base = v.split('~').next().unwrap_or("").as_bytes();
            let looks = base.len() >= 7
                && base[..4].iter().all(u8::is_ascii_digit)
                && base[4] == b'_'
                && base[base.len() - 1].is_ascii_alphabetic();
            if code.trim() == "8" && looks && !names.iter().any(|n| n == v) {
                names.push(v.to_string());
            }
        }
    }
    names
}

/// Replaces the value lines of layer `from` (group code 8 and the LAYER table's name).
fn rename_layer(dxf: &str, from: &str, to: &str) -> String {
    let eol = if dxf.contains("\r\n") { "\r\n" } else { "\n" };
    dxf.split(eol)
        .map(|l| if l.trim() == from { to } else { l })
        .collect::<Vec<_>>()
        .join(eol)
}

/// The mutations of one drawing: (name, new content).
fn mutations(file: &Path, content: &str) -> Vec<(String, String)> {
    let mut m = vec![
        ("empty".to_string(), String::new()),
        ("cut".to_string(), {
            let mut cut = content.len() / 2;
            while !content.is_char_boundary(cut) {
                cut -= 1;
            }
            content[..cut].to_string()
        }),
    ];
    let is_text = file.extension().is_some_and(|e| e == "mpath");
    if is_text {
        if let Some(p) = content.find("path ") {
            let end = content[p..].find('{').map_or(content.len(), |e| p + e);
            let lower = format!("{}{}", &content[..p], content[p..end].to_lowercase());
            m.push(("lowercase name".into(), lower + &content[end..]));
        }
        let no_end: String = content
            .lines()
            .filter(|l| !l.trim_start().starts_with("end "))
            .map(|l| format!("{l}\n"))
            .collect();
        m.push(("end marker deleted".into(), no_end));
        m.push(("O0".into(), content.replacen(" O2", " O0", 1)));
        m.push(("T broken".into(), content.replacen(" T", " T#", 1)));
        m.push(("F0,0001".into(), content.replacen(" O2", " O2 F0,0001", 1)));
        if let Some(p) = content.find('>') {
            let mut s = content.to_string();
            s.insert(p + 1, '9');
            m.push(("missing subpath".into(), s));
        }
    } else {
        let layers = path_layers(content);
        if let Some(first) = layers.first() {
            let mut renamed = content.to_string();
            for l in &layers {
                renamed = rename_layer(&renamed, l, "1000-1A");
            }
            m.push(("layers 1000-1A".into(), renamed));
            m.push((
                "lowercase layer".into(),
                rename_layer(content, first, &first.to_lowercase()),
            ));
        }
        m.push(("O0".into(), content.replacen("\\PO", "\\PO0", 1)));
        m.push((
            "F0,0001".into(),
            content.replacen("\\PO", "\\PF0,0001\\PO", 1),
        ));
        if let Some(p) = content.find("\\P>").or_else(|| content.find('>')) {
            let mut s = content.to_string();
            let at = s[p..].find('>').map_or(p, |q| p + q) + 1;
            s.insert(at, '9');
            m.push(("missing subpath".into(), s));
        }
    }
    m.retain(|(_, c)| c != content || c.is_empty());
    m
}

/// Copies the drawings (and a millpath.toml) of `src` into `dst`.
fn copy_folder(src: &Path, dst: &Path) -> Vec<PathBuf> {
    std::fs::create_dir_all(dst).unwrap();
    let mut drawings = Vec::new();
    for e in std::fs::read_dir(src).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_owned();
        let ext = p.extension().map(|e| e.to_string_lossy().to_lowercase());
        match ext.as_deref() {
            Some("dxf") | Some("mpath") => {
                std::fs::copy(&p, dst.join(&name)).unwrap();
                drawings.push(dst.join(&name));
            }
            Some("toml") => {
                std::fs::copy(&p, dst.join(&name)).unwrap();
            }
            _ => {}
        }
    }
    if !dst.join("millpath.toml").exists() {
        std::fs::write(
            dst.join("millpath.toml"),
            "feed = 150\nsweep_speed = 500\nsweep_height = 15\n",
        )
        .unwrap();
    }
    drawings.sort();
    drawings
}

#[derive(Default)]
struct Counts {
    files: usize,
    mutations: usize,
    agreeing: usize,
    /// Files of several paths, or whose path defines variables.
    libraries: usize,
}

/// Runs check and compile on `file` (in its folder): why they disagree (`None`: they agree),
/// and whether the file is a library of several paths.
fn disagreement(dir: &Path, file: &Path) -> (Option<String>, bool) {
    let name = file.file_name().unwrap().to_string_lossy().into_owned();
    let check = run(dir, &["check", &name]);
    let compile = run(dir, &["compile", &name]);
    let mp061 = Msg::MoreThanOnePath.code();
    if compile
        .heads
        .iter()
        .any(|h| h.contains(&Msg::VariablesNotGiven.code()))
    {
        // a path with variables: check gives it its check values, compile none (it says so)
        return (None, true);
    }
    if check.checked > 1 {
        // a library: compile's other diagnostics are among check's
        let missing: Vec<&String> = compile
            .heads
            .iter()
            .filter(|h| !h.contains(&mp061) && !check.heads.contains(h))
            .collect();
        let why = (!missing.is_empty()).then(|| format!("library: check lacks {missing:?}"));
        return (why, true);
    }
    let why = (check.status != compile.status || check.heads != compile.heads).then(|| {
        format!(
            "check exit {} {:?}\ncompile exit {} {:?}",
            check.status, check.heads, compile.status, compile.heads
        )
    });
    (why, false)
}

#[test]
fn check_reports_what_compile_reports() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let shared = root.join("../shared");
    let mut folders = vec![root.join("examples/plate"), root.join("examples/text")];
    for sub in ["conformance/fixtures", "samples"] {
        if shared.join(sub).is_dir() {
            folders.push(shared.join(sub));
        } else {
            eprintln!("skipping {}: ../shared is absent", sub);
        }
    }
    let tmp = tempfile::tempdir().unwrap();
    let mut counts = Counts::default();
    let mut failures = Vec::new();
    for (i, folder) in folders.iter().enumerate() {
        let dir = tmp.path().join(i.to_string());
        for file in copy_folder(folder, &dir) {
            let original = std::fs::read(&file).unwrap();
            let text = String::from_utf8_lossy(&original).into_owned();
            counts.files += 1;
            let mut cases = vec![("as drawn".to_string(), None)];
            cases.extend(
                mutations(&file, &text)
                    .into_iter()
                    .map(|(n, c)| (n, Some(c))),
            );
            for (what, content) in cases {
                if let Some(c) = &content {
                    std::fs::write(&file, c).unwrap();
                    counts.mutations += 1;
                }
                let (why, library) = disagreement(&dir, &file);
                match why {
                    None => counts.agreeing += 1,
                    Some(why) => failures.push(format!("{} ({what}):\n{why}", file.display())),
                }
                counts.libraries += usize::from(library && content.is_none());
                std::fs::write(&file, &original).unwrap();
            }
        }
    }
    eprintln!(
        "check ≡ compile: {} files, {} mutations, {} of {} runs agreeing ({} files are libraries)",
        counts.files,
        counts.mutations,
        counts.agreeing,
        counts.files + counts.mutations,
        counts.libraries
    );
    assert!(counts.files >= 4, "the examples at least");
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn the_issues_two_examples_agree() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(
        dir.join("millpath.toml"),
        "feed = 150\nsweep_speed = 500\nsweep_height = 15\n",
    )
    .unwrap();
    std::fs::write(dir.join("empty.mpath"), "").unwrap();
    let plate = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate/1234.1P.dxf"),
    )
    .unwrap();
    std::fs::write(
        dir.join("1234.1P.dxf"),
        rename_layer(&plate, "1234_1P", "1000-1A"),
    )
    .unwrap();
    for (file, msg) in [
        ("empty.mpath", Msg::NoErrorFreePathInFile),
        ("1234.1P.dxf", Msg::NoErrorFreePath),
    ] {
        let check = run(dir, &["check", file]);
        let compile = run(dir, &["compile", file]);
        assert_eq!((check.status, compile.status), (1, 1), "{file}");
        assert!(
            check.heads.iter().any(|h| h.contains(&msg.code())),
            "{file}"
        );
        assert_eq!(check.heads, compile.heads, "{file}");
    }
}
