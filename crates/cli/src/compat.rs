//! Drop-in command lines of the reference tools: `pathdxf2gcode` and `pathgcodeadjustz`
//! (`/f150`, `-f 150`, decimal comma, exit statuses 0/1/2/3, same output files).

use millpath_core::args;
use millpath_core::diag::{Diagnostic, Msg, Origin};
use millpath_core::{Lang, Settings};
use std::path::Path;

/// Parsed reference options.
#[derive(Debug, Default)]
pub struct Parsed {
    pub settings: Settings,
    pub files: Vec<String>,
    pub help: bool,
    pub errors: Vec<Diagnostic>,
    pub m: Option<f64>,
    pub x: Option<String>,
    have_f: bool,
    have_v: bool,
    have_s: bool,
}

/// Which tool's options are parsed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tool {
    Dxf2GCode,
    AdjustZ,
}

fn number(opt: &str, value: &str, errors: &mut Vec<Diagnostic>) -> Option<f64> {
    match millpath_core::params::parse_number(value) {
        Some(v) if v.is_finite() && v >= 0.0 => Some(v),
        Some(v) if v.is_finite() => {
            errors.push(Diagnostic::error(
                Msg::OptionNegative,
                Origin::Options,
                args![opt, value],
            ));
            None
        }
        _ => {
            errors.push(Diagnostic::error(
                Msg::OptionNotNumber,
                Origin::Options,
                args![opt, value],
            ));
            None
        }
    }
}

/// Is this argument a file although it starts with `/`? (Unix absolute paths: the reference
/// runs on Windows where `/` always starts an option.) Decision: an existing file or a path
/// ending in `.dxf`/`.gcode`/`.txt` with a further `/` is a file.
fn looks_like_absolute_file(arg: &str) -> bool {
    if !arg.starts_with('/') || arg.len() < 3 {
        return false;
    }
    let lower = arg.to_ascii_lowercase();
    Path::new(arg).is_file()
        || (arg[1..].contains('/')
            && [".dxf", ".gcode", ".txt", ".mpath"]
                .iter()
                .any(|s| lower.ends_with(s)))
}

