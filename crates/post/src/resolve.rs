//! Finding a post: a built-in's name, or a post file read through the caller's reader.

use crate::error::{ErrorKind, PostError};
use crate::Post;

/// A post by name (built-in) or path: `read` reads a file (the caller's file system). A name
/// without `/`, `\` or `.toml` is a built-in's; anything else a file, relative to `base`.
pub fn resolve(
    name_or_path: &str,
    base: &std::path::Path,
    read: &dyn Fn(&std::path::Path) -> Result<String, String>,
) -> Result<Post, PostError> {
    let n = name_or_path.trim();
    let is_path = n.contains(['/', '\\']) || n.to_ascii_lowercase().ends_with(".toml");
    if !is_path {
        return crate::builtin::post(n).ok_or_else(|| PostError {
            file: n.to_string(),
            line: 0,
            column: 0,
            key: String::new(),
            kind: ErrorKind::Unknown(n.to_string(), crate::builtin::NAMES.join(", ")),
        });
    }
    let path = base.join(n);
    let file = path.display().to_string();
    let text = read(&path).map_err(|e| PostError {
        file: file.clone(),
        line: 0,
        column: 0,
        key: String::new(),
        kind: ErrorKind::Unreadable(e),
    })?;
    crate::load::load(&file, &text)
}
