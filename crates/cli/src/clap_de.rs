//! clap's own texts (option errors, help headings) in the language of the run.
//!
//! The language is chosen before parsing, as the messages after it are: `--lang de` or
//! `--lang=de` anywhere on the command line; without it `lang` of the millpath.toml the
//! command would read (the nearest one above its first existing input, else above the
//! current directory); else English. The locale (`LANG`, `LC_ALL`) is not asked: no other
//! message of millpath follows it, and a run must not change language between its first
//! message and its second.
//!
//! German errors are written from clap's error kind and context (the parts clap's own
//! formatter uses), through clap's `ErrorFormatter` hook, so exit status and stream stay
//! clap's. Help pages keep clap's layout; their fixed words are translated by one table.

use crate::config;
use clap::error::{ContextKind, ContextValue, ErrorFormatter, ErrorKind};
use clap::{CommandFactory, FromArgMatches};
use millpath_core::Lang;
use std::path::Path;

/// Parses the command line, with clap's messages in the run's language.
pub fn parse<P: CommandFactory + FromArgMatches>(raw: &[String]) -> P {
    let lang = lang_before_parsing(raw);
    let command = match lang {
        Lang::En => P::command(),
        Lang::De => crate::help_de::german(P::command()),
    };
    let result = command
        .try_get_matches_from(raw)
        .and_then(|m| P::from_arg_matches(&m));
    match result {
        Ok(p) => p,
        Err(e) if lang == Lang::En => e.exit(),
        Err(e) => exit_german(e),
    }
}

/// The language of the run, from the raw arguments and the settings file.
pub fn lang_before_parsing(raw: &[String]) -> Lang {
    let args = raw.iter().skip(1).take_while(|a| *a != "--");
    let mut flag = None;
    let mut next_is_value = false;
    for a in args {
        if next_is_value {
            flag = Some(a.as_str());
            next_is_value = false;
        } else if a == "--lang" {
            next_is_value = true;
        } else if let Some(v) = a.strip_prefix("--lang=") {
            flag = Some(v);
        }
    }
    if let Some(v) = flag {
        return Lang::from_name(v);
    }
    let input = raw
        .iter()
        .skip(2)
        .map(Path::new)
        .find(|p| !p.as_os_str().to_string_lossy().starts_with('-') && p.exists());
    let here = Path::new(config::FILE_NAME);
    input
        .and_then(config::find_for)
        .or_else(|| config::find(here))
        .and_then(|p| config::lang_in(&p))
        .unwrap_or_default()
}

fn exit_german(e: clap::Error) -> ! {
    use std::io::Write;
    let (to_stderr, code) = (e.use_stderr(), e.exit_code());
    let text = match e.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => help_de(&e.render().to_string()),
        _ => e.apply::<German>().render().to_string(),
    };
    if to_stderr {
        let _ = std::io::stderr().write_all(text.as_bytes());
    } else {
        let _ = std::io::stdout().write_all(text.as_bytes());
    }
    let _ = std::io::stdout().flush();
    std::process::exit(code)
}

/// The fixed words of clap's help pages and usage lines, English → German (longer texts
/// first where one contains another).
const HELP_WORDS: &[(&str, &str)] = &[
    (
        "Print this message or the help of the given subcommand(s)",
        "Diese Hilfe oder die Hilfe des angegebenen Befehls anzeigen",
    ),
    (
        "Print help (see a summary with '-h')",
        "Hilfe anzeigen (Kurzfassung mit '-h')",
    ),
    (
        "Print help (see more with '--help')",
        "Hilfe anzeigen (mehr mit '--help')",
    ),
    ("Print help", "Hilfe anzeigen"),
    ("Print version", "Version anzeigen"),
    ("Usage:", "Aufruf:"),
    ("Commands:", "Befehle:"),
    ("Arguments:", "Argumente:"),
    ("Options:", "Optionen:"),
    ("[OPTIONS]", "[OPTIONEN]"),
    ("<COMMAND>", "<BEFEHL>"),
    ("[COMMAND]", "[BEFEHL]"),
    ("[default: ", "[Standard: "),
    ("[possible values: ", "[mögliche Werte: "),
    ("[aliases: ", "[Aliasse: "),
];

