//! What the machine is, as settings: the controller's dialect, how the checker reads its
//! post's programs, and the machine's limits.
//! Settings-level types, below `load/settings.rs` and the emitter that use them.

pub mod checked;
pub mod dialect;
pub mod grbl;
pub mod limits;
pub mod time_model;

pub use checked::{NotRead, Reading};
pub use dialect::{Dialect, DEFAULT_SPINDLE_DWELL};
pub use grbl::{Grbl, GrblValues};
pub use limits::{Axes, Machine, DEFAULT_PATH_TOLERANCE};
pub use time_model::{Planner, TimeModel, FEED_OVERRIDE_RANGE, NO_FEED_OVERRIDE};
