//! Every program `compile` writes gets a second opinion from the independent G-code checker;
//! its findings come back as warnings at the element that wrote the line.

mod support;

use millpath_core::diag::{Msg, Origin, Severity};
use support::*;

#[test]
fn clean_programs_get_no_remarks() {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1,2 B-0,3")
        .end(L, (30.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "DASHED", (10.0, 0.0), (20.0, 0.0), "")
        .circle(L, "CONTINUOUS", (20.0, 0.0), 3.0, "")
        .line(L, "DASHED", (20.0, 0.0), (30.0, 0.0), "");
    let run = compile_one(&d);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    assert!(!run.outputs.is_empty());
}

#[test]
fn a_nested_comment_is_reported_at_the_element_that_wrote_it() {
    // the Q text is copied into a comment; its `(` nests comments, which LinuxCNC rejects
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1,2 B-0,3")
        .end(L, (20.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (20.0, 0.0), "Qslot(outer");
    let run = compile_one(&d);
    let remark = run
        .diags
        .iter()
        .find(|d| d.msg == Msg::SecondOpinion)
        .unwrap_or_else(|| panic!("no second opinion: {:?}", run.messages()));
    assert_eq!(remark.severity, Severity::Warning);
    let text = remark.message(Default::default());
    assert!(text.contains("Q:slot(outer"), "{text}");
    assert!(
        matches!(&remark.origin, Origin::Entity(e) if e.code_name == "LINE"),
        "{:?}",
        remark.origin
    );
    // a warning only: the reference dialect's program is still written, byte for byte
    assert!(!run.outputs.is_empty());
}

#[test]
fn for_a_real_controller_an_objection_stops_the_write() {
    use millpath_core::emit::dialect::Dialect;
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1,2 B-0,3")
        .end(L, (20.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (20.0, 0.0), "Qslot(outer");
    let run = compile_with(
        &[("1000.1P.dxf", d.dxf())],
        "1000.1P.dxf",
        millpath_core::Settings {
            dialect: Dialect::LinuxCnc,
            ..settings()
        },
    );
    let remark = run
        .diags
        .iter()
        .find(|d| d.msg == Msg::SecondOpinion)
        .unwrap_or_else(|| panic!("no second opinion: {:?}", run.messages()));
    assert_eq!(remark.severity, Severity::Error);
    assert!(
        run.outputs.is_empty(),
        "a program LinuxCNC rejects was written"
    );
    // without the nested comment the same drawing is written
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1,2 B-0,3")
        .end(L, (20.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (20.0, 0.0), "Qslot-outer");
    let run = compile_with(
        &[("1000.1P.dxf", d.dxf())],
        "1000.1P.dxf",
        millpath_core::Settings {
            dialect: Dialect::LinuxCnc,
            ..settings()
        },
    );
    assert!(run.diags.is_empty(), "{:?}", run.messages());
    assert!(!run.outputs.is_empty());
}
