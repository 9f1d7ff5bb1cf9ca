//! Helpers shared by the end-to-end tests (each test file uses some of them).
#![allow(dead_code)]

pub mod lsp_client;

use std::path::Path;
use std::process::{Command, Output};

/// Runs the binary in `dir` with `args`.
pub fn millpath(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// Copies the text examples (`examples/text`: drawings and millpath.toml) into `dir`.
pub fn copy_text_examples(dir: &Path) {
    let from = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/text");
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, dir.join(p.file_name().unwrap())).unwrap();
    }
}

/// Runs the binary in `dir` with `args`, without colour: its exit status and its standard
/// output followed by its standard error.
pub fn status_and_text(dir: &Path, args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.code().unwrap_or(-1), text)
}

/// The machine settings `compile` asks for, as options (F150, sweeps at 500 mm/min, 15 mm up).
pub const MACHINE: [&str; 6] = [
    "--feed",
    "150",
    "--sweep-speed",
    "500",
    "--sweep-height",
    "15",
];
