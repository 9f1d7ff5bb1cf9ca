//! Whose rules the checker applies: a family of controllers and how it reads a line.
//!
//! A post-processor declares its family; the caller maps it to a [`Dialect`]:
//!
//! | family | dialect | controllers | reads |
//! |---|---|---|---|
//! | — | `Reference` | PathDxf2GCode's programs | rs274 lines, F never reset |
//! | `rs274` | `LinuxCnc` | LinuxCNC, Mach3/4, UCCNC, Centroid | `( )` and `;` comments, `%`, `N` first, `G4 P` seconds |
//! | `grbl` | `Grbl` | GRBL 1.1, FluidNC, grblHAL | `( )` and `;` comments, no `%`, `N` anywhere, `G4 P` seconds |
//! | `marlin` | `Marlin` | Marlin routers | `;` comments only, no `%`, one command a line, no modal motion, `G4 P` ms / `S` s, no M30 |
//! | `xcam` | `Xcam` | xCAM's `.NCC` exchange format | `ncc.rs`: contours, millings, drillings rebuilt as moves |
//!
//! A line number is a whole number from 0 to the family's largest; above 1000000 every
//! number is absurd to the checker, whatever the controller takes (GRBL 10000000).
//!
//! Mach3's `G4 P` is seconds or milliseconds by a setting ("G04 dwell param in ms"): the
//! `rs274` family assumes seconds, Mach3's setting off.

/// Whose rules decide the feed-rate checks and how a line is read ([`Dialect::rules`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Dialect {
    /// F is modal and never reset (what the reference tool's programs assume).
    #[default]
    Reference,
    /// The `rs274` family, by LinuxCNC's rs274ngc: G93/G94/G95 reset the feed rate (executed
    /// before F on the same line); nested comments are errors; axis words need a motion mode.
    LinuxCnc,
    /// The `grbl` family, by grbl 1.1: F is kept across G94; leaving G93 resets it; starts in
    /// G00.
    Grbl,
    /// The `marlin` family: Marlin firmware on a router (one command a line, `;` comments).
    Marlin,
    /// The `xcam` family: xCAM's exchange format (`.NCC`), no G-code: its contours, millings
    /// and drillings are read by `ncc.rs`, which hands their moves to the machine model.
    Xcam,
}

/// The unit of `G4 P`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DwellUnit {
    Seconds,
    Milliseconds,
}

/// How a family reads a line: the rules the checker holds a program to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rules {
    /// The largest line number `N` the controller takes (the checker's bound on numbers,
    /// 1000000, is met first where it is larger).
    pub max_line_number: u32,
    /// `N` must be the first word of its line (after a block delete `/`).
    pub line_number_first: bool,
    /// `( )` comments are read as comments (else a `(` is a finding).
    pub paren_comments: bool,
    /// `%` delimiter lines are read (else a `%` is a finding).
    pub percent: bool,
    /// The motion mode (G0–G3) stays in effect for later lines of axis words alone.
    pub modal_motion: bool,
    /// One G or M command a line: a second one is ignored by the controller.
    pub one_command_per_line: bool,
    /// The unit of `G4 P` (`G4 S` is seconds where it is read).
    pub dwell_p: DwellUnit,
    /// `G4 S` (seconds) is a dwell.
    pub dwell_s: bool,
    /// M2/M30 end the program (else other codes end it, [`Rules::end_codes`]).
    pub m2_m30_end: bool,
}

