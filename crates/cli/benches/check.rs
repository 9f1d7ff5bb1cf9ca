//! `millpath check` end to end: each iteration spawns the `millpath` binary built for the
//! bench (`check --quiet`, output thrown away), so what is measured is exactly the command
//! users run — reading, all paths checked, files in parallel — plus one process start.
//!
//! ```sh
//! cargo bench -p millpath --bench check                 # everything
//! cargo bench -p millpath --bench check -- shared       # only the 38 shared drawings
//! cargo bench -p millpath --bench check -- 'chain_20000|short_chains'
//! ```
//!
//! Cases: the shared drawings (`../shared/conformance/fixtures` and `../shared/samples`,
//! skipped with a message when absent); ONE chain of 20,000 and of 100,000 mill segments;
//! 100,000 segments in chains of 10 separated by sweeps; 10,000 files (copies of our own
//! drawings, `bench/drawings.rs`). Drawings are generated into a temporary folder.
//!
//! A case whose first check takes longer than 30 s is reported with that one time and not
//! sampled (criterion needs at least 10 samples); `MILLPATH_BENCH_SLOW=1` samples it anyway.

#[path = "../../../bench/drawings.rs"]
mod drawings;

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const SLOW: Duration = Duration::from_secs(30);

fn check(inputs: &[PathBuf]) {
    let status = Command::new(env!("CARGO_BIN_EXE_millpath"))
        .arg("check")
        .arg("--quiet")
        .args(inputs)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .expect("millpath runs");
    // 0: clean, 1: errors in the drawings (the shared fixtures have some); never 2 or a crash
    assert!(
        matches!(status.code(), Some(0 | 1)),
        "check failed: {status}"
    );
}

/// Samples `check inputs`, with a sample count and time fitted to a first timed run.
fn bench_check(c: &mut Criterion, name: &str, inputs: &[PathBuf]) {
    if !c_filter_matches(name) {
        return;
    }
    let t0 = Instant::now();
    check(inputs);
    let first = t0.elapsed();
    if first > SLOW && std::env::var_os("MILLPATH_BENCH_SLOW").is_none() {
        eprintln!(
            "check/{name}: one run took {:.1} s; not sampled (MILLPATH_BENCH_SLOW=1 samples it)",
            first.as_secs_f64()
        );
        return;
    }
    let mut g = c.benchmark_group("check");
    if first > Duration::from_millis(500) {
        // slow cases: 10 samples of one run each (flat: runs per sample = ⌈time / (10 · one run)⌉),
        // no warm-up beyond the first run; criterion may say the samples take longer
        g.sample_size(10)
            .sampling_mode(SamplingMode::Flat)
            .warm_up_time(Duration::from_millis(1))
            .measurement_time(first.mul_f64(8.0));
    }
    g.bench_function(name, |b| b.iter(|| check(inputs)));
    g.finish();
}

/// Criterion filters by name only once the case runs; this skips generating and the first
/// timed run of cases that are filtered out (`cargo bench … -- 'REGEX'`, as criterion does).
fn c_filter_matches(name: &str) -> bool {
    const WITH_VALUE: &[&str] = &[
        "--save-baseline",
        "--baseline",
        "--load-baseline",
        "--sample-size",
        "--warm-up-time",
        "--measurement-time",
        "--profile-time",
        "--output-format",
        "--color",
        "--nresamples",
        "--noise-threshold",
        "--confidence-level",
        "--significance-level",
        "--plotting-backend",
        "-s",
        "-b",
        "-c",
    ];
    let mut filters = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if WITH_VALUE.contains(&a.as_str()) {
            args.next();
        } else if !a.starts_with('-') {
            filters.push(a);
        }
    }
    let id = format!("check/{name}");
    let exact = std::env::args().any(|a| a == "--exact");
    filters.is_empty()
        || filters.iter().any(|f| match regex::Regex::new(f) {
            _ if exact => id == *f,
            Ok(re) => re.is_match(&id),
            Err(_) => id.contains(f.as_str()),
        })
}

fn shared_drawings() -> Option<Vec<PathBuf>> {
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared");
    let dirs = [shared.join("conformance/fixtures"), shared.join("samples")];
    if !dirs.iter().all(|d| d.is_dir()) {
        return None;
    }
    Some(dirs.to_vec())
}

fn write(dir: &Path, name: &str, text: String) -> Vec<PathBuf> {
    let f = dir.join(name);
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(&f, text).unwrap();
    vec![f]
}

fn bench(c: &mut Criterion) {
    let tmp = tempfile::tempdir().unwrap();
    let t = tmp.path();
    match shared_drawings() {
        Some(dirs) => bench_check(c, "shared_38_drawings", &dirs),
        None => eprintln!("../shared is absent: skipping check/shared_38_drawings"),
    }
    if c_filter_matches("chain_20000") {
        let f = write(
            &t.join("chain20k"),
            "1000.1P.dxf",
            drawings::one_chain(20_000),
        );
        bench_check(c, "chain_20000", &f);
    }
    if c_filter_matches("chain_100000") {
        let f = write(
            &t.join("chain100k"),
            "1000.1P.dxf",
            drawings::one_chain(100_000),
        );
        bench_check(c, "chain_100000", &f);
    }
    if c_filter_matches("short_chains_100000") {
        let f = write(
            &t.join("chains100k"),
            "1000.1P.dxf",
            drawings::short_chains(100_000, 10),
        );
        bench_check(c, "short_chains_100000", &f);
    }
    if c_filter_matches("files_10000") {
        let dir = t.join("files10k");
        drawings::own_copies(10_000, &dir).unwrap();
        bench_check(c, "files_10000", &[dir]);
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
