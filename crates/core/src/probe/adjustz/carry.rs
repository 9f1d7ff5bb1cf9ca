//! A new `_Z.txt` over one the machinist may have filled in (compile, issue 31): whether
//! the old file stays, is simply replaced, or is kept aside with the values that still
//! belong to a probe of the new set carried over. No file I/O: the command line reads the
//! files and writes what this decides.
//!
//! A measured value belongs to a probe of the new set when the point is the same in the
//! drawing (`[x y]` of the comment), in the program (where the probing program touches) and
//! in its nominal height (`T`), each as written, to 0.001. Both are needed: the comment holds
//! a subpath's probe in its own drawing's coordinates (a subpath placed elsewhere keeps it),
//! the program its output coordinates (a moved start point moves them all).

use super::grid_set::point_of;
use super::log_match::{probe_points, ProbePoint};
use super::zfile::{sane_number, split_z_line};
use super::MAX_LINE;
use crate::diag::Lang;
use crate::digest::nominal_z_line;
use std::collections::{HashMap, VecDeque};

/// The `_Z.txt` an earlier compile left where the new one goes.
pub struct OldZ<'a> {
    /// Its bytes, or why they could not be read.
    pub bytes: Result<&'a [u8], Unreadable>,
    /// The probe points of the old probing program, when it is of the same compile as the
    /// old `_Z.txt` (its digest is that of the old `_Z.txt` and `_Clean.gcode`); asked only
    /// when the old file holds values (the old `_Clean.gcode` may be large).
    pub points: &'a dyn Fn() -> Option<Vec<ProbePoint>>,
    /// The old `_Clean.gcode` carries the new set's digest: the old compile made this very
    /// set (when the old `_Z.txt` names its probes).
    pub same_set: bool,
}

/// What to do with the old `_Z.txt`.
#[derive(Debug, Clone, PartialEq)]
pub enum ZPlan {
    /// It holds nothing the new file does not: write the new one over it.
    Write,
    /// It names the same probes, line by line, touched at the same points of the program,
    /// and holds `values` measured values: leave it exactly as it is (and do not write the
    /// new one).
    Keep { values: usize },
    /// It holds what the new file would lose: keep it beside under another name, and write
    /// `content` (the new file, with the values carried over that [`Aside`] counts).
    Aside { content: String, why: Aside },
}

/// Why the old `_Z.txt` is kept aside, with what was carried over.
#[derive(Debug, Clone, PartialEq)]
pub enum Aside {
    /// Of its `values` measured values, `carried` went to the new file; `unfilled` probes of
    /// the new set have none.
    Compared {
        values: usize,
        carried: usize,
        unfilled: usize,
    },
    /// Its probing program is missing or of another compile: no point can be compared.
    Unchecked { values: usize },
    /// It is not a `_Z.txt` this reader can take apart.
    Unreadable(Unreadable),
}

/// Why an old `_Z.txt` could not be read.
#[derive(Debug, Clone, PartialEq)]
pub enum Unreadable {
    /// The file could not be read (the OS's words).
    Io(String),
    /// It is larger than this many MiB: no `_Z.txt` compile wrote.
    TooLarge(u64),
    /// NUL bytes without a byte-order mark, or bytes that are not UTF-8.
    NotText,
    /// This line (1-based) is not `(…/T=t) #n=value`, or too long.
    Line(usize),
}

impl Unreadable {
    pub fn describe(&self, lang: Lang) -> String {
        match (self, lang) {
            (Unreadable::Io(e), _) => e.clone(),
            (Unreadable::TooLarge(mib), Lang::En) => format!("it is larger than {mib} MiB"),
            (Unreadable::TooLarge(mib), Lang::De) => format!("sie ist größer als {mib} MiB"),
            (Unreadable::NotText, Lang::En) => "it is no UTF-8 or UTF-16 text".to_string(),
            (Unreadable::NotText, Lang::De) => "sie ist kein UTF-8- oder UTF-16-Text".to_string(),
            (Unreadable::Line(n), Lang::En) => {
                format!("line {n} is not of the form (…/T=t) #n=value")
            }
            (Unreadable::Line(n), Lang::De) => {
                format!("Zeile {n} hat nicht die Form (…/T=t) #n=Wert")
            }
        }
    }
}

