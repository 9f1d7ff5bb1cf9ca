//! The playground's state: its files in memory (`.mpath` as editor buffers, `millpath.toml`
//! and anything else as memory files under them), one analysis per file and version, and
//! every answer as JSON text. Plain Rust, so the native tests run the code the page runs.
//!
//! The playground's state: `.mpath` files as buffers of an `ide::Workspace`, `millpath.toml` as a
//! `MemFileSystem` under them (`Workspace::memory`, no disk); one analysis per file and change;
//! diagnostics, hover, completion, format, the path at the cursor, compile's files (`compile_file`;
//! a library: the preview of the path), the toolpath data, `dxf2text` of bytes, `text2dxf`, all as
//! JSON with UTF-16 offsets. The post selector (`set_post`, a built-in's name) is the editor's
//! `post` setting: every answer, the G-code first, is written by that post.

use crate::offsets::{from_utf16, to_utf16};
use millpath_core::diag::{FileRef, Severity};
use millpath_core::load::fs::is_text_file;
use millpath_core::{compile_file, Lang, MemFileSystem, Session};
use millpath_ide::{Analysis, Workspace};
use serde_json::{json, Value};
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::Arc;

#[derive(Default)]
pub struct Playground {
    ws: Workspace,
    memory: MemFileSystem,
    /// Bumped by every change of a file or the language: older analyses are stale.
    generation: u64,
    /// The last analysis of each file and the generation it was made in (a stale one still
    /// serves the incremental parse of the next).
    analyses: RefCell<HashMap<PathBuf, (u64, Rc<Analysis>)>>,
}

impl Playground {
    pub fn new(lang: &str) -> Playground {
        let mut p = Playground::default();
        p.set_lang(lang);
        p
    }

    fn lang(&self) -> Lang {
        Lang::from_name(self.ws.client.lang.as_deref().unwrap_or("en"))
    }

    /// The messages' language (`en`, `de`): the editor's setting, over `millpath.toml`'s.
    pub fn set_lang(&mut self, lang: &str) {
        self.ws.client.lang = Some(if lang == "de" { "de" } else { "en" }.to_string());
        self.generation += 1;
    }

    /// The post that writes the programs (a built-in's name, as `--post NAME`, over the
    /// `post =` of `millpath.toml`); empty: `millpath.toml`'s, else the dialect's.
    pub fn set_post(&mut self, name: &str) {
        let name = name.trim();
        self.ws.client.post = (!name.is_empty()).then(|| name.to_string());
        self.generation += 1;
    }

    /// The built-in posts for the selector: `[{name, description, family}]`.
    pub fn posts() -> String {
        let list: Vec<Value> = millpath_post::builtin::NAMES
            .iter()
            .filter_map(|n| millpath_post::builtin::get(n))
            .map(|p| json!({ "name": p.name, "description": p.description, "family": p.family.name() }))
            .collect();
        Value::Array(list).to_string()
    }

    /// Adds or replaces a file: a `.mpath` text as a buffer, anything else (`millpath.toml`)
    /// as a file under the buffers.
    pub fn set_file(&mut self, path: &str, content: &str) {
        let p = PathBuf::from(path);
        if is_text_file(&p) {
            self.ws.overlays.insert(p, content.to_string());
        } else {
            self.memory.add(p, content.as_bytes().to_vec());
            self.ws.memory = Some(Arc::new(self.memory.clone()));
        }
        self.generation += 1;
    }

    pub fn remove_file(&mut self, path: &str) {
        let p = PathBuf::from(path);
        self.ws.overlays.remove(&p);
        if self.memory.files.remove(&p).is_some() {
            self.ws.memory = Some(Arc::new(self.memory.clone()));
        }
        self.analyses.borrow_mut().remove(&p);
        self.generation += 1;
    }

    /// The current analysis of `path` (made once per generation).
    fn analysis(&self, path: &Path) -> Rc<Analysis> {
        let prev = self.analyses.borrow().get(path).cloned();
        if let Some((g, a)) = &prev {
            if *g == self.generation {
                return a.clone();
            }
        }
        let a = millpath_ide::analyze_from(&self.ws, path, prev.as_ref().map(|p| &*p.1), &|| false)
            .map(Rc::new)
            .unwrap_or_else(|| Rc::new(millpath_ide::analyze(&self.ws, path)));
        self.analyses
            .borrow_mut()
            .insert(path.to_path_buf(), (self.generation, a.clone()));
        a
    }

