//! Hostile post files (`tests/hostile/*.toml`) give located errors, in English and German:
//! each file's expected line, column, key and message part are in `tests/hostile/expected.tsv`.
//! Nothing panics, and no post comes out of a bad file.

use millpath_post::{load, Lang};
use std::path::PathBuf;

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/hostile")
}

#[test]
fn every_hostile_post_gives_its_located_error() {
    let expected = std::fs::read_to_string(dir().join("expected.tsv")).unwrap();
    let mut files: Vec<String> = std::fs::read_dir(dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 20, "at least twenty hostile posts");
    let mut rows = 0;
    for line in expected
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
    {
        let cols: Vec<&str> = line.split('\t').collect();
        let [file, at, key, part] = cols[..] else {
            panic!("bad row: {line}")
        };
        let text = std::fs::read_to_string(dir().join(file)).unwrap();
        let err = load(file, &text).expect_err(file);
        let en = err.render(Lang::En);
        let de = err.render(Lang::De);
        assert_eq!(format!("{}:{}", err.line, err.column), at, "{file}: {en}");
        assert_eq!(err.key, key, "{file}: {en}");
        assert!(en.contains(part), "{file}: `{part}` not in {en}");
        assert!(en.starts_with(&format!("{file}:")), "{en}");
        assert_ne!(en, de, "{file}: the German message differs");
        rows += 1;
    }
    assert_eq!(rows, files.len(), "every hostile file has its expectation");
}

#[test]
fn the_built_in_posts_load() {
    for name in millpath_post::builtin::NAMES {
        let p = millpath_post::builtin::get(name).unwrap();
        assert_eq!(p.name, name);
        let again = load("copy.toml", millpath_post::builtin::source(name).unwrap()).unwrap();
        assert_eq!(again.templates, p.templates);
    }
}

#[test]
fn truncated_posts_never_panic() {
    // every prefix of a real post, cut anywhere: an error or a post, never a panic
    let text = millpath_post::builtin::source("linuxcnc").unwrap();
    let mut ok = 0;
    for (i, _) in text.char_indices() {
        if load("cut.toml", &text[..i]).is_ok() {
            ok += 1;
        }
    }
    assert!(ok < text.len() / 4, "most prefixes are refused");
}

#[test]
fn printed_errors_for_the_fixtures() {
    // `cargo test -- --nocapture printed` shows each file's message (kept as a quick look)
    for e in std::fs::read_dir(dir()).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "toml") {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            let err = load(&name, &std::fs::read_to_string(&p).unwrap()).unwrap_err();
            eprintln!(
                "{name}\t{}:{}\t{}\t{}",
                err.line,
                err.column,
                err.key,
                err.render(Lang::En)
            );
        }
    }
}
