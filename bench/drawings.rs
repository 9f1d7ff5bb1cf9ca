//! Big drawings for benchmarks, built with `millpath_dxf::writer::DxfWriter` like the test
//! drawings of `crates/core/tests/support`.
//!
//! Shared by `crates/core/examples/gen_drawings.rs` (the command-line generator) and
//! `crates/cli/benches/check.rs` (criterion), which include this file as a module. Nothing it
//! generates is committed: callers write into temporary directories.
#![allow(dead_code)]

use millpath_dxf::writer::DxfWriter;
use std::path::{Path, PathBuf};

/// Parameter text of every generated path start: O2 T2 I1,2 B-0,3 (two passes).
pub const PARAMS: &str = "O2 T2 I1,2 B-0,3";

/// Mill segments per row before a chain turns back (keeps the drawing compact).
const ROW: usize = 100;

type Pt = (f64, f64);

fn start(w: &mut DxfWriter, layer: &str, at: Pt) {
    w.circle(layer, Some("PHANTOM"), at, 0.5);
    let lines: Vec<&str> = PARAMS.split(' ').collect();
    w.mtext(layer, at, 0.5, &lines);
}

fn end(w: &mut DxfWriter, layer: &str, at: Pt) {
    w.circle(layer, Some("PHANTOM"), at, 1.0);
}

/// The points of a serpentine of `n` connected segments from `origin`: rows of zigzags
/// (x steps of 1 mm, y alternating by 1 mm), one step up by 3 mm between rows. No two
/// segments overlap or cross, and every inner point joins exactly two segments.
fn serpentine(origin: Pt, n: usize) -> Vec<Pt> {
    let mut pts = Vec::with_capacity(n + 1);
    let (mut x, mut base) = (0i64, 0i64);
    let mut dir = 1i64;
    let mut col = 0usize; // zigzag steps done in this row
    pts.push((origin.0, origin.1));
    for _ in 0..n {
        if col == ROW {
            base += 3;
            dir = -dir;
            col = 0;
        } else {
            x += dir;
            col += 1;
        }
        let y = base + (col % 2) as i64;
        pts.push((origin.0 + x as f64, origin.1 + y as f64));
    }
    pts
}

/// Path layer `NNNN_MP` for path `NNNN.MP`.
pub fn layer(file: u32, path: usize) -> String {
    format!("{file:04}_{path}P")
}

/// (a) One path (`1000.1P`) whose mill segments form ONE chain of `n` connected CONTINUOUS
/// lines from the start marker to the end marker.
pub fn one_chain(n: usize) -> String {
    let l = layer(1000, 1);
    let mut w = DxfWriter::new();
    let pts = serpentine((0.0, 0.0), n);
    start(&mut w, &l, pts[0]);
    end(&mut w, &l, pts[n]);
    for s in pts.windows(2) {
        w.line(&l, Some("CONTINUOUS"), s[0], s[1]);
    }
    w.finish()
}

/// (b) One path (`1000.1P`) with `n` mill segments in chains of `chain_len` (at most 100)
/// connected segments, 100 chains a row; DASHED sweeps lead from the end of each chain to
/// the start of the next (between rows around the row, so that no sweep crosses a chain).
pub fn short_chains(n: usize, chain_len: usize) -> String {
    assert!(chain_len > 0 && chain_len <= ROW && n >= chain_len);
    let l = layer(1000, 1);
    let mut w = DxfWriter::new();
    let chains = n / chain_len;
    let pitch = (chain_len + 5) as f64;
    let mut last: Option<Pt> = None;
    let mut first = (0.0, 0.0);
    for c in 0..chains {
        let len = if c + 1 == chains {
            n - c * chain_len
        } else {
            chain_len
        };
        let (col, row) = ((c % ROW) as f64, (c / ROW) as f64);
        let pts = serpentine((col * pitch, row * 5.0), len);
        match last {
            None => first = pts[0],
            Some(p) if c % ROW == 0 => {
                // around: right, along the gap between the rows, down to the next start
                let a = (p.0 + 2.0, row * 5.0 - 2.0);
                let b = (pts[0].0 - 2.0, row * 5.0 - 2.0);
                w.line(&l, Some("DASHED"), p, a);
                w.line(&l, Some("DASHED"), a, b);
                w.line(&l, Some("DASHED"), b, pts[0]);
            }
            Some(p) => {
                w.line(&l, Some("DASHED"), p, pts[0]);
            }
        }
        for s in pts.windows(2) {
            w.line(&l, Some("CONTINUOUS"), s[0], s[1]);
        }
        last = Some(pts[len]);
    }
    start(&mut w, &l, first);
    end(&mut w, &l, last.unwrap_or(first));
    w.finish()
}

/// (b') One file (`1000.dxf`) with `paths` paths `1000.1P` … each of one chain of
/// `per_path` (at most 100) segments.
pub fn many_paths(paths: usize, per_path: usize) -> String {
    assert!(per_path > 0 && per_path <= ROW);
    let mut w = DxfWriter::new();
    for p in 0..paths {
        let l = layer(1000, p + 1);
        let origin = (((p % ROW) * (per_path + 5)) as f64, ((p / ROW) * 5) as f64);
        let pts = serpentine(origin, per_path);
        start(&mut w, &l, pts[0]);
        end(&mut w, &l, pts[per_path]);
        for s in pts.windows(2) {
            w.line(&l, Some("CONTINUOUS"), s[0], s[1]);
        }
    }
    w.finish()
}

/// The example drawing of the repository (`examples/plate/1234.1P.dxf`).
pub const EXAMPLE_PLATE: &str = include_str!("../examples/plate/1234.1P.dxf");

/// Our own small set of drawings (file name, content) that copies are made of: the example
/// plate, a chain of 50 segments, 100 segments in chains of 10, and 20 paths of 5 segments.
/// All of them check without errors.
pub fn own_set() -> Vec<(String, String)> {
    let renamed = |text: String, file: u32| text.replace("1000_", &format!("{file:04}_"));
    vec![
        ("1234.1P.dxf".into(), EXAMPLE_PLATE.to_string()),
        ("1001.1P.dxf".into(), renamed(one_chain(50), 1001)),
        ("1002.1P.dxf".into(), renamed(short_chains(100, 10), 1002)),
        ("1003.dxf".into(), renamed(many_paths(20, 5), 1003)),
    ]
}

/// (c) `k` copies of a set of drawings: `out/copy00000/…`, `out/copy00001/…`, each a
/// folder with every file of the set (so subpaths are found beside their parents). Returns
/// the written files in the order `check` visits them.
pub fn copies(set: &[(String, Vec<u8>)], k: usize, out: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut files = Vec::with_capacity(k * set.len());
    for i in 0..k {
        let dir = out.join(format!("copy{i:05}"));
        std::fs::create_dir_all(&dir)?;
        let mut names: Vec<&(String, Vec<u8>)> = set.iter().collect();
        names.sort_by(|a, b| a.0.cmp(&b.0));
        for (name, content) in names {
            let f = dir.join(name);
            std::fs::write(&f, content)?;
            files.push(f);
        }
    }
    Ok(files)
}

/// `copies` of `own_set` until there are at least `n_files` files.
pub fn own_copies(n_files: usize, out: &Path) -> std::io::Result<Vec<PathBuf>> {
    let set: Vec<(String, Vec<u8>)> = own_set()
        .into_iter()
        .map(|(n, t)| (n, t.into_bytes()))
        .collect();
    copies(&set, n_files.div_ceil(set.len()), out)
}
