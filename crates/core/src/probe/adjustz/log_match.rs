//! Matching a probe log's measurements to the probes of a set: each probe point is where the
//! probing program touches (its `G38` lines, in `_Z.txt`'s order), each measurement belongs to
//! the probe at its XY within a tolerance, and the result is `_Z.txt` filled in.
//!
//! Why the probing program and not `_Z.txt`'s `[x y]`: that comment holds the probe centre in
//! its own drawing's coordinates (reference-output.md §12.3), the program the machine runs
//! holds it in output coordinates (start point at 0/0, subpaths placed).
//!
//! The probe points of `_Probing.gcode` (its `G38` moves, output coordinates), each measurement
//! matched by XY within `--tolerance`; missing/extra/duplicate/beyond `--max` located; `_Z.txt`
//! filled in for `adjust_with_log` (mod.rs).

use super::bounds::{line_origin, LIMIT};
use super::probe_log::Measurement;
use super::zfile::split_z_line;
use crate::args;
use crate::diag::{Diags, Msg, Origin};
use crate::geom::f3;

/// Default `--tolerance`, mm: our probing programs print 3 decimals, controllers log what
/// they reached (LinuxCNC: the commanded XY, GRBL: steps of a few µm).
pub const DEFAULT_TOLERANCE: f64 = 0.05;
/// Largest `--tolerance`, mm: beyond this, neighbouring probes could be confused.
pub const MAX_TOLERANCE: f64 = 1.0;

/// `None` when `tol` is a usable tolerance, else the option error.
pub fn check_tolerance(tol: f64, text: &str) -> Option<crate::diag::Diagnostic> {
    (!(tol.is_finite() && tol > 0.0 && tol <= MAX_TOLERANCE)).then(|| {
        crate::diag::Diagnostic::error(Msg::ProbeLogToleranceInvalid, Origin::Options, args![text])
    })
}

/// One probe point of the probing program: where it touches and its 1-based line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbePoint {
    pub line: usize,
    pub x: f64,
    pub y: f64,
}

/// The number of a `X`/`Y` word in a `G00` line.
fn word(line: &str, letter: char) -> Option<f64> {
    line.split_whitespace()
        .find_map(|w| w.strip_prefix(letter))
        .and_then(|v| v.parse::<f64>().ok())
        .filter(|v| v.is_finite() && v.abs() <= LIMIT)
}

/// The XY of every probe move of a probing program (`G38.x`; `G31` of Mach and UCCNC), in
/// order (the current XY when it starts; our probing programs move only Z there).
pub fn probe_points(probing: &str) -> Vec<ProbePoint> {
    let (mut x, mut y) = (0.0, 0.0);
    let mut out = Vec::new();
    for (i, line) in probing.lines().enumerate() {
        let code = line.split(['(', ';']).next().unwrap_or("");
        if code
            .split_whitespace()
            .any(|w| w.starts_with("G38") || w == "G31")
        {
            out.push(ProbePoint { line: i + 1, x, y });
        } else if code.split_whitespace().any(|w| w == "G00" || w == "G0") {
            x = word(code, 'X').unwrap_or(x);
            y = word(code, 'Y').unwrap_or(y);
        }
    }
    out
}

/// The probing program, the `_Z.txt` and the log of one set, by file name and text.
pub struct LogInputs<'a> {
    pub probing: (&'a str, &'a str),
    pub z: (&'a str, &'a str),
    pub log: (&'a str, &'a [Measurement]),
}