/// One probe line of a `_Z.txt`.
struct ZEntry<'a> {
    /// The nominal part (`(comment) #n=`), as the digest reads it.
    nominal: String,
    /// `[x y]` of the comment.
    xy: Option<(f64, f64)>,
    /// `T` of the comment.
    t: Option<f64>,
    /// The measured value as typed (empty: none).
    value: &'a str,
}

/// The probe lines of a `_Z.txt` text; `Err(line)` at the first line of another form.
fn entries(text: &str) -> Result<Vec<ZEntry<'_>>, usize> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let (t_text, _, value) = split_z_line(line)
            .filter(|_| line.len() <= MAX_LINE)
            .ok_or(i + 1)?;
        out.push(ZEntry {
            nominal: nominal_z_line(line),
            xy: point_of(line),
            t: sane_number(t_text).ok(),
            value,
        });
    }
    Ok(out)
}

/// A probe point as compared: comment XY, T and program XY, in thousandths.
type Key = [i64; 5];

fn key(e: &ZEntry, p: &ProbePoint) -> Option<Key> {
    let (x, y) = e.xy?;
    let milli = |v: f64| (v * 1000.0).round() as i64;
    Some([milli(x), milli(y), milli(e.t?), milli(p.x), milli(p.y)])
}

/// What compile does with `old` when it writes `new_z` (its own `_Z.txt`, unfilled) of the
/// set whose probing program is `new_probing`.
pub fn plan_new_z(old: &OldZ, new_z: &str, new_probing: &str) -> ZPlan {
    let aside = |why| ZPlan::Aside {
        content: new_z.to_string(),
        why,
    };
    let bytes = match &old.bytes {
        Ok(b) => *b,
        Err(e) => return aside(Aside::Unreadable(e.clone())),
    };
    if bytes == new_z.as_bytes() || bytes.iter().all(u8::is_ascii_whitespace) {
        return ZPlan::Write;
    }
    let decoded = match crate::load::text_file::decode(bytes) {
        Ok(d) if !d.text.contains('\u{fffd}') => d.text,
        _ => return aside(Aside::Unreadable(Unreadable::NotText)),
    };
    let old_lines = match entries(&decoded) {
        Ok(l) => l,
        Err(line) => return aside(Aside::Unreadable(Unreadable::Line(line))),
    };
    let values = old_lines.iter().filter(|e| !e.value.is_empty()).count();
    if values == 0 {
        return ZPlan::Write;
    }
    let new_points = probe_points(new_probing);
    let Some(new_lines) = entries(new_z).ok().filter(|l| l.len() == new_points.len()) else {
        return aside(Aside::Unchecked { values });
    };
    let same_nominal = old_lines.len() == new_lines.len()
        && old_lines
            .iter()
            .zip(&new_lines)
            .all(|(a, b)| a.nominal == b.nominal);
    if same_nominal && old.same_set {
        return ZPlan::Keep { values };
    }
    let Some(old_points) = (old.points)().filter(|p| p.len() == old_lines.len()) else {
        return aside(Aside::Unchecked { values });
    };
    let milli = |v: f64| (v * 1000.0).round() as i64;
    let same_probes = same_nominal
        && old_points
            .iter()
            .zip(&new_points)
            .all(|(a, b)| (milli(a.x), milli(a.y)) == (milli(b.x), milli(b.y)));
    if same_probes {
        return ZPlan::Keep { values };
    }
    // a last line without a line end may be cut off: `2.15` read as `2.1`
    let cut_last = !decoded.ends_with('\n') && !decoded.ends_with('\r');
    let last = old_lines.len().saturating_sub(1);
    let mut measured: HashMap<Key, VecDeque<&str>> = HashMap::new();
    for (i, (e, p)) in old_lines.iter().zip(&old_points).enumerate() {
        let usable = sane_number(e.value).is_ok() && !(cut_last && i == last);
        if let (true, Some(k)) = (usable, key(e, p)) {
            measured.entry(k).or_default().push_back(e.value);
        }
    }
    // the new file's lines in order, each probe line given its carried value
    let mut carried = 0;
    let mut content = String::with_capacity(new_z.len() + 16 * new_lines.len());
    let mut probes = new_lines.iter().zip(&new_points);
    for line in new_z.split_inclusive('\n') {
        let body = line.trim_end_matches(['\r', '\n']);
        if body.trim().is_empty() {
            content.push_str(line);
            continue;
        }
        let value = probes
            .next()
            .and_then(|(e, p)| key(e, p))
            .and_then(|k| measured.get_mut(&k)?.pop_front());
        match value {
            Some(v) => {
                carried += 1;
                content.push_str(body.trim_end());
                content.push_str(v);
                content.push_str(&line[body.len()..]);
            }
            None => content.push_str(line),
        }
    }
    ZPlan::Aside {
        content,
        why: Aside::Compared {
            values,
            carried,
            unfilled: new_lines.len() - carried,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const Z: &str = "([10.000 5.000]/T=3.000) #51=\n([50.000 5.000]/L:1/T=3.000) #52=\n";
    const PROBING: &str =
        "%\nG00 X0.000 Y5.000\nG38.3 Z-2 F50\nG00 X40.000 Y5.000\nG38.3 Z-2 F50\n%\n";

    fn filled(a: &str, b: &str) -> String {
        Z.replace("#51=", &format!("#51={a}"))
            .replace("#52=", &format!("#52={b}"))
    }

    fn points() -> Option<Vec<ProbePoint>> {
        Some(probe_points(PROBING))
    }

    fn none() -> Option<Vec<ProbePoint>> {
        None
    }

    fn old(text: &str) -> OldZ<'_> {
        OldZ {
            bytes: Ok(text.as_bytes()),
            points: &points,
            same_set: false,
        }
    }

    #[test]
    fn the_same_probes_keep_the_file_and_nothing_to_lose_is_replaced() {
        let z = filled("2,95", "3.1");
        assert_eq!(plan_new_z(&old(&z), Z, PROBING), ZPlan::Keep { values: 2 });
        // Notepad's CR LF and byte-order mark: still the same probes
        let notepad = format!("\u{feff}{}", z.replace('\n', "\r\n"));
        assert_eq!(
            plan_new_z(&old(&notepad), Z, PROBING),
            ZPlan::Keep { values: 2 }
        );
        // the same probes touched elsewhere (the start point moved): compared, none carried
        let moved = PROBING.replace("Y5.000", "Y4.000");
        let ZPlan::Aside { content, why } = plan_new_z(&old(&z), Z, &moved) else {
            panic!()
        };
        assert_eq!(content, Z);
        assert!(matches!(why, Aside::Compared { carried: 0, .. }), "{why:?}");
        // the old probing program gone, but the old _Clean.gcode is of this very set
        let same = OldZ {
            bytes: Ok(z.as_bytes()),
            points: &none,
            same_set: true,
        };
        assert_eq!(plan_new_z(&same, Z, PROBING), ZPlan::Keep { values: 2 });
        // ... and only for the same probes
        let other = Z.replace("50.000", "45.000");
        assert!(matches!(
            plan_new_z(&same, &other, PROBING),
            ZPlan::Aside {
                why: Aside::Unchecked { values: 2 },
                ..
            }
        ));
        for nothing in [Z, "", "\n \n", "([10.000 5.000]/T=3.000) #51=\n"] {
            assert_eq!(
                plan_new_z(&old(nothing), Z, PROBING),
                ZPlan::Write,
                "{nothing:?}"
            );
        }
    }

    #[test]
    fn values_of_unchanged_points_are_carried_over() {
        let z = filled("2,95", "3.1");
        // the second probe moved in the drawing and in the program
        let new_z = Z.replace("50.000 5.000", "45.000 5.000");
        let new_probing = PROBING.replace("X40.000", "X35.000");
        let ZPlan::Aside { content, why } = plan_new_z(&old(&z), &new_z, &new_probing) else {
            panic!()
        };
        assert_eq!(
            content,
            "([10.000 5.000]/T=3.000) #51=2,95\n([45.000 5.000]/L:1/T=3.000) #52=\n"
        );
        assert_eq!(
            why,
            Aside::Compared {
                values: 2,
                carried: 1,
                unfilled: 1
            }
        );
        // the same comment, but the program touches elsewhere (a subpath placed elsewhere):
        // nothing is carried
        let moved = PROBING
            .replace("X0.000", "X1.000")
            .replace("X40.000", "X41.000");
        let ZPlan::Aside { why, .. } = plan_new_z(&old(&z), &new_z, &moved) else {
            panic!()
        };
        assert_eq!(
            why,
            Aside::Compared {
                values: 2,
                carried: 0,
                unfilled: 2
            }
        );
        // another nominal height is another probe
        let higher = new_z.replace("T=3.000) #51", "T=3.500) #51");
        let ZPlan::Aside { why, .. } = plan_new_z(&old(&z), &higher, &new_probing) else {
            panic!()
        };
        assert!(matches!(why, Aside::Compared { carried: 0, .. }), "{why:?}");
    }

    #[test]
    fn a_probe_added_keeps_the_old_values_and_the_order_of_the_new_file() {
        let z = filled("2.9", "3.1");
        let new_z = format!(
            "([0.000 0.000]/T=3.000) #51=\n{}",
            Z.replace("#52", "#53").replace("#51", "#52")
        );
        let new_probing = PROBING.replace("%\nG00", "%\nG00 X-10.000 Y0.000\nG38.3 Z-2 F50\nG00");
        let ZPlan::Aside { content, why } = plan_new_z(&old(&z), &new_z, &new_probing) else {
            panic!()
        };
        assert_eq!(
            content,
            "([0.000 0.000]/T=3.000) #51=\n([10.000 5.000]/T=3.000) #52=2.9\n([50.000 5.000]/L:1/T=3.000) #53=3.1\n"
        );
        assert!(matches!(
            why,
            Aside::Compared {
                carried: 2,
                unfilled: 1,
                ..
            }
        ));
    }

    #[test]
    fn hostile_old_files_are_kept_aside() {
        let new_z = Z.replace("50.000", "45.000");
        let unreadable = |bytes: &[u8]| {
            let o = OldZ {
                bytes: Ok(bytes),
                points: &none,
                same_set: false,
            };
            match plan_new_z(&o, &new_z, PROBING) {
                ZPlan::Aside {
                    content,
                    why: Aside::Unreadable(u),
                } => {
                    assert_eq!(content, new_z);
                    u
                }
                other => panic!("{other:?}"),
            }
        };
        assert_eq!(unreadable(b"\x00\x01garbage"), Unreadable::NotText);
        assert_eq!(unreadable(b"#51=2.9\xff\n"), Unreadable::NotText);
        assert_eq!(
            unreadable(b"([10.000 5.000]/T=3.000) #51=2.9\n([50.0"),
            Unreadable::Line(2)
        );
        assert_eq!(unreadable(b"hello\n"), Unreadable::Line(1));
        let io = OldZ {
            bytes: Err(Unreadable::Io("Permission denied".into())),
            points: &none,
            same_set: false,
        };
        assert!(matches!(
            plan_new_z(&io, Z, PROBING),
            ZPlan::Aside {
                why: Aside::Unreadable(Unreadable::Io(_)),
                ..
            }
        ));
        // without the old probing program nothing can be compared
        let z = filled("2.9", "3.1");
        let o = OldZ {
            bytes: Ok(z.as_bytes()),
            points: &none,
            same_set: false,
        };
        assert_eq!(
            plan_new_z(&o, &new_z, PROBING),
            ZPlan::Aside {
                content: new_z.clone(),
                why: Aside::Unchecked { values: 2 }
            }
        );
        // a value on a last line without a line end may be cut off: not carried
        let cut = filled("2.9", "3.1");
        let cut = cut.trim_end();
        let same_points = Z.replace("T=3.000) #51", "T=3.000) #61");
        let ZPlan::Aside { why, .. } = plan_new_z(&old(cut), &same_points, PROBING) else {
            panic!()
        };
        assert_eq!(
            why,
            Aside::Compared {
                values: 2,
                carried: 1,
                unfilled: 1
            }
        );
        // a value that is no number is not carried, but counted
        let z = filled("abc", "3.1");
        let ZPlan::Aside { why, .. } = plan_new_z(&old(&z), &same_points, PROBING) else {
            panic!()
        };
        assert!(matches!(
            why,
            Aside::Compared {
                values: 2,
                carried: 1,
                ..
            }
        ));
    }
}