/// A help page or usage text with clap's fixed words in German.
pub fn help_de(text: &str) -> String {
    let mut out = text.to_string();
    for (en, de) in HELP_WORDS {
        out = out.replace(en, de);
    }
    out
}

/// clap's errors in German.
struct German;

impl ErrorFormatter for German {
    fn format_error(error: &clap::error::Error<Self>) -> clap::builder::StyledStr {
        let mut s = format!("Fehler: {}", what(error));
        let tip = |s: &mut String, what: &str, v: &ContextValue| {
            s.push_str(&format!("\n\n  Tipp: ähnlich ist {what} {}", quoted(v)));
        };
        if let Some(v) = error.get(ContextKind::SuggestedSubcommand) {
            tip(&mut s, "der Befehl", v);
        }
        if let Some(v) = error.get(ContextKind::SuggestedArg) {
            tip(&mut s, "das Argument", v);
        }
        if let Some(v) = error.get(ContextKind::SuggestedValue) {
            tip(&mut s, "der Wert", v);
        }
        if let Some(ContextValue::StyledStrs(tips)) = error.get(ContextKind::Suggested) {
            for t in tips {
                // clap's tips are English sentences around an argument; keep the argument
                let t = t.to_string();
                let quoted: Vec<&str> = t.split('\'').skip(1).step_by(2).collect();
                match quoted[..] {
                    // "to pass '-x' as a value, use '-- -x'"
                    [arg, with_dashes] => s.push_str(&format!(
                        "\n  Tipp: um '{arg}' als Wert zu übergeben: '{with_dashes}'"
                    )),
                    [one, ..] => s.push_str(&format!("\n  Tipp: '{one}'")),
                    [] => {}
                }
            }
        }
        if let Some(ContextValue::StyledStr(usage)) = error.get(ContextKind::Usage) {
            s.push_str("\n\n");
            s.push_str(&help_de(&usage.to_string()));
        }
        s.push_str("\n\nMehr dazu mit '--help'.\n");
        s.into()
    }
}

/// `'a'` or `'a', 'b'`.
fn quoted(v: &ContextValue) -> String {
    match v {
        ContextValue::String(s) => format!("'{s}'"),
        ContextValue::Strings(v) => v
            .iter()
            .map(|s| format!("'{s}'"))
            .collect::<Vec<_>>()
            .join(", "),
        ContextValue::StyledStr(s) => format!("'{s}'"),
        ContextValue::StyledStrs(v) => v
            .iter()
            .map(|s| format!("'{s}'"))
            .collect::<Vec<_>>()
            .join(", "),
        ContextValue::Number(n) => n.to_string(),
        _ => String::new(),
    }
}

