//! Editor questions about MillPath files, answered as plain data (byte offsets, strings):
//! diagnostics, hover, G-code preview, inlay hints, navigation, symbols, completion,
//! formatting, code actions, semantic tokens and code lenses. Only `millpath-lsp` knows LSP.

pub mod features;
pub mod line_index;

use millpath_core::diag::{Diagnostic, FileRef, Origin};
use millpath_core::front::drawing::{build_paths, DrawnObject, RawPath};
use millpath_core::front::text::objects_of;
use millpath_core::load::config::{self, FileConfig, Have};
use millpath_core::load::fs::{is_text_file, FileSystem};
use millpath_core::{compile_file, Diags, Session, Settings};
use millpath_syntax::{parse, File};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub use line_index::{LineIndex, Pos};

/// Open documents (unsaved buffers win over the disk) and editor settings.
#[derive(Debug, Clone, Default)]
pub struct Workspace {
    pub overlays: HashMap<PathBuf, String>,
    /// Machine settings from the editor; they override `millpath.toml`.
    pub client: FileConfig,
    /// Workspace folders (for references and workspace symbols).
    pub roots: Vec<PathBuf>,
}

/// The file system as the editor sees it: open buffers over the disk.
pub struct WorkspaceFs<'a> {
    overlays: &'a HashMap<PathBuf, String>,
}

impl FileSystem for WorkspaceFs<'_> {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        match self.overlays.get(path) {
            Some(t) => Ok(t.clone().into_bytes()),
            None => std::fs::read(path),
        }
    }
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        let mut v = millpath_core::OsFileSystem
            .list_dir(dir)
            .unwrap_or_default();
        for p in self.overlays.keys() {
            if p.parent() == Some(dir) && !v.contains(p) {
                v.push(p.clone());
            }
        }
        Ok(v)
    }
    fn is_dir(&self, dir: &Path) -> bool {
        dir.is_dir() || self.overlays.keys().any(|p| p.parent() == Some(dir))
    }
    fn stamp(&self, path: &Path) -> Option<millpath_core::load::parse_cache::FileStamp> {
        use millpath_core::load::parse_cache::FileStamp;
        match self.overlays.get(path) {
            Some(t) => Some(FileStamp::of_contents(t.as_bytes())),
            None => FileStamp::of_disk_file(path),
        }
    }
}

/// Where a machine setting comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum SettingSource {
    Default,
    File(PathBuf),
    Editor,
}

impl SettingSource {
    pub fn describe(&self) -> String {
        match self {
            SettingSource::Default => "default".into(),
            SettingSource::File(p) => format!("{} ({})", config::FILE_NAME, p.display()),
            SettingSource::Editor => "editor settings".into(),
        }
    }
}

/// Settings of a document and where the machine values come from.
#[derive(Debug, Clone)]
pub struct DocSettings {
    pub settings: Settings,
    pub feed: SettingSource,
    pub sweep_height: SettingSource,
    pub probe_feed: SettingSource,
    /// A `millpath.toml` that does not parse.
    pub config_error: Option<(PathBuf, String)>,
}

impl Workspace {
    pub fn fs(&self) -> WorkspaceFs<'_> {
        WorkspaceFs {
            overlays: &self.overlays,
        }
    }

    pub fn text(&self, path: &Path) -> Option<String> {
        self.overlays
            .get(path)
            .cloned()
            .or_else(|| std::fs::read_to_string(path).ok())
    }

    /// `millpath.toml` (nearest above the file), then the editor's settings.
    pub fn settings_for(&self, path: &Path) -> DocSettings {
        let mut s = Settings::default();
        let mut have = Have::default();
        let mut ds = DocSettings {
            settings: Settings::default(),
            feed: SettingSource::Default,
            sweep_height: SettingSource::Default,
            probe_feed: SettingSource::Default,
            config_error: None,
        };
        let fs = self.fs();
        let mut dir = path.parent();
        while let Some(d) = dir {
            let candidate = d.join(config::FILE_NAME);
            if let Ok(bytes) = fs.read(&candidate) {
                match config::parse(&String::from_utf8_lossy(&bytes), d) {
                    Ok(cfg) => {
                        cfg.apply(&mut s, &mut have);
                        let src = SettingSource::File(candidate.clone());
                        if cfg.feed.is_some() {
                            ds.feed = src.clone();
                        }
                        if cfg.sweep_height.is_some() {
                            ds.sweep_height = src.clone();
                        }
                        if cfg.probe_feed.is_some() {
                            ds.probe_feed = src;
                        }
                    }
                    Err(e) => ds.config_error = Some((candidate, e)),
                }
                break;
            }
            dir = d.parent();
        }
        self.client.apply(&mut s, &mut have);
        if self.client.feed.is_some() {
            ds.feed = SettingSource::Editor;
        }
        if self.client.sweep_height.is_some() {
            ds.sweep_height = SettingSource::Editor;
        }
        if self.client.probe_feed.is_some() {
            ds.probe_feed = SettingSource::Editor;
        }
        ds.settings = s;
        ds
    }
}

