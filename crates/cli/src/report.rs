//! Rendering diagnostics: the reference's `****` lines, human-readable text, JSON and
//! GitHub annotations.
//!
//! Diagnostics as reference `****` lines, human text (one format for DXF and `.mpath`:
//! `error[MPnnn]: message`, `--> location`, then for text the source line drawn by ariadne), JSON,
//! GitHub annotations; locations: a path as a whole at its `path NAME` line (text) or with its name
//! (DXF), a file that cannot be read/written/removed at that file ; GitHub and SARIF paths relative
//! to `GITHUB_WORKSPACE` or the repository, `/`, no `./`; Windows: a file outside the root keeps
//! its drive (`C:/…`), SARIF URIs `file:///C:/…` (UNC shares as the host), canonical paths without
//! `\\?\` (`dunce`).

use millpath_core::diag::{Diagnostic, Origin, Severity};
use millpath_core::Lang;
use serde_json::json;
use std::path::{Path, PathBuf};

pub fn severity_word(s: Severity, lang: Lang) -> &'static str {
    match (s, lang) {
        (Severity::Error, Lang::En) => "error",
        (Severity::Error, Lang::De) => "Fehler",
        (Severity::Warning, Lang::En) => "warning",
        (Severity::Warning, Lang::De) => "Warnung",
    }
}

/// `error[MP012]: message` with the location and related locations on further lines.
pub fn human(d: &Diagnostic, lang: Lang) -> String {
    let mut s = head(d, lang);
    if let Origin::Entity(e) = &d.origin {
        let word = if lang == Lang::De { "Pfad" } else { "path" };
        s.push_str(&format!("\n   = {word} {}", e.path));
    }
    for r in &d.related {
        s.push_str(&format!("\n   = {}: {}", r.note, location(&r.origin, lang)));
    }
    s
}

/// `error[MP012]: message` and the `  --> location` line.
fn head(d: &Diagnostic, lang: Lang) -> String {
    format!(
        "{}[{}]: {}\n  --> {}",
        severity_word(d.severity, lang),
        d.msg.code(),
        message(d, lang),
        location(&shown_origin(d), lang)
    )
}

/// Whether reports on a stream that `is_terminal` get colour: only on a terminal, and never
/// with `NO_COLOR` set (<https://no-color.org>).
pub fn use_color(is_terminal: bool) -> bool {
    is_terminal && !matches!(std::env::var_os("NO_COLOR"), Some(v) if !v.is_empty())
}

/// Like [`human`], but an error in a `.mpath` file shows its source line with the span
/// underlined (ariadne; colour only when `color`).
pub fn human_rich(d: &Diagnostic, lang: Lang, color: bool) -> String {
    let Origin::Span {
        file, start, end, ..
    } = &d.origin
    else {
        return human(d, lang);
    };
    // the text the spans count in: decoded as the compiler read it (BOM, UTF-16)
    let Ok(bytes) = std::fs::read(&file.path) else {
        return human(d, lang);
    };
    let Ok(decoded) = millpath_core::load::text_file::decode(&bytes) else {
        return human(d, lang);
    };
    let src = decoded.text;
    match snippet(
        d,
        lang,
        color,
        &file.path.display().to_string(),
        &src,
        *start as usize,
        *end as usize,
    ) {
        Some(s) => s,
        None => human(d, lang),
    }
}

