//! adjust-z: `_Clean.gcode` + measured `_Z.txt` → `_Milling.gcode` (reference-output.md §15).
//!
//! Beyond the reference, adjust-z refuses anything that could make a dangerous program
//! (docs/differences.md): every number must be finite and within ±[`LIMIT`]; the nominal
//! height of each probe comes from `_Clean.gcode` (the `w*[#n-TH]` terms), and `_Z.txt` must
//! agree with it and hold exactly the probes used there; `_Clean.gcode` must be a complete
//! program; lines and expression nesting are bounded. [`adjust`] is the one entry point.
//!
//! Adjust-z's entry points (`adjust`, `adjust_set`: digest check, then reading, then rewriting;
//! reference-output.md §15) and `base_path`; the bounds on what it reads are in `bounds.rs`.

mod bounds;
mod carry;
mod expr;
mod follow;
mod grid_set;
mod log_match;
mod probe_log;
mod rewrite;
mod set_check;
mod words;
mod zfile;

pub use crate::digest::{
    banner_index, banner_index_of_first, banner_with_digest, set_digest, set_digest_lines,
    stored_digest, SET_WORD,
};
pub use bounds::{check_max, MaxOption, LIMIT, MAX_DEPTH, MAX_LINE};
pub use carry::{plan_new_z, Aside, OldZ, Unreadable, ZPlan};
pub use expr::eval;
pub use follow::{split_summary, Followed, CHORD_TOL, MAX_LINES, SPLIT_WORD};
pub use log_match::{
    check_tolerance, fill_z_from_log, probe_points, LogInputs, ProbePoint, DEFAULT_TOLERANCE,
    MAX_TOLERANCE,
};
pub use probe_log::{
    detect, read_measurements, LogFormat, Measurement, MAX_LOG_BYTES, MAX_LOG_LINES,
};
use rewrite::rewrite_program;
pub use rewrite::{measured_values, read_clean, CleanProgram, Probe, PROBES_WORD};
pub use set_check::{check_set, SetFile};
pub use zfile::{parse_z_file, ZLine};

use crate::args;
use crate::diag::{Diags, Msg, Origin};
use bounds::line_origin;
use millpath_post::Post;

/// The file argument reduced to its base: `.dxf`, `_Clean.gcode`, `_Z.txt` or `.gcode` removed.
pub fn base_path(arg: &str) -> String {
    let lower = arg.to_ascii_lowercase();
    for suffix in [".dxf", "_clean.gcode", "_z.txt", ".gcode", ".mpath"] {
        if lower.ends_with(suffix) {
            return arg[..arg.len() - suffix.len()].to_string();
        }
    }
    arg.to_string()
}

/// The whole of adjust-z for one part: `_Milling.gcode`'s content, or `None` after errors
/// (each naming its file and line). Nothing is produced unless every check passes. A height
/// map's moves are written as the `linuxcnc` post writes them ([`adjust_set`] takes the post).
pub fn adjust(
    clean: &str,
    clean_file: &str,
    z: &str,
    z_file: &str,
    max: f64,
    opt: MaxOption,
    diags: &mut Diags,
) -> Option<String> {
    let clean = SetFile {
        name: clean_file,
        text: clean,
    };
    let z = SetFile {
        name: z_file,
        text: z,
    };
    adjust_set(
        clean,
        z,
        None,
        max,
        opt,
        crate::Dialect::LinuxCnc.post(),
        diags,
    )
}

/// Whether a `_Z.txt` lists the points of a height map (`[heightmap]`: `#1000` on), not
/// drawn probes.
fn is_height_map(lines: &[ZLine]) -> bool {
    let grid_var = |l: &ZLine| {
        l.name
            .strip_prefix('#')
            .and_then(|n| n.parse::<usize>().ok())
            .is_some_and(|n| n >= crate::probe::heightmap::FIRST_VAR)
    };
    !lines.is_empty() && lines.iter().all(grid_var)
}

