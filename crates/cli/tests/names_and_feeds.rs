//! Path names in the wrong case and feeds that round to nothing (issue 20, item 12): the
//! reference's case-insensitive layer test is kept with a warning, a subpath written in the
//! wrong case gets a hint, and a feed below 1 mm/min is a located error wherever it comes from.

mod common;

use millpath_core::Msg;
use std::path::Path;

fn millpath(dir: &Path, args: &[&str]) -> (i32, String) {
    common::status_and_text(dir, args)
}

fn examples(sub: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(sub)
}

/// A folder with the text examples and their millpath.toml.
fn text_examples() -> tempfile::TempDir {
    let tmp = tempfile::tempdir().unwrap();
    for e in std::fs::read_dir(examples("text")).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, tmp.path().join(p.file_name().unwrap())).unwrap();
    }
    tmp
}

#[test]
fn a_lowercase_layer_is_a_path_with_a_warning() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::copy(examples("plate/millpath.toml"), dir.join("millpath.toml")).unwrap();
    let dxf = std::fs::read_to_string(examples("plate/1234.1P.dxf")).unwrap();
    std::fs::write(dir.join("1234.1P.dxf"), dxf.replace("1234_1P", "1234_1p")).unwrap();
    for cmd in ["check", "compile"] {
        let (status, text) = millpath(dir, &[cmd, "1234.1P.dxf"]);
        // reference-input.md §1.3: the layer test ignores case, so the path stays a path
        assert_eq!(status, 0, "{cmd}: {text}");
        assert!(
            text.contains(&Msg::PathNameCase.code()) && text.contains("did you mean 1234.1P?"),
            "{cmd}: {text}"
        );
    }
    assert!(dir.join("1234.1P_Milling.gcode").exists());
    // the right case: no word
    std::fs::write(dir.join("1234.1P.dxf"), &dxf).unwrap();
    let (status, text) = millpath(dir, &["check", "1234.1P.dxf"]);
    assert_eq!(status, 0);
    assert!(!text.contains(&Msg::PathNameCase.code()), "{text}");
}

#[test]
fn a_subpath_in_the_wrong_case_gets_a_hint() {
    let tmp = text_examples();
    let dir = tmp.path();
    let project = std::fs::read_to_string(dir.join("2010.mpath")).unwrap();
    std::fs::write(
        dir.join("2010.mpath"),
        project.replace(">2001.1P", ">2001.1p"),
    )
    .unwrap();
    for cmd in ["check", "compile"] {
        let (status, text) = millpath(dir, &[cmd, "2010.mpath"]);
        assert_eq!(status, 1, "{cmd}: {text}");
        assert!(
            text.contains(&Msg::SubpathNotFoundCase.code())
                && text.contains("did you mean 2001.1P?"),
            "{cmd}: {text}"
        );
    }
    // a name that is nowhere gets the plain message
    std::fs::write(
        dir.join("2010.mpath"),
        project.replace(">2001.1P", ">2001.7P"),
    )
    .unwrap();
    let (_, text) = millpath(dir, &["check", "2010.mpath"]);
    assert!(text.contains(&Msg::CouldNotFind.code()), "{text}");
    assert!(!text.contains("did you mean"), "{text}");
}

#[test]
fn a_feed_that_rounds_to_nothing_is_an_error_at_its_text() {
    let tmp = text_examples();
    let dir = tmp.path();
    let part = std::fs::read_to_string(dir.join("2001.mpath")).unwrap();
    std::fs::write(
        dir.join("2001.mpath"),
        part.replacen(" O2", " O2 F0,0001", 1),
    )
    .unwrap();
    for cmd in ["check", "compile"] {
        let (status, text) = millpath(dir, &[cmd, "2001.mpath"]);
        assert_eq!(status, 1, "{cmd}: {text}");
        assert!(text.contains(&Msg::FeedTooSmall.code()), "{cmd}: {text}");
        // located at the line that holds the text
        assert!(text.contains("2001.mpath:4:"), "{cmd}: {text}");
    }
    assert!(!dir.join("2001_Milling.gcode").exists());
    // 1 mm/min is slow, but a feed
    std::fs::write(dir.join("2001.mpath"), part.replacen(" O2", " O2 F1", 1)).unwrap();
    let (status, text) = millpath(dir, &["compile", "2001.mpath"]);
    assert_eq!(status, 0, "{text}");
    std::fs::write(dir.join("2001.mpath"), &part).unwrap();
    // from the options and from millpath.toml: an option error
    let (status, text) = millpath(dir, &["compile", "--feed", "0.0001", "2001.mpath"]);
    assert_eq!(status, 2, "{text}");
    assert!(text.contains(&Msg::FeedTooSmall.code()), "{text}");
    assert!(text.contains("--> Options"), "{text}");
    let toml = std::fs::read_to_string(dir.join("millpath.toml")).unwrap();
    std::fs::write(
        dir.join("millpath.toml"),
        toml.replace("probe_feed = 50", "probe_feed = 0.01"),
    )
    .unwrap();
    let (status, text) = millpath(dir, &["check", "2001.mpath"]);
    assert_eq!(status, 2, "{text}");
    assert!(
        text.contains(&Msg::FeedTooSmall.code()) && text.contains("probe_feed"),
        "{text}"
    );
    // located at the file that gave it; the same value as an option is the option's
    let at_toml = text
        .lines()
        .skip_while(|l| !l.contains(&Msg::FeedTooSmall.code()))
        .nth(1)
        .unwrap_or_default();
    assert!(
        at_toml.starts_with("  --> ") && at_toml.ends_with("millpath.toml"),
        "{text}"
    );
    let (_, text) = millpath(dir, &["check", "--probe-feed", "0.01", "2001.mpath"]);
    assert!(text.contains("--> Options"), "{text}");
}
