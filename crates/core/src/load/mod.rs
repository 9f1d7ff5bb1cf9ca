//! Loading: the file system, settings, `millpath.toml`, name patterns, subpath search and the
//! process-wide caches of compiled patterns and parsed files.

pub mod clamps;
pub mod config;
pub mod fs;
pub mod name_regex;
pub mod names;
pub mod parse_cache;
pub mod paths;
pub mod regex_cache;
pub mod search;
pub mod session;
pub mod settings;
pub mod text_file;