fn snippet(
    d: &Diagnostic,
    lang: Lang,
    color: bool,
    name: &str,
    src: &str,
    start: usize,
    end: usize,
) -> Option<String> {
    use ariadne::{Color, Config, Label, Report, ReportKind, Source};
    if start > src.len() || !src.is_char_boundary(start) {
        return None;
    }
    // ariadne counts characters, the spans are bytes
    let end = end.clamp(start, src.len());
    let end = (end..=src.len()).find(|&e| src.is_char_boundary(e))?;
    let a = src[..start].chars().count();
    let b = (a + src[start..end].chars().count()).max(a + 1);
    let (kind, label) = match (d.severity, lang) {
        (Severity::Error, Lang::En) => (ReportKind::Custom("error", Color::Red), "error here"),
        (Severity::Error, Lang::De) => (ReportKind::Custom("Fehler", Color::Red), "Fehler hier"),
        (Severity::Warning, Lang::En) => {
            (ReportKind::Custom("warning", Color::Yellow), "warning here")
        }
        (Severity::Warning, Lang::De) => {
            (ReportKind::Custom("Warnung", Color::Yellow), "Warnung hier")
        }
    };
    let mut label = Label::new((name, a..b)).with_message(label);
    if color {
        label = label.with_color(if d.severity == Severity::Error {
            Color::Red
        } else {
            Color::Yellow
        });
    }
    let mut buf = Vec::new();
    Report::build(kind, name, a)
        .with_config(Config::default().with_color(color))
        .with_code(d.msg.code())
        .with_message(message(d, lang))
        .with_label(label)
        .finish()
        .write((name, Source::from(src)), &mut buf)
        .ok()?;
    let mut drawn = String::from_utf8_lossy(&buf).trim_end().to_string();
    if !color {
        // ariadne colours a custom report kind's name even without colour
        drawn = strip_ansi(&drawn);
    }
    // one format for every front-end: `error[MP042]: message` and `--> file:line:col` as in
    // [`human`], then ariadne's drawing of the line without its own heading
    let mut s = head(d, lang);
    for line in drawn.lines().skip(1) {
        s.push('\n');
        match line.find("╭─[") {
            Some(at) => s.push_str(&format!("{}╭─", &line[..at])),
            None => s.push_str(line),
        }
    }
    for r in &d.related {
        s.push_str(&format!("\n   = {}: {}", r.note, location(&r.origin, lang)));
    }
    Some(s)
}

