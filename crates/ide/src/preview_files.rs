//! The G-code of one path as `millpath compile` writes it: what `preview.rs` computes, and
//! what an analysis keeps of it for its version.

/// The G-code of one path as `millpath compile` writes it.
#[derive(Debug, Clone, PartialEq)]
pub struct Preview {
    pub path: String,
    /// `_Milling.gcode`, or `_Clean.gcode` when the path has probes.
    pub gcode: String,
    pub probing: Option<String>,
    pub z_txt: Option<String>,
    /// The five statistics lines.
    pub stats: Vec<String>,
    /// The exact estimated time, `h:mm:ss` (the statistics keep whole minutes); empty when
    /// the path is refused.
    pub time: String,
    /// Errors that would stop `millpath compile` from writing the files.
    pub errors: Vec<String>,
}
