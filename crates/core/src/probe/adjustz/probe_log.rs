//! Reading a controller's probe log: the measured contacts of a probing program, each with
//! its line, whatever wrote them. The format is found from the content:
//!
//! - LinuxCNC's `(PROBEOPEN file)` log: nine numbers a line, `X Y Z A B C U V W`, in the
//!   coordinates of the program (work coordinates);
//! - a sender's console log with GRBL reports `[PRB:x,y,z:1]`: GRBL reports machine
//!   coordinates, so the log must also hold the work offset `[G54:x,y,z]` (and `[G92:…]`,
//!   when present) that `$#` prints; every other line is ignored;
//! - lines of three numbers `x y z` (bCNC's `.xyz`; its `.probe` files start with a header
//!   of three lines, skipped; work coordinates);
//! - a filled-in `_Z.txt`: the caller reads it as today.

use super::bounds::{line_origin, LIMIT, MAX_LINE};
use crate::args;
use crate::diag::{Diags, Msg};

/// Largest probe log read, in bytes (a probe log of a drawing is a few kB; a console log of
/// a long session stays far below this).
pub const MAX_LOG_BYTES: usize = 16 * 1024 * 1024;
/// Most lines of a probe log.
pub const MAX_LOG_LINES: usize = 200_000;

/// What wrote the log.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LogFormat {
    LinuxCnc,
    Grbl,
    /// `x y z` lines (bCNC `.probe`).
    Xyz,
    /// A filled-in `_Z.txt`.
    ZFile,
}

impl LogFormat {
    /// The name in messages.
    pub fn name(self) -> &'static str {
        match self {
            LogFormat::LinuxCnc => "LinuxCNC PROBEOPEN",
            LogFormat::Grbl => "GRBL",
            LogFormat::Xyz => "x y z",
            LogFormat::ZFile => "_Z.txt",
        }
    }
}

/// One probe contact in work coordinates, with its 1-based line in the log.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    pub line: usize,
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// A number of the log: finite and within ±[`LIMIT`].
fn number(text: &str) -> Option<f64> {
    text.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && v.abs() <= LIMIT)
}

/// Does this line look like one of `_Z.txt` (`(…/T=…) #n=…`)?
fn is_z_line(line: &str) -> bool {
    let t = line.trim();
    t.starts_with('(') && t.contains("/T=") && t.contains('#') && t.contains('=')
}

/// The format of `text`, from its first non-blank line (GRBL: any `[PRB:` report);
/// `None` when it is none of them.
pub fn detect(text: &str) -> Option<LogFormat> {
    if text.contains("[PRB:") {
        return Some(LogFormat::Grbl);
    }
    let first = text.lines().find(|l| !l.trim().is_empty())?;
    if is_z_line(first) {
        return Some(LogFormat::ZFile);
    }
    let words: Vec<&str> = first.split_whitespace().collect();
    let numeric = words.iter().all(|w| w.parse::<f64>().is_ok());
    match words.len() {
        9 if numeric => Some(LogFormat::LinuxCnc),
        3 if numeric => Some(LogFormat::Xyz),
        _ => None,
    }
}

/// Reads the measurements of a log in `format` (not [`LogFormat::ZFile`]); every error names
/// `file` and its line. The log's size and lines are bounded.
pub fn read_measurements(
    text: &str,
    file: &str,
    format: LogFormat,
    diags: &mut Diags,
) -> Vec<Measurement> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if text.len() > MAX_LOG_BYTES || text.lines().nth(MAX_LOG_LINES).is_some() {
        let limit = format!("{MAX_LOG_BYTES} bytes / {MAX_LOG_LINES} lines");
        diags.error(Msg::ProbeLogTooLarge, line_origin(file, 1), args![limit]);
        return Vec::new();
    }
    // LinuxCNC and bCNC end every line: without its end, the last number may be cut short
    // (2.15 read as 2.1); GRBL's reports carry their own end, `]`
    let columns_format = matches!(format, LogFormat::LinuxCnc | LogFormat::Xyz);
    if columns_format && !text.trim_end_matches([' ', '\t']).ends_with('\n') {
        let last = text.lines().count().max(1);
        diags.error(Msg::ProbeLogCutOff, line_origin(file, last), vec![]);
        return Vec::new();
    }
    match format {
        LogFormat::LinuxCnc => columns(text, file, 9, format, diags),
        LogFormat::Xyz => {
            let skip = bcnc_header_lines(text);
            let mut m = columns(text, file, 3, format, diags);
            m.retain(|m| m.line > skip);
            m
        }
        LogFormat::Grbl => grbl(text, file, diags),
        LogFormat::ZFile => Vec::new(),
    }
}