/// `_Z.txt` filled in with the measured heights of the log, or `None` after errors (each
/// naming the point and its file and line): a probe without a measurement, a measurement of no
/// probe, two for one probe, a height further than `max` from the nominal one.
pub fn fill_z_from_log(inputs: LogInputs, tol: f64, max: f64, diags: &mut Diags) -> Option<String> {
    let before = diags.error_count();
    let (probing_file, probing) = inputs.probing;
    let (z_file, z) = inputs.z;
    let (log_file, log) = inputs.log;
    let points = probe_points(probing);
    // the probe lines of _Z.txt, in tour order like the program's G38 moves
    let z_lines: Vec<(usize, &str)> = z
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| (i + 1, l))
        .collect();
    let mut probes = Vec::new();
    for &(line, text) in &z_lines {
        match split_z_line(text) {
            Some((t, digits, _)) => probes.push((line, format!("#{digits}"), t)),
            None => diags.error(Msg::ZLineFormat, line_origin(z_file, line), vec![]),
        }
    }
    if diags.error_count() > before {
        return None;
    }
    if points.len() != probes.len() {
        diags.error(
            Msg::ProbeLogProbingMismatch,
            line_origin(probing_file, 1),
            args![probing_file, points.len(), z_file, probes.len()],
        );
        return None;
    }
    // measurement index per probe
    let mut taken: Vec<Option<usize>> = vec![None; points.len()];
    for (mi, m) in log.iter().enumerate() {
        let origin = line_origin(log_file, m.line);
        let dist = |p: &ProbePoint| (p.x - m.x).hypot(p.y - m.y);
        let mut near: Vec<usize> = (0..points.len())
            .filter(|&k| dist(&points[k]) <= tol)
            .collect();
        // the nearest first; equal distances (one point probed twice) in tour order
        near.sort_by(|&a, &b| {
            dist(&points[a])
                .total_cmp(&dist(&points[b]))
                .then(a.cmp(&b))
        });
        let Some(&first) = near.first() else {
            diags.error(
                Msg::ProbeLogExtra,
                origin,
                args![f3(m.x), f3(m.y), probing_file, tol],
            );
            continue;
        };
        match near.iter().find(|&&k| taken[k].is_none()) {
            Some(&k) => taken[k] = Some(mi),
            None => {
                let earlier = taken[first].map_or(0, |e| log[e].line);
                diags.error(
                    Msg::ProbeLogDuplicate,
                    origin,
                    args![probes[first].1, f3(m.x), f3(m.y), earlier],
                );
            }
        }
    }
    let mut values = Vec::with_capacity(points.len());
    for (k, p) in points.iter().enumerate() {
        let (_, name, t_text) = &probes[k];
        let Some(mi) = taken[k] else {
            diags.error(
                Msg::ProbeLogMissing,
                line_origin(probing_file, p.line),
                args![log_file, name, f3(p.x), f3(p.y)],
            );
            continue;
        };
        let m = log[mi];
        // the nominal height as _Z.txt says it; adjust-z checks it against _Clean.gcode
        let t = t_text.replace(',', ".").parse::<f64>().ok();
        if t.is_none_or(|t| !t.is_finite() || (m.z - t).abs() > max) {
            diags.error(
                Msg::ProbeLogTooFar,
                line_origin(log_file, m.line),
                args![m.z, name, t_text, max],
            );
            continue;
        }
        values.push(m.z);
    }
    if diags.error_count() > before {
        return None;
    }
    // the lines as compile wrote them, each value after its `=` (shortest text that reads
    // back as the same number: the same program as with the value typed in)
    let mut filled = String::with_capacity(z.len() + 16 * values.len());
    let mut next = values.iter();
    for line in z.lines() {
        if line.trim().is_empty() {
            filled.push('\n');
            continue;
        }
        let head = line.rfind('=').map_or(line, |e| &line[..=e]);
        let v = next.next().copied().unwrap_or(f64::NAN);
        filled.push_str(&format!("{head}{v}\n"));
    }
    Some(filled)
}

#[cfg(test)]
mod tests {
    use super::*;

    const PROBING: &str = "%\n(banner)\nG00 Z5.000\nG00 X0.000 Y0.000\nG00 X10.000 Y5.000\nG00 Z4.000\nG38.3 Z0 F50.000\nG04 P4\nG00 Z5.000\nG00 X50.000 Y5.000\nG00 Z4.000\nG38.3 Z0 F50.000\nG04 P4\nG00 Z5.000\nG00 X0.000 Y0.000\nM30\n%\n";
    const Z: &str = "([10.000 5.000]/T=3.000) #51=\n([50.000 5.000]/L:1/T=3.000) #52=\n";

    fn m(line: usize, x: f64, y: f64, z: f64) -> Measurement {
        Measurement { line, x, y, z }
    }

    fn fill(log: &[Measurement], max: f64) -> (Option<String>, Vec<(Msg, String)>, Diags) {
        let mut d = Diags::default();
        let inputs = LogInputs {
            probing: ("p", PROBING),
            z: ("z", Z),
            log: ("log", log),
        };
        let out = fill_z_from_log(inputs, DEFAULT_TOLERANCE, max, &mut d);
        let msgs = d.list.iter().map(|x| (x.msg, x.origin.context())).collect();
        (out, msgs, d)
    }

