//! Editor questions about MillPath files, answered as plain data (byte offsets, strings):
//! diagnostics, hover, G-code preview, inlay hints, navigation, symbols, completion,
//! formatting, code actions, semantic tokens, code lenses, rename, folding, links,
//! highlights and selection ranges. Only `millpath-lsp` knows LSP.
//!
//! `Workspace` (open buffers, editor settings, folders, column encoding, `memory`: files in memory
//! instead of the disk for the playground), settings with their sources (`millpath.toml`, editor,
//! default; `missing_machine`), `analyze`/`analyze_from`: the diagnostics through the same code as
//! `millpath check` (one check-mode `Session`, the buffer's paths read by `Session::text_paths`,
//! DXF drawings loaded by the session, then `compile_file` with `quick_check`: every path planned
//! as compile plans it, but not given to the second opinion, whose stock simulation took the answer
//! to 27 ms at 2,000 elements and 270–310 ms at 20,000, and emitted without the order of fast
//! milling (`emit::quick_check_until`: passes level by level, the same moves and diagnostics, test
//! `core/tests/quick_check.rs`; a long chain's order was half of its answer): 1–2 ms at 2,000 and
//! 17–26 ms at 20,000 on a loaded machine, `bench lsp_latency`; its record counts the moves
//! without making them, see the bench's doc for figures; a path's walk is taken from the
//! previous analysis when the edit cannot change it (`traversals`, `core/build/traverse_memo.rs`),
//! an edit inside one element line parses that line alone (`reparse`) and takes the other
//! elements' drawn objects and the line index from the previous analysis, offsets moved
//! (`core/front/text_edit.rs`: only when those objects came without a diagnostic),
//! the object-by-offset table is made on first use, the raw paths are shared with the session
//! (`Session::add_shared_paths`), not copied: 8–10 ms at 20,000), the tree and drawn objects for
//! the features, the files and folders the analysis read (its dependencies, recorded by a wrapping
//! `FileSystem`); gives up between stages when `cancelled()`, and inside the compiler through
//! `Session::stop` (asked between elements and passes).
//!
//! Posts (issue 32): `settings_for` resolves `post =` as `millpath compile` does (the post
//! file, as saved, is a dependency of every document it writes for); `toml_doc` checks
//! `millpath.toml` and post files, `post_names` completes and explains post names.

mod call_hierarchy;
mod code_actions;
mod code_lens;
mod common;
mod completion;
mod cut_view;
mod diagnostic_range;
mod document_links;
mod effective;
mod folding;
mod formatting;
mod heightmap_view;
mod highlight;
mod hover;
mod inlay_hints;
pub mod line_index;
mod navigation;
mod param_doc;
mod post_names;
mod preview;
mod preview_files;
mod provenance;
mod rename;
pub mod reparse;
mod selection;
mod semantic_delta;
mod semantic_tokens;
mod symbols;
mod toml_doc;
mod toolpath;
pub mod walk;
pub mod workspace_check;

pub use call_hierarchy::{incoming_calls, outgoing_calls, prepare_call_hierarchy, Call, CallItem};
pub use code_actions::{code_actions, Action};
pub use code_lens::{code_lenses, code_lenses_until, Lens};
pub use common::{element_at, Location, TextEdit};
pub use completion::{completion, Completion};
pub use diagnostic_range::diagnostic_range;
pub use document_links::{document_links, Link};
pub use effective::{effective_values, Effective};
pub use folding::{folding_ranges, Fold, FoldKind};
pub use formatting::{format, format_range};
pub use heightmap_view::with_surface;
pub use highlight::{document_highlights, Highlight};
pub use hover::{hover, Hover};
pub use inlay_hints::{inlay_hints, inlay_hints_in, Hint};
pub use navigation::{definition, references};
pub use param_doc::param_doc;
pub use post_names::{completion as settings_completion, hover as settings_hover};
pub use preview::{preview, preview_of, preview_of_until, preview_until};
pub use preview_files::Preview;
pub use rename::{prepare_rename, rename, FileEdit};
pub use selection::selection_ranges;
pub use semantic_delta::{apply_token_edit, relative_tokens, token_edit, RelToken, TokenEdit};
pub use semantic_tokens::{semantic_tokens, SemToken, TOKEN_TYPES};
pub use symbols::{document_symbols, workspace_symbols, Symbol};
pub use toml_doc::{analyze as analyze_toml, is_toml};
pub use toolpath::{
    toolpath, toolpath_html, toolpath_moves, toolpath_moves_of, toolpath_svg, toolpath_until,
};

