//! The machine's limits (`[machine]` in millpath.toml): per-axis velocity and acceleration
//! and the path tolerance, which the time model (`emit/timing/`) plans with.

use serde::Deserialize;

/// The path tolerance (G64 P, mm) when none is set.
pub const DEFAULT_PATH_TOLERANCE: f64 = 0.05;

/// One value per axis.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axes {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

impl Axes {
    /// The same value on every axis.
    pub fn all(v: f64) -> Axes {
        Axes { x: v, y: v, z: v }
    }
    pub fn values(&self) -> [(&'static str, f64); 3] {
        [("x", self.x), ("y", self.y), ("z", self.z)]
    }
}

/// The machine's limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Machine {
    /// Maximum velocity per axis (mm/min); sweeps run at it.
    pub max_velocity: Axes,
    /// MAX_ACCELERATION per axis (mm/s²).
    pub max_acceleration: Axes,
    /// G64 P: how far (mm) a blended corner may leave the programmed path.
    pub path_tolerance: f64,
}