/// `s` without ANSI escape sequences (`ESC [ … letter`).
fn strip_ansi(s: &str) -> String {
    let mut out = String::new();
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c == '\u{1b}' {
            for c in chars.by_ref() {
                if c.is_ascii_alphabetic() {
                    break;
                }
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// A location a person can find, in the message language: `file:line (LINE on layer L,
/// handle H, at [x y])`; a path as a whole: `file:line:col (path NAME)` at its `path NAME`
/// line in a text file, `file (path NAME)` in a DXF.
pub fn location(o: &Origin, lang: Lang) -> String {
    match (o, lang) {
        (Origin::Options, Lang::De) => "Optionen".into(),
        (Origin::Input, Lang::De) => "Eingabe".into(),
        (Origin::Path { name, file }, _) => {
            let word = if lang == Lang::De { "Pfad" } else { "path" };
            match path_header(&file.path, name) {
                Some((line, col)) => {
                    format!("{}:{line}:{col} ({word} {name})", file.path.display())
                }
                None => format!("{} ({word} {name})", file.path.display()),
            }
        }
        _ => o.location_in(lang).unwrap_or_else(|| o.context()),
    }
}

/// Line and column (1-based) of the `path NAME` line of a text file.
fn path_header(file: &std::path::Path, name: &str) -> Option<(usize, usize)> {
    if !millpath_core::load::fs::is_text_file(file) {
        return None;
    }
    let text = std::fs::read_to_string(file).ok()?;
    text.lines().enumerate().find_map(|(i, l)| {
        let rest = l.trim_start().strip_prefix("path")?;
        let word = rest
            .trim_start()
            .split(|c: char| c.is_whitespace() || c == '{')
            .next()?;
        (rest.starts_with(char::is_whitespace) && word.trim_matches('"') == name)
            .then(|| (i + 1, l.len() - l.trim_start().len() + 1))
    })
}

/// The messages about a file as a whole whose first argument is that file.
fn names_its_file(msg: millpath_core::Msg) -> bool {
    use millpath_core::Msg;
    matches!(
        msg,
        Msg::CannotRead
            | Msg::CannotLoadDxf
            | Msg::FileTooLarge
            | Msg::CannotWrite
            | Msg::StaleMillingRemoved
            | Msg::CannotRemove
            | Msg::StaleOutputRemoved
            | Msg::OutputSetRestored
    )
}

/// Each diagnostic once: a subpath embedded by several checked files is read, and its
/// warnings found, once per file; the report (and the warning count) names each place once.
pub fn once_each(diags: Vec<Diagnostic>) -> Vec<Diagnostic> {
    let mut seen = std::collections::HashSet::new();
    diags
        .into_iter()
        .filter(|d| seen.insert(format!("{d:?}")))
        .collect()
}

/// Where a report locates a diagnostic: a file that cannot be read, written or removed at
/// that file, not at "Options"/"Input" (the reference's `****` lines keep those).
pub fn shown_origin(d: &Diagnostic) -> std::borrow::Cow<'_, Origin> {
    use std::borrow::Cow;
    match (&d.origin, d.args.first()) {
        (Origin::Options | Origin::Input, Some(f)) if names_its_file(d.msg) => {
            Cow::Owned(Origin::File(millpath_core::diag::FileRef::new(f.into())))
        }
        _ => Cow::Borrowed(&d.origin),
    }
}

/// The diagnostics as they are reported: a file that cannot be read is located at that file
/// (not at "Input"), and it gets no second message that it has no error-free path.
pub fn tidy(diags: Vec<Diagnostic>) -> Vec<Diagnostic> {
    use millpath_core::diag::FileRef;
    use millpath_core::Msg;
    let unreadable: Vec<String> = diags
        .iter()
        .filter(|d| {
            matches!(
                d.msg,
                Msg::CannotRead | Msg::CannotLoadDxf | Msg::FileTooLarge
            )
        })
        .filter_map(|d| d.args.first().cloned())
        .collect();
    diags
        .into_iter()
        .filter(|d| {
            !(matches!(d.msg, Msg::NoErrorFreePath | Msg::NoErrorFreePathInFile)
                && d.args.first().is_some_and(|f| unreadable.contains(f)))
        })
        .map(|mut d| {
            if matches!(d.msg, Msg::CannotRead | Msg::FileTooLarge)
                && matches!(d.origin, Origin::Input)
            {
                if let Some(f) = d.args.first() {
                    d.origin = Origin::File(FileRef::new(f.into()));
                }
            }
            d
        })
        .collect()
}

fn location_fields(o: &Origin) -> serde_json::Value {
    match o {
        Origin::Entity(e) => json!({
            "file": e.file.path.display().to_string(),
            "line": e.line,
            "entity": e.code_name,
            "layer": e.layer,
            "handle": e.handle,
            "path": e.path,
            "x": e.pos.x,
            "y": e.pos.y,
        }),
        Origin::Path { name, file } => {
            json!({ "file": file.path.display().to_string(), "path": name })
        }
        Origin::File(f) => json!({ "file": f.path.display().to_string() }),
        Origin::FileLine { file, line } => json!({ "file": file, "line": line }),
        Origin::Span {
            file,
            start,
            end,
            line,
            col,
        } => {
            json!({ "file": file.path.display().to_string(), "line": line, "column": col, "start": start, "end": end })
        }
        Origin::Options | Origin::Input => json!({}),
    }
}

pub fn json_value(d: &Diagnostic, lang: Lang) -> serde_json::Value {
    json!({
        "severity": severity_word(d.severity, Lang::En),
        "code": d.msg.code(),
        "name": d.msg.name(),
        "message": message(d, lang),
        "context": d.origin.context(),
        "location": location_fields(&shown_origin(d)),
        "related": d.related.iter().map(|r| json!({ "note": r.note, "location": location_fields(&r.origin) })).collect::<Vec<_>>(),
    })
}

/// Percent-encodes a path for a URI (RFC 3986): unreserved characters and `/` stay, every
/// other byte of the UTF-8 text becomes `%XX`.
pub fn percent_encode_path(p: &str) -> String {
    let mut out = String::new();
    for b in p.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// A file path as a `file:///…` URI (absolute paths). Windows paths by their text, on every
/// platform: `\\` as `/`, a drive letter kept as it is (`C:\a` → `file:///C:/a`, as
/// VS Code and GitHub write it), `\\?\` prefixes dropped, UNC shares as the URI's host
/// (`\\server\share\a` → `file://server/share/a`).
pub fn file_uri(p: &std::path::Path) -> String {
    let s = slashed(&p.to_string_lossy());
    if let Some(unc) = s.strip_prefix("//") {
        return format!("file://{}", percent_encode_path(unc));
    }
    if has_drive(&s) {
        return format!("file:///{}:{}", &s[..1], percent_encode_path(&s[2..]));
    }
    let s = if s.starts_with('/') {
        s
    } else {
        format!("/{s}")
    };
    format!("file://{}", percent_encode_path(&s))
}

/// A Windows path's text with `/` between parts and without a `\\?\` prefix
/// (`\\?\UNC\server\share` → `//server/share`).
fn slashed(text: &str) -> String {
    let text = match text.strip_prefix(r"\\?\UNC\") {
        Some(unc) => format!(r"\\{unc}"),
        None => text.strip_prefix(r"\\?\").unwrap_or(text).to_string(),
    };
    text.replace('\\', "/")
}

/// Whether a path's text starts with a drive letter (`C:`).
fn has_drive(s: &str) -> bool {
    let b = s.as_bytes();
    b.len() >= 2 && b[0].is_ascii_alphabetic() && b[1] == b':'
}

/// The SARIF artifact location of a file: relative to `%SRCROOT%` (the workspace or
/// repository, as for GitHub annotations), files outside it as `file:///` URIs.
fn artifact_location(file: &str) -> serde_json::Value {
    let rel = repo_path(Path::new(file));
    // (a drive only on Windows: `a:b.mpath` is a file name on Unix)
    if rel.starts_with('/') || (cfg!(windows) && has_drive(&rel)) {
        return json!({ "uri": file_uri(Path::new(&rel)) });
    }
    json!({ "uri": percent_encode_path(&rel), "uriBaseId": "%SRCROOT%" })
}

fn sarif_location(o: &Origin) -> Option<serde_json::Value> {
    let (file, line, col) = match o {
        Origin::Entity(e) => (e.file.path.display().to_string(), e.line, 1),
        Origin::Span {
            file, line, col, ..
        } => (
            file.path.display().to_string(),
            *line as usize,
            *col as usize,
        ),
        Origin::FileLine { file, line } => (file.to_string(), *line, 1),
        Origin::Path { file, name } => {
            let (line, col) = path_header(&file.path, name).unwrap_or((1, 1));
            (file.path.display().to_string(), line, col)
        }
        Origin::File(file) => (file.path.display().to_string(), 1, 1),
        Origin::Options | Origin::Input => return None,
    };
    Some(json!({
        "physicalLocation": {
            "artifactLocation": artifact_location(&file),
            "region": { "startLine": line.max(1), "startColumn": col.max(1) }
        }
    }))
}

/// A message template with its placeholders shown as `…` (`{0} value missing` → `… value
/// missing`), for rule descriptions.
pub fn template_text(t: &str) -> String {
    let mut out = String::new();
    let mut rest = t;
    while let Some(i) = rest.find('{') {
        out.push_str(&rest[..i]);
        match rest[i..].find('}') {
            Some(j) if rest[i + 1..i + j].chars().all(|c| c.is_ascii_digit()) && j > 1 => {
                out.push('…');
                rest = &rest[i + j + 1..];
            }
            _ => {
                out.push('{');
                rest = &rest[i + 1..];
            }
        }
    }
    out.push_str(rest);
    out
}

/// A SARIF 2.1.0 log of the diagnostics (for code-scanning tools).
pub fn sarif(diags: &[Diagnostic], lang: Lang) -> serde_json::Value {
    let mut rules: Vec<&Diagnostic> = Vec::new();
    for d in diags {
        if !rules.iter().any(|r| r.msg == d.msg) {
            rules.push(d);
        }
    }
    let results: Vec<serde_json::Value> = diags
        .iter()
        .map(|d| {
            json!({
                "ruleId": d.msg.code(),
                "level": if d.severity == Severity::Error { "error" } else { "warning" },
                "message": { "text": message(d, lang) },
                "locations": sarif_location(&shown_origin(d)).into_iter().collect::<Vec<_>>(),
                "relatedLocations": d.related.iter().filter_map(|r| {
                    let mut l = sarif_location(&r.origin)?;
                    l["message"] = json!({ "text": r.note });
                    Some(l)
                }).collect::<Vec<_>>(),
            })
        })
        .collect();
    let root = {
        let u = file_uri(&ci_root().1);
        if u.ends_with('/') {
            u
        } else {
            format!("{u}/")
        }
    };
    json!({
        "version": "2.1.0",
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "runs": [{
            "tool": { "driver": {
                "name": "millpath",
                "version": env!("CARGO_PKG_VERSION"),
                "rules": rules.iter().map(|d| json!({
                    "id": d.msg.code(),
                    "name": d.msg.name(),
                    "shortDescription": { "text": template_text(d.msg.template(lang)) },
                })).collect::<Vec<_>>(),
            }},
            "originalUriBaseIds": { "%SRCROOT%": { "uri": root } },
            "results": results,
        }]
    })
}

/// The folder CI paths are relative to: `GITHUB_WORKSPACE` when set, else the repository
/// (the nearest folder up from the current one that holds `.git`), else the current folder.
/// GitHub attaches an annotation to a pull-request line only by its repository path.
fn ci_root() -> &'static (PathBuf, PathBuf) {
    static ROOT: std::sync::OnceLock<(PathBuf, PathBuf)> = std::sync::OnceLock::new();
    ROOT.get_or_init(|| {
        let cwd = std::env::current_dir().unwrap_or_default();
        let workspace = std::env::var_os("GITHUB_WORKSPACE")
            .filter(|w| !w.is_empty())
            .map(|w| {
                let w = PathBuf::from(w);
                dunce::canonicalize(&w).unwrap_or(w)
            });
        let repo = || {
            cwd.ancestors()
                .take(64)
                .find(|d| d.join(".git").exists())
                .map(Path::to_path_buf)
        };
        let root = workspace.or_else(repo).unwrap_or_else(|| cwd.clone());
        (cwd, root)
    })
}

/// A file as CI tools want it: relative to the workspace or repository, `/` between parts,
/// no `.` parts (`./3001.mpath` → `3001.mpath`).
pub fn repo_path(file: &Path) -> String {
    let (cwd, root) = ci_root();
    ci_path(file, cwd, root)
}

/// [`repo_path`] for a given current folder and root: `..` resolved by the text of the path
/// (a file outside the root keeps its absolute path).
pub fn ci_path(file: &Path, cwd: &Path, root: &Path) -> String {
    use std::path::Component;
    let joined = if file.is_absolute() {
        file.to_path_buf()
    } else {
        cwd.join(file)
    };
    let mut abs = PathBuf::new();
    for c in joined.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                abs.pop();
            }
            c => abs.push(c.as_os_str()),
        }
    }
    let shown = abs.strip_prefix(root).unwrap_or(&abs);
    // Windows: the drive (`C:`) or share of a file outside the root, `\\?\` dropped
    let prefix = shown.components().find_map(|c| match c {
        Component::Prefix(p) => Some(slashed(&p.as_os_str().to_string_lossy())),
        _ => None,
    });
    let parts: Vec<String> = shown
        .components()
        .filter_map(|c| match c {
            Component::Normal(p) => Some(p.to_string_lossy().into_owned()),
            _ => None,
        })
        .collect();
    let rel = parts.join("/");
    if let Some(prefix) = prefix {
        format!("{prefix}/{rel}")
    } else if shown.is_absolute() {
        format!("/{rel}")
    } else {
        rel
    }
}

