//! Writes a drawing with ONE path of N connected CONTINUOUS lines (a zigzag), to time the
//! pass order of long chains (§7.2):
//!
//! ```text
//! cargo run -p millpath-core --example long_chain -- 100000 /tmp/lc/1000.1P.dxf
//! millpath check -f 150 -v 500 -s 15 /tmp/lc/1000.1P.dxf
//! ```

use millpath_dxf::writer::DxfWriter;

fn main() {
    let mut args = std::env::args().skip(1);
    let n: usize = args
        .next()
        .and_then(|a| a.parse().ok())
        .expect("usage: long_chain N OUT.dxf");
    let out = args.next().expect("usage: long_chain N OUT.dxf");
    let layer = "1000_1P";
    let pt = |i: usize| (i as f64 * 2.0, (i % 2) as f64 * 3.0);
    let mut w = DxfWriter::new();
    // start marker with its parameters (one MTEXT line each), end marker
    w.circle(layer, Some("PHANTOM"), pt(0), 0.5);
    w.mtext(layer, pt(0), 0.5, &["O2", "T2", "I1,2", "B-0,3"]);
    w.circle(layer, Some("PHANTOM"), pt(n), 1.0);
    for i in 0..n {
        w.line(layer, Some("CONTINUOUS"), pt(i), pt(i + 1));
    }
    std::fs::write(&out, w.finish()).expect("write the drawing");
    eprintln!("{n} lines -> {out}");
}
