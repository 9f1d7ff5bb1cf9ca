//! `check`'s reports for CI: GitHub annotations with repository paths, a JSON/SARIF document
//! even when there is nothing to check, `--quiet` printing the report only, and folders
//! collected once through symbolic-link loops.

use std::path::Path;
use std::process::{Command, Output};

fn check(dir: &Path, workspace: Option<&Path>, args: &[&str]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_millpath"));
    c.arg("check").args(args).current_dir(dir);
    match workspace {
        Some(w) => c.env("GITHUB_WORKSPACE", w),
        None => c.env_remove("GITHUB_WORKSPACE"),
    };
    c.output().unwrap()
}

/// A repository with a folder `parts` holding one good and one broken drawing.
fn repo() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let parts = dir.path().join("parts");
    std::fs::create_dir_all(dir.path().join(".git")).unwrap();
    std::fs::create_dir_all(&parts).unwrap();
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/text");
    for f in ["2001.mpath", "millpath.toml"] {
        std::fs::copy(examples.join(f), parts.join(f)).unwrap();
    }
    std::fs::write(parts.join("3001.mpath"), "path 3001.1P {\n").unwrap();
    dir
}

fn file_props(stdout: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(stdout)
        .lines()
        .filter_map(|l| {
            let f = l.split_once(" file=")?.1;
            Some(f.split(',').next()?.to_string())
        })
        .collect()
}

#[test]
fn github_paths_are_relative_to_the_repository() {
    let dir = repo();
    let parts = dir.path().join("parts");
    // `paths: "."` of the Action, run inside a folder of the repository
    let o = check(&parts, None, &["--format", "github", "."]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(file_props(&o.stdout), ["parts/3001.mpath"]);
    // from the root, `./parts`
    let o = check(dir.path(), None, &["--format", "github", "./parts"]);
    assert_eq!(file_props(&o.stdout), ["parts/3001.mpath"]);
    // GITHUB_WORKSPACE wins over the repository found
    let o = check(&parts, Some(&parts), &["--format", "github", "."]);
    assert_eq!(file_props(&o.stdout), ["3001.mpath"]);
    // SARIF: the same path below %SRCROOT%
    let o = check(&parts, None, &["--format", "sarif", "."]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let loc = &v["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"];
    assert_eq!(loc["uri"], "parts/3001.mpath");
    assert_eq!(loc["uriBaseId"], "%SRCROOT%");
}

#[test]
fn nothing_to_check_is_still_a_report() {
    let dir = tempfile::tempdir().unwrap();
    for (format, parse) in [("json", true), ("sarif", true), ("github", false)] {
        let o = check(dir.path(), None, &["--format", format, "."]);
        assert_eq!(o.status.code(), Some(3), "{format}");
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(out.contains("no drawings"), "{format}: {out}");
        if parse {
            let v: serde_json::Value = serde_json::from_str(&out).unwrap();
            assert!(v.is_object(), "{format}");
        }
    }
    let v: serde_json::Value =
        serde_json::from_slice(&check(dir.path(), None, &["--format", "json", "."]).stdout)
            .unwrap();
    assert_eq!(v["errors"], 1);
    assert_eq!(v["files"], 0);
}

/// A feed in millpath.toml that no machine runs: exit 2 (a settings error), and still a
/// report in the format asked for, located at millpath.toml (GitHub annotates that file).
#[test]
fn a_settings_error_is_a_report_at_millpath_toml() {
    let dir = repo();
    let parts = dir.path().join("parts");
    std::fs::remove_file(parts.join("3001.mpath")).unwrap();
    std::fs::write(
        parts.join("millpath.toml"),
        "feed = 0.0001\nsweep_speed = 1000\nsweep_height = 10\n",
    )
    .unwrap();
    let o = check(dir.path(), Some(dir.path()), &["--format", "json", "parts"]);
    assert_eq!(o.status.code(), Some(2));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["errors"], 1, "{v}");
    assert!(v["diagnostics"][0]["message"]
        .as_str()
        .is_some_and(|m| m.contains("feed 0.0001 mm/min")));
    let o = check(
        dir.path(),
        Some(dir.path()),
        &["--format", "github", "parts"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(file_props(&o.stdout), ["parts/millpath.toml"]);
    let o = check(
        dir.path(),
        Some(dir.path()),
        &["--format", "sarif", "parts"],
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v.is_object());
}

/// A millpath.toml that is no TOML at all: still a report a reader can parse, at that file.
#[test]
fn an_unreadable_millpath_toml_is_a_report_too() {
    let dir = repo();
    let parts = dir.path().join("parts");
    std::fs::write(
        parts.join("millpath.toml"),
        "feed = [1\nsweep_speed = 1000\n",
    )
    .unwrap();
    let o = check(dir.path(), Some(dir.path()), &["--format", "json", "parts"]);
    assert_eq!(o.status.code(), Some(2));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["errors"], 1, "{v}");
    let d = &v["diagnostics"][0];
    assert!(
        d["message"].as_str().is_some_and(|m| m.contains("line 2")),
        "{v}"
    );
    assert!(d["location"]["file"]
        .as_str()
        .is_some_and(|f| f.ends_with("millpath.toml")));
    let o = check(
        dir.path(),
        Some(dir.path()),
        &["--format", "github", "parts"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(file_props(&o.stdout), ["parts/millpath.toml"]);
    let o = check(
        dir.path(),
        Some(dir.path()),
        &["--format", "sarif", "parts"],
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v.is_object());
}

#[test]
fn quiet_prints_the_report_only() {
    let dir = repo();
    let parts = dir.path().join("parts");
    let o = check(&parts, None, &["--quiet", "."]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("----"), "{err}");
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("checked 2 file(s): 1 error(s)"), "{out}");
    let loud = check(&parts, None, &["."]);
    assert!(String::from_utf8_lossy(&loud.stderr).contains("---- "));
}

#[cfg(unix)]
#[test]
fn a_symlink_loop_reads_each_file_once() {
    let dir = repo();
    let parts = dir.path().join("parts");
    std::os::unix::fs::symlink(dir.path(), parts.join("loop")).unwrap();
    let o = check(&parts, None, &["--format", "json", "."]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["files"], 2, "{v}");
    assert_eq!(v["errors"], 1, "{v}");
}
