//! Where the time of one analysis goes (development aid): `cargo run --release -p millpath-ide --example timing`.
use std::time::Instant;

fn main() {
    let mut s = String::from("path 3000.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n");
    let n = 1998;
    let mut lines = String::new();
    for i in 0..n {
        let kind = if i % 4 == 3 { "sweep" } else { "mill" };
        let y0 = if i % 2 == 0 { 0.0 } else { 5.0 };
        lines.push_str(&format!(
            "  {kind} ({i}, {y0}) -> ({}, {})\n",
            i + 1,
            5.0 - y0
        ));
    }
    s.push_str(&format!("  end ({n}, 0)\n{lines}}}\n"));
    let dir = std::env::temp_dir().join("millpath-timing");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("3000.mpath");
    std::fs::write(&path, &s).unwrap();
    let ws = millpath_ide::Workspace::default();
    for _ in 0..3 {
        let t = Instant::now();
        let (ast, _) = millpath_syntax::parse(&s);
        let t_parse = t.elapsed();
        let t = Instant::now();
        let a = millpath_ide::analyze(&ws, &path);
        let t_all = t.elapsed();
        println!(
            "parse {:?}, analyze {:?} ({} diags, {} paths)",
            t_parse,
            t_all,
            a.diagnostics.len(),
            ast.paths().count()
        );
    }
}