use millpath_core::build::traverse_memo::TraversalMemo;
use millpath_core::diag::{Diagnostic, FileRef, Origin};
use millpath_core::front::drawing::{DrawnObject, RawPath};
use millpath_core::front::text::objects_of;
use millpath_core::front::text_edit::{objects_after_edit, LineEdit, PrevObjects};
use millpath_core::load::config::{self, FileConfig, Have};
use millpath_core::load::fs::{is_text_file, FileSystem};
use millpath_core::{compile_file, Diags, Session, Settings};
use millpath_syntax::{parse, File};
use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

pub use line_index::{LineIndex, Pos};

/// Open documents (unsaved buffers win over the disk) and editor settings.
#[derive(Debug, Clone, Default)]
pub struct Workspace {
    pub overlays: HashMap<PathBuf, String>,
    /// Machine settings from the editor; they override `millpath.toml`.
    pub client: FileConfig,
    /// Workspace folders (for references and workspace symbols).
    pub roots: Vec<PathBuf>,
    /// Columns count UTF-8 bytes (negotiated `positionEncoding`), else UTF-16 code units.
    pub utf8: bool,
    /// Settings fixed by the caller for every file (`millpath render`: its options over
    /// `millpath.toml`, read as every command reads them); `None` in the editor.
    pub fixed: Option<Settings>,
    /// Files held in memory instead of the disk (the browser playground: there is no disk);
    /// the overlays still win over them.
    pub memory: Option<Arc<millpath_core::MemFileSystem>>,
    /// `--heightmap-step` and `--heightmap-margin` over the file's `[heightmap]` (`millpath
    /// diff`), as `compile` takes them: the step keeps the other keys, a margin alone widens
    /// the file's grid.
    pub heightmap_options: (Option<f64>, Option<f64>),
    /// Analyses read the document's paths and build no model (`millpath diff`: the toolpath
    /// of each path builds and plans it once, walking through the analysis's memo, and
    /// reports the build's and the emitter's errors; the analysis's diagnostics then lack
    /// them).
    pub paths_only: bool,
}

/// The file system as the editor sees it: open text buffers over the disk. A DXF drawing is
/// always read from the disk (an editor's text of it is decoded from its code page and no
/// longer the drawing's bytes).
pub struct WorkspaceFs<'a> {
    overlays: &'a HashMap<PathBuf, String>,
    memory: Option<&'a millpath_core::MemFileSystem>,
}

impl WorkspaceFs<'_> {
    fn overlay(&self, path: &Path) -> Option<&String> {
        self.overlays.get(path).filter(|_| is_text_file(path))
    }
    /// What is under the overlays: the memory files, else the disk.
    fn base(&self) -> &dyn FileSystem {
        match self.memory {
            Some(m) => m,
            None => &millpath_core::OsFileSystem,
        }
    }
}

impl FileSystem for WorkspaceFs<'_> {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        match self.overlay(path) {
            Some(t) => Ok(t.clone().into_bytes()),
            None => self.base().read(path),
        }
    }
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        let mut v = self.base().list_dir(dir).unwrap_or_default();
        for p in self.overlays.keys() {
            if p.parent() == Some(dir) && !v.contains(p) {
                v.push(p.clone());
            }
        }
        Ok(v)
    }
    fn is_dir(&self, dir: &Path) -> bool {
        self.base().is_dir(dir) || self.overlays.keys().any(|p| p.parent() == Some(dir))
    }
    fn stamp(&self, path: &Path) -> Option<millpath_core::load::parse_cache::FileStamp> {
        use millpath_core::load::parse_cache::FileStamp;
        match (self.overlay(path), self.memory) {
            (Some(t), _) => Some(FileStamp::of_contents(t.as_bytes())),
            (None, Some(m)) => m.files.get(path).map(|b| FileStamp::of_contents(b)),
            (None, None) => FileStamp::of_disk_file(path),
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
        self.describe_in(millpath_core::Lang::En)
    }

    /// [`SettingSource::describe`] in the message language.
    pub fn describe_in(&self, lang: millpath_core::Lang) -> String {
        let de = lang == millpath_core::Lang::De;
        match self {
            SettingSource::Default => if de { "Standard" } else { "default" }.into(),
            SettingSource::File(p) => format!("{} ({})", config::FILE_NAME, p.display()),
            SettingSource::Editor => if de {
                "Editor-Einstellungen"
            } else {
                "editor settings"
            }
            .into(),
        }
    }
}

