//! Finding and reading `millpath.toml` (walking up from the input file).

pub use millpath_core::load::config::{FileConfig, Have, FILE_NAME};
use std::path::{Path, PathBuf};

/// The nearest `millpath.toml` at or above the directory of `input`.
pub fn find(input: &Path) -> Option<PathBuf> {
    let abs = dunce::canonicalize(input)
        .ok()
        .or_else(|| std::env::current_dir().ok().map(|d| d.join(input)))?;
    let mut dir = abs.parent();
    while let Some(d) = dir {
        let candidate = d.join(FILE_NAME);
        if candidate.is_file() {
            return Some(candidate);
        }
        dir = d.parent();
    }
    None
}

/// The nearest `millpath.toml` for an input: above a file, or in and above a folder.
pub fn find_for(input: &Path) -> Option<PathBuf> {
    if input.is_dir() {
        find(&input.join(FILE_NAME))
    } else {
        find(input)
    }
}

/// `lang` of a settings file, read on its own: the language of the messages must be known
/// before the first one, also the messages about the file's other keys.
pub fn lang_in(path: &Path) -> Option<millpath_core::Lang> {
    let text = crate::read::text(path).ok()?;
    let lang = |t: &toml::Table| {
        t.get("lang")
            .and_then(toml::Value::as_str)
            .map(millpath_core::Lang::from_name)
    };
    match text.parse::<toml::Table>() {
        Ok(table) => lang(&table),
        // a file with a syntax error: its top-level `lang = "de"` line alone still gives
        // the language of that error
        Err(_) => text
            .lines()
            .take_while(|l| !l.trim_start().starts_with('['))
            .filter_map(|l| l.parse::<toml::Table>().ok())
            .find_map(|t| lang(&t)),
    }
}

/// Reads and parses a settings file; the error text names the file and the line.
pub fn load(path: &Path) -> Result<FileConfig, String> {
    let text = crate::read::text(path).map_err(|e| format!("{}: {e}", path.display()))?;
    millpath_core::load::config::parse(&text, path.parent().unwrap_or(Path::new(".")))
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// [`load`] with the error in the message language: the file's place and the usual words
/// of the TOML reader's errors in German (the keys and values stay as written).
pub fn load_in(path: &Path, lang: millpath_core::Lang) -> Result<FileConfig, String> {
    load(path).map_err(|e| match lang {
        millpath_core::Lang::En => e,
        millpath_core::Lang::De => toml_error_de(&e),
    })
}

/// The nearest `millpath.toml` above `input` in `files` (a git revision's files at their
/// work-tree paths) and its settings, read as [`load_in`] reads one from the disk; `None`
/// when the revision has none.
pub fn load_from(
    files: &dyn millpath_core::load::fs::FileSystem,
    input: &Path,
    lang: millpath_core::Lang,
) -> Option<Result<FileConfig, String>> {
    let (path, bytes) = input.ancestors().skip(1).find_map(|dir| {
        let p = dir.join(FILE_NAME);
        files.read(&p).ok().map(|b| (p, b))
    })?;
    let text = match millpath_core::load::text_file::decode(&bytes) {
        Ok(d) => d.text.into_owned(),
        Err(_) => String::from_utf8_lossy(&bytes).into_owned(),
    };
    let base = path.parent().unwrap_or(Path::new("."));
    Some(
        millpath_core::load::config::parse(&text, base).map_err(|e| {
            let e = format!("{}: {e}", path.display());
            match lang {
                millpath_core::Lang::En => e,
                millpath_core::Lang::De => toml_error_de(&e),
            }
        }),
    )
}

fn toml_error_de(e: &str) -> String {
    const WORDS: &[(&str, &str)] = &[
        ("TOML parse error at line ", "TOML-Fehler in Zeile "),
        (", column ", ", Spalte "),
        ("unknown field", "unbekannter Schlüssel"),
        ("expected one of", "erlaubt ist einer von"),
        ("invalid type:", "falscher Typ:"),
        ("invalid value:", "falscher Wert:"),
        ("invalid length", "falsche Länge"),
        ("an array of length", "eine Liste der Länge"),
        ("invalid array", "ungültige Liste"),
        ("unknown variant", "unbekannter Wert"),
        ("missing field", "fehlender Schlüssel"),
        ("duplicate key", "doppelter Schlüssel"),
        ("expected", "erwartet"),
        ("string", "Text"),
        ("integer", "ganze Zahl"),
        ("floating point", "Zahl"),
        ("a sequence", "eine Liste"),
        ("sequence", "Liste"),
        ("invalid", "ungültig"),
    ];
    let mut out = e.to_string();
    for (en, de) in WORDS {
        out = out.replace(en, de);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn found_by_walking_up_and_relative_dirs_resolved() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join(FILE_NAME), "feed = 150\nsweep_speed = 500\nsweep_height = 15\nsearch_dirs = [\"parts\"]\nrestrictions = [\"L$:L$\"]\n").unwrap();
        let sub = dir.path().join("a/b");
        std::fs::create_dir_all(&sub).unwrap();
        std::fs::write(sub.join("x.dxf"), "").unwrap();
        let found = find(&sub.join("x.dxf")).unwrap();
        let cfg = load(&found).unwrap();
        assert_eq!(cfg.feed, Some(150.0));
        assert!(cfg.search_dirs[0].ends_with("parts"));
        let mut s = millpath_core::Settings::default();
        let mut have = Have::default();
        cfg.apply(&mut s, &mut have);
        assert!(have.feed && have.sweep_speed && have.sweep_height);
        assert_eq!(s.restrictions, vec![("L$".to_string(), "L$".to_string())]);
    }

    #[test]
    fn lang_is_read_even_beside_a_bad_key() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join(FILE_NAME);
        std::fs::write(&p, "lang = \"de\"\nfeeed = 3\n").unwrap();
        assert!(load(&p).is_err());
        assert_eq!(lang_in(&p), Some(millpath_core::Lang::De));
        assert_eq!(find_for(dir.path()), Some(p.clone()));
        // a syntax error further down: the error itself in German
        std::fs::write(&p, "lang = \"de\"\nfeed = [\n").unwrap();
        assert_eq!(lang_in(&p), Some(millpath_core::Lang::De));
        let e = load_in(&p, millpath_core::Lang::De).unwrap_err();
        assert!(
            e.contains("TOML-Fehler in Zeile 2") && e.contains("ungültige Liste"),
            "{e}"
        );
        // a box of three numbers given two
        std::fs::write(&p, "[[clamp]]\nname = \"v\"\nmin = [0, 0]\n").unwrap();
        let e = load_in(&p, millpath_core::Lang::De).unwrap_err();
        assert!(
            e.contains("falsche Länge 2, erwartet eine Liste der Länge 3"),
            "{e}"
        );
    }

    #[test]
    fn unknown_keys_and_bad_values_are_errors_with_lines() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join(FILE_NAME);
        std::fs::write(&p, "feed = 150\nfeeed = 3\n").unwrap();
        let e = load(&p).unwrap_err();
        assert!(e.contains("feeed") && e.contains("line 2"), "{e}");
        std::fs::write(&p, "feed = \"fast\"\n").unwrap();
        assert!(load(&p).is_err());
    }
}