/// 3 when `text` starts with the header of bCNC's `.probe` files, else 0. bCNC (Probe.save
/// in CNC.py) writes `xmin xmax xn`, `ymin ymax yn`, `zmin zmax feed`, two empty lines, then
/// the grid's `x y z` lines (an empty line after each row); its `.xyz` files are the points
/// alone. The header is told from points by the two empty lines and the whole counts ≥ 2.
fn bcnc_header_lines(text: &str) -> usize {
    let lines: Vec<&str> = text.lines().take(5).collect();
    let count = |l: &str| {
        let w: Vec<&str> = l.split_whitespace().collect();
        w.len() == 3
            && w.iter().all(|x| number(x).is_some())
            && w[2].parse::<u32>().is_ok_and(|n| n >= 2)
    };
    let header = lines.len() == 5
        && count(lines[0])
        && count(lines[1])
        && lines[2].split_whitespace().count() == 3
        && lines[3].trim().is_empty()
        && lines[4].trim().is_empty();
    if header {
        3
    } else {
        0
    }
}

/// Lines of `n` numbers, the first three X Y Z; blank lines are skipped.
fn columns(
    text: &str,
    file: &str,
    n: usize,
    format: LogFormat,
    diags: &mut Diags,
) -> Vec<Measurement> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let origin = line_origin(file, i + 1);
        if line.len() > MAX_LINE {
            diags.error(Msg::LineTooLong, origin, args![MAX_LINE]);
            continue;
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.is_empty() {
            continue;
        }
        if words.len() != n {
            diags.error(
                Msg::ProbeLogBadLine,
                origin,
                args![n, format.name(), line.trim()],
            );
            continue;
        }
        let mut v = [0.0; 3];
        let mut ok = true;
        // only X Y Z matter, but a broken A…W says the line is not what LinuxCNC wrote
        for (k, w) in words.iter().enumerate() {
            match number(w) {
                Some(x) if k < 3 => v[k] = x,
                Some(_) => {}
                None => {
                    diags.error(Msg::ProbeLogBadNumber, origin.clone(), args![w]);
                    ok = false;
                    break;
                }
            }
        }
        if ok {
            out.push(Measurement {
                line: i + 1,
                x: v[0],
                y: v[1],
                z: v[2],
            });
        }
    }
    out
}

/// The bracketed GRBL report `[TAG:…]` in `line`, if any: its text between `TAG:` and `]`.
fn report<'a>(line: &'a str, tag: &str) -> Option<&'a str> {
    let start = line.find(&format!("[{tag}:"))? + tag.len() + 2;
    let len = line[start..].find(']')?;
    Some(&line[start..start + len])
}

/// `x,y,z` of a GRBL report.
fn triple(text: &str) -> Option<[f64; 3]> {
    let mut it = text.split(',').map(|w| number(w.trim()));
    let v = [it.next()??, it.next()??, it.next()??];
    it.next().is_none().then_some(v)
}

/// GRBL 1.1 gives work coordinates as machine position minus work offset (G54 … + G92;
/// our programs select G54 and no tool length offset). Rounded to 1 µm: GRBL prints 3
/// decimals, the subtraction must not add binary noise.
fn work(machine: f64, offset: f64) -> f64 {
    ((machine - offset) * 1e6).round() / 1e6
}

