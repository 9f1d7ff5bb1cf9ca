//! Post names in `millpath.toml`: completion of `post = "…"` (the built-in posts with their
//! one-line description, and the `.toml` files of the project's `posts/` folder) and hover on
//! the name (the post's family, what it can do, where it comes from).

use crate::completion::Completion;
use crate::hover::Hover;
use crate::toml_doc::{is_settings_file, post_value};
use crate::{Analysis, Workspace};
use millpath_core::load::fs::FileSystem;
use millpath_post::{ArcMode, Post, Probing};
use std::path::Path;

/// Files of `posts/` offered at most (a folder of thousands is cut).
const MAX_FILES: usize = 200;

fn de(a: &Analysis) -> bool {
    a.settings.settings.lang == millpath_core::Lang::De
}

/// A post file as the loader reads it, through the editor's view.
fn reader(ws: &Workspace) -> impl Fn(&Path) -> Result<String, String> + '_ {
    move |p: &Path| {
        let bytes = ws.fs().read(p).map_err(|e| e.to_string())?;
        String::from_utf8(bytes).map_err(|e| e.to_string())
    }
}

/// Completion inside (or right after the `=` of) `post = …` of `millpath.toml`.
pub fn completion(a: &Analysis, ws: &Workspace, offset: usize) -> Vec<Completion> {
    if !is_settings_file(&a.path) {
        return Vec::new();
    }
    let offset = offset.min(a.src.len());
    let line_start = a.src[..offset].rfind('\n').map_or(0, |p| p + 1);
    let before = &a.src[line_start..offset];
    let Some(value) = before.trim_start().strip_prefix("post") else {
        return Vec::new();
    };
    let Some(value) = value.trim_start().strip_prefix('=') else {
        return Vec::new();
    };
    // inside the quotes the name alone, else the quoted name
    let quoted = value.trim_start().starts_with(['"', '\'']);
    let insert = |n: &str| {
        if quoted {
            n.to_string()
        } else {
            format!("\"{n}\"")
        }
    };
    let mut out: Vec<Completion> = millpath_post::builtin::NAMES
        .iter()
        .filter_map(|n| millpath_post::builtin::get(n))
        .map(|p| Completion {
            label: p.name.clone(),
            detail: p.description.clone(),
            insert: insert(&p.name),
        })
        .collect();
    let dir = a.path.parent().unwrap_or(Path::new(""));
    let fs = ws.fs();
    let mut files: Vec<_> = fs
        .list_dir(&dir.join("posts"))
        .unwrap_or_default()
        .into_iter()
        .filter(|p| crate::toml_doc::is_toml(p))
        .collect();
    files.sort();
    files.truncate(MAX_FILES);
    let read = reader(ws);
    for f in files {
        let Some(name) = f.file_name().and_then(|n| n.to_str()) else {
            continue;
        };
        let rel = format!("posts/{name}");
        let detail =
            match millpath_post::load(&f.display().to_string(), &read(&f).unwrap_or_default()) {
                Ok(p) => p.description,
                Err(_) if de(a) => "Post-Datei (mit Fehlern)".into(),
                Err(_) => "post file (with errors)".into(),
            };
        out.push(Completion {
            insert: insert(&rel),
            label: rel,
            detail,
        });
    }
    out
}

/// Hover on the value of `post = "…"` in `millpath.toml`.
pub fn hover(a: &Analysis, ws: &Workspace, offset: usize) -> Option<Hover> {
    if !is_settings_file(&a.path) {
        return None;
    }
    let (start, end) = post_value(&a.src)?;
    if offset < start || offset > end {
        return None;
    }
    let name = &a.src[start..end];
    let dir = a.path.parent().unwrap_or(Path::new(""));
    let german = de(a);
    let markdown = match millpath_post::resolve(name, dir, &reader(ws)) {
        Ok(p) => describe(&p, german),
        Err(e) => e.render(if german {
            millpath_post::Lang::De
        } else {
            millpath_post::Lang::En
        }),
    };
    Some(Hover {
        markdown,
        start,
        end,
    })
}

/// A post's family and what it can do, as Markdown.
pub fn describe(p: &Post, german: bool) -> String {
    let yes_no = |b: bool| match (b, german) {
        (true, false) => "yes",
        (false, false) => "no",
        (true, true) => "ja",
        (false, true) => "nein",
    };
    let probing = match p.capabilities.probing {
        Probing::None => yes_no(false),
        Probing::G38_2 => "G38.2",
        Probing::G38_3 => "G38.3",
        Probing::G31 => "G31",
    };
    let arcs = match (p.format.arcs, german) {
        (ArcMode::Ij, _) => "G2/G3 I J".to_string(),
        (ArcMode::R, _) => "G2/G3 R".to_string(),
        (ArcMode::Lines, false) => format!("as lines (chord {} mm)", p.format.chord_tolerance),
        (ArcMode::Lines, true) => format!("als Geraden (Sehne {} mm)", p.format.chord_tolerance),
    };
    let origin = match p.origin.strip_prefix("builtin:") {
        Some(n) if german => format!("eingebaut (`millpath post show {n}` gibt die Datei aus)"),
        Some(n) => format!("built in (`millpath post show {n}` prints it as a file)"),
        None => format!("`{}`", p.origin),
    };
    let rows: [(&str, &str, String); 7] = [
        ("Family", "Familie", p.family.name().to_string()),
        ("Probing", "Antasten", probing.to_string()),
        (
            "Probe log",
            "Messprotokoll",
            yes_no(p.capabilities.probe_log).to_string(),
        ),
        (
            "Spindle",
            "Spindel",
            yes_no(p.capabilities.spindle).to_string(),
        ),
        (
            "Dwell",
            "Verweilen",
            yes_no(p.capabilities.dwell).to_string(),
        ),
        ("Arcs", "Bögen", arcs),
        ("From", "Herkunft", origin),
    ];
    let mut md = format!("**post {}** — {}\n\n", p.name, p.description);
    for (en, de, v) in rows {
        md.push_str(&format!("- {}: {v}\n", if german { de } else { en }));
    }
    md
}
