//! One file per subcommand; `main.rs` only parses the command line and dispatches here.
//!
//! One file per subcommand: `compile.rs` (each drawing in a session of its own with its nearest
//! millpath.toml; the good ones written, a summary of those not), `check.rs` (files checked in
//! parallel, rayon, one `Session` per file; printed in input order; progress bar on a terminal from
//! 50 files), `verify.rs` (`--surface`: the map measured on the machine over the program's record),
//! `adjust_z.rs` (`--probe-log`: the log read bounded, one program), `dxf2text.rs`, `text2dxf.rs`
//! (its own options; refuses to overwrite a drawing it would damage, `--into`, `--force`), `fmt.rs`
//! (keeps line ends and a BOM, writes UTF-16 as UTF-8, names mixed line ends), `render.rs`, `diff.rs` (versions from files or git, the report of
//! `millpath-history`), `merge.rs` (git's merge driver; the merge is `millpath_history::merge`),
//! `pathdxf2gcode.rs`, `pathgcodeadjustz.rs`.

pub mod adjust_z;
pub mod check;
pub mod compile;
pub mod diff;
pub mod dxf2text;
pub mod fmt;
pub mod merge;
pub mod pathdxf2gcode;
pub mod pathgcodeadjustz;
pub mod post;
pub mod render;
pub mod text2dxf;
pub mod verify;
