//! The controller a program is written for (`dialect =` in millpath.toml, `--dialect`): a
//! setting, below the emitter that writes for it (`emit/dialect.rs`).

use serde::Deserialize;

/// The controller a program is written for.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Dialect {
    /// PathDxf2GCode's output, byte-identical (the default).
    #[default]
    Reference,
    /// LinuxCNC (rs274ngc).
    #[serde(rename = "linuxcnc")]
    LinuxCnc,
    /// GRBL 1.1.
    Grbl,
}

impl Dialect {
    pub const ALL: [Dialect; 3] = [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl];

    pub fn name(self) -> &'static str {
        match self {
            Dialect::Reference => "reference",
            Dialect::LinuxCnc => "linuxcnc",
            Dialect::Grbl => "grbl",
        }
    }

    pub fn from_name(name: &str) -> Option<Dialect> {
        Dialect::ALL
            .into_iter()
            .find(|d| d.name().eq_ignore_ascii_case(name.trim()))
    }
}

impl std::fmt::Display for Dialect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Seconds the program waits after starting the spindle, unless set.
pub const DEFAULT_SPINDLE_DWELL: f64 = 2.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for d in Dialect::ALL {
            assert_eq!(Dialect::from_name(d.name()), Some(d));
        }
        assert_eq!(Dialect::from_name("LinuxCNC"), Some(Dialect::LinuxCnc));
        assert_eq!(Dialect::from_name("mach3"), None);
        assert_eq!(Dialect::default(), Dialect::Reference);
    }
}
