//! Texts are assigned to elements in file order (reference-input.md §2.4): when two texts of
//! one kind want the same element, a CAD program that re-saves the drawing in another order
//! can move a text to another element. That place gets a warning (MP132); the assignment
//! itself stays the reference's.

mod support;

use millpath_core::Msg;
use support::*;

/// Two large circles on the path layer (any circle but an end marker may take a text), the
/// path's start and end markers, and `texts` (position, value, TEXT or MTEXT) in that order.
fn drawing(texts: &[((f64, f64), &str, bool)]) -> Drawing {
    let mut d = Drawing::new();
    d.start(L, (0.0, 0.0), "O2 T2 M20x2 I2 B-1")
        .end(L, (40.0, 0.0))
        .line(L, "DASHED", (0.0, 0.0), (40.0, 0.0), "");
    d.w.circle(L, Some("CONTINUOUS"), (10.0, 0.0), 3.0);
    d.w.circle(L, Some("CONTINUOUS"), (16.0, 0.0), 3.0);
    for &(at, value, mtext) in texts {
        if mtext {
            d.w.mtext(L, at, 0.5, &[value]);
        } else {
            d.w.text(L, at, 0.5, value);
        }
    }
    d
}

fn warned(run: &Run, msg: Msg) -> Vec<String> {
    run.diags
        .iter()
        .filter(|d| d.msg == msg)
        .map(|d| d.message(millpath_core::Lang::En))
        .collect()
}

#[test]
fn a_text_whose_element_an_earlier_text_took_is_warned_in_either_order() {
    // both texts are nearer to the circle at x = 10 than to the one at x = 16
    let a = ((12.0, 0.0), "F100", false);
    let b = ((12.5, 0.0), "F200", false);
    for (first, second) in [(a, b), (b, a)] {
        let run = compile_one(&drawing(&[first, second]));
        let w = warned(&run, Msg::TextTakenFirst);
        assert_eq!(w.len(), 1, "{:?}", run.messages());
        assert!(
            w[0].contains(&format!("text '{}'", second.1))
                && w[0].contains(&format!("text '{}' took", first.1)),
            "{}",
            w[0]
        );
    }
}

/// Checks `texts`: every text finds an element (no NoOverlap) and none is warned (MP132).
fn assert_unwarned(texts: &[((f64, f64), &str, bool)]) {
    let run = compile_one(&drawing(texts));
    let shown = run.messages();
    assert!(!run.errors().contains(&Msg::NoOverlap), "{shown:?}");
    assert!(warned(&run, Msg::TextTakenFirst).is_empty(), "{shown:?}");
}

#[test]
fn equal_texts_and_texts_of_the_other_kind_are_no_order_question() {
    // the same value on either circle gives the same parameters
    assert_unwarned(&[((12.0, 0.0), "F100", false), ((12.5, 0.0), "F100", false)]);
    // every TEXT is assigned before every MTEXT, whatever the file order
    assert_unwarned(&[((12.0, 0.0), "F100", true), ((12.5, 0.0), "F200", false)]);
}

#[test]
fn texts_each_nearest_to_their_own_free_element_are_not_warned() {
    assert_unwarned(&[((11.0, 0.0), "F100", false), ((15.0, 0.0), "F200", false)]);
}

#[test]
fn the_warnings_read_in_german_too() {
    let run = compile_one(&drawing(&[
        ((12.0, 0.0), "F100", false),
        ((12.5, 0.0), "F200", false),
    ]));
    let d = run
        .diags
        .iter()
        .find(|d| d.msg == Msg::TextTakenFirst)
        .unwrap();
    let de = d.message(millpath_core::Lang::De);
    assert!(de.contains("Reihenfolge") && de.contains("'F200'"), "{de}");
}
