//! `check` checks files in parallel, yet reports exactly what checking the same files one by
//! one, in the given order, reports.

#[path = "../../../bench/drawings.rs"]
mod drawings;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn millpath(dir: &Path, args: &[&str], threads: Option<usize>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_millpath"));
    cmd.args(args).current_dir(dir);
    if let Some(n) = threads {
        cmd.env("RAYON_NUM_THREADS", n.to_string());
    }
    cmd.output().unwrap()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// `sub/`: a slower drawing first (a chain of 600 segments), then 50 variants of the example
/// plate — clean ones, ones with errors, ones with warnings — and `sub/text/` with the text
/// examples (one embeds another). Returns the files in the order `check sub` visits them.
fn many_files(root: &Path) -> Vec<String> {
    let example = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate/1234.1P.dxf"),
    )
    .unwrap();
    let sub = root.join("sub");
    std::fs::create_dir_all(sub.join("text")).unwrap();
    let mut files = vec!["sub/1000.1P.dxf".to_string()];
    std::fs::write(sub.join("1000.1P.dxf"), drawings::one_chain(600)).unwrap();
    let mut plates = Vec::new();
    for i in 1..=50 {
        let mut d = example.replace("1234_1P", &format!("1234_{i}P"));
        match i % 5 {
            1 => d = d.replace("O2\\P", "O9\\P"),          // errors
            2 => d = d.replace("I1,5", "I1,5\\PZq"),       // a warning
            3 => d = d.replace("\\PD2,5", "\\PD2,5\\PQ7"), // another error
            _ => {}
        }
        let name = format!("1234.{i}P.dxf");
        std::fs::write(sub.join(&name), d).unwrap();
        plates.push(format!("sub/{name}"));
    }
    plates.sort();
    files.extend(plates);
    let texts = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/text");
    let mut mpaths: Vec<PathBuf> = std::fs::read_dir(&texts)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "mpath"))
        .collect();
    mpaths.sort();
    for p in mpaths {
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        std::fs::copy(&p, sub.join("text").join(&name)).unwrap();
        files.push(format!("sub/text/{name}"));
    }
    files
}

#[test]
fn checking_many_files_reports_like_checking_them_one_by_one_in_order() {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path();
    let files = many_files(root);
    let args_of = |format: &str, inputs: &[String]| -> Vec<String> {
        let mut a = vec!["check".into(), "--format".into(), format.into()];
        a.extend(inputs.iter().cloned());
        a
    };
    let run = |args: &[String], threads: Option<usize>| {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        millpath(root, &a, threads)
    };
    let singles: Vec<Output> = files
        .iter()
        .map(|f| run(&args_of("github", std::slice::from_ref(f)), None))
        .collect();

    // github: the annotations of the directory are those of each file, in order
    let whole = run(&args_of("github", &["sub".into()]), None);
    let expected: String = singles.iter().map(|o| text(&o.stdout)).collect();
    assert!(expected.contains("::error ") && expected.contains("::warning "));
    assert_eq!(text(&whole.stdout), expected);
    assert_eq!(whole.status.code(), Some(1));

    // every format: the directory, the files listed in that order, and one worker agree
    for format in ["human", "json", "github", "sarif"] {
        let dir_run = run(&args_of(format, &["sub".into()]), None);
        let listed = run(&args_of(format, &files), None);
        let one_worker = run(&args_of(format, &["sub".into()]), Some(1));
        for other in [&listed, &one_worker] {
            assert_eq!(text(&dir_run.stdout), text(&other.stdout), "{format}");
            assert_eq!(text(&dir_run.stderr), text(&other.stderr), "{format}");
            assert_eq!(dir_run.status.code(), other.status.code(), "{format}");
        }
    }

    // human: every file's progress lines in order on stderr, then every file's diagnostics in
    // order and the summary on stdout
    let (mut info, mut diags) = (String::new(), String::new());
    for f in &files {
        let o = run(&args_of("human", std::slice::from_ref(f)), None);
        info.push_str(&text(&o.stderr));
        let out = text(&o.stdout);
        let mut lines: Vec<&str> = out.lines().collect();
        assert!(lines.pop().unwrap().starts_with("checked 1 file(s)"));
        for l in lines {
            diags.push_str(l);
            diags.push('\n');
        }
    }
    let whole_run = run(&args_of("human", &["sub".into()]), None);
    let whole = text(&whole_run.stdout);
    let summary = whole.lines().last().unwrap().to_string();
    assert!(
        summary.starts_with(&format!("checked {} file(s): ", files.len())),
        "{summary}"
    );
    assert_eq!(whole, format!("{diags}{summary}\n"));
    assert_eq!(text(&whole_run.stderr), info);

    // json: the same diagnostics in the same order, counted over all files
    let whole: serde_json::Value =
        serde_json::from_slice(&run(&args_of("json", &["sub".into()]), None).stdout).unwrap();
    let mut all = Vec::new();
    let mut errors = 0;
    for f in &files {
        let v: serde_json::Value =
            serde_json::from_slice(&run(&args_of("json", std::slice::from_ref(f)), None).stdout)
                .unwrap();
        all.extend(v["diagnostics"].as_array().unwrap().iter().cloned());
        errors += v["errors"].as_u64().unwrap();
    }
    assert_eq!(whole["files"], files.len());
    assert_eq!(whole["errors"], errors);
    assert_eq!(whole["diagnostics"], serde_json::Value::Array(all));
}

#[test]
fn quiet_prints_the_same_report_and_nothing_else() {
    let dir = tempfile::tempdir().unwrap();
    let files = many_files(dir.path());
    let loud = millpath(dir.path(), &["check", "sub"], None);
    let quiet = millpath(dir.path(), &["check", "--quiet", "sub"], None);
    assert_eq!(text(&loud.stdout), text(&quiet.stdout));
    assert!(text(&loud.stderr).contains("---- "));
    assert_eq!(text(&quiet.stderr), "");
    assert_eq!(loud.status.code(), quiet.status.code());
    // no progress bar drawn into a pipe
    assert!(!text(&loud.stderr).contains(&format!("/{} files", files.len())));
}
