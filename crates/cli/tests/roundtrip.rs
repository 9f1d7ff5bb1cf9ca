//! DXF ⇄ text round trips over every drawing of ../shared (skips when it is absent):
//! compiling a DXF, its text form and the DXF written back from that text gives the same
//! G-code (or the same diagnostics), and dxf2text of the written-back DXF is the first text.

use millpath_core::Msg;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_millpath"))
}

fn shared() -> Option<PathBuf> {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared");
    if p.join("conformance/fixtures").is_dir() {
        Some(p)
    } else {
        eprintln!("skipped: ../shared is not there");
        None
    }
}

fn dxfs(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("dxf")))
        .collect();
    v.sort();
    v
}

fn stem(p: &Path) -> String {
    p.file_stem().unwrap().to_string_lossy().into_owned()
}

/// Three folders: the original drawings, their text forms, the DXFs written from the texts.
fn convert_all(shared: &Path) -> (tempfile::TempDir, [PathBuf; 3]) {
    let root = tempfile::tempdir().unwrap();
    let dirs = [
        root.path().join("dxf"),
        root.path().join("text"),
        root.path().join("back"),
    ];
    for d in &dirs {
        std::fs::create_dir(d).unwrap();
    }
    let mut inputs = dxfs(&shared.join("conformance/fixtures"));
    inputs.extend(dxfs(&shared.join("samples")));
    for f in inputs {
        let s = stem(&f);
        std::fs::copy(&f, dirs[0].join(f.file_name().unwrap())).unwrap();
        let text = bin().arg("dxf2text").arg(&f).output().unwrap();
        assert!(
            text.status.success(),
            "dxf2text {}: {}",
            f.display(),
            String::from_utf8_lossy(&text.stderr)
        );
        let text_path = dirs[1].join(format!("{s}.mpath"));
        std::fs::write(&text_path, &text.stdout).unwrap();
        let back_path = dirs[2].join(format!("{s}.dxf"));
        let o = bin()
            .arg("text2dxf")
            .arg(&text_path)
            .arg("-o")
            .arg(&back_path)
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "text2dxf {s}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let again = bin().arg("dxf2text").arg(&back_path).output().unwrap();
        assert_eq!(
            String::from_utf8_lossy(&again.stdout),
            String::from_utf8_lossy(&text.stdout),
            "dxf2text of the written-back {s}"
        );
    }
    (root, dirs)
}

fn run_case(dir: &Path, args: &[String], ext: &str) -> (i32, BTreeMap<String, String>) {
    let work = tempfile::tempdir().unwrap();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, work.path().join(p.file_name().unwrap())).unwrap();
    }
    let n = args.len();
    let args: Vec<String> = args
        .iter()
        .enumerate()
        .map(|(i, a)| {
            if i + 1 < n || a.starts_with('/') {
                a.clone()
            } else {
                let base = a.strip_suffix(".dxf").unwrap_or(a);
                format!("{base}{ext}")
            }
        })
        .collect();
    let o = bin()
        .arg("pathdxf2gcode")
        .args(&args)
        .args(["/l", "de"])
        .current_dir(work.path())
        .output()
        .unwrap();
    let mut outs = BTreeMap::new();
    for e in std::fs::read_dir(work.path()).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        if name.ends_with(".gcode") || name.ends_with("_Z.txt") {
            // the file name is the only difference allowed: X.mpath vs X.dxf (and with it
            // the probing set's digest, which covers the file-name comment: masked)
            let text = std::fs::read_to_string(&p).unwrap();
            let text = match text.find(" set=") {
                Some(at) => format!("{}{}", &text[..at + 5], &text[(at + 21).min(text.len())..]),
                None => text,
            };
            outs.insert(name, text.replace(".mpath", ".dxf"));
        }
    }
    (o.status.code().unwrap_or(-1), outs)
}

fn diagnostics(dir: &Path) -> BTreeMap<String, Vec<(String, String)>> {
    let mut out = BTreeMap::new();
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    for f in files {
        let o = bin()
            .args(["check", "--format", "json"])
            .arg(f.file_name().unwrap())
            .current_dir(dir)
            .output()
            .unwrap();
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let mut list: Vec<(String, String)> = v["diagnostics"]
            .as_array()
            .unwrap()
            .iter()
            // a polyline or block the reference ignores has no text form: its warning
            // belongs to the original drawing only
            .filter(|d| d["name"] != "IgnoredEntity")
            .map(|d| {
                let msg = d["message"].as_str().unwrap().replace(".mpath", ".dxf");
                // "Unsupported X value; <where the text is>": the text's position differs by nature
                let msg = msg.split("; ").next().unwrap().to_string();
                let code = d["code"].as_str().unwrap().to_string();
                // the order warning names the drawing's entities or the text's lines
                let same = |m: Msg| code == m.code();
                if same(Msg::OrderDecides) || same(Msg::OrderDecidesText) {
                    return ("order".to_string(), "the order decides".to_string());
                }
                (code, msg)
            })
            .collect();
        list.sort();
        out.insert(stem(&f), list);
    }
    out
}

#[test]
fn dxf_text_and_written_back_dxf_compile_identically() {
    let Some(shared) = shared() else { return };
    let (_root, dirs) = convert_all(&shared);
    let cases = shared.join("conformance/cases");
    let mut names: Vec<PathBuf> = std::fs::read_dir(&cases)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    names.sort();
    let mut compared = 0;
    for case in names {
        let spec: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(case.join("args.json")).unwrap())
                .unwrap();
        let args: Vec<String> = spec["args"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a.as_str().unwrap().to_string())
            .collect();
        let a = run_case(&dirs[0], &args, ".dxf");
        let b = run_case(&dirs[1], &args, ".mpath");
        let c = run_case(&dirs[2], &args, ".dxf");
        assert_eq!(a, b, "text form of {}", case.display());
        assert_eq!(a, c, "written-back DXF of {}", case.display());
        compared += a.1.len();
    }
    assert!(compared >= 13, "{compared} output files compared");
    // every drawing on its own, with the same machine settings: same files, same exit status
    let mut stems: Vec<String> = std::fs::read_dir(&dirs[0])
        .unwrap()
        .map(|e| stem(&e.unwrap().path()))
        .collect();
    stems.sort();
    let mut written = 0;
    for s in &stems {
        let args = vec![
            "/f150".to_string(),
            "/v500".into(),
            "/s15".into(),
            "/z50".into(),
            format!("{s}.dxf"),
        ];
        let a = run_case(&dirs[0], &args, ".dxf");
        assert_eq!(a, run_case(&dirs[1], &args, ".mpath"), "text form of {s}");
        assert_eq!(
            a,
            run_case(&dirs[2], &args, ".dxf"),
            "written-back DXF of {s}"
        );
        written += a.1.len();
    }
    assert!(written >= 25, "{written} files");
    let (da, db, dc) = (
        diagnostics(&dirs[0]),
        diagnostics(&dirs[1]),
        diagnostics(&dirs[2]),
    );
    assert_eq!(da.len(), 38);
    assert_eq!(da, db, "diagnostics of the text forms");
    assert_eq!(da, dc, "diagnostics of the written-back DXFs");
}
