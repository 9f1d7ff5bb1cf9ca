//! Profiling harness (not a test): the editor's analysis of the bench's 20k files, edit
//! after edit, timed in process. `cargo run --release -p millpath-ide --example
//! latency_profile -- [short|long] [n] [runs]`.
use millpath_ide::{analyze_from, Analysis, Workspace};
use std::path::Path;
use std::time::Instant;

fn zigzag(n: usize, infeed: &str, long: bool) -> String {
    let mut s = format!("path 3000.1P {{\n  start (0, 0)  M10x3 O2 T3 I{infeed} B-0,2\n");
    let segments = n - 2;
    let mut x = 0.0;
    let mut lines = String::new();
    for i in 0..segments {
        let y0 = if i % 2 == 0 { 0.0 } else { 5.0 };
        let kind = if !long && i % 4 == 3 { "sweep" } else { "mill" };
        lines.push_str(&format!(
            "  {kind} ({x}, {y0}) -> ({}, {})\n",
            x + 1.0,
            5.0 - y0
        ));
        x += 1.0;
    }
    let y_end = if segments.is_multiple_of(2) { 0.0 } else { 5.0 };
    s.push_str(&format!("  end ({x}, {y_end})\n{lines}}}\n"));
    s
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let long = args.get(1).is_some_and(|a| a == "long");
    let n: usize = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(20_000);
    let runs: usize = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(40);
    let dir = std::env::temp_dir().join(format!("latency_profile_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n",
    )
    .unwrap();
    let path = dir.join("3000.mpath");
    let mut ws = Workspace::default();
    ws.overlays.insert(path.clone(), zigzag(n, "1,5", long));
    let mut prev = analyze_from(&ws, &path, None, &|| false).unwrap();
    assert!(prev.diagnostics.is_empty(), "{:?}", prev.diagnostics);
    let texts = [zigzag(n, "1,2", long), zigzag(n, "1,5", long)];
    let mut times = Vec::new();
    let mut cpu = Vec::new();
    for i in 0..runs {
        ws.overlays.insert(path.clone(), texts[i % 2].clone());
        let (t0, c0) = (Instant::now(), cpu_ns());
        let a = edit_analysis(&ws, &path, &prev);
        let (t1, c1) = (Instant::now(), cpu_ns());
        prev = a;
        times.push((t1 - t0, t1.elapsed()));
        cpu.push(c1.zip(c0).map(|(b, a)| b.saturating_sub(a)));
    }
    times.sort();
    let med = times[times.len() / 2];
    println!(
        "analysis median {:.2} ms (min {:.2}), drop of the previous {:.2} ms",
        med.0.as_secs_f64() * 1e3,
        times[0].0.as_secs_f64() * 1e3,
        med.1.as_secs_f64() * 1e3
    );
    // on a busy machine the wall clock counts the waits for a core; this thread's CPU time
    // (Linux) does not
    let mut cpu: Vec<u64> = cpu.into_iter().flatten().collect();
    cpu.sort_unstable();
    if !cpu.is_empty() {
        println!(
            "analysis CPU time median {:.2} ms (min {:.2})",
            cpu[cpu.len() / 2] as f64 / 1e6,
            cpu[0] as f64 / 1e6
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// One analysis after an edit (its own function: `valgrind --tool=callgrind
/// --toggle-collect=latency_profile::edit_analysis` counts the edits without the first analysis).
#[inline(never)]
fn edit_analysis(ws: &Workspace, path: &Path, prev: &Analysis) -> Analysis {
    analyze_from(ws, path, Some(prev), &|| false).unwrap()
}

/// This thread's CPU time in ns (Linux: /proc/thread-self/schedstat, first field).
fn cpu_ns() -> Option<u64> {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}