fn grbl(text: &str, file: &str, diags: &mut Diags) -> Vec<Measurement> {
    let mut contacts: Vec<(usize, [f64; 3])> = Vec::new();
    let mut g54: Option<(usize, [f64; 3], String)> = None;
    let mut g92 = [0.0; 3];
    let mut previous_tlo = false;
    let before = diags.error_count();
    for (i, line) in text.lines().enumerate() {
        let origin = line_origin(file, i + 1);
        if line.len() > MAX_LINE {
            diags.error(Msg::LineTooLong, origin, args![MAX_LINE]);
            continue;
        }
        if let Some(r) = report(line, "G54") {
            let Some(v) = triple(r) else {
                diags.error(Msg::ProbeLogBadNumber, origin.clone(), args![r]);
                continue;
            };
            match &g54 {
                Some((_, old, text)) if *old != v => {
                    diags.error(
                        Msg::ProbeLogGrblOffsetChanged,
                        origin.clone(),
                        args![text, r],
                    );
                }
                Some(_) => {}
                None => g54 = Some((i + 1, v, r.to_string())),
            }
        }
        if let Some(r) = report(line, "G92") {
            match triple(r) {
                Some(v) => g92 = v,
                None => diags.error(Msg::ProbeLogBadNumber, origin.clone(), args![r]),
            }
        }
        let after_tlo = std::mem::replace(&mut previous_tlo, report(line, "TLO").is_some());
        let Some(r) = report(line, "PRB") else {
            // blank lines and sender chatter keep `$#`'s TLO → PRB sequence together
            previous_tlo |= after_tlo && line.trim().is_empty();
            continue;
        };
        // `$#` repeats the last contact after its [TLO:…] line: not a new measurement
        if after_tlo {
            continue;
        }
        let (coords, flag) = r.rsplit_once(':').unwrap_or((r, ""));
        if flag.trim() != "1" {
            diags.error(Msg::ProbeLogNoContact, origin, args![line.trim()]);
            continue;
        }
        match triple(coords) {
            Some(v) => contacts.push((i + 1, v)),
            None => diags.error(Msg::ProbeLogBadNumber, origin, args![coords]),
        }
    }
    let Some((_, offset, _)) = g54 else {
        if diags.error_count() == before {
            diags.error(Msg::ProbeLogGrblOffset, line_origin(file, 1), vec![]);
        }
        return Vec::new();
    };
    contacts
        .into_iter()
        .map(|(line, v)| Measurement {
            line,
            x: work(v[0], offset[0] + g92[0]),
            y: work(v[1], offset[1] + g92[1]),
            z: work(v[2], offset[2] + g92[2]),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> (Option<LogFormat>, Vec<Measurement>, Vec<(Msg, String)>) {
        let mut d = Diags::default();
        let f = detect(text);
        let m = f.map_or_else(Vec::new, |f| read_measurements(text, "log", f, &mut d));
        let msgs = d.list.iter().map(|x| (x.msg, x.origin.context())).collect();
        (f, m, msgs)
    }

    #[test]
    fn linuxcnc_probeopen_log() {
        let log = "10.000000 5.000000 2.950000 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000\n\
                   50.000000 5.000000 3.100000 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000\n";
        let (f, m, msgs) = read(log);
        assert_eq!(f, Some(LogFormat::LinuxCnc));
        assert!(msgs.is_empty(), "{msgs:?}");
        assert_eq!(m.len(), 2);
        assert_eq!((m[1].line, m[1].x, m[1].y, m[1].z), (2, 50.0, 5.0, 3.1));
        // a short line, a NaN
        let bad = log.replacen(" 0.000000\n", "\n", 2);
        let (_, _, msgs) = read(&format!("{log}{}\n", bad.lines().nth(1).unwrap()));
        assert_eq!(msgs, [(Msg::ProbeLogBadLine, "log:3".to_string())]);
        let (_, m, msgs) = read(&log.replace("3.100000", "nan"));
        assert_eq!(msgs, [(Msg::ProbeLogBadNumber, "log:2".to_string())]);
        assert_eq!(m.len(), 1);
        let (_, _, msgs) = read(&log.replace("3.100000", "1e7"));
        assert_eq!(msgs, [(Msg::ProbeLogBadNumber, "log:2".to_string())]);
    }

    #[test]
    fn grbl_console_log() {
        let log = "> $#\n[G54:-100.000,-50.000,-20.000]\n[G92:0.000,0.000,0.000]\n\
                   [TLO:0.000]\n[PRB:0.000,0.000,0.000:0]\nok\n> G38.3 Z0 F50\n\
                   <Idle|MPos:-90.000,-45.000,-17.000|FS:0,0>\n[PRB:-90.000,-45.000,-17.050:1]\nok\n\
                   [MSG:hello]\nok [PRB:-50.000,-45.000,-16.900:1]\n";
        let (f, m, msgs) = read(log);
        assert_eq!(f, Some(LogFormat::Grbl));
        assert!(msgs.is_empty(), "{msgs:?}");
        let got: Vec<_> = m.iter().map(|m| (m.line, m.x, m.y, m.z)).collect();
        assert_eq!(got, [(9, 10.0, 5.0, 2.95), (12, 50.0, 5.0, 3.1)]);
        // no contact
        let (_, _, msgs) = read(&log.replace("-16.900:1", "-16.900:0"));
        assert_eq!(msgs, [(Msg::ProbeLogNoContact, "log:12".to_string())]);
        assert_eq!(
            {
                let mut d = Diags::default();
                read_measurements(
                    &log.replace("-16.900:1", "-16.900:0"),
                    "log",
                    LogFormat::Grbl,
                    &mut d,
                );
                d.list[0].message(crate::Lang::En)
            },
            "GRBL reports no contact here (ok [PRB:-50.000,-45.000,-16.900:0]): the probe did not touch the surface; probe this point again"
        );
        // without the work offset
        let (_, m, msgs) = read("[PRB:1.000,2.000,3.000:1]\n");
        assert!(m.is_empty());
        assert_eq!(msgs, [(Msg::ProbeLogGrblOffset, "log:1".to_string())]);
        // an offset that changes
        let (_, _, msgs) = read(&format!("{log}[G54:0.000,0.000,0.000]\n"));
        assert_eq!(
            msgs,
            [(Msg::ProbeLogGrblOffsetChanged, "log:13".to_string())]
        );
        // a broken report
        let (_, _, msgs) = read(&log.replace("-17.050:1", "nan:1"));
        assert_eq!(msgs, [(Msg::ProbeLogBadNumber, "log:9".to_string())]);
    }

    #[test]
    fn xyz_lines_and_z_files_and_unknown_content() {
        let (f, m, msgs) = read("10 5 2.95\n\n50 5 3.1\n");
        assert_eq!(f, Some(LogFormat::Xyz));
        assert!(msgs.is_empty());
        assert_eq!((m[1].line, m[1].z), (3, 3.1));
        // bCNC's .probe: a header of three lines and two empty lines, rows of x y z
        let probe = "0 40 2\n0 10 2\n-10 3 50\n\n\n0 0 2.9\n40 0 3\n\n0 10 3.1\n40 10 3.2\n\n";
        let (f, m, msgs) = read(probe);
        assert_eq!(f, Some(LogFormat::Xyz));
        assert!(msgs.is_empty(), "{msgs:?}");
        let got: Vec<_> = m.iter().map(|m| (m.line, m.x, m.y, m.z)).collect();
        assert_eq!(
            got,
            [
                (6, 0.0, 0.0, 2.9),
                (7, 40.0, 0.0, 3.0),
                (9, 0.0, 10.0, 3.1),
                (10, 40.0, 10.0, 3.2)
            ]
        );
        // a last line without its end may be a cut number
        let (_, m, msgs) = read("10 5 2.95\n50 5 3.1");
        assert!(m.is_empty());
        assert_eq!(msgs, [(Msg::ProbeLogCutOff, "log:2".to_string())]);
        // points alone (.xyz), rows of three: no header
        assert_eq!(read("0 0 1\n1 0 1\n2 0 1\n\n0 1 1\n").1.len(), 4);
        assert_eq!(
            detect("([10.000 5.000]/T=3.000) #51=2.95\n"),
            Some(LogFormat::ZFile)
        );
        for unknown in ["", "hello\n", "1 2\n", "G38.3 Z0\n", "1 2 3 4 5\n", "[PRB:"] {
            let f = detect(unknown);
            assert!(
                f.is_none() || unknown.starts_with('['),
                "{unknown:?}: {f:?}"
            );
        }
    }

    #[test]
    fn too_large_logs_are_refused() {
        let log = "1 2 3\n".repeat(MAX_LOG_LINES + 1);
        let (_, m, msgs) = read(&log);
        assert!(m.is_empty());
        assert_eq!(msgs, [(Msg::ProbeLogTooLarge, "log:1".to_string())]);
    }

    #[test]
    fn truncated_and_mangled_logs_never_panic() {
        let logs = [
            "10.000000 5.000000 2.950000 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000\n",
            "[G54:-100.000,-50.000,-20.000]\n[TLO:0.000]\n[PRB:1,2,3:1]\nok [PRB:-90.000,-45.000,-17.050:1]\n",
            "10 5 2.95\n50 5 3.1\n",
        ];
        for log in logs {
            for cut in 0..=log.len() {
                for text in [&log[..cut], &log[cut..]] {
                    let mut d = Diags::default();
                    if let Some(f) = detect(text) {
                        for m in read_measurements(text, "log", f, &mut d) {
                            assert!(m.x.is_finite() && m.y.is_finite() && m.z.is_finite());
                        }
                    }
                    let mangled = text.replace(['0', ','], "é]");
                    if let Some(f) = detect(&mangled) {
                        read_measurements(&mangled, "log", f, &mut d);
                    }
                }
            }
        }
    }
}
