//! What the machine is, as settings: the controller's dialect and the machine's limits.
//! Settings-level types, below `load/settings.rs` and the emitter that use them.

pub mod dialect;
pub mod grbl;
pub mod limits;
pub mod time_model;

pub use dialect::{Dialect, DEFAULT_SPINDLE_DWELL};
pub use grbl::{Grbl, GrblValues};
pub use limits::{Axes, Machine, DEFAULT_PATH_TOLERANCE};
pub use time_model::{Planner, TimeModel};
