//! The DXF reader on any bytes: a drawing or an error, never a panic, a hang or a blow-up;
//! the extended mode's resolution of polylines and blocks likewise.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(d) = millpath_dxf::read_dxf(data) {
        let _ = millpath_dxf::explode::resolve(&d);
    }
});
