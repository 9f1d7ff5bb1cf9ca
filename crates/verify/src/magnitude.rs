//! The largest magnitude of any number a program may hold: the parser refuses larger ones
//! (`parse.rs`), and the surface record (`surface.rs`) and adjusted programs (`adjusted.rs`)
//! are held to the same bound.

/// Largest accepted magnitude of any number.
pub const MAX_MAGNITUDE: f64 = 1e6;