/// Settings of a document and where the machine values come from.
#[derive(Debug, Clone)]
pub struct DocSettings {
    pub settings: Settings,
    pub feed: SettingSource,
    pub sweep_height: SettingSource,
    pub sweep_speed: SettingSource,
    pub probe_feed: SettingSource,
    /// A `millpath.toml` that does not parse.
    pub config_error: Option<(PathBuf, String)>,
    /// The post file `post =` names (a dependency of every document it writes for).
    pub post_file: Option<PathBuf>,
    /// A `post =` that names no built-in post and no readable, valid post file: the
    /// settings file and the loader's located message (in the settings' language).
    pub post_error: Option<(PathBuf, String)>,
}

impl Workspace {
    pub fn fs(&self) -> WorkspaceFs<'_> {
        WorkspaceFs {
            overlays: &self.overlays,
            memory: self.memory.as_deref(),
        }
    }

    /// A line index of a text with the negotiated column encoding.
    pub fn line_index(&self, text: &str) -> LineIndex {
        LineIndex::with_encoding(text, self.utf8)
    }

    pub fn text(&self, path: &Path) -> Option<String> {
        self.overlays
            .get(path)
            .cloned()
            // decoded as the compiler reads it: BOM dropped, UTF-16 decoded
            .or_else(|| {
                let bytes = self.fs().base().read(path).ok()?;
                let decoded = millpath_core::load::text_file::decode(&bytes).ok()?;
                Some(decoded.text.into_owned())
            })
    }

    /// `millpath.toml` (nearest above the file), then the editor's settings.
    pub fn settings_for(&self, path: &Path) -> DocSettings {
        if let Some(fixed) = &self.fixed {
            return DocSettings {
                settings: fixed.clone(),
                feed: SettingSource::Editor,
                sweep_height: SettingSource::Editor,
                sweep_speed: SettingSource::Editor,
                probe_feed: SettingSource::Editor,
                config_error: None,
                post_file: None,
                post_error: None,
            };
        }
        let mut s = Settings::default();
        let mut have = Have::default();
        let mut ds = DocSettings {
            settings: Settings::default(),
            feed: SettingSource::Default,
            sweep_height: SettingSource::Default,
            sweep_speed: SettingSource::Default,
            probe_feed: SettingSource::Default,
            config_error: None,
            post_file: None,
            post_error: None,
        };
        // the `post =` of millpath.toml and the folder its file is found from
        let mut post: Option<(String, PathBuf, PathBuf)> = None;
        let fs = self.fs();
        let mut dir = path.parent();
        while let Some(d) = dir {
            let candidate = d.join(config::FILE_NAME);
            if let Ok(bytes) = fs.read(&candidate) {
                // as the command line reads it: a mark dropped, UTF-16 decoded
                let text = match millpath_core::load::text_file::decode(&bytes) {
                    Ok(decoded) => decoded.text.into_owned(),
                    Err(_) => String::from_utf8_lossy(&bytes).into_owned(),
                };
                match config::parse(&text, d) {
                    Ok(cfg) => {
                        cfg.apply(&mut s, &mut have);
                        post = cfg
                            .post
                            .clone()
                            .map(|p| (p, cfg.base_dir.clone(), candidate.clone()));
                        if !cfg.clamp.is_empty() {
                            s.clamps_file = Some(candidate.clone());
                        }
                        let src = SettingSource::File(candidate.clone());
                        if cfg.feed.is_some() {
                            ds.feed = src.clone();
                        }
                        if cfg.sweep_height.is_some() {
                            ds.sweep_height = src.clone();
                        }
                        if cfg.sweep_speed.is_some() {
                            ds.sweep_speed = src.clone();
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
        // a margin without a grid widens nothing (the command line refused it for the work
        // tree's settings; a revision's may have no [heightmap])
        let (step, margin) = self.heightmap_options;
        s.override_heightmap(step, margin);
        if self.client.feed.is_some() {
            ds.feed = SettingSource::Editor;
        }
        if self.client.sweep_height.is_some() {
            ds.sweep_height = SettingSource::Editor;
        }
        if self.client.sweep_speed.is_some() {
            ds.sweep_speed = SettingSource::Editor;
        }
        if self.client.probe_feed.is_some() {
            ds.probe_feed = SettingSource::Editor;
        }
        // the editor's `dialect` over the file's `post`, its `post` over both (as the
        // command line's options over millpath.toml)
        if self.client.dialect.is_some() {
            post = None;
        }
        if let Some(p) = &self.client.post {
            let base = self.roots.first().cloned().unwrap_or_default();
            post = Some((p.clone(), base, PathBuf::from("editor settings")));
        }
        if let Some((name, base, from)) = post {
            self.select_post(&mut s, &mut ds, &name, &base, &from);
        }
        ds.settings = s;
        ds
    }

    /// Sets the dialect and post `name` selects, as `millpath compile` does (a built-in's
    /// name, or a post file relative to `base`, read through the editor's view: an open
    /// buffer of the post file wins over the disk).
    fn select_post(
        &self,
        s: &mut Settings,
        ds: &mut DocSettings,
        name: &str,
        base: &Path,
        from: &Path,
    ) {
        let fs = self.fs();
        let read = |p: &Path| -> Result<String, String> {
            let bytes = fs.read(p).map_err(|e| e.to_string())?;
            // as `millpath compile` reads it
            String::from_utf8(bytes).map_err(|e| e.to_string())
        };
        if let Some(file) = post_file_of(name, base) {
            ds.post_file = Some(file);
        }
        match millpath_core::emit::dialect::select_post(name, base, &read, s.lang) {
            Ok((dialect, post)) => {
                s.dialect = dialect;
                s.post = post;
            }
            Err(e) => ds.post_error = Some((from.to_path_buf(), e)),
        }
    }
}

/// The file a `post =` value names (`None`: a built-in's name), as the post loader reads it.
pub fn post_file_of(name: &str, base: &Path) -> Option<PathBuf> {
    let n = name.trim();
    let is_path = n.contains(['/', '\\']) || n.to_ascii_lowercase().ends_with(".toml");
    is_path.then(|| base.join(n))
}

impl DocSettings {
    /// The machine settings that neither `millpath.toml` nor the editor gives (`millpath
    /// compile` refuses to run without them; the defaults F150, S15 are only placeholders).
    pub fn missing_machine(&self) -> Vec<&'static str> {
        [
            ("feed", &self.feed),
            ("sweep_speed", &self.sweep_speed),
            ("sweep_height", &self.sweep_height),
        ]
        .into_iter()
        .filter(|(_, s)| **s == SettingSource::Default)
        .map(|(n, _)| n)
        .collect()
    }

    /// The message for [`DocSettings::missing_machine`], `None` when nothing is missing.
    pub fn missing_message(&self) -> Option<String> {
        let m = self.missing_machine();
        if m.is_empty() {
            return None;
        }
        Some(match self.settings.lang {
            millpath_core::Lang::De => format!(
                "Maschinenwerte fehlen: {} (in millpath.toml oder den Editor-Einstellungen angeben); die Vorschau nimmt Platzhalter",
                m.join(", ")
            ),
            millpath_core::Lang::En => format!(
                "missing machine settings: {} (set them in millpath.toml or the editor settings); the preview uses placeholders",
                m.join(", ")
            ),
        })
    }
}

/// A map keyed by offsets or indices, hashed fast (a drawing of 100,000 elements looks
/// each element up several times).
pub(crate) type FastMap<K, V> = HashMap<K, V, foldhash::fast::RandomState>;

/// Everything known about one document (text, or a DXF drawing: diagnostics only).
#[derive(Debug)]
pub struct Analysis {
    pub path: PathBuf,
    pub src: String,
    pub index: LineIndex,
    pub ast: File,
    /// Diagnostics located in this document (syntax and compiler), in order: exactly what
    /// `millpath check` reports for the file.
    pub diagnostics: Vec<Diagnostic>,
    pub objects: Vec<DrawnObject>,
    /// Which circles of `objects` were written as `drill` (`true`) or `helix`.
    pub(crate) declared: Vec<(usize, bool)>,
    /// `objects` came without a diagnostic, one per element: the next version may reuse them
    /// (`core/front/text_edit.rs`).
    pub(crate) objects_clean: bool,
    /// The document's paths as the compiler read them (shared with its session).
    pub paths: Vec<Arc<RawPath>>,
    pub settings: DocSettings,
    /// Every other file the analysis read or looked at (subpaths, `millpath.toml`): a change
    /// of one of them makes this analysis stale.
    pub deps: BTreeSet<PathBuf>,
    /// Folders searched for subpaths: a file appearing there may resolve a missing one.
    pub dirs: BTreeSet<PathBuf>,
    /// The text parsed without syntax errors (the next version may reuse the tree).
    pub syntax_ok: bool,
    /// Drawn object index by the byte offset of its element (made on first use: the
    /// diagnostics do not need it).
    pub(crate) object_at: OnceLock<FastMap<usize, usize>>,
    /// Per path: segment object → index of the first segment of its chain (computed once).
    pub(crate) chain_first: Mutex<HashMap<String, Arc<FastMap<usize, usize>>>>,
    /// Previews computed for this version (code lenses, the preview request).
    pub(crate) previews: Mutex<HashMap<Option<String>, Result<Preview, String>>>,
    /// The walks of this analysis, for the next one of the document (an edit that changes
    /// no geometry, kind, order or marker walks no path again).
    pub traversals: TraversalMemo,
    /// The models the check built, held only to be freed with the analysis: the server frees
    /// a replaced analysis after the next answer (`lsp/src/worker.rs`), not on its way.
    pub(crate) _models: Vec<Arc<millpath_core::model::Model>>,
}

/// The workspace file system, recording what an analysis reads (its dependencies).
struct Recorder<'a> {
    inner: WorkspaceFs<'a>,
    files: Mutex<BTreeSet<PathBuf>>,
    dirs: Mutex<BTreeSet<PathBuf>>,
}

impl Recorder<'_> {
    fn file(&self, p: &Path) {
        if let Ok(mut f) = self.files.lock() {
            f.insert(p.to_path_buf());
        }
    }
    fn dir(&self, p: &Path) {
        if let Ok(mut f) = self.dirs.lock() {
            f.insert(p.to_path_buf());
        }
    }
}

impl FileSystem for Recorder<'_> {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        self.file(path);
        self.inner.read(path)
    }
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        self.dir(dir);
        self.inner.list_dir(dir)
    }
    fn is_dir(&self, dir: &Path) -> bool {
        self.dir(dir);
        self.inner.is_dir(dir)
    }
    fn stamp(&self, path: &Path) -> Option<millpath_core::load::parse_cache::FileStamp> {
        self.file(path);
        self.inner.stamp(path)
    }
}

