//! The text files read whole around a compile (`_Z.txt`, `_Clean.gcode`, `_Probing.gcode`,
//! probe logs, `millpath.toml`, programs to verify), in any encoding `.mpath` files may
//! have: core's `load/text_file.rs` decodes them (UTF-8 with or without a mark, UTF-16 with
//! one, as Notepad saves "Unicode").

use millpath_core::load::text_file;
use std::path::Path;

/// The text of the file `path`.
pub fn text(path: impl AsRef<Path>) -> std::io::Result<String> {
    text_file::text_of(std::fs::read(path)?)
}
