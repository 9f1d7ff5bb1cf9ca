//! The built-in posts: files in `posts/`, embedded. `millpath post show NAME` prints one as
//! an editable file; loading that file gives the same post.

use crate::Post;
use std::sync::OnceLock;

/// The built-in posts' names, in the order `millpath post list` shows them.
pub const NAMES: [&str; 10] = [
    "reference",
    "linuxcnc",
    "grbl",
    "mach3",
    "uccnc",
    "centroid",
    "fluidnc",
    "grblhal",
    "marlin",
    "xcam",
];

const SOURCES: [&str; 10] = [
    include_str!("../posts/reference.toml"),
    include_str!("../posts/linuxcnc.toml"),
    include_str!("../posts/grbl.toml"),
    include_str!("../posts/mach3.toml"),
    include_str!("../posts/uccnc.toml"),
    include_str!("../posts/centroid.toml"),
    include_str!("../posts/fluidnc.toml"),
    include_str!("../posts/grblhal.toml"),
    include_str!("../posts/marlin.toml"),
    include_str!("../posts/xcam.toml"),
];

/// The text of a built-in post.
pub fn source(name: &str) -> Option<&'static str> {
    let i = NAMES
        .iter()
        .position(|n| n.eq_ignore_ascii_case(name.trim()))?;
    Some(SOURCES[i])
}

/// A built-in post, loaded once per process.
pub fn get(name: &str) -> Option<&'static Post> {
    static LOADED: OnceLock<Vec<Post>> = OnceLock::new();
    let i = NAMES
        .iter()
        .position(|n| n.eq_ignore_ascii_case(name.trim()))?;
    let all = LOADED.get_or_init(|| {
        NAMES
            .iter()
            .zip(SOURCES)
            .map(|(n, s)| {
                crate::load(&format!("builtin:{n}"), s)
                    .unwrap_or_else(|e| panic!("built-in post {n} is invalid: {e}"))
            })
            .collect()
    });
    Some(&all[i])
}

/// A built-in post as an owned value.
pub fn post(name: &str) -> Option<Post> {
    get(name).cloned()
}