    /// What `millpath check` reports for the file, located in UTF-16 offsets of its text:
    /// `[{from, to, line, severity, code, message}]`.
    pub fn diagnostics(&self, path: &str) -> String {
        let a = self.analysis(Path::new(path));
        let lang = self.lang();
        let list: Vec<Value> = a
            .diagnostics
            .iter()
            .map(|d| {
                let (s, e) = millpath_ide::diagnostic_range(&a, &d.origin).unwrap_or((0, 0));
                json!({
                    "from": to_utf16(&a.src, s),
                    "to": to_utf16(&a.src, e),
                    "line": a.index.pos(s).line + 1,
                    "severity": if d.severity == Severity::Error { "error" } else { "warning" },
                    "code": d.msg.code(),
                    "message": d.message(lang),
                })
            })
            .collect();
        Value::Array(list).to_string()
    }

    /// The hover at UTF-16 offset `at`: `{from, to, markdown}` or `null`.
    pub fn hover(&self, path: &str, at: usize) -> String {
        let a = self.analysis(Path::new(path));
        match millpath_ide::hover(&a, &self.ws, from_utf16(&a.src, at)) {
            Some(h) => json!({
                "from": to_utf16(&a.src, h.start),
                "to": to_utf16(&a.src, h.end),
                "markdown": h.markdown,
            })
            .to_string(),
            None => "null".into(),
        }
    }

    /// Completions at UTF-16 offset `at`: `{from, items: [{label, detail, insert}]}`, `from`
    /// being the start of the word they replace.
    pub fn completion(&self, path: &str, at: usize) -> String {
        let a = self.analysis(Path::new(path));
        let offset = from_utf16(&a.src, at);
        let before = &a.src[..offset];
        let word = before.rsplit(char::is_whitespace).next().unwrap_or("");
        let start = offset - word.strip_prefix('>').unwrap_or(word).len();
        let items: Vec<Value> = millpath_ide::completion(&a, &self.ws, offset)
            .into_iter()
            .map(|c| json!({ "label": c.label, "detail": c.detail, "insert": c.insert }))
            .collect();
        json!({ "from": to_utf16(&a.src, start), "items": items }).to_string()
    }

    /// The canonical form of the file, or `null` when it does not parse.
    pub fn format(&self, path: &str) -> String {
        let a = self.analysis(Path::new(path));
        json!(millpath_ide::format(&a)).to_string()
    }

    /// The path whose block holds UTF-16 offset `at` (else the file's first): `null` if none.
    pub fn path_at(&self, path: &str, at: usize) -> String {
        let a = self.analysis(Path::new(path));
        let offset = from_utf16(&a.src, at);
        let mut paths = a.ast.paths();
        let first = a.ast.paths().next().map(|p| p.name.value.clone());
        let here = paths
            .find(|p| p.span.start <= offset && offset <= p.span.end)
            .map(|p| p.name.value.clone());
        json!(here.or(first)).to_string()
    }

