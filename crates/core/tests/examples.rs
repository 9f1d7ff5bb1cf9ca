//! The example drawings shipped in `examples/` are generated here, so they stay of our own
//! making and in step with the writer. `UPDATE_EXAMPLES=1 cargo test` rewrites them.

mod support;

use std::path::PathBuf;
use support::*;

fn plate() -> String {
    let l = "1234_1P";
    let mut d = Drawing::new();
    d.start(l, (0.0, 0.0), "M3x40 O2 T3 I1,5 B-0,2 D2,5")
        .end(l, (80.0, 0.0))
        .line(l, "DASHED", (0.0, 0.0), (10.0, 10.0), "")
        // pocket outline, milled through
        .line(l, "CONTINUOUS", (10.0, 10.0), (50.0, 10.0), "")
        .line(l, "CONTINUOUS", (50.0, 10.0), (50.0, 30.0), "")
        .line(l, "CONTINUOUS", (50.0, 30.0), (10.0, 30.0), "")
        .line(l, "CONTINUOUS", (10.0, 30.0), (10.0, 10.0), "")
        .line(l, "DASHED", (10.0, 10.0), (30.0, 20.0), "")
        // an 8 mm hole milled as a helix
        .circle(l, "CONTINUOUS", (30.0, 20.0), 4.0, "")
        .line(l, "DASHED", (30.0, 20.0), (60.0, 20.0), "")
        // a drilled 2 mm hole and a marking line
        .circle(l, "CONTINUOUS", (60.0, 20.0), 1.0, "")
        .line(l, "DIVIDE", (60.0, 20.0), (70.0, 20.0), "")
        .line(l, "DASHED", (70.0, 20.0), (80.0, 0.0), "");
    d.dxf()
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn example_drawings_are_current_and_compile() {
    let path = root().join("examples/plate/1234.1P.dxf");
    let text = plate();
    if std::env::var_os("UPDATE_EXAMPLES").is_some() {
        std::fs::write(&path, &text).unwrap();
    }
    let committed = std::fs::read_to_string(&path)
        .expect("examples/plate/1234.1P.dxf (run with UPDATE_EXAMPLES=1)");
    assert_eq!(
        committed, text,
        "example is stale: run UPDATE_EXAMPLES=1 cargo test -p millpath-core --test examples"
    );
    let run = compile(&[("1234.1P.dxf", text)], "1234.1P.dxf");
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    let body = run.body().join("\n");
    assert!(body.contains("MillHelix l=[30.000 20.000] r=4.000"));
    assert!(body.contains("Drill l=[60.000 20.000]"));
    // the mark is cut once at D2.5
    assert!(
        body.contains("MillLine s=[60.000 20.000] e=[70.000 20.000] fr=2.500 to=2.500"),
        "{body}"
    );
}
