//! The formatter: a file without syntax errors formats to text that parses without errors
//! and formats to itself again.
#![no_main]

use libfuzzer_sys::fuzz_target;
use millpath_syntax::{format, parse};

fuzz_target!(|src: &str| {
    let (tree, errors) = parse(src);
    if !errors.is_empty() {
        return;
    }
    let once = format(&tree, src);
    let (tree2, errors2) = parse(&once);
    assert!(
        errors2.is_empty(),
        "formatted text does not parse: {errors2:?}\n{once}"
    );
    let twice = format(&tree2, &once);
    assert_eq!(once, twice, "formatting is not idempotent");
});