    /// The files `millpath compile` writes for the file, `{files: [{name, content}], stats,
    /// messages}`. A file of several paths (a library, which compile refuses) gives the
    /// preview of `name`, the path under the cursor, as compile would write it alone.
    pub fn compile(&self, path: &str, name: Option<String>) -> String {
        let p = Path::new(path);
        let a = self.analysis(p);
        let lang = self.lang();
        let ds = self.ws.settings_for(p);
        let mut messages: Vec<String> = ds.missing_message().into_iter().collect();
        if a.ast.paths().count() > 1 {
            let pv = millpath_ide::preview(&self.ws, p, name.as_deref()).unwrap_or_else(|e| {
                millpath_ide::Preview {
                    path: name.clone().unwrap_or_default(),
                    gcode: String::new(),
                    probing: None,
                    z_txt: None,
                    stats: Vec::new(),
                    time: String::new(),
                    errors: vec![e],
                }
            });
            messages.extend(pv.errors);
            let prefix = millpath_core::output_prefix(p, "");
            let stem = prefix.file_name().map(|s| s.to_string_lossy().into_owned());
            let stem = format!("{}_{}", stem.unwrap_or_default(), pv.path);
            let mut files = Vec::new();
            if let Some(pr) = pv.probing {
                files.push(json!({ "name": format!("{stem}_Probing.gcode"), "content": pr }));
            }
            if let Some(z) = pv.z_txt {
                files.push(json!({ "name": format!("{stem}_Z.txt"), "content": z }));
            }
            if !pv.gcode.is_empty() {
                let kind = if files.is_empty() { "Milling" } else { "Clean" };
                files.insert(
                    0,
                    json!({ "name": format!("{stem}_{kind}.gcode"), "content": pv.gcode }),
                );
            }
            return json!({ "files": files, "stats": pv.stats, "messages": messages }).to_string();
        }
        let fs = self.ws.fs();
        let mut session = match Session::new(ds.settings, &fs) {
            Ok(s) => s,
            Err(errs) => {
                messages.extend(errs.iter().map(|d| d.message(lang)));
                return json!({ "files": [], "stats": [], "messages": messages }).to_string();
            }
        };
        let outcome = compile_file(&mut session, p, &millpath_core::banner());
        messages.extend(
            session
                .diags
                .list
                .iter()
                .filter(|d| d.severity == Severity::Error)
                .map(|d| match d.origin.location_in(lang) {
                    Some(at) => format!("{at}: {}", d.message(lang)),
                    None => d.message(lang),
                }),
        );
        let files: Vec<Value> = outcome
            .outputs
            .iter()
            .map(|o| {
                let n = o.path.file_name().map(|n| n.to_string_lossy().into_owned());
                json!({ "name": n.unwrap_or_default(), "content": o.content })
            })
            .collect();
        let stats: Vec<String> = outcome
            .stats
            .iter()
            .flat_map(|(_, s)| s.lines(lang).to_vec())
            .collect();
        json!({ "files": files, "stats": stats, "messages": messages }).to_string()
    }

    /// The toolpath view's data of path `name` (default: the file's first), as the editors
    /// get it; `{error}` when there is none.
    pub fn toolpath(&self, path: &str, name: Option<String>) -> String {
        match millpath_ide::toolpath(&self.ws, Path::new(path), name.as_deref()) {
            Ok(v) => v.to_string(),
            Err(e) => json!({ "error": e }).to_string(),
        }
    }

    /// `millpath dxf2text` of a drawing's bytes, with the settings a file at `path` would
    /// have: `{text, messages}` or `{error}`.
    pub fn dxf2text(&self, path: &str, bytes: &[u8]) -> String {
        let p = Path::new(path);
        let s = self.ws.settings_for(p).settings;
        let lang = self.lang();
        let patterns =
            match millpath_core::load::names::Patterns::shared(&s.path_pattern, &s.file_pattern) {
                Ok(x) => x,
                Err((c, pat, e)) => {
                    return json!({ "error": format!("/{c} '{pat}': {e}") }).to_string()
                }
            };
        let file = FileRef::new(p.to_path_buf());
        match millpath_core::convert::dxf_to_text(bytes, &file, &patterns, s.input) {
            Ok((text, diags)) => {
                let messages: Vec<String> = diags.iter().map(|d| d.message(lang)).collect();
                json!({ "text": text, "messages": messages }).to_string()
            }
            Err(d) => json!({ "error": d.message(lang) }).to_string(),
        }
    }

    /// `millpath text2dxf` of a file: `{dxf}` or `{error}` (syntax errors refuse it).
    pub fn text2dxf(&self, path: &str) -> String {
        let p = Path::new(path);
        let s = self.ws.settings_for(p).settings;
        let lang = self.lang();
        let src = self.ws.text(p).unwrap_or_default();
        let patterns =
            match millpath_core::load::names::Patterns::shared(&s.path_pattern, &s.file_pattern) {
                Ok(x) => x,
                Err((c, pat, e)) => {
                    return json!({ "error": format!("/{c} '{pat}': {e}") }).to_string()
                }
            };
        let file = FileRef::new(p.to_path_buf());
        match millpath_core::convert::text_to_dxf(&src, &file, &patterns) {
            Ok(dxf) => json!({ "dxf": dxf }).to_string(),
            Err(errs) => {
                let e: Vec<String> = errs.iter().map(|d| d.message(lang)).collect();
                json!({ "error": e.join("; ") }).to_string()
            }
        }
    }
}
