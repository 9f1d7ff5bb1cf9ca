//! File names of one compile: the input named on the command line completed (`.dxf` when
//! it has no known extension), and the prefix of its output files.

use std::path::{Path, PathBuf};

/// The input argument completed like the reference does: `.dxf` appended when missing.
pub fn complete_input(arg: &str) -> PathBuf {
    let lower = arg.to_ascii_lowercase();
    if lower.ends_with(".dxf") || lower.ends_with(".mpath") {
        PathBuf::from(arg)
    } else {
        PathBuf::from(format!("{arg}.dxf"))
    }
}

/// Output prefix: the input path minus its extension, plus the path's `R` suffix (public:
/// the command line finds the outputs of an earlier compile of a drawing by it).
pub fn output_prefix(input: &Path, suffix: &str) -> PathBuf {
    let s = input.to_string_lossy();
    let cut = match s.rfind('.') {
        Some(p) if !s[p..].contains('/') => &s[..p],
        _ => &s[..],
    };
    PathBuf::from(format!("{cut}{suffix}"))
}
