//! The whole compiler, as `compile` and as `check` (which is what the language server runs),
//! on any drawing, DXF or text: no panic, no hang, no blow-up, and whatever it writes holds
//! only finite numbers within ±1e6.
#![no_main]

use libfuzzer_sys::fuzz_target;
use millpath_core::{compile_file, MemFileSystem, Session, Settings};
use std::path::Path;

fn assert_sane(gcode: &str) {
    for line in gcode.lines() {
        assert!(!line.contains("NaN") && !line.contains("inf"), "{line}");
        for word in line.split([' ', '(', ')', '[', ']', '=', '+', '*']) {
            if word.starts_with(|c: char| "XYZIJF".contains(c)) {
                if let Ok(v) = word[1..].parse::<f64>() {
                    assert!(v.abs() <= 1e6, "{line}");
                }
            }
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&kind, body)) = data.split_first() else {
        return;
    };
    // one byte chooses the front-end, so both get the same corpus
    let name = if kind & 1 == 0 {
        "1000.1P.dxf"
    } else {
        "1000.1P.mpath"
    };
    let mut fs = MemFileSystem::default();
    fs.add(name, body.to_vec());
    for check in [false, true] {
        let settings = Settings {
            check,
            ..Settings::default()
        };
        let mut session = Session::new(settings, &fs).expect("default settings");
        let outcome = compile_file(&mut session, Path::new(name), "fuzz");
        for o in &outcome.outputs {
            assert_sane(&o.content);
        }
    }
});