/// Analyses a document: parses it and runs the compiler's check over every path in it.
pub fn analyze(ws: &Workspace, path: &Path) -> Analysis {
    analyze_with(ws, path, &|| false).expect("not cancelled")
}

/// [`analyze`] that gives up (`None`) when `cancelled()` turns true between its stages
/// (a newer edit made the result useless).
///
/// The diagnostics go through the same code as `millpath check`: one [`Session`] in check
/// mode, the text's paths read by [`Session::text_paths`] (the buffer is parsed once and the
/// tree kept for the editor features), DXF drawings loaded by the session itself, then
/// [`compile_file`].
pub fn analyze_with(ws: &Workspace, path: &Path, cancelled: &dyn Fn() -> bool) -> Option<Analysis> {
    analyze_from(ws, path, None, cancelled)
}

/// [`analyze_with`] that parses incrementally from the previous analysis of the document
/// (a keystroke in one element line parses that line only, see [`reparse`]).
pub fn analyze_from(
    ws: &Workspace,
    path: &Path,
    prev: Option<&Analysis>,
    cancelled: &dyn Fn() -> bool,
) -> Option<Analysis> {
    analyze_source(ws, path, prev, None, cancelled)
}

/// [`analyze`] of a text document whose tree the caller has parsed already (`tree`: the
/// tree of the document's text as the workspace has it, without syntax errors): the text
/// is not parsed again (`millpath diff` reads each version's text once).
pub fn analyze_parsed(ws: &Workspace, path: &Path, tree: File) -> Analysis {
    analyze_source(ws, path, None, Some(tree), &|| false).expect("not cancelled")
}