/// `::error file=F,line=L,title=millpath MP012::message`
pub fn github(d: &Diagnostic, lang: Lang) -> String {
    let kind = if d.severity == Severity::Error {
        "error"
    } else {
        "warning"
    };
    let mut props = Vec::new();
    let origin = shown_origin(d);
    if let Some(f) = origin.file() {
        props.push(format!("file={}", escape_prop(&repo_path(&f.path))));
    } else if let Origin::FileLine { file, .. } = origin.as_ref() {
        props.push(format!(
            "file={}",
            escape_prop(&repo_path(std::path::Path::new(&**file)))
        ));
    }
    match &d.origin {
        Origin::Entity(e) => props.push(format!("line={}", e.line)),
        Origin::Span { line, col, .. } => props.push(format!("line={line},col={col}")),
        Origin::FileLine { line, .. } => props.push(format!("line={line}")),
        Origin::Path { file, name } => {
            if let Some((line, col)) = path_header(&file.path, name) {
                props.push(format!("line={line},col={col}"));
            }
        }
        _ => {}
    }
    props.push(format!(
        "title={}",
        escape_prop(&format!("millpath {}", d.msg.code()))
    ));
    let mut msg = message(d, lang);
    match &d.origin {
        Origin::Entity(e) if lang == Lang::De => {
            msg = format!(
                "{msg} ({} auf Layer {} bei {})",
                e.code_name, e.layer, e.pos
            );
        }
        Origin::Entity(e) => {
            msg = format!("{msg} ({} on layer {} at {})", e.code_name, e.layer, e.pos);
        }
        Origin::Path { name, .. } => {
            msg = format!(
                "{msg} ({} {name})",
                if lang == Lang::De { "Pfad" } else { "path" }
            );
        }
        _ => {}
    }
    // the hints ("did you mean B?") and related places, as the human format gives them
    for r in &d.related {
        msg.push_str(&format!("\n= {}: {}", r.note, location(&r.origin, lang)));
    }
    format!("::{kind} {}::{}", props.join(","), escape_data(&msg))
}