pub fn parse(args: &[String], tool: Tool) -> Parsed {
    let mut p = Parsed::default();
    let mut i = 0;
    while i < args.len() {
        let arg = &args[i];
        i += 1;
        if !(arg.starts_with('/') || arg.starts_with('-')) || looks_like_absolute_file(arg) {
            p.files.push(arg.clone());
            continue;
        }
        // GNU-style help is help too (exit 2 as for /h), not "Option /- not supported"
        if arg.eq_ignore_ascii_case("--help") {
            p.help = true;
            break;
        }
        if arg.len() == 1 {
            p.errors.push(Diagnostic::error(
                Msg::MissingOptionValue,
                Origin::Options,
                args![arg],
            ));
            continue;
        }
        if arg[1..].eq_ignore_ascii_case("debug") {
            continue;
        }
        let mut chars = arg[1..].chars();
        let letter = chars.next().unwrap_or(' ').to_ascii_lowercase();
        let rest: String = chars.collect();
        let opt = format!("/{letter}");
        if letter == 'h' || letter == '?' {
            p.help = true;
            break;
        }
        if letter == 'c' && tool == Tool::Dxf2GCode {
            p.settings.check = true;
            continue;
        }
        let takes_value = match tool {
            Tool::Dxf2GCode => "fvszxdnpel".contains(letter),
            Tool::AdjustZ => "mxl".contains(letter),
        };
        if !takes_value {
            p.errors.push(Diagnostic::error(
                Msg::OptionNotSupported,
                Origin::Options,
                args![opt],
            ));
            continue;
        }
        let value = if !rest.is_empty() {
            rest
        } else if i < args.len() {
            i += 1;
            args[i - 1].clone()
        } else {
            p.errors.push(Diagnostic::error(
                Msg::MissingOptionValue,
                Origin::Options,
                args![opt],
            ));
            continue;
        };
        let s = &mut p.settings;
        match letter {
            'f' => {
                if let Some(v) = number(&opt, &value, &mut p.errors) {
                    s.feed = v;
                    p.have_f = true;
                }
            }
            'v' => {
                if let Some(v) = number(&opt, &value, &mut p.errors) {
                    s.sweep_speed = v;
                    p.have_v = true;
                }
            }
            's' => {
                if let Some(v) = number(&opt, &value, &mut p.errors) {
                    s.sweep_height = v;
                    p.have_s = true;
                }
            }
            'z' => s.probe_feed = number(&opt, &value, &mut p.errors),
            'm' => {
                p.m = number(&opt, &value, &mut p.errors);
                // a limit of NaN, 0 or beyond ±1e6 would switch the check off or make it useless
                if let Some(d) = p.m.and_then(|m| {
                    millpath_core::probe::adjustz::check_max(
                        m,
                        &value,
                        millpath_core::probe::adjustz::MaxOption::Slash,
                    )
                }) {
                    p.errors.push(d);
                }
            }
            'x' => match regex::Regex::new(&value) {
                Ok(_) => {
                    if tool == Tool::Dxf2GCode {
                        s.debug_pattern = Some(value);
                    } else {
                        p.x = Some(value);
                    }
                }
                Err(e) => p.errors.push(Diagnostic::error(
                    Msg::BadRegex,
                    Origin::Options,
                    args![opt, value, e],
                )),
            },
            'd' => s.search_dirs.push(value.into()),
            'n' => s.path_pattern = value,
            'p' => s.file_pattern = value,
            'e' => match value.split_once(':') {
                Some((a, b)) => s.restrictions.push((a.to_string(), b.to_string())),
                None => p.errors.push(Diagnostic::error(
                    Msg::EFormat,
                    Origin::Options,
                    args![value],
                )),
            },
            'l' => {
                if value.is_empty()
                    || !value
                        .chars()
                        .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
                {
                    p.errors.push(Diagnostic::error(
                        Msg::OptionNotSupported,
                        Origin::Options,
                        args![format!("/l {value}")],
                    ));
                } else {
                    s.lang = Lang::from_name(&value);
                }
            }
            _ => {}
        }
    }
    if tool == Tool::Dxf2GCode {
        let s = &p.settings;
        if !p.have_f || s.feed <= 0.0 {
            p.errors
                .push(Diagnostic::error(Msg::FMissing, Origin::Options, vec![]));
        }
        if !p.have_v || s.sweep_speed <= 0.0 {
            p.errors
                .push(Diagnostic::error(Msg::VMissing, Origin::Options, vec![]));
        }
        if !p.have_s || s.sweep_height <= 0.0 {
            p.errors
                .push(Diagnostic::error(Msg::SMissing, Origin::Options, vec![]));
        }
    } else if !p.help && p.m.is_none() {
        p.errors
            .push(Diagnostic::error(Msg::MissingM, Origin::Options, vec![]));
    }
    p
}

/// The reference tools' answer to a command line they cannot run, printed after the
/// banner: the option errors and the help (exit 2), or "no files" (exit 3). `None` when the
/// command line can run.
pub fn refused(args: &[String], parsed: &Parsed, help: &str) -> Option<u8> {
    use millpath_core::diag::{Diagnostic, Msg, Origin};
    let lang = parsed.settings.lang;
    if args.is_empty() || parsed.help || !parsed.errors.is_empty() {
        for e in &parsed.errors {
            eprintln!("{}", e.reference_line(lang));
        }
        eprintln!();
        eprintln!("{help}");
        return Some(2);
    }
    if parsed.files.is_empty() {
        eprintln!(
            "{}",
            Diagnostic::error(Msg::NoDxfFiles, Origin::Options, vec![]).reference_line(lang)
        );
        return Some(3);
    }
    None
}

