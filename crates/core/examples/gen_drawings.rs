//! Generates big drawings for benchmarks (never committed: write them to a temporary folder).
//!
//! ```sh
//! cargo run --release -p millpath-core --example gen_drawings -- chain 100000 /tmp/b/1000.1P.dxf
//! cargo run --release -p millpath-core --example gen_drawings -- chains 100000 10 /tmp/b/1000.1P.dxf
//! cargo run --release -p millpath-core --example gen_drawings -- paths 10000 10 /tmp/b/1000.dxf
//! cargo run --release -p millpath-core --example gen_drawings -- copies 2500 /tmp/b/copies
//! cargo run --release -p millpath-core --example gen_drawings -- copies 100 /tmp/b/shared F.dxf…
//! ```
//!
//! `chain N`: one path, one chain of N connected mill segments. `chains N LEN`: one path, N
//! mill segments in chains of LEN separated by sweeps. `paths P LEN`: P paths of LEN
//! segments in one file. `copies K DIR [FILE…]`: K folders `DIR/copyNNNNN` each with a copy
//! of the files (default: our own set — the example plate and three generated drawings).

#[path = "../../../bench/drawings.rs"]
mod drawings;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

const USAGE: &str = "usage: gen_drawings chain N OUT.dxf | chains N LEN OUT.dxf | paths P LEN OUT.dxf | copies K DIR [FILE...]";

fn write(out: &str, text: String) -> Result<(), String> {
    let out = Path::new(out);
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    std::fs::write(out, text).map_err(|e| format!("{}: {e}", out.display()))
}

fn number(s: Option<&String>) -> Result<usize, String> {
    let s = s.ok_or(USAGE)?;
    s.replace('_', "")
        .parse()
        .map_err(|_| format!("not a number: {s}\n{USAGE}"))
}

fn run(args: &[String]) -> Result<(), String> {
    match args.first().map(String::as_str) {
        Some("chain") if args.len() == 3 => {
            write(&args[2], drawings::one_chain(number(args.get(1))?))
        }
        Some("chains") if args.len() == 4 => write(
            &args[3],
            drawings::short_chains(number(args.get(1))?, number(args.get(2))?),
        ),
        Some("paths") if args.len() == 4 => write(
            &args[3],
            drawings::many_paths(number(args.get(1))?, number(args.get(2))?),
        ),
        Some("copies") if args.len() >= 3 => {
            let k = number(args.get(1))?;
            let out = PathBuf::from(&args[2]);
            let files = if args.len() == 3 {
                drawings::own_set()
                    .into_iter()
                    .map(|(n, t)| (n, t.into_bytes()))
                    .collect()
            } else {
                let mut set = Vec::new();
                for f in &args[3..] {
                    let name = Path::new(f)
                        .file_name()
                        .ok_or_else(|| format!("not a file: {f}"))?
                        .to_string_lossy()
                        .into_owned();
                    set.push((name, std::fs::read(f).map_err(|e| format!("{f}: {e}"))?));
                }
                set
            };
            let written = drawings::copies(&files, k, &out).map_err(|e| e.to_string())?;
            eprintln!("{} files in {}", written.len(), out.display());
            Ok(())
        }
        _ => Err(USAGE.into()),
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(2)
        }
    }
}
