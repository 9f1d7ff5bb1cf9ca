//! The state of the post's pass events (`pass.rs`), kept in the emitter: below it, so the
//! emitter holds it without importing the code that writes the events.

use crate::geom::P3;

/// The pass being written, and how many there were.
#[derive(Debug, Default)]
pub(crate) struct Passes {
    pub(super) open: Option<Open>,
    pub(super) count: i64,
}

#[derive(Debug)]
pub(super) struct Open {
    pub(super) number: i64,
    pub(super) lowest: f64,
    pub(super) feed: f64,
}

/// Where the tool is before the first move: above the origin at the start height.
pub(crate) fn start_position(sx: f64) -> P3 {
    P3 {
        x: 0.0,
        y: 0.0,
        z: sx,
    }
}
