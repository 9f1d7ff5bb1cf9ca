//! Whose rules the checker applies: the reference controller's, LinuxCNC's or grbl's.

/// Whose rules decide the feed-rate checks (and a few strictness details).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Dialect {
    /// F is modal and never reset (what the reference tool's programs assume).
    #[default]
    Reference,
    /// LinuxCNC's rs274ngc: G93/G94/G95 reset the feed rate (executed before F on the same
    /// line); nested comments are errors; axis words need a motion mode.
    LinuxCnc,
    /// grbl 1.1: F is kept across G94; leaving G93 resets it; starts in G00.
    Grbl,
}

impl Dialect {
    pub fn name(self) -> &'static str {
        match self {
            Dialect::Reference => "reference",
            Dialect::LinuxCnc => "linuxcnc",
            Dialect::Grbl => "grbl",
        }
    }
    /// The controller's name as shown in messages.
    pub fn controller(self) -> &'static str {
        match self {
            Dialect::Reference => "the reference controller",
            Dialect::LinuxCnc => "LinuxCNC",
            Dialect::Grbl => "grbl",
        }
    }
}

impl std::str::FromStr for Dialect {
    type Err = String;
    fn from_str(s: &str) -> Result<Dialect, String> {
        match s.to_ascii_lowercase().as_str() {
            "reference" => Ok(Dialect::Reference),
            "linuxcnc" => Ok(Dialect::LinuxCnc),
            "grbl" => Ok(Dialect::Grbl),
            other => Err(format!(
                "unknown dialect {other:?} (reference, linuxcnc or grbl)"
            )),
        }
    }
}
