//! One file per subcommand; `main.rs` only parses the command line and dispatches here.

pub mod adjust_z;
pub mod check;
pub mod compile;
pub mod dxf2text;
pub mod fmt;
pub mod pathdxf2gcode;
pub mod pathgcodeadjustz;
pub mod post;
pub mod render;
pub mod text2dxf;
pub mod verify;
