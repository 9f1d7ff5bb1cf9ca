//! TOML documents in the editor: `millpath.toml` and post files. A `.toml` file is a post
//! when it lies in a `posts/` folder, when the nearest `millpath.toml` names it by `post =`,
//! or when it holds a `[post]` table with a `family` key. A post document gets the post
//! loader's located error (line, column, key; in the settings' language); `millpath.toml`
//! its own parse error and a `post =` that loads no post, at that line.
//!
//! The buffer's text is checked as typed, but the programs (preview, diagnostics of the
//! drawings) are written with the saved post file, as `millpath compile` reads it: a save
//! re-checks the documents that use it (a loaded post lives as long as the settings and
//! programs that share it, `emit::dialect::select_post`).

use crate::{Analysis, DocSettings, LineIndex, Workspace};
use millpath_core::diag::{Diagnostic, FileRef, Origin};
use millpath_core::load::config;
use millpath_core::Lang;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

/// A `.toml` document (settings or a post), not a drawing.
pub fn is_toml(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
}

/// `millpath.toml`.
pub fn is_settings_file(path: &Path) -> bool {
    path.file_name().is_some_and(|n| n == config::FILE_NAME)
}

/// Whether the `.toml` document is a post file (see the module's doc).
pub fn is_post_file(path: &Path, text: &str, settings: &DocSettings) -> bool {
    if !is_toml(path) || is_settings_file(path) {
        return false;
    }
    let in_posts = path
        .parent()
        .and_then(Path::file_name)
        .is_some_and(|d| d == "posts");
    in_posts || settings.post_file.as_deref() == Some(path) || has_post_table(text)
}

/// A `[post]` table with a `family` key (a line scan: a document of any size is read once).
fn has_post_table(text: &str) -> bool {
    let mut in_post = false;
    for line in text.lines() {
        let t = line.trim();
        if t.starts_with('[') {
            in_post = t.starts_with("[post]");
        } else if in_post {
            let key = t.split('=').next().unwrap_or("").trim();
            if key == "family" && t.contains('=') {
                return true;
            }
        }
    }
    false
}

fn post_lang(lang: Lang) -> millpath_post::Lang {
    match lang {
        Lang::De => millpath_post::Lang::De,
        _ => millpath_post::Lang::En,
    }
}

/// The byte offset of a 1-based line and character column.
fn offset_of(text: &str, line: usize, column: usize) -> usize {
    let start = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum::<usize>()
        .min(text.len());
    let rest = &text[start..];
    rest.char_indices()
        .nth(column.saturating_sub(1))
        .map_or(start + rest.len(), |(i, _)| start + i)
}

/// An error of the document from `start` to the end of its line.
fn located(path: &Path, text: &str, start: usize, message: String) -> Diagnostic {
    let end = text[start..]
        .find(['\r', '\n'])
        .map_or(text.len(), |e| start + e);
    let before = &text[..start];
    let line = before.matches('\n').count() as u32 + 1;
    let col = before[before.rfind('\n').map_or(0, |p| p + 1)..]
        .chars()
        .count() as u32
        + 1;
    Diagnostic::error(
        millpath_core::Msg::SettingsUnusable,
        Origin::Span {
            file: FileRef::new(path.to_path_buf()),
            start: start as u32,
            end: end as u32,
            line,
            col,
        },
        millpath_core::args![message],
    )
}

/// The post loader's error of a post document, located.
pub fn post_diagnostics(path: &Path, text: &str, lang: Lang) -> Vec<Diagnostic> {
    match millpath_post::load(&path.display().to_string(), text) {
        Ok(_) => Vec::new(),
        Err(e) => {
            let start = if e.line == 0 {
                0
            } else {
                offset_of(text, e.line, e.column)
            };
            let message = match e.key.as_str() {
                "" => e.message(post_lang(lang)),
                key => format!("{key}: {}", e.message(post_lang(lang))),
            };
            vec![located(path, text, start, message)]
        }
    }
}

/// The value of `post = "…"` in a settings text: its byte range inside the quotes.
pub fn post_value(text: &str) -> Option<(usize, usize)> {
    let mut at = 0;
    for line in text.split_inclusive('\n') {
        let t = line.trim_start();
        // top-level keys only: `post` below a table header is another key
        if t.starts_with('[') {
            return None;
        }
        if let Some(rest) = t.strip_prefix("post") {
            let rest_trim = rest.trim_start();
            if let Some(v) = rest_trim.strip_prefix('=') {
                let v_at = at + (line.len() - v.len());
                let quote = v.find(['"', '\''])?;
                let q = v.as_bytes()[quote] as char;
                let start = v_at + quote + 1;
                let len = text[start..].find([q, '\n']).unwrap_or(text.len() - start);
                return Some((start, start + len));
            }
        }
        at += line.len();
    }
    None
}

