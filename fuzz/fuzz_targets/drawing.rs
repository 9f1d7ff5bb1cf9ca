//! Structure-aware: valid drawings (paths, chains, markers, holes, subpaths across files,
//! probes, hostile parameter texts, three dialects) built from the fuzzer's bytes, compiled
//! from their text and from their DXF: no panic, finite output, the same G-code from both
//! front-ends, and no error of the independent checker (`src/invariants.rs`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| millpath_fuzz::run(data));
