//! The DXF reader on any bytes: a drawing or an error, never a panic, a hang or a blow-up.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = millpath_dxf::read_dxf(data);
});
