//! The cut part of the toolpath view: the checker's stock after the program, exported with
//! its lowerings in program order; its resolution from `cut_cell`.

mod support;

use base64::Engine;
use millpath_ide::toolpath;
use support::{p, workspace};

const SLOT: &str = "path 3001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2 S10\n  end (60, 0)\n  sweep (0, 0) -> (10, 0)\n  mill (10, 0) -> (50, 0)\n  sweep (50, 0) -> (60, 0)\n}\n";

fn floats(v: &serde_json::Value) -> Vec<f32> {
    let raw = base64::engine::general_purpose::STANDARD
        .decode(v.as_str().unwrap())
        .unwrap();
    raw.chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

#[test]
fn the_cut_part_is_the_stock_after_the_program_at_the_checkers_resolution() {
    let (dir, ws) = workspace(&[("3001.mpath", SLOT)]);
    let file = p(dir.path(), "3001.mpath");
    let tp = toolpath(&ws, &file, None).unwrap();
    let cut = &tp["cut"];
    assert_eq!(cut["cell"], 0.25);
    assert_eq!(cut["top"], 3.0);
    let heights = floats(&cut["heights"]);
    let (nx, ny) = (
        cut["nx"].as_u64().unwrap() as usize,
        cut["ny"].as_u64().unwrap() as usize,
    );
    assert_eq!(heights.len(), nx * ny);
    let lowest = heights.iter().cloned().fold(f32::INFINITY, f32::min);
    assert_eq!(lowest, -0.2);
    assert_eq!(cut["lowest"].as_f64().unwrap() as f32, -0.2);
    // the lowerings, replayed in order, give the heights after the program
    let cells = base64::engine::general_purpose::STANDARD
        .decode(cut["cells"].as_str().unwrap())
        .unwrap();
    let zs = floats(&cut["z"]);
    let mut replay = vec![3.0f32; nx * ny];
    for (k, z) in cells.chunks_exact(4).zip(&zs) {
        replay[u32::from_le_bytes([k[0], k[1], k[2], k[3]]) as usize] = *z;
    }
    assert_eq!(replay, heights);
    // the slot's centre line is at its depth, a point 1.5 mm beside it untouched
    let at = |x: f64, y: f64| {
        let (x0, y0, c) = (
            cut["x0"].as_f64().unwrap(),
            cut["y0"].as_f64().unwrap(),
            0.25,
        );
        heights[((y - y0) / c) as usize * nx + ((x - x0) / c) as usize]
    };
    assert_eq!(at(30.1, 0.1), -0.2);
    assert_eq!(at(30.1, 1.6), 3.0);
    // cut_cell sets the resolution
    std::fs::write(
        dir.path().join("millpath.toml"),
        "feed = 300\nsweep_speed = 1000\nsweep_height = 10\ncut_cell = 0.5\n",
    )
    .unwrap();
    let tp = toolpath(&ws, &file, None).unwrap();
    assert_eq!(tp["cut"]["cell"], 0.5);
}