/// The sentence saying what is wrong, from the error's kind and context.
fn what(e: &clap::error::Error<German>) -> String {
    let get = |k| e.get(k).map(quoted).unwrap_or_default();
    let arg = get(ContextKind::InvalidArg);
    let value = get(ContextKind::InvalidValue);
    let values_list = |s: String| match e.get(ContextKind::ValidValue) {
        Some(v @ ContextValue::Strings(list)) if !list.is_empty() => {
            format!("{s}\n  [mögliche Werte: {}]", quoted(v).replace('\'', ""))
        }
        _ => s,
    };
    match e.kind() {
        ErrorKind::InvalidValue if value == "''" => values_list(format!(
            "{arg} braucht einen Wert, aber keiner wurde angegeben"
        )),
        ErrorKind::InvalidValue => values_list(format!("ungültiger Wert {value} für {arg}")),
        ErrorKind::ValueValidation => {
            let number = std::error::Error::source(e).is_some_and(|s| {
                s.downcast_ref::<std::num::ParseFloatError>().is_some()
                    || s.downcast_ref::<std::num::ParseIntError>().is_some()
            });
            let hint = if number { ": keine Zahl" } else { "" };
            format!("ungültiger Wert {value} für {arg}{hint}")
        }
        ErrorKind::UnknownArgument => format!("unerwartetes Argument {arg}"),
        ErrorKind::InvalidSubcommand => {
            format!("unbekannter Befehl {}", get(ContextKind::InvalidSubcommand))
        }
        ErrorKind::MissingRequiredArgument => {
            let list = match e.get(ContextKind::InvalidArg) {
                Some(ContextValue::Strings(v)) => v.join("\n    "),
                _ => String::new(),
            };
            format!("diese nötigen Argumente fehlen:\n    {list}")
        }
        ErrorKind::MissingSubcommand => format!(
            "{} braucht einen Befehl{}",
            get(ContextKind::InvalidSubcommand),
            match e.get(ContextKind::ValidSubcommand) {
                Some(v) => format!("\n  [Befehle: {}]", quoted(v).replace('\'', "")),
                None => String::new(),
            }
        ),
        ErrorKind::ArgumentConflict => {
            let prior = get(ContextKind::PriorArg);
            if prior.is_empty() || prior == arg {
                format!("das Argument {arg} darf nur einmal vorkommen")
            } else {
                format!("das Argument {arg} geht nicht zusammen mit {prior}")
            }
        }
        ErrorKind::TooManyValues => {
            format!("unerwarteter Wert {value} für {arg}; es werden keine weiteren erwartet")
        }
        ErrorKind::TooFewValues | ErrorKind::WrongNumberOfValues => format!(
            "falsche Zahl von Werten für {arg}: {} angegeben",
            get(ContextKind::ActualNumValues)
        ),
        ErrorKind::NoEquals => format!("{arg} braucht ein Gleichheitszeichen vor dem Wert"),
        ErrorKind::InvalidUtf8 => "ein Argument ist kein gültiges UTF-8".into(),
        _ => "ungültige Befehlszeile".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn raw(args: &[&str]) -> Vec<String> {
        std::iter::once("millpath")
            .chain(args.iter().copied())
            .map(String::from)
            .collect()
    }

    #[test]
    fn lang_flag_is_found_before_parsing() {
        assert_eq!(
            lang_before_parsing(&raw(&["check", "--lang", "de", "--bogus"])),
            Lang::De
        );
        assert_eq!(lang_before_parsing(&raw(&["check", "--lang=de"])), Lang::De);
        assert_eq!(
            lang_before_parsing(&raw(&["check", "--lang=de", "--lang", "en"])),
            Lang::En
        );
        // after `--` it is a file name
        assert_eq!(
            lang_before_parsing(&raw(&["check", "--", "--lang=de"])),
            Lang::En
        );
    }

    #[test]
    fn lang_of_the_settings_file_of_the_input() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join(config::FILE_NAME), "lang = \"de\"\n").unwrap();
        let input = dir.path().join("a.mpath");
        std::fs::write(&input, "").unwrap();
        let input = input.display().to_string();
        assert_eq!(lang_before_parsing(&raw(&["check", &input])), Lang::De);
        assert_eq!(
            lang_before_parsing(&raw(&["check", "--lang", "en", &input])),
            Lang::En
        );
    }

    #[test]
    fn help_words_are_german() {
        let h = help_de(
            "Usage: millpath check [OPTIONS] <PATHS>...\n\nOptions:\n  -h, --help  Print help\n",
        );
        assert_eq!(
            h,
            "Aufruf: millpath check [OPTIONEN] <PATHS>...\n\nOptionen:\n  -h, --help  Hilfe anzeigen\n"
        );
    }
}