/// A diagnostic's message for the reports. The reference's texts that end in the place of
/// the parameter text (`Unsupported b value; 1004.mpath:4:17`, kept in its `****` lines)
/// lose that second location here: the report locates the message itself.
pub fn message(d: &Diagnostic, lang: Lang) -> String {
    d.located_message(lang)
}

fn escape_data(s: &str) -> String {
    s.replace('%', "%25")
        .replace('\r', "%0D")
        .replace('\n', "%0A")
}

fn escape_prop(s: &str) -> String {
    escape_data(s).replace(':', "%3A").replace(',', "%2C")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_paths_become_file_uris_with_their_drive() {
        let uri = |s: &str| file_uri(Path::new(s));
        assert_eq!(
            uri(r"C:\Users\Jörg\a b.dxf"),
            "file:///C:/Users/J%C3%B6rg/a%20b.dxf"
        );
        assert_eq!(uri(r"\\?\D:\cnc\x.mpath"), "file:///D:/cnc/x.mpath");
        assert_eq!(uri(r"\\server\share\x.dxf"), "file://server/share/x.dxf");
        assert_eq!(
            uri(r"\\?\UNC\server\share\x.dxf"),
            "file://server/share/x.dxf"
        );
        assert_eq!(uri("C:/w/"), "file:///C:/w/");
        assert_eq!(uri("/home/a:b/x.dxf"), "file:///home/a%3Ab/x.dxf");
    }
    use millpath_core::diag::{EntityOrigin, FileRef};
    use millpath_core::geom::P2;
    use millpath_core::Msg;

    fn sample() -> Diagnostic {
        let file = FileRef::new("dir/a.dxf".into());
        Diagnostic::error(
            Msg::ValueMissing,
            Origin::Entity(std::sync::Arc::new(EntityOrigin {
                file,
                line: 120,
                handle: "A4".into(),
                layer: "8999_1P".into(),
                code_name: "LINE",
                pos: P2::new(1.0, 2.0),
                path: "8999.1P".into(),
            })),
            vec!["B".into()],
        )
    }

    #[test]
    fn formats() {
        let d = sample();
        assert_eq!(
            d.reference_line(Lang::En),
            "**** LINE @ [1.000 2.000] # 8999.1P[a.dxf]: B value missing"
        );
        let h = human(&d, Lang::De);
        assert!(
            h.starts_with("Fehler[") && h.contains("B-Wert fehlt") && h.contains("dir/a.dxf:120"),
            "{h}"
        );
        let j = json_value(&d, Lang::En);
        assert_eq!(j["location"]["line"], 120);
        assert_eq!(j["location"]["layer"], "8999_1P");
        let sarif = sarif(std::slice::from_ref(&d), Lang::En);
        let r = &sarif["runs"][0]["results"][0];
        assert_eq!(r["level"], "error");
        assert_eq!(
            r["locations"][0]["physicalLocation"]["region"]["startLine"],
            120
        );
        assert_eq!(
            sarif["runs"][0]["tool"]["driver"]["rules"][0]["id"],
            r["ruleId"]
        );
        let g = github(&d, Lang::En);
        assert!(
            g.contains(" file=") && g.contains("dir/a.dxf,line=120,title=millpath MP"),
            "{g}"
        );
    }

    #[test]
    fn ci_paths_are_repository_relative_with_slashes() {
        let root = Path::new("/repo");
        let cwd = Path::new("/repo/parts");
        assert_eq!(
            ci_path(Path::new("./3001.mpath"), cwd, root),
            "parts/3001.mpath"
        );
        assert_eq!(ci_path(Path::new("3001.mpath"), root, root), "3001.mpath");
        assert_eq!(ci_path(Path::new("./a/./b.dxf"), root, root), "a/b.dxf");
        assert_eq!(
            ci_path(Path::new("../other/x.dxf"), cwd, root),
            "other/x.dxf"
        );
        assert_eq!(ci_path(Path::new("/repo/p/x.dxf"), cwd, root), "p/x.dxf");
        // outside the repository: the absolute path
        assert_eq!(ci_path(Path::new("/tmp/x.dxf"), cwd, root), "/tmp/x.dxf");
        assert_eq!(ci_path(Path::new("../../x.dxf"), cwd, root), "/x.dxf");
    }

    /// A `.mpath` error with its source line starts as a DXF error does: `error[MPnnn]:`,
    /// then `--> file:line:col` (not ariadne's `[MPnnn] error:` heading).
    #[test]
    fn text_errors_have_the_format_of_drawing_errors() {
        let src = "path X {\n  mil (0, 0) -> (1, 1)\n}\n";
        let file = FileRef::new("dir/a.mpath".into());
        let mut diags = millpath_core::Diags::default();
        millpath_core::front::text::text_objects(src, &file, &mut diags).unwrap();
        let d = diags.list.remove(0);
        for lang in [Lang::En, Lang::De] {
            let (start, end) = (12, 15);
            let rich = snippet(&d, lang, false, "dir/a.mpath", src, start, end).unwrap();
            let plain = human(&d, lang);
            let head: Vec<&str> = rich.lines().take(2).collect();
            assert_eq!(head, plain.lines().take(2).collect::<Vec<_>>(), "{rich}");
            assert_eq!(head[1], "  --> dir/a.mpath:2:3");
            assert!(rich.contains(" 2 │   mil (0, 0)"), "{rich}");
            assert!(
                !rich.contains("] error:") && !rich.contains("] Fehler:"),
                "{rich}"
            );
        }
        assert_eq!(
            human(&d, Lang::En).lines().next().unwrap(),
            format!(
                "error[{}]: `mil` is not an element kind: did you mean `mill`?",
                Msg::SyntaxKindDidYouMean.code()
            )
        );
        assert!(human(&d, Lang::De).starts_with("Fehler["));
    }
}