    #[test]
    fn probe_points_are_where_the_program_probes() {
        let p = probe_points(PROBING);
        assert_eq!(
            p,
            [
                ProbePoint {
                    line: 7,
                    x: 10.0,
                    y: 5.0
                },
                ProbePoint {
                    line: 12,
                    x: 50.0,
                    y: 5.0
                }
            ]
        );
        // Mach's and UCCNC's G31 probes are probe points too (their pause is M0)
        let mach = PROBING.replace("G38.3", "G31").replace("G04 P4", "M0");
        assert_eq!(probe_points(&mach), p);
    }

    #[test]
    fn fills_in_each_probe_in_any_order() {
        let (out, msgs, _) = fill(&[m(1, 50.001, 5.0, 3.1), m(2, 10.0, 4.99, 2.95)], 0.5);
        assert!(msgs.is_empty(), "{msgs:?}");
        assert_eq!(
            out.unwrap(),
            "([10.000 5.000]/T=3.000) #51=2.95\n([50.000 5.000]/L:1/T=3.000) #52=3.1\n"
        );
    }

    #[test]
    fn missing_extra_duplicate_and_too_far_are_refused() {
        let (out, msgs, d) = fill(&[m(1, 10.0, 5.0, 2.95)], 0.5);
        assert!(out.is_none());
        assert_eq!(msgs, [(Msg::ProbeLogMissing, "p:12".to_string())]);
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "No measurement in log for probe #52 at X50.000 Y5.000"
        );
        let (out, msgs, _) = fill(
            &[
                m(1, 10.0, 5.0, 2.95),
                m(2, 50.0, 5.0, 3.0),
                m(3, 30.0, 5.0, 3.0),
            ],
            0.5,
        );
        assert!(out.is_none());
        assert_eq!(msgs, [(Msg::ProbeLogExtra, "log:3".to_string())]);
        let (out, msgs, d) = fill(
            &[
                m(1, 10.0, 5.0, 2.95),
                m(2, 50.0, 5.0, 3.0),
                m(4, 10.01, 5.0, 3.0),
            ],
            0.5,
        );
        assert!(out.is_none());
        assert_eq!(msgs, [(Msg::ProbeLogDuplicate, "log:4".to_string())]);
        assert_eq!(
            d.list[0].message(crate::Lang::De),
            "Eine zweite Messung für Messpunkt #51 bei X10.010 Y5.000 (die erste steht in Zeile 1)"
        );
        let (out, msgs, d) = fill(&[m(1, 10.0, 5.0, 2.95), m(2, 50.0, 5.0, 3.6)], 0.5);
        assert!(out.is_none());
        assert_eq!(msgs, [(Msg::ProbeLogTooFar, "log:2".to_string())]);
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "Measured height 3.6 for probe #52 differs from its nominal height 3.000 by more than --max=0.5"
        );
    }

    #[test]
    fn one_point_probed_twice_takes_two_measurements_in_order() {
        let probing = PROBING.replace("G00 X50.000 Y5.000\n", "");
        let mut d = Diags::default();
        let log = [m(1, 10.0, 5.0, 2.9), m(2, 10.0, 5.0, 3.05)];
        let inputs = LogInputs {
            probing: ("p", &probing),
            z: ("z", Z),
            log: ("log", &log),
        };
        let out = fill_z_from_log(inputs, DEFAULT_TOLERANCE, 0.5, &mut d).unwrap();
        assert!(out.ends_with("#51=2.9\n([50.000 5.000]/L:1/T=3.000) #52=3.05\n"));
    }

    #[test]
    fn a_program_and_z_file_that_disagree_are_refused() {
        let mut d = Diags::default();
        let inputs = LogInputs {
            probing: ("p", PROBING),
            z: ("z", "([10.000 5.000]/T=3.000) #51=\n"),
            log: ("log", &[]),
        };
        assert!(fill_z_from_log(inputs, DEFAULT_TOLERANCE, 0.5, &mut d).is_none());
        assert_eq!(d.list[0].msg, Msg::ProbeLogProbingMismatch);
    }

    #[test]
    fn tolerance_must_be_sane() {
        for bad in [f64::NAN, f64::INFINITY, 0.0, -0.1, 1.5] {
            assert!(check_tolerance(bad, "x").is_some(), "{bad}");
        }
        assert!(check_tolerance(DEFAULT_TOLERANCE, "0.05").is_none());
    }
}
