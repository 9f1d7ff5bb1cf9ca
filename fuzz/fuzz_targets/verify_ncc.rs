//! verify's reader of xCAM's `.NCC` files (the `xcam` family) on any text: a report with
//! located findings, never a panic, a hang or a blow-up.
#![no_main]

use libfuzzer_sys::fuzz_target;
use millpath_verify::{verify, Dialect, Options};

fuzz_target!(|text: &str| {
    let options = Options {
        dialect: Dialect::Xcam,
        top: Some(2.0),
        tool: Some(2.0),
        ..Default::default()
    };
    let r = verify(text, &options);
    let lines = text.split('\n').count();
    for f in &r.findings {
        assert!(f.line.is_none_or(|l| l >= 1 && l <= lines), "{f:?}");
    }
});