/// [`adjust`] with the `_Probing.gcode` beside them, when there is one: a set whose files
/// come from different compiles is refused first ([`check_set`]), as its other errors would
/// only be consequences of the mix. `post` is the post the set was written with: a height
/// map's moves are written in its words.
pub fn adjust_set(
    clean: SetFile,
    z: SetFile,
    probing: Option<SetFile>,
    max: f64,
    opt: MaxOption,
    post: &Post,
    diags: &mut Diags,
) -> Option<String> {
    let before = diags.error_count();
    if let Some(d) = check_max(max, &max.to_string(), opt) {
        diags.push(d);
        return None;
    }
    let (clean, z) = (clean.without_bom(), z.without_bom());
    let probing = probing.map(SetFile::without_bom);
    let (clean_file, z_file) = (clean.name, z.name);
    let (clean_text, z_text) = (clean.text, z.text);
    if !check_set(clean, z, probing, diags) {
        return None;
    }
    let lines = parse_z_file(z_text, z_file, diags);
    if is_height_map(&lines) {
        // a grid's clean program is nominal: its moves are made to follow the surface; a cut
        // off or unfinished program is refused as for drawn probes
        read_clean(clean_text, clean_file, diags);
        if diags.error_count() > before {
            return None;
        }
        let map = grid_set::surface(z_text, z_file, &lines, max, opt, diags)?;
        return follow::follow(clean_text, clean_file, &map, post, diags).map(|f| f.text);
    }
    let prog = read_clean(clean_text, clean_file, diags);
    if diags.error_count() > before {
        return None;
    }
    let vars = measured_values(&prog, clean_file, &lines, z_file, max, opt, diags);
    if diags.error_count() > before {
        return None;
    }
    let milling = rewrite_program(clean_text, clean_file, &prog, &vars, diags);
    if diags.error_count() > before {
        return None;
    }
    // only our own compiles (with a digest) get the measured values for `verify`: a reference
    // `_Clean.gcode` gives the reference's `_Milling.gcode` unchanged
    Some(match stored_digest(clean_text) {
        Some(_) => rewrite::record_measured(&milling, &prog, &vars),
        None => milling,
    })
}

