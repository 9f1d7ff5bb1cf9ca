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

/// The machine settings `compile` asks for, as options (F150, sweeps at 500 mm/min, 15 mm up).
pub const MACHINE: [&str; 6] = [
    "--feed",
    "150",
    "--sweep-speed",
    "500",
    "--sweep-height",
    "15",
];