fn analyze_source(
    ws: &Workspace,
    path: &Path,
    prev: Option<&Analysis>,
    tree: Option<File>,
    cancelled: &dyn Fn() -> bool,
) -> Option<Analysis> {
    let is_text = is_text_file(path);
    let src = if is_text {
        ws.text(path).unwrap_or_default()
    } else {
        // a drawing: its lines, for positions only
        ws.fs()
            .read(path)
            .map(|b| String::from_utf8_lossy(&b).into_owned())
            .unwrap_or_default()
    };
    let settings = ws.settings_for(path);
    let prev = prev.filter(|p| p.path == path);
    let (ast, syntax_errors, splice) = if let Some(tree) = tree.filter(|_| is_text) {
        (tree, Vec::new(), None)
    } else if is_text {
        let prev = prev.filter(|p| p.syntax_ok).map(|p| reparse::Previous {
            src: &p.src,
            ast: &p.ast,
        });
        reparse::reparse_spliced(prev, &src)
    } else {
        let (ast, errors) = parse("");
        (ast, errors, None)
    };
    let syntax_ok = syntax_errors.is_empty();
    if cancelled() {
        return None;
    }
    // the previous version's file, whose objects may be reused
    let file = prev
        .and_then(|p| p.objects.first())
        .and_then(|o| match &o.origin {
            Origin::Span { file, .. } if file.path == path => Some(file.clone()),
            _ => None,
        })
        .unwrap_or_else(|| FileRef::new(path.to_path_buf()));
    let fs = Recorder {
        inner: ws.fs(),
        files: Mutex::default(),
        dirs: Mutex::default(),
    };
    let traversals = TraversalMemo::after(prev.filter(|p| p.path == path).map(|p| &p.traversals));
    let mut check = settings.settings.clone();
    check.check = true;
    // answered while typing: no second opinion (its stock simulation is `millpath check`'s)
    check.quick_check = true;
    let mut objects = Vec::new();
    let mut declared = Vec::new();
    let mut objects_clean = false;
    let mut paths = Vec::new();
    let mut models = Vec::new();
    let mut diagnostics;
    match Session::new(check, &fs) {
        Ok(mut session) => {
            // a newer edit stops the compiler between elements and passes as well
            session.stop = Some(cancelled);
            session.traversals = Some(&traversals);
            if is_text {
                let mut local = Diags::default();
                // `Session::text_paths`, its objects made from the previous version's where
                // one element line changed
                let broken = Session::broken_paths(&ast, &syntax_errors);
                let reused = splice
                    .zip(prev.filter(|p| p.objects_clean))
                    .and_then(|(sp, p)| {
                        let edit = LineEdit {
                            item: sp.item,
                            element: sp.element,
                            line_start: sp.line_start,
                            old_line_end: sp.old_line_end,
                            delta: sp.delta,
                        };
                        let prev = PrevObjects {
                            objects: &p.objects,
                            declared: &p.declared,
                        };
                        objects_after_edit(prev, &ast, &edit, &src, &file, &mut local)
                    });
                let made = match reused {
                    Some(made) => made,
                    None => objects_of(&ast, syntax_errors, &src, &file, &mut local),
                };
                objects_clean = syntax_ok && made.is_ok() && local.list.is_empty();
                let made = made.and_then(|text| {
                    let p = session.paths_of_text(&text, &broken, &file, &mut local)?;
                    Ok((text, p))
                });
                match made {
                    Ok((text, p)) => {
                        objects = text.objects;
                        declared = text.declared;
                        paths = p.into_iter().map(Arc::new).collect::<Vec<_>>();
                        local.list.into_iter().for_each(|d| session.diags.push(d));
                        session.add_shared_paths(path, paths.clone());
                    }
                    Err(abort) => {
                        local.list.into_iter().for_each(|d| session.diags.push(d));
                        session.diags.push(abort);
                        session.add_paths(path, Vec::new());
                    }
                }
                if cancelled() {
                    return None;
                }
            }
            if !(ws.paths_only && is_text) {
                compile_file(&mut session, path, &millpath_core::banner());
                models = session.take_models();
            }
            diagnostics = session.diags.list;
            diagnostics.retain(|d| in_file(d, path));
        }
        Err(errs) => {
            // invalid patterns: no paths, but the tree's objects for the editor
            diagnostics = errs;
            let mut local = Diags::default();
            if is_text {
                if let Ok(t) = objects_of(&ast, syntax_errors, &src, &file, &mut local) {
                    objects = t.objects;
                }
            }
            diagnostics.extend(local.list);
        }
    }
    if cancelled() {
        return None;
    }
    if let Some((cfg, e)) = &settings.config_error {
        diagnostics.push(Diagnostic::error(
            millpath_core::Msg::CannotRead,
            Origin::Input,
            millpath_core::args![cfg.display(), e],
        ));
    }
    if let Some((from, e)) = &settings.post_error {
        // `millpath compile` refuses to run with it: as its message, located at `post`
        diagnostics.push(Diagnostic::error(
            millpath_core::Msg::SettingsUnusable,
            Origin::Input,
            millpath_core::args![format!("{}: post: {e}", from.display())],
        ));
    }
    // an edit inside one line moves the previous index (same encoding) instead of a scan
    let index = match (splice, prev) {
        (Some(sp), Some(p)) if p.index.is_utf8() == ws.utf8 => {
            LineIndex::after_edit(&p.index, &src, sp.old_line_end, sp.delta)
        }
        _ => ws.line_index(&src),
    };
    let mut deps = fs.files.into_inner().unwrap_or_default();
    // the post file writes this document's programs: editing it re-checks the document
    deps.extend(settings.post_file.clone());
    deps.remove(path);
    // the settings: any `millpath.toml` above the file
    deps.extend(path.ancestors().skip(1).map(|d| d.join(config::FILE_NAME)));
    let dirs = fs.dirs.into_inner().unwrap_or_default();
    Some(Analysis {
        path: path.to_path_buf(),
        src,
        index,
        ast,
        diagnostics,
        objects,
        declared,
        objects_clean,
        paths,
        settings,
        deps,
        dirs,
        syntax_ok,
        object_at: OnceLock::new(),
        chain_first: Mutex::default(),
        previews: Mutex::default(),
        traversals,
        _models: models,
    })
}

