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

/// A `Q` text with `(` once made a nested comment (LinuxCNC rejects it, the second opinion
/// objected). It is now written safely (`(` → `[`), with the warning `Msg::CommentTextChanged` at the element whose
/// text it is, and the second opinion has nothing to object to, in every dialect.
#[test]
fn a_q_text_with_a_parenthesis_is_written_safely_at_its_element() {
    use millpath_core::machine::Dialect;
    for dialect in [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl] {
        let mut d = Drawing::new();
        d.start(L, (0.0, 0.0), "O2 T2 I1,2 B-0,3")
            .end(L, (20.0, 0.0))
            .line(L, "CONTINUOUS", (0.0, 0.0), (20.0, 0.0), "Qslot(outer");
        let run = compile_with(
            &[("1000.1P.dxf", d.dxf())],
            "1000.1P.dxf",
            millpath_core::Settings {
                dialect,
                ..settings()
            },
        );
        assert!(
            !run.diags.iter().any(|d| d.msg == Msg::SecondOpinion),
            "{dialect}: {:?}",
            run.messages()
        );
        let warning = run
            .diags
            .iter()
            .find(|d| d.msg == Msg::CommentTextChanged)
            .unwrap_or_else(|| panic!("{dialect}: no warning: {:?}", run.messages()));
        assert_eq!(warning.severity, Severity::Warning);
        assert!(
            warning.message(Default::default()).contains("'slot[outer'"),
            "{:?}",
            run.messages()
        );
        assert!(
            matches!(&warning.origin, Origin::Entity(e) if e.code_name == "LINE"),
            "{:?}",
            warning.origin
        );
        let program = run.output("_Milling.gcode");
        assert!(program.contains("(Q:slot[outer)"), "{program}");
    }
}
