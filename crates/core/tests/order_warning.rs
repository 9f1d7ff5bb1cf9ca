//! The warning where the drawing's entity order decides the walk (MP118), on drawings of our
//! own: where it comes, where not, and that its N value pins the choice without changing
//! the G-code.

mod support;

use millpath_core::diag::{Msg, Origin};
use support::*;

fn square(first_text: &str) -> Drawing {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1 B0,5")
        .end(L, (0.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), first_text)
        .line(L, "CONTINUOUS", (10.0, 0.0), (10.0, 10.0), "")
        .line(L, "CONTINUOUS", (10.0, 10.0), (0.0, 10.0), "")
        .line(L, "CONTINUOUS", (0.0, 10.0), (0.0, 0.0), "");
    d
}

#[test]
fn a_loop_started_at_a_corner_warns_at_the_line_taken_and_n_pins_it() {
    let run = compile_one(&square(""));
    assert!(run.errors().is_empty(), "{:?}", run.messages());
    assert_eq!(run.warnings(), [Msg::OrderDecides]);
    let d = &run.diags[0];
    assert_eq!(d.args, ["2", "N9997"]);
    let Origin::Entity(e) = &d.origin else {
        panic!("{:?}", d.origin)
    };
    assert_eq!((e.code_name, e.pos.x, e.pos.y), ("LINE", 0.0, 0.0));
    assert_eq!(d.related.len(), 1, "the other edge at the corner");
    let pinned = compile_one(&square("N9997"));
    assert!(pinned.diags.is_empty(), "{:?}", pinned.messages());
    assert_eq!(
        pinned.output("_Milling.gcode"),
        run.output("_Milling.gcode"),
        "the pin keeps the G-code"
    );
}

#[test]
fn duplicates_are_no_choice() {
    // out, back and out again along the same line, the way back drawn the other way round
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1 B0,5")
        .end(L, (10.0, 0.0))
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "CONTINUOUS", (10.0, 0.0), (0.0, 0.0), "")
        .line(L, "CONTINUOUS", (0.0, 0.0), (10.0, 0.0), "");
    let run = compile_one(&d);
    assert!(run.diags.is_empty(), "{:?}", run.messages());
}

#[test]
fn a_choice_no_single_n_can_pin_gets_the_general_advice() {
    // two branches, each marked on the way out and milled back: at the second visit of the
    // star point, N9997 on the branch taken would win the first visit already
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 I1 B0,5 D1")
        .end(L, (0.0, 0.0))
        .line(L, "DIVIDE", (0.0, 0.0), (10.0, 0.0), "")
        .line(L, "CONTINUOUS", (10.0, 0.0), (0.0, 0.0), "")
        .line(L, "DIVIDE", (0.0, 0.0), (0.0, 10.0), "")
        .line(L, "CONTINUOUS", (0.0, 10.0), (0.0, 0.0), "");
    let run = compile_one(&d);
    assert!(run.errors().is_empty(), "{:?}", run.messages());
    let got: Vec<(Msg, &Vec<String>)> = run.diags.iter().map(|d| (d.msg, &d.args)).collect();
    assert_eq!(
        got,
        [
            (Msg::OrderDecides, &vec!["4".to_string(), "N9997".into()]),
            (Msg::OrderDecidesNoPin, &vec!["2".to_string()])
        ]
    );
}