/// [`adjust_set`] with the measured heights read from a controller's probe log instead of
/// the values typed into `_Z.txt` (which still names each probe and its nominal height): each
/// measurement is matched by XY, within `tol`, to a `G38` move of the probing program, which
/// is therefore required. A filled-in `_Z.txt` as the log is read as today.
pub fn adjust_with_log(
    set: [SetFile; 2],
    probing: Option<SetFile>,
    log: SetFile,
    tol: f64,
    max: f64,
    post: &Post,
    diags: &mut Diags,
) -> Option<String> {
    let [clean, z] = set.map(SetFile::without_bom);
    let (probing, log) = (probing.map(SetFile::without_bom), log.without_bom());
    let opt = MaxOption::Long;
    let Some(probing) = probing else {
        let name = format!("{}_Probing.gcode", base_path(clean.name));
        diags.error(Msg::ProbeLogNoProbing, Origin::Input, args![name]);
        return None;
    };
    if let Some(d) = check_tolerance(tol, &tol.to_string()) {
        diags.push(d);
        return None;
    }
    let format = match probe_log::detect(log.text) {
        Some(LogFormat::ZFile) => {
            return adjust_set(clean, log, Some(probing), max, opt, post, diags)
        }
        Some(f) => f,
        None => {
            let first = log.text.lines().position(|l| !l.trim().is_empty());
            let at = line_origin(log.name, first.map_or(1, |i| i + 1));
            diags.error(Msg::ProbeLogUnknownFormat, at, vec![]);
            return None;
        }
    };
    // a mix of compiles first: the matching's errors would only be its consequences
    if !check_set(clean, z, Some(probing), diags) {
        return None;
    }
    let before = diags.error_count();
    let measured = read_measurements(log.text, log.name, format, diags);
    if diags.error_count() > before {
        return None;
    }
    let inputs = LogInputs {
        probing: (probing.name, probing.text),
        z: (z.name, z.text),
        log: (log.name, &measured),
    };
    let filled = fill_z_from_log(inputs, tol, max, diags)?;
    let z = SetFile {
        name: z.name,
        text: &filled,
    };
    adjust_set(clean, z, Some(probing), max, opt, post, diags)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rewrite::{has_expression_mark, z_regex};

    const CLEAN: &str =
        "%\nG00 Z5.000\nG01 Z0.800(=0.800+0.794*[#51-2.000]+0.206*[#52-2.000])\nM30\n%\n";
    const Z: &str = "([57.358 242.020]/T=2.000) #51=2,1\n\n([1.000 2.000]/L:a/T=2.000) #52=2.2\n";

    fn run(clean: &str, z: &str, max: f64) -> (Option<String>, Vec<Msg>, Diags) {
        let mut d = Diags::default();
        let out = adjust(clean, "c", z, "z", max, MaxOption::Slash, &mut d);
        let msgs = d.list.iter().map(|x| x.msg).collect();
        (out, msgs, d)
    }

    #[test]
    fn adjusts_good_input_unchanged() {
        let (out, msgs, _) = run(CLEAN, Z, 1.0);
        assert!(msgs.is_empty(), "{msgs:?}");
        assert_eq!(
            out.unwrap(),
            "%\nG00 Z5.000\nG01 Z0.921(==0.800+0.794*[#51-2.000]+0.206*[#52-2.000])\nM30\n%\n"
        );
    }

    #[test]
    fn non_finite_or_insane_numbers_are_refused() {
        for bad in [
            "NaN",
            "inf",
            "Infinity",
            "-Infinity",
            "1e999",
            "2e6",
            "-1000001",
        ] {
            let z = Z.replace("#51=2,1", &format!("#51={bad}"));
            let (out, msgs, d) = run(CLEAN, &z, 1e6);
            assert!(out.is_none(), "{bad}");
            assert!(
                msgs == [Msg::ZNotNumber] || msgs == [Msg::ZOutOfRange],
                "{bad}: {msgs:?}"
            );
            assert_eq!(d.list[0].origin.context(), "z:1");
            let z = Z.replace("T=2.000) #51", &format!("T={bad}) #51"));
            assert!(run(CLEAN, &z, 1e6).0.is_none(), "T={bad}");
        }
        let (_, _, d) = run(CLEAN, &Z.replace("#51=2,1", "#51=NaN"), 1.0);
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "Value 'NaN' for #51 is not a valid number"
        );
        let (_, msgs, _) = run(CLEAN, &Z.replace("#51=2,1", "#51=2e6"), 1.0);
        assert_eq!(msgs, [Msg::ZOutOfRange]);
    }

    #[test]
    fn max_must_be_finite_and_positive() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0, -1.0, 2e6] {
            let (out, msgs, _) = run(CLEAN, Z, bad);
            assert!(out.is_none(), "{bad}");
            assert_eq!(msgs, [Msg::MaxInvalid], "{bad}");
        }
        let d = check_max(f64::NAN, "NaN", MaxOption::Long).unwrap();
        assert_eq!(
            d.message(crate::Lang::En),
            "--max value NaN must be a finite number > 0 and at most 1000000"
        );
        assert!(check_max(0.5, "0.5", MaxOption::Slash).is_none());
    }

    #[test]
    fn nominal_height_comes_from_clean_gcode() {
        // editing T in _Z.txt does not move the limit: the T must match _Clean.gcode
        let z = Z.replace("T=2.000) #51=2,1", "T=-50) #51=-50");
        let (out, msgs, d) = run(CLEAN, &z, 0.5);
        assert!(out.is_none());
        assert_eq!(msgs, [Msg::ZNominalMismatch]);
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "T=-50 for #51 differs from its nominal height 2.000 in c:3"
        );
        assert_eq!(d.list[0].origin.context(), "z:1");
        // the limit is measured from the nominal height of _Clean.gcode
        let z = Z.replace("#51=2,1", "#51=2.6");
        assert_eq!(run(CLEAN, &z, 0.5).1, [Msg::ZTooFar]);
        // T written differently but equal is fine
        let z = Z.replace("T=2.000) #51", "T=2) #51");
        assert!(run(CLEAN, &z, 0.5).0.is_some());
        // a probe of _Clean.gcode without a value
        let (out, msgs, d) = run(CLEAN, "([0 0]/T=2.000) #51=2\n", 0.5);
        assert!(out.is_none());
        assert_eq!(msgs, [Msg::ZProbeMissing]);
        assert_eq!(d.list[0].origin.context(), "c:3");
        // one probe with two nominal heights in _Clean.gcode
        let clean = CLEAN.replace("M30", "G01 Z1.000(=1.000+1.000*[#51-3.000])\nM30");
        assert_eq!(run(&clean, Z, 0.5).1, [Msg::ZProbeHeightsDiffer]);
        // a probe variable outside a [#n-TH] term
        let clean = CLEAN.replace("M30", "G01 Z1.000(=1.000+#51)\nM30");
        assert_eq!(run(&clean, Z, 0.5).1, [Msg::ZProbeTermForm]);
    }

    #[test]
    fn negative_nominal_heights() {
        let clean = "%\nG01 Z-1.000(=-1.000+1.000*[#51--1.500])\nM30\n%\n";
        let (out, msgs, _) = run(clean, "([0 0]/T=-1.500) #51=-1,4\n", 0.5);
        assert!(msgs.is_empty(), "{msgs:?}");
        assert_eq!(
            out.unwrap(),
            "%\nG01 Z-0.900(==-1.000+1.000*[#51--1.500])\nM30\n%\n"
        );
    }

    #[test]
    fn incomplete_programs_are_refused() {
        for (clean, line) in [
            ("", 1),
            ("\n\n", 1),
            ("G00 Z5.000\nM30\n%\n", 1),
            ("%\nG00 Z5.000\nM30\n", 3),
            ("%\nG00 Z5.000\n%\n", 3),
            ("%\nG01 Z0.800(=0.800+0.794*[#51-2.000]+0.206*[#52-2.0", 2),
            ("%\n", 1),
        ] {
            let (out, msgs, d) = run(clean, "", 0.5);
            assert!(out.is_none(), "{clean:?}");
            assert!(
                msgs.contains(&Msg::ZIncompleteProgram),
                "{clean:?}: {msgs:?}"
            );
            let d = d
                .list
                .iter()
                .find(|d| d.msg == Msg::ZIncompleteProgram)
                .unwrap();
            assert_eq!(d.origin.context(), format!("c:{line}"), "{clean:?}");
        }
        // trailing blank lines and CR LF are fine
        let crlf = CLEAN.replace('\n', "\r\n") + "\r\n";
        assert!(run(&crlf, Z, 1.0).0.is_some());
    }

    #[test]
    fn a_byte_order_mark_is_read_past_and_not_written() {
        // Notepad saves `_Clean.gcode` and `_Z.txt` with a BOM; LinuxCNC rejects one in the
        // program adjust-z writes ("Bad character")
        let plain = run(CLEAN, Z, 1.0).0.unwrap();
        let (out, msgs, _) = run(&format!("\u{feff}{CLEAN}"), &format!("\u{feff}{Z}"), 1.0);
        assert!(msgs.is_empty(), "{msgs:?}");
        assert_eq!(out.unwrap(), plain);
    }

    #[test]
    fn unknown_probes_in_z_file_are_errors() {
        let z = format!("{Z}([0 0]/T=2.000) #99=2\n");
        let (out, msgs, d) = run(CLEAN, &z, 1.0);
        assert!(out.is_none());
        assert_eq!(msgs, [Msg::ZUnknownProbe]);
        assert_eq!(d.list[0].origin.context(), "z:4");
    }

    #[test]
    fn too_far_names_the_measured_value_first() {
        let z = Z.replace("#51=2,1", "#51=9,9");
        let (_, _, d) = run(CLEAN, &z, 0.5);
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "Value 9,9 for #51 differs from 2.000 by more than /m=0.5"
        );
        let mut d = Diags::default();
        adjust(CLEAN, "c", &z, "z", 0.5, MaxOption::Long, &mut d);
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "Value 9,9 for #51 differs from 2.000 by more than --max=0.5"
        );
        assert_eq!(
            d.list[0].message(crate::Lang::De),
            "Wert 9,9 für #51 weicht von 2.000 um mehr als --max=0.5 ab"
        );
    }

    #[test]
    fn clean_lines_the_rewriting_cannot_handle_are_refused() {
        // a second expression on a line would stay uncorrected
        let clean = CLEAN.replace(
            "M30",
            "G01 X1.000(=1.000+1.000*[#51-2.000]) Z0.800(=0.800+1.000*[#51-2.000])\nM30",
        );
        assert_eq!(run(&clean, Z, 1.0).1, [Msg::ZUnreadableExpression]);
        let clean = CLEAN.replace("M30", "G01 Z0.800(=0.800 + 1.000*[#51-2.000])\nM30");
        assert_eq!(run(&clean, Z, 1.0).1, [Msg::ZUnreadableExpression]);
        // an already adjusted line carries an old measurement
        let clean = CLEAN.replace("M30", "G01 Z0.900(==0.800+1.000*[#51-2.000])\nM30");
        assert_eq!(run(&clean, Z, 1.0).1, [Msg::ZAlreadyAdjusted]);
        // a long line
        let clean = CLEAN.replace("M30", &format!("({})\nM30", "x".repeat(MAX_LINE)));
        assert_eq!(run(&clean, Z, 1.0).1, [Msg::LineTooLong]);
        // comments may say anything
        let clean = CLEAN.replace("M30", "  (a (=b (==c)\n; G00 Z1(=x\nM30");
        assert!(run(&clean, Z, 1.0).0.is_some());
        // expression errors name the line
        let clean = CLEAN.replace("[#52-2.000])", "[#52-2.000)");
        let (_, msgs, d) = run(&clean, Z, 1.0);
        assert_eq!(msgs, [Msg::ExprBracketExpected]);
        assert_eq!(d.list[0].origin.context(), "c:3");
    }

    #[test]
    fn rewrites_lines_once() {
        let (out, _, _) = run(CLEAN, Z, 1.0);
        let out = out.unwrap();
        // the adjusted program no longer matches: nothing is left to rewrite
        assert!(!has_expression_mark(&out));
        assert!(z_regex().captures(&out).is_none());
    }

    #[test]
    fn a_height_maps_clean_program_cut_off_is_refused() {
        let z = "([0.000 0.000]/T=2.000) #1000=2.1\n([10.000 0.000]/T=2.000) #1001=2.2\n";
        let whole = "%\n(MILLPATH-STOCK T=2.000 O=1.000)\nG00 Z5.000\nG00 X0.000 Y0.000\nG00 Z3.000\nG01 F100.000 Z1.000\nG01 X10.000 Z1.000\nG00 Z5.000\nM30\n%\n";
        let (out, msgs, _) = run(whole, z, 1.0);
        assert!(msgs.is_empty(), "{msgs:?}");
        assert!(out.unwrap().contains("\nG01 X10.000 Y0.000 Z1.200\n"));
        // cut off before its end: the rest of the cuts would be missing from the program
        let cut = &whole[..whole.find("G00 Z5.000\nM30").unwrap()];
        let (out, msgs, _) = run(cut, z, 1.0);
        assert!(out.is_none());
        assert_eq!(msgs, [Msg::ZIncompleteProgram]);
    }

    #[test]
    fn base_paths() {
        assert_eq!(base_path("a/8999.19P.dxf"), "a/8999.19P");
        assert_eq!(base_path("8999.19P_Clean.gcode"), "8999.19P");
        assert_eq!(base_path("8999.19P_Z.txt"), "8999.19P");
        assert_eq!(base_path("x.GCODE"), "x");
        assert_eq!(base_path("x"), "x");
    }

    #[test]
    fn grbl_programs_without_percent_are_complete() {
        let grbl = CLEAN.replace("%\n", "");
        assert!(run(&grbl, Z, 1.0).0.is_some());
        let cut = grbl.replace("M30\n", "");
        assert_eq!(run(&cut, Z, 1.0).1, [Msg::ZIncompleteProgram]);
    }

    #[test]
    fn own_compiles_get_the_measured_values_for_verify() {
        let stamp = |clean: &str| {
            let clean = clean.replacen("%\n", "%\n(millpath V.1)\n", 1);
            let d = set_digest(Z, &clean);
            clean.replace("(millpath V.1)", &format!("(millpath V.1 set={d})"))
        };
        // reference dialect: the banner comment carries them
        let (out, msgs, _) = run(&stamp(CLEAN), Z, 1.0);
        assert!(msgs.is_empty(), "{msgs:?}");
        let out = out.unwrap();
        let line2 = out.lines().nth(1).unwrap();
        assert!(
            line2.ends_with(" MILLPATH-PROBES #51=2.100 #52=2.200)"),
            "{line2}"
        );
        assert_eq!(out.lines().count(), stamp(CLEAN).lines().count());
        // other dialects: lines after the stock comment
        let with_stock =
            CLEAN.replace("G00 Z5.000", "(MILLPATH-STOCK T=2.000 O=1.000)\nG00 Z5.000");
        let out = run(&stamp(&with_stock), Z, 1.0).0.unwrap();
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines[3], "(MILLPATH-PROBES #51=2.100 #52=2.200)");
        assert!(!lines[1].contains("MILLPATH-PROBES"));
        // a reference _Clean.gcode (no digest) gives the reference's output unchanged
        let plain = run(CLEAN, Z, 1.0).0.unwrap();
        assert!(!plain.contains("MILLPATH-PROBES"));
    }

    #[test]
    fn heights_from_a_probe_log_give_the_typed_program() {
        let probing = "%\n(b)\nG00 X0.000 Y0.000\nG00 X10.000 Y5.000\nG38.3 Z0 F50.000\nG00 X50.000 Y5.000\nG38.3 Z0 F50.000\nM30\n%\n";
        let unfilled = "([57.358 242.020]/T=2.000) #51=\n([1.000 2.000]/L:a/T=2.000) #52=\n";
        let set = |name, text| SetFile { name, text };
        let with_log = |log: &str, d: &mut Diags| {
            adjust_with_log(
                [set("c", CLEAN), set("z", unfilled)],
                Some(set("p", probing)),
                SetFile {
                    name: "log",
                    text: log,
                },
                DEFAULT_TOLERANCE,
                0.5,
                crate::Dialect::LinuxCnc.post(),
                d,
            )
        };
        let typed = run(CLEAN, Z, 0.5).0.unwrap();
        for log in [
            "10.000000 5.000000 2.100000 0 0 0 0 0 0\n50.000000 5.000000 2.200000 0 0 0 0 0 0\n",
            "[G54:-1.000,-2.000,-3.000]\n[PRB:49.000,3.000,-0.800:1]\nok\n[PRB:9.000,3.000,-0.900:1]\n",
            "10 5 2.1\n50 5 2.2\n",
            Z,
        ] {
            let mut d = Diags::default();
            let out = with_log(log, &mut d);
            assert!(d.list.is_empty(), "{log}: {:?}", d.list);
            assert_eq!(out.unwrap(), typed, "{log}");
        }
        // every cut of a log either gives the typed program or is refused with an error
        let grbl = "[G54:-1.000,-2.000,-3.000]\n[PRB:49.000,3.000,-0.800:1]\nok\n[PRB:9.000,3.000,-0.900:1]\n";
        for log in [
            "10.000000 5.000000 2.100000 0 0 0 0 0 0\n50.000000 5.000000 2.200000 0 0 0 0 0 0\n",
            grbl,
        ] {
            for cut in 0..log.len() {
                for part in [&log[..cut], &log[cut..]] {
                    let mut d = Diags::default();
                    match with_log(part, &mut d) {
                        Some(out) => assert_eq!(out, typed, "{part:?}"),
                        None => assert!(d.has_errors(), "{part:?}"),
                    }
                }
            }
        }
        // unknown content, named at its first line
        let mut d = Diags::default();
        assert!(with_log("\nG38.3 Z0\n", &mut d).is_none());
        assert_eq!(d.list[0].msg, Msg::ProbeLogUnknownFormat);
        assert_eq!(d.list[0].origin.context(), "log:2");
        assert!(d.list[0]
            .message(crate::Lang::De)
            .starts_with("Kein Antast-Protokoll, das millpath liest"));
        // a NaN height and a no-contact report: refused, nothing produced
        let mut d = Diags::default();
        assert!(with_log("10 5 NaN\n50 5 2.2\n", &mut d).is_none());
        assert_eq!(d.list[0].msg, Msg::ProbeLogBadNumber);
        let mut d = Diags::default();
        assert!(with_log("[G54:0,0,0]\n[PRB:10,5,2.1:1]\n[PRB:50,5,2.2:0]\n", &mut d).is_none());
        assert_eq!(d.list[0].msg, Msg::ProbeLogNoContact);
        // without the probing program there is nothing to match against
        let mut d = Diags::default();
        let out = adjust_with_log(
            [set("x_Clean.gcode", CLEAN), set("z", unfilled)],
            None,
            set("log", "10 5 2.1\n"),
            DEFAULT_TOLERANCE,
            0.5,
            crate::Dialect::LinuxCnc.post(),
            &mut d,
        );
        assert!(out.is_none());
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "--probe-log needs x_Probing.gcode: its probe points say which probe each measurement belongs to"
        );
    }
}