/// The errors of a `millpath.toml` document: its parse error, a `post =` that loads no post.
fn settings_diagnostics(ws: &Workspace, path: &Path, text: &str, lang: Lang) -> Vec<Diagnostic> {
    let dir = path.parent().unwrap_or(Path::new(""));
    let cfg = match config::parse(text, dir) {
        Ok(c) => c,
        Err(e) => {
            // toml's message names its line and column: "… at line 3, column 7"
            let start = parse_position(&e).map_or(0, |(l, c)| offset_of(text, l, c));
            return vec![located(path, text, start, e.trim().to_string())];
        }
    };
    let Some(name) = &cfg.post else {
        return Vec::new();
    };
    let fs = ws.fs();
    let read = |p: &Path| -> Result<String, String> {
        let bytes = millpath_core::load::fs::FileSystem::read(&fs, p).map_err(|e| e.to_string())?;
        String::from_utf8(bytes).map_err(|e| e.to_string())
    };
    match millpath_post::resolve(name, &cfg.base_dir, &read) {
        Ok(_) => Vec::new(),
        Err(e) => {
            let start = post_value(text).map_or(0, |(s, _)| s);
            vec![located(path, text, start, e.render(post_lang(lang)))]
        }
    }
}

/// "at line L, column C" in a toml error.
fn parse_position(message: &str) -> Option<(usize, usize)> {
    let rest = &message[message.find("line ")? + 5..];
    let line: usize = rest[..rest.find(|c: char| !c.is_ascii_digit())?]
        .parse()
        .ok()?;
    let rest = &rest[rest.find("column ")? + 7..];
    let end = rest
        .find(|c: char| !c.is_ascii_digit())
        .unwrap_or(rest.len());
    Some((line, rest[..end].parse().ok()?))
}

/// The analysis of a `.toml` document: its diagnostics (none for a TOML file that is neither
/// settings nor a post), no drawing.
pub fn analyze(ws: &Workspace, path: &Path) -> Analysis {
    let src = ws.text(path).unwrap_or_default();
    let settings = ws.settings_for(path);
    let lang = settings.settings.lang;
    let diagnostics = if is_settings_file(path) {
        settings_diagnostics(ws, path, &src, lang)
    } else if is_post_file(path, &src, &settings) {
        post_diagnostics(path, &src, lang)
    } else {
        Vec::new()
    };
    let mut deps: BTreeSet<PathBuf> = path
        .ancestors()
        .skip(1)
        .map(|d| d.join(config::FILE_NAME))
        .collect();
    deps.extend(settings.post_file.clone());
    deps.remove(path);
    Analysis {
        path: path.to_path_buf(),
        index: LineIndex::with_encoding(&src, ws.utf8),
        src,
        ast: millpath_syntax::parse("").0,
        diagnostics,
        objects: Vec::new(),
        paths: Vec::new(),
        settings,
        deps,
        dirs: BTreeSet::new(),
        // not MillPath text: no tree to reuse, no formatting
        syntax_ok: false,
        declared: Vec::new(),
        // no objects to reuse after an edit
        objects_clean: false,
        object_at: OnceLock::new(),
        chain_first: Mutex::default(),
        previews: Mutex::default(),
        traversals: Default::default(),
        _models: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_post_table_with_a_family_makes_a_post() {
        assert!(has_post_table(
            "# x\n[post]\nname = \"a\"\nfamily = \"grbl\"\n"
        ));
        assert!(!has_post_table(
            "[post]\nname = \"a\"\n[format]\nfamily = 1\n"
        ));
        assert!(!has_post_table("family = \"grbl\"\n"));
    }

    #[test]
    fn the_post_value_is_found_inside_its_quotes() {
        let t = "feed = 1\npost = \"posts/m.toml\"\n[machine]\npost = 3\n";
        let (s, e) = post_value(t).unwrap();
        assert_eq!(&t[s..e], "posts/m.toml");
        assert_eq!(post_value("[a]\npost = \"x\"\n"), None);
        // unterminated: to the line's end
        let t = "post = \"grb\nfeed = 1\n";
        let (s, e) = post_value(t).unwrap();
        assert_eq!(&t[s..e], "grb");
    }

    #[test]
    fn lines_and_columns_become_offsets() {
        let t = "ab\nä c\n";
        assert_eq!(offset_of(t, 2, 3), 6);
        assert_eq!(offset_of(t, 9, 9), t.len());
        assert_eq!(
            parse_position("TOML parse error at line 3, column 7\n"),
            Some((3, 7))
        );
    }
}
