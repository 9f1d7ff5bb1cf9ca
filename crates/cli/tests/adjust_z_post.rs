//! adjust-z's height-map follower writes in the words of the program's post (issue 32): a
//! height-map set compiled with a post file of line numbers and modal words, measured and
//! adjusted, is numbered again from its start, leaves out the words the post leaves out, and
//! is read clean by verify; adjust-z finds the post in millpath.toml as compile did, or is
//! given it with `--post`; a post it cannot load is refused, located.

mod common;

use common::{copy_text_examples as example, millpath};

/// `post show linuxcnc` with line numbers (from 10, step 5) and modal F and motion words.
fn numbered(dir: &std::path::Path) -> String {
    String::from_utf8(millpath(dir, &["post", "show", "linuxcnc"]).stdout)
        .unwrap()
        .replace("name = \"linuxcnc\"", "name = \"mymill\"")
        .replace("modal = []", "modal = [\"F\", \"motion\"]")
        .replace(
            "[comments]",
            "[line_numbers]\nstart = 10\nstep = 5\n\n[comments]",
        )
}

/// Every probe of a `_Z.txt` measured 0.2 mm above its nominal top on the right, rising in X.
fn fill(z: &str) -> String {
    z.lines()
        .map(|l| {
            let top: f64 = l
                .split("/T=")
                .nth(1)
                .and_then(|r| r.split(')').next())
                .and_then(|t| t.parse().ok())
                .unwrap();
            let x: f64 = l
                .split(" X")
                .nth(1)
                .and_then(|r| r.split([' ', '/', ')']).next())
                .and_then(|t| t.parse().ok())
                .unwrap_or(0.0);
            format!("{l}{:.3}\n", top + 0.002 * x)
        })
        .collect()
}

#[test]
fn a_height_map_set_of_a_numbered_post_is_adjusted_in_its_words() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    example(d);
    std::fs::write(d.join("mymill.toml"), numbered(d)).unwrap();
    let own = std::fs::read_to_string(d.join("millpath.toml")).unwrap();
    std::fs::write(
        d.join("millpath.toml"),
        format!("post = \"mymill.toml\"\n{own}[heightmap]\nstep = 6\nmargin = 1\n"),
    )
    .unwrap();
    let out = millpath(d, &["compile", "2010.mpath"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let z = std::fs::read_to_string(d.join("2010_Z.txt")).unwrap();
    std::fs::write(d.join("2010_Z.txt"), fill(&z)).unwrap();
    let out = millpath(d, &["adjust-z", "--max", "1", "2010_Clean.gcode"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let milling = std::fs::read_to_string(d.join("2010_Milling.gcode")).unwrap();
    assert!(milling.contains("(MILLPATH-SURFACE"), "{milling}");
    // numbered again from the start, every line but the % lines
    let numbered: Vec<&str> = milling.lines().filter(|l| *l != "%").collect();
    for (k, l) in numbered.iter().enumerate() {
        let want = format!("N{} ", 10 + 5 * k);
        assert!(l.starts_with(&want), "line {k}: {l}");
    }
    // split pieces repeat neither their motion nor their feed
    assert!(
        numbered
            .iter()
            .any(|l| l.split(' ').nth(1).is_some_and(|w| w.starts_with('X'))),
        "{milling}"
    );
    let verified = millpath(
        d,
        &["verify", "--dialect", "linuxcnc", "2010_Milling.gcode"],
    );
    assert!(
        verified.status.success(),
        "{}",
        String::from_utf8_lossy(&verified.stdout)
    );

    // the post given as an option instead: the same program
    let first = milling.clone();
    let toml = std::fs::read_to_string(d.join("millpath.toml")).unwrap();
    std::fs::write(
        d.join("millpath.toml"),
        toml.replace("post = \"mymill.toml\"\n", ""),
    )
    .unwrap();
    let out = millpath(
        d,
        &[
            "adjust-z",
            "--post",
            "mymill.toml",
            "--max",
            "1",
            "2010_Clean.gcode",
        ],
    );
    assert!(out.status.success());
    assert_eq!(
        std::fs::read_to_string(d.join("2010_Milling.gcode")).unwrap(),
        first
    );

    // a post file that cannot be loaded: refused, located, nothing written
    std::fs::remove_file(d.join("2010_Milling.gcode")).unwrap();
    std::fs::write(
        d.join("bad.toml"),
        "[post]\nname = \"bad\"\nfamily = \"rs274\"\n[templates]\nlinear = \"G1 {feeed}\"\n",
    )
    .unwrap();
    let out = millpath(
        d,
        &[
            "adjust-z",
            "--post",
            "bad.toml",
            "--max",
            "1",
            "2010_Clean.gcode",
        ],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("--post: bad.toml:5:"), "{err}");
    assert!(!d.join("2010_Milling.gcode").exists());
}