impl Dialect {
    pub const ALL: [Dialect; 5] = [
        Dialect::Reference,
        Dialect::LinuxCnc,
        Dialect::Grbl,
        Dialect::Marlin,
        Dialect::Xcam,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Dialect::Reference => "reference",
            Dialect::LinuxCnc => "linuxcnc",
            Dialect::Grbl => "grbl",
            Dialect::Marlin => "marlin",
            Dialect::Xcam => "xcam",
        }
    }

    /// The post family read by these rules (`reference` is read as `rs274`).
    pub fn family(self) -> &'static str {
        match self {
            Dialect::Reference | Dialect::LinuxCnc => "rs274",
            Dialect::Grbl => "grbl",
            Dialect::Marlin => "marlin",
            Dialect::Xcam => "xcam",
        }
    }

    /// The controller's name as shown in messages.
    pub fn controller(self) -> &'static str {
        match self {
            Dialect::Reference => "the reference controller",
            Dialect::LinuxCnc => "LinuxCNC",
            Dialect::Grbl => "grbl",
            Dialect::Marlin => "Marlin",
            Dialect::Xcam => "xCAM",
        }
    }

    /// How this family reads a line.
    pub fn rules(self) -> Rules {
        match self {
            // rs274ngc: "N" only at the start ("Bad character 'n' used" elsewhere); LinuxCNC
            // 2.9 takes any unsigned number (also N10.5): the checker's bound on numbers
            // xcam: the blocks the NCC reader makes are read by the rs274 rules
            Dialect::Reference | Dialect::LinuxCnc | Dialect::Xcam => Rules {
                max_line_number: 1_000_000,
                line_number_first: true,
                paren_comments: true,
                percent: true,
                modal_motion: true,
                one_command_per_line: false,
                dwell_p: DwellUnit::Seconds,
                dwell_s: false,
                m2_m30_end: true,
            },
            // grbl 1.1's gcode.c: N anywhere, MAX_LINE_NUMBER 10000000; protocol.c strips
            // `( )` and `;` comments and has no `%`
            Dialect::Grbl => Rules {
                max_line_number: 10_000_000,
                line_number_first: false,
                paren_comments: true,
                percent: false,
                modal_motion: true,
                one_command_per_line: false,
                dwell_p: DwellUnit::Seconds,
                dwell_s: false,
                m2_m30_end: true,
            },
            // Marlin's G-code parser: an optional N, one command, its parameters; `;`
            // comments (parentheses only with PAREN_COMMENTS, off by default); motion is
            // not modal without GCODE_MOTION_MODES (off by default); G4 P ms, S s; M30
            // deletes a file on the SD card and M2 does not exist
            Dialect::Marlin => Rules {
                max_line_number: i32::MAX as u32,
                line_number_first: true,
                paren_comments: false,
                percent: false,
                modal_motion: false,
                one_command_per_line: true,
                dwell_p: DwellUnit::Milliseconds,
                dwell_s: true,
                m2_m30_end: false,
            },
        }
    }
}

impl Rules {
    /// The M codes whose line, last in the program, ends it when M2/M30 do not: the spindle
    /// off (M5) or the steppers off (M18, M84).
    pub fn end_codes(&self) -> &'static [u32] {
        if self.m2_m30_end {
            &[2, 30]
        } else {
            &[5, 18, 84]
        }
    }
}

impl std::str::FromStr for Dialect {
    type Err = String;
    /// A dialect's name, or a post family's (`rs274` reads as `linuxcnc`).
    fn from_str(s: &str) -> Result<Dialect, String> {
        match s.to_ascii_lowercase().as_str() {
            "reference" => Ok(Dialect::Reference),
            "linuxcnc" | "rs274" => Ok(Dialect::LinuxCnc),
            "grbl" => Ok(Dialect::Grbl),
            "marlin" => Ok(Dialect::Marlin),
            "xcam" => Ok(Dialect::Xcam),
            other => Err(format!(
                "unknown dialect {other:?} (reference, linuxcnc or rs274, grbl, marlin, xcam)"
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_families_read_back() {
        for d in Dialect::ALL {
            assert_eq!(d.name().parse::<Dialect>(), Ok(d));
        }
        assert_eq!("rs274".parse::<Dialect>(), Ok(Dialect::LinuxCnc));
        assert_eq!("Marlin".parse::<Dialect>(), Ok(Dialect::Marlin));
        assert_eq!("xcam".parse::<Dialect>(), Ok(Dialect::Xcam));
        assert!("mach3".parse::<Dialect>().is_err());
        assert_eq!(Dialect::Reference.family(), "rs274");
    }

    #[test]
    fn the_families_differ_where_their_controllers_do() {
        let (rs, grbl, marlin) = (
            Dialect::LinuxCnc.rules(),
            Dialect::Grbl.rules(),
            Dialect::Marlin.rules(),
        );
        assert!(rs.percent && !grbl.percent && !marlin.percent);
        assert!(rs.line_number_first && !grbl.line_number_first);
        assert!(!marlin.paren_comments && !marlin.modal_motion && marlin.one_command_per_line);
        assert_eq!(marlin.dwell_p, DwellUnit::Milliseconds);
        assert_eq!(rs.end_codes(), &[2, 30]);
        assert_eq!(marlin.end_codes(), &[5, 18, 84]);
    }
}