pub fn help_dxf2gcode(lang: Lang) -> &'static str {
    match lang {
        Lang::En => {
            "\
Usage: millpath pathdxf2gcode [options] FILE.dxf...
Compiles path drawings to G-code, compatible with PathDxf2GCode.
  /f FEED       feed for milling moves in mm/min (required, > 0)
  /v SPEED      sweep speed in mm/min, for time estimates (required, > 0)
  /s HEIGHT     sweep height of the top-level path in mm (required, > 0)
  /z FEED       probe feed in mm/min (default: /f)
  /c            check all paths of each file, write nothing
  /x REGEX      show which element each matching text was assigned to
  /d DIR        further directory to search for subpaths (repeatable)
  /n REGEX      path-name pattern (default ([0-9]{4})[.]([0-9]+)([A-Z]))
  /p REGEX      file-name pattern (default ([0-9]{4})(?:[.]([0-9]+))?)
  /e P:C        paths matching P may only embed subpaths matching C (repeatable)
  /l LANG       message language (en, de)
  /h, /?        this help
Options may start with / or -, values may follow directly or as the next argument,
a decimal comma is accepted. Exit status: 0 ok, 1 errors in the drawings, 2 option
errors or help, 3 no files given."
        }
        Lang::De => {
            "\
Aufruf: millpath pathdxf2gcode [Optionen] DATEI.dxf...
Übersetzt Pfadzeichnungen in G-Code, kompatibel mit PathDxf2GCode.
  /f VORSCHUB   Vorschub für Fräsbewegungen in mm/min (nötig, > 0)
  /v TEMPO      Leerfahrt-Geschwindigkeit in mm/min, für Zeitschätzungen (nötig, > 0)
  /s HÖHE       Leerfahrt-Höhe des Hauptpfads in mm (nötig, > 0)
  /z VORSCHUB   Fühl-Vorschub in mm/min (Standard: /f)
  /c            alle Pfade jeder Datei prüfen, nichts schreiben
  /x REGEX      Zuordnung passender Texte zu Elementen anzeigen
  /d VERZ       weiteres Suchverzeichnis für Teilpfade (mehrfach möglich)
  /n REGEX      Muster für Pfadnamen (Standard ([0-9]{4})[.]([0-9]+)([A-Z]))
  /p REGEX      Muster für Dateinamen (Standard ([0-9]{4})(?:[.]([0-9]+))?)
  /e P:C        Pfade passend zu P dürfen nur Teilpfade passend zu C einbetten
  /l SPRACHE    Sprache der Meldungen (en, de)
  /h, /?        diese Hilfe
Optionen beginnen mit / oder -, Werte direkt dahinter oder als nächstes Argument,
Dezimalkomma erlaubt. Exit-Status: 0 ok, 1 Fehler in Zeichnungen, 2 Optionsfehler
oder Hilfe, 3 keine Dateien angegeben."
        }
    }
}