impl Analysis {
    /// An error is reported in the document (syntax or compiler).
    pub fn has_errors(&self) -> bool {
        self.diagnostics
            .iter()
            .any(|d| d.severity == millpath_core::diag::Severity::Error)
    }

    /// The drawn object of the element starting at `offset`.
    pub(crate) fn object_at(&self, offset: usize) -> Option<usize> {
        let map = self.object_at.get_or_init(|| {
            self.objects
                .iter()
                .enumerate()
                .filter_map(|(i, o)| match &o.origin {
                    Origin::Span { start, .. } => Some((*start as usize, i)),
                    _ => None,
                })
                .collect()
        });
        map.get(&offset).copied()
    }

    /// Whether a change of `changed` (a buffer or a file on disk) can change this analysis.
    pub fn depends_on(&self, changed: &Path) -> bool {
        self.deps.contains(changed) || changed.parent().is_some_and(|d| self.dirs.contains(d))
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

/// Every drawing file below the workspace folders (text and DXF; a bounded walk, see
/// [`walk`]) and the open buffers.
pub fn workspace_files(ws: &Workspace) -> Vec<PathBuf> {
    let mut out = walk::drawing_files(&ws.roots).files;
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

/// Re-analyses a document (convenience for tests and the server).
pub fn reanalyze(ws: &Workspace, path: &Path) -> Analysis {
    analyze(ws, path)
}