/// Everything known about one text document.
#[derive(Debug)]
pub struct Analysis {
    pub path: PathBuf,
    pub src: String,
    pub index: LineIndex,
    pub ast: File,
    /// Diagnostics located in this document (syntax and compiler), in order.
    pub diagnostics: Vec<Diagnostic>,
    pub objects: Vec<DrawnObject>,
    pub paths: Vec<RawPath>,
    pub settings: DocSettings,
}

/// Analyses a document: parses it and runs the compiler's check over every path in it.
pub fn analyze(ws: &Workspace, path: &Path) -> Analysis {
    let src = ws.text(path).unwrap_or_default();
    let settings = ws.settings_for(path);
    let (ast, syntax_errors) = parse(&src);
    let file = FileRef::new(path.to_path_buf());
    let mut local = Diags::default();
    let s = &settings.settings;
    let mut abort = None;
    let text = match objects_of(&ast, syntax_errors, &src, &file, &mut local) {
        Ok(t) => t,
        Err(d) => {
            abort = Some(d);
            Default::default()
        }
    };
    let paths = match millpath_core::load::names::Patterns::shared(&s.path_pattern, &s.file_pattern)
    {
        Ok(p) => build_paths(
            &text.objects,
            &file,
            &p.path_cs,
            &s.path_pattern,
            &mut local,
        )
        .unwrap_or_else(|d| {
            abort = Some(d);
            Vec::new()
        }),
        Err(_) => Vec::new(),
    };
    text.check_declared_kinds(&paths, &mut local);
    let mut diagnostics = local.list;
    diagnostics.extend(abort);
    // the compiler's check over every path, with this buffer as parsed above
    let fs = ws.fs();
    let mut check = settings.settings.clone();
    check.check = true;
    match Session::new(check, &fs) {
        Ok(mut session) => {
            session.add_paths(path, paths.clone());
            compile_file(&mut session, path, &millpath_core::banner());
            diagnostics.extend(session.diags.list.into_iter().filter(|d| in_file(d, path)));
        }
        Err(errs) => diagnostics.extend(errs),
    }
    if let Some((cfg, e)) = &settings.config_error {
        diagnostics.push(Diagnostic::error(
            millpath_core::Msg::CannotRead,
            Origin::Input,
            millpath_core::args![cfg.display(), e],
        ));
    }
    let index = LineIndex::new(&src);
    Analysis {
        path: path.to_path_buf(),
        src,
        index,
        ast,
        diagnostics,
        objects: text.objects,
        paths,
        settings,
    }
}

/// Whether a diagnostic points into the file (others belong to the files they point to).
fn in_file(d: &Diagnostic, path: &Path) -> bool {
    match &d.origin {
        Origin::Span { file, .. } | Origin::Path { file, .. } | Origin::File(file) => {
            file.path == path
        }
        Origin::Entity(e) => e.file.path == path,
        Origin::Options | Origin::Input | Origin::FileLine { .. } => true,
    }
}

/// Every drawing file below the workspace folders (text and DXF).
pub fn workspace_files(ws: &Workspace) -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>, depth: usize) {
        if depth > 12 {
            return;
        }
        let Ok(rd) = std::fs::read_dir(dir) else {
            return;
        };
        let mut entries: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
        entries.sort();
        for e in entries {
            let hidden = e
                .file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with('.') || n == "target");
            if e.is_dir() && !hidden {
                walk(&e, out, depth + 1);
            } else if is_text_file(&e)
                || e.extension().is_some_and(|x| x.eq_ignore_ascii_case("dxf"))
            {
                out.push(e);
            }
        }
    }
    let mut out = Vec::new();
    for r in &ws.roots {
        walk(r, &mut out, 0);
    }
    for p in ws.overlays.keys() {
        if !out.contains(p) {
            out.push(p.clone());
        }
    }
    out
}

/// A file reference for core APIs.
pub fn file_ref(path: &Path) -> Arc<FileRef> {
    FileRef::new(path.to_path_buf())
}