pub fn help_adjustz(lang: Lang) -> &'static str {
    match lang {
        Lang::En => {
            "\
Usage: millpath pathgcodeadjustz /m MAX [/x REGEX] [/l LANG] FILE...
Turns NAME_Clean.gcode and the measured NAME_Z.txt into NAME_Milling.gcode.
  /m MAX        largest allowed difference between a measured and the nominal height (mm, > 0)
  /x REGEX      print the input lines that match
  /l LANG       message language (en, de)
FILE may be NAME.dxf, NAME_Clean.gcode, NAME_Z.txt or NAME."
        }
        Lang::De => {
            "\
Aufruf: millpath pathgcodeadjustz /m MAX [/x REGEX] [/l SPRACHE] DATEI...
Erzeugt aus NAME_Clean.gcode und der gemessenen NAME_Z.txt die NAME_Milling.gcode.
  /m MAX        größte erlaubte Abweichung zwischen gemessener und Soll-Höhe (mm, > 0)
  /x REGEX      passende Eingabezeilen ausgeben
  /l SPRACHE    Sprache der Meldungen (en, de)
DATEI kann NAME.dxf, NAME_Clean.gcode, NAME_Z.txt oder NAME sein."
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn a(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn attached_and_separate_values_and_decimal_comma() {
        let p = parse(&a(&["A", "/v1.1", "/f2,2", "/s3.3", "Z"]), Tool::Dxf2GCode);
        assert!(p.errors.is_empty(), "{:?}", p.errors);
        assert_eq!(
            (
                p.settings.sweep_speed,
                p.settings.feed,
                p.settings.sweep_height
            ),
            (1.1, 2.2, 3.3)
        );
        assert_eq!(p.files, vec!["A", "Z"]);
        let p = parse(
            &a(&["-f", "1.1", "-v", "2,2", "/s", "3.3"]),
            Tool::Dxf2GCode,
        );
        assert!(p.errors.is_empty());
        assert_eq!(p.settings.sweep_speed, 2.2);
    }

    #[test]
    fn string_options() {
        let p = parse(
            &a(&[
                "/dDIR1",
                "/n([0-9]+)",
                "/dDIR2",
                "/f1",
                "/v1",
                "/s1",
                "/c",
                "/e",
                "L$:L$",
                "/ldE",
            ]),
            Tool::Dxf2GCode,
        );
        assert!(p.errors.is_empty());
        assert_eq!(
            p.settings.search_dirs,
            vec![std::path::PathBuf::from("DIR1"), "DIR2".into()]
        );
        assert_eq!(p.settings.path_pattern, "([0-9]+)");
        assert!(p.settings.check);
        assert_eq!(p.settings.restrictions, vec![("L$".into(), "L$".into())]);
        assert_eq!(p.settings.lang, Lang::De);
    }

    #[test]
    fn errors() {
        let p = parse(&a(&["/d", "DIR1", "/p"]), Tool::Dxf2GCode);
        assert!(p.errors.iter().any(|e| e.msg == Msg::MissingOptionValue));
        let p = parse(&a(&["-"]), Tool::Dxf2GCode);
        assert!(p.errors.iter().any(|e| e.msg == Msg::MissingOptionValue));
        let p = parse(&a(&["/q1", "/fx", "/v-1", "/s1"]), Tool::Dxf2GCode);
        let msgs: Vec<Msg> = p.errors.iter().map(|e| e.msg).collect();
        assert!(msgs.contains(&Msg::OptionNotSupported));
        assert!(msgs.contains(&Msg::OptionNotNumber));
        assert!(msgs.contains(&Msg::OptionNegative));
        assert!(msgs.contains(&Msg::FMissing));
        assert!(msgs.contains(&Msg::VMissing));
        assert_eq!(
            p.errors
                .iter()
                .find(|e| e.msg == Msg::OptionNotNumber)
                .unwrap()
                .message(Lang::En),
            "Option value x for /f is not a number"
        );
        let p = parse(&a(&["/?"]), Tool::Dxf2GCode);
        assert!(p.help);
        let p = parse(&a(&["/x", "("]), Tool::Dxf2GCode);
        assert!(p.errors.iter().any(|e| e.msg == Msg::BadRegex));
        let p = parse(&a(&["/eNOCOLON", "/f1", "/v1", "/s1"]), Tool::Dxf2GCode);
        assert!(p.errors.iter().any(|e| e.msg == Msg::EFormat));
    }

    #[test]
    fn adjustz_options() {
        let p = parse(&a(&["/m0,5", "x_Clean.gcode"]), Tool::AdjustZ);
        assert!(p.errors.is_empty());
        assert_eq!(p.m, Some(0.5));
        let p = parse(&a(&["x"]), Tool::AdjustZ);
        assert!(p.errors.iter().any(|e| e.msg == Msg::MissingM));
    }

    #[test]
    fn adjustz_max_must_be_finite_and_positive() {
        for bad in ["NaN", "inf", "Infinity", "1e999", "0", "0,0", "-1", "2e6"] {
            let p = parse(&a(&["/m", bad, "x"]), Tool::AdjustZ);
            assert!(!p.errors.is_empty(), "/m {bad}");
        }
        let p = parse(&a(&["/m0", "x"]), Tool::AdjustZ);
        assert_eq!(
            p.errors[0].message(Lang::En),
            "/m value 0 must be a finite number > 0 and at most 1000000"
        );
    }

    #[test]
    fn unix_absolute_paths_are_files() {
        let p = parse(
            &a(&["/f1", "/v1", "/s1", "/home/me/parts/8999.01P.dxf"]),
            Tool::Dxf2GCode,
        );
        assert_eq!(p.files, vec!["/home/me/parts/8999.01P.dxf"]);
    }
}
