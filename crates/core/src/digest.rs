//! The digest of a probing set (written by `emit/program.rs` and `stage.rs`, checked by
//! adjust-z's `probe/adjustz/set_check.rs`): `_Probing.gcode`, `_Z.txt` and `_Clean.gcode` of one compile.
//!
//! `_Z.txt` itself cannot carry it (the reference's `_Z.txt` is compared whole, and the
//! machinist fills it in), so the digest covers what adjust-z can recompute from the files it
//! reads: the nominal part of every `_Z.txt` line (`(comment) #n=`, the measured value left
//! out) and every line of `_Clean.gcode` but its banner line. Compile writes it into the
//! banner line (line 2; line 1 in grbl, which has no `%`) of `_Clean.gcode` and
//! `_Probing.gcode` as ` set=<16 hex digits>`, a line the reference's outputs are compared
//! without. SipHash-2-4 with fixed keys: the digest guards against files of different
//! compiles put together by accident, not against forgery.

use siphasher::sip::SipHasher24;
use std::hash::Hasher;

/// The word before the digest in a banner line.
pub const SET_WORD: &str = "set=";

/// Index of the banner line: the line after a leading `%`, else the first line.
pub fn banner_index(program: &str) -> usize {
    banner_index_of_first(program.lines().next())
}

/// [`banner_index`] from a program's first line.
pub fn banner_index_of_first(first: Option<&str>) -> usize {
    usize::from(first.is_some_and(|l| l.trim() == "%"))
}

/// The nominal part of a `_Z.txt` line: `(comment) #n=` without the value and blanks; a line
/// of another form as it is (it is reported when the file is read).
fn nominal_z_line(line: &str) -> String {
    let t = line.trim();
    let nominal = (|| {
        let close = t.strip_prefix('(')?.find(')')? + 1;
        let rest = t[close + 1..].trim_start().strip_prefix('#')?.trim_start();
        let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        let (name, after) = rest.split_at(digits);
        after.trim_start().strip_prefix('=')?;
        (digits > 0).then(|| format!("{} #{name}=", &t[..=close]))
    })();
    nominal.unwrap_or_else(|| t.to_string())
}

/// The digest of a set: `_Z.txt` (filled in or not) and `_Clean.gcode` (with or without a
/// digest in its banner line), as 16 lower-case hex digits.
pub fn set_digest(z_txt: &str, clean: &str) -> String {
    set_digest_lines(z_txt, clean.lines())
}

/// [`set_digest`] over the lines of `_Clean.gcode` as they are read (a staged program is
/// not held in memory).
pub fn set_digest_lines<S: AsRef<str>>(z_txt: &str, clean: impl Iterator<Item = S>) -> String {
    let mut h = SipHasher24::new_with_keys(0, 0);
    h.write(b"millpath probing set 1\n");
    let z_txt = z_txt.strip_prefix('\u{feff}').unwrap_or(z_txt);
    for line in z_txt.lines().filter(|l| !l.trim().is_empty()) {
        h.write(nominal_z_line(line).as_bytes());
        h.write(b"\n");
    }
    h.write(b"--\n");
    let mut clean = clean.peekable();
    let banner = banner_index_of_first(clean.peek().map(AsRef::as_ref));
    for (i, line) in clean.enumerate() {
        if i != banner {
            h.write(line.as_ref().trim_end().as_bytes());
            h.write(b"\n");
        }
    }
    format!("{:016x}", h.finish())
}

/// The digest in a program's banner line, if it has one.
pub fn stored_digest(program: &str) -> Option<&str> {
    let line = program.lines().nth(banner_index(program))?;
    let at = line.find(SET_WORD)? + SET_WORD.len();
    let hex = line.get(at..at + 16)?;
    hex.bytes().all(|b| b.is_ascii_hexdigit()).then_some(hex)
}

/// `banner` with the digest, as written into line 2 of `_Clean.gcode` and `_Probing.gcode`.
pub fn banner_with_digest(banner: &str, digest: &str) -> String {
    format!("{banner} {SET_WORD}{digest}")
}

#[cfg(test)]
mod tests {
    use super::*;

    const CLEAN: &str = "%\n(millpath V.1)\nG01 Z0.800(=0.800+1.000*[#51-2.000])\nM30\n%\n";
    const Z: &str = "([1.000 2.000]/T=2.000) #51=\n";

    fn stamped(clean: &str, z: &str) -> String {
        let d = set_digest(z, clean);
        clean.replace("(millpath V.1)", &format!("(millpath V.1 set={d})"))
    }

    #[test]
    fn measured_values_blanks_and_line_ends_keep_the_digest() {
        let d = set_digest(Z, CLEAN);
        assert_eq!(d.len(), 16);
        for z in [
            "([1.000 2.000]/T=2.000) #51=2,1\n",
            "([1.000 2.000]/T=2.000)  # 51 = 2.1 \r\n\n",
            "\u{feff}([1.000 2.000]/T=2.000) #51=\n",
        ] {
            assert_eq!(set_digest(z, CLEAN), d, "{z:?}");
        }
        assert_eq!(set_digest(Z, &CLEAN.replace('\n', "\r\n")), d);
        // the banner line is not covered: the digest can be written into it
        assert_eq!(set_digest(Z, &stamped(CLEAN, Z)), d);
    }

    #[test]
    fn a_moved_probe_or_another_program_changes_the_digest() {
        let d = set_digest(Z, CLEAN);
        assert_ne!(
            set_digest(&Z.replace("1.000 2.000", "1.000 3.000"), CLEAN),
            d
        );
        assert_ne!(set_digest(&Z.replace("T=2.000", "T=2.500"), CLEAN), d);
        assert_ne!(set_digest(&Z.replace("#51", "#52"), CLEAN), d);
        assert_ne!(
            set_digest(Z, &CLEAN.replace("Z0.800(=0.800", "Z0.500(=0.500")),
            d
        );
        assert_ne!(set_digest(&format!("{Z}{Z}"), CLEAN), d);
    }

    #[test]
    fn digest_is_found_in_the_banner_line_only() {
        let clean = stamped(CLEAN, Z);
        assert_eq!(stored_digest(&clean), Some(set_digest(Z, CLEAN).as_str()));
        assert_eq!(stored_digest(CLEAN), None);
        assert_eq!(stored_digest("%\n(a)\n(set=0123456789abcdef)\n"), None);
        assert_eq!(
            stored_digest("(x set=0123456789abcdef)\nM30\n"),
            Some("0123456789abcdef")
        );
        assert_eq!(stored_digest("%\n(x set=0123)\n"), None);
        assert_eq!(stored_digest(""), None);
    }
}
