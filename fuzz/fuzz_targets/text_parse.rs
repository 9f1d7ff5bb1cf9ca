//! The text-language parser on any text: a tree with error nodes, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|src: &str| {
    let _ = millpath_syntax::parse(src);
});
