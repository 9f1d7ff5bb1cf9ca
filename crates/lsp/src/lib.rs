//! The MillPath language server (`millpath lsp`): LSP over stdio with tower-lsp-server.
//! All answers come from `millpath-ide`; this crate converts between LSP types and plain
//! data, debounces analyses, drops stale ones and keeps running when a handler fails.

use millpath_core::diag::{Diagnostic as CoreDiagnostic, Origin, Severity};
use millpath_core::load::config::FileConfig;
use millpath_ide::{analyze_from, Analysis, LineIndex, Pos, Workspace};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::collections::HashMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tower_lsp_server::jsonrpc::{Error, Result};
use tower_lsp_server::ls_types::*;
use tower_lsp_server::{Client, LanguageServer, LspService, Server};

/// Parameters of `millpath/gcodePreview`.
#[derive(Debug, Deserialize, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct PreviewParams {
    pub text_document: TextDocumentIdentifier,
    /// The path to preview; default: the first path of the document.
    pub path: Option<String>,
}

/// Result of `millpath/gcodePreview`: the files `millpath compile` would write.
#[derive(Debug, Deserialize, Serialize, PartialEq)]
#[serde(rename_all = "camelCase")]
pub struct PreviewResult {
    pub path: String,
    pub gcode: String,
    pub probing: Option<String>,
    pub z_txt: Option<String>,
    pub stats: Vec<String>,
    pub errors: Vec<String>,
}

/// One analysis of one version of an open document, shared by every request about it.
struct Entry {
    generation: u64,
    ws: Arc<Workspace>,
    cell: tokio::sync::OnceCell<Option<Arc<Analysis>>>,
}

struct State {
    ws: Workspace,
    /// Bumped on every change of an open document (or of a file it depends on); an analysis
    /// of an older generation is abandoned and never published.
    generation: HashMap<PathBuf, u64>,
    /// The client's version of each open document (sent back with its diagnostics).
    versions: HashMap<PathBuf, i32>,
    /// The analysis of the current (or last requested) generation of each open document.
    entries: HashMap<PathBuf, Arc<Entry>>,
    /// The last completed analysis of each open document: its dependencies (which files it
    /// read for its subpaths, which folders it searched) form the dependency graph.
    last: HashMap<PathBuf, Arc<Analysis>>,
    debounce: Duration,
    /// The client can register `workspace/didChangeWatchedFiles` dynamically.
    watch_files: bool,
}

pub struct Backend {
    client: Client,
    state: Arc<Mutex<State>>,
}

/// Buffers opened with the language id `millpath` whose file name is not `*.mpath`.
static TEXT_BUFFERS: Mutex<Vec<String>> = Mutex::new(Vec::new());

/// Made-up paths and the documents they stand for, so answers go back to the editor's URI.
static MADE_UP: Mutex<Vec<(PathBuf, String)>> = Mutex::new(Vec::new());

fn made_up(path: PathBuf, uri: &Uri) -> PathBuf {
    if let Ok(mut m) = MADE_UP.lock() {
        if !m.iter().any(|(p, _)| *p == path) {
            m.push((path.clone(), uri.as_str().to_string()));
        }
    }
    path
}

/// The path of a document. A `file:` URI is its path; any other (an editor's `untitled:`
/// buffer, …) and a buffer opened as `millpath` get a made-up `*.mpath` path: text, never a
/// drawing to load.
fn to_path(uri: &Uri) -> Option<PathBuf> {
    let text = TEXT_BUFFERS
        .lock()
        .is_ok_and(|b| b.iter().any(|u| u == uri.as_str()));
    if uri.scheme().as_str() != "file" {
        let name: String = uri
            .as_str()
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' || c == '.' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        return Some(made_up(
            std::env::temp_dir()
                .join("millpath-buffers")
                .join(format!("{name}.mpath")),
            uri,
        ));
    }
    let p = uri.to_file_path()?.into_owned();
    Some(if text && !millpath_core::load::fs::is_text_file(&p) {
        let ext = format!(
            "{}.mpath",
            p.extension().and_then(|e| e.to_str()).unwrap_or("")
        );
        made_up(p.with_extension(ext), uri)
    } else {
        p
    })
}

fn to_uri(path: &Path) -> Option<Uri> {
    let original = MADE_UP.lock().ok().and_then(|m| {
        m.iter()
            .find(|(p, _)| p == path)
            .and_then(|(_, u)| u.parse::<Uri>().ok())
    });
    original.or_else(|| Uri::from_file_path(path))
}

fn pos(p: Pos) -> Position {
    Position {
        line: p.line,
        character: p.col,
    }
}

fn range(idx: &LineIndex, start: usize, end: usize) -> Range {
    Range {
        start: pos(idx.pos(start)),
        end: pos(idx.pos(end)),
    }
}

fn offset(a: &Analysis, p: Position) -> usize {
    a.index.offset(Pos {
        line: p.line,
        col: p.character,
    })
}

fn internal_error_diagnostic() -> Vec<Diagnostic> {
    vec![Diagnostic {
        message: "millpath: internal error while analysing this file".into(),
        severity: Some(DiagnosticSeverity::ERROR),
        ..Default::default()
    }]
}

/// Applies one incremental change (an LSP range in the negotiated encoding) to a text.
pub fn apply_edit(text: &mut String, r: Range, new_text: &str, utf8: bool) {
    let idx = LineIndex::with_encoding(text, utf8);
    let at = |p: Position| {
        idx.offset(Pos {
            line: p.line,
            col: p.character,
        })
    };
    let (start, end) = (at(r.start), at(r.end));
    let (start, end) = (start.min(end), end.max(start));
    text.replace_range(start..end, new_text);
}

/// Runs a handler body, turning a panic into an error answer (the server goes on).
fn guarded<T>(f: impl FnOnce() -> T) -> Result<T> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|_| {
        let mut e = Error::internal_error();
        e.message = "millpath: internal error while answering this request".into();
        e
    })
}

/// Where a core diagnostic lands in the document.
fn diagnostic_range(a: &Analysis, origin: &Origin) -> Range {
    match origin {
        Origin::Span { start, end, .. } => {
            // one line is enough to point at an element
            let line_end = a.src[*start..(*end).min(a.src.len())]
                .find('\n')
                .map_or(*end, |p| start + p);
            range(&a.index, *start, line_end)
        }
        Origin::Path { name, .. } => match a.ast.paths().find(|p| &p.name.value == name) {
            Some(p) => range(&a.index, p.name.span.start, p.name.span.end),
            None => Range::default(),
        },
        // a drawing: the entity's DXF line (1-based, as `millpath check` reports it)
        Origin::Entity(e) => line_range(a, e.line),
        Origin::FileLine { line, .. } => line_range(a, *line),
        _ => Range::default(),
    }
}

/// The whole 1-based line `line` of the document.
fn line_range(a: &Analysis, line: usize) -> Range {
    let l = line.saturating_sub(1) as u32;
    let start = a.index.offset(Pos { line: l, col: 0 });
    let end = a.src[start..]
        .find(['\r', '\n'])
        .map_or(a.src.len(), |e| start + e);
    range(&a.index, start, end)
}

fn location(origin: &Origin, ws: &Workspace) -> Option<Location> {
    match origin {
        Origin::Span {
            file, start, end, ..
        } => {
            let text = ws.text(&file.path)?;
            let idx = ws.line_index(&text);
            Some(Location {
                uri: to_uri(&file.path)?,
                range: range(&idx, *start, *end),
            })
        }
        Origin::Entity(e) => {
            let line = e.line.saturating_sub(1) as u32;
            let p = Position { line, character: 0 };
            Some(Location {
                uri: to_uri(&e.file.path)?,
                range: Range { start: p, end: p },
            })
        }
        _ => None,
    }
}

fn to_lsp_diagnostic(a: &Analysis, ws: &Workspace, d: &CoreDiagnostic) -> Diagnostic {
    let lang = a.settings.settings.lang;
    let related: Vec<DiagnosticRelatedInformation> = d
        .related
        .iter()
        .filter_map(|r| {
            Some(DiagnosticRelatedInformation {
                location: location(&r.origin, ws)?,
                message: r.note.clone(),
            })
        })
        .collect();
    Diagnostic {
        range: diagnostic_range(a, &d.origin),
        severity: Some(if d.severity == Severity::Error {
            DiagnosticSeverity::ERROR
        } else {
            DiagnosticSeverity::WARNING
        }),
        code: Some(NumberOrString::String(d.msg.code())),
        source: Some("millpath".into()),
        message: d.message(lang),
        related_information: if related.is_empty() {
            None
        } else {
            Some(related)
        },
        ..Default::default()
    }
}

/// All diagnostics of a document as LSP diagnostics.
pub fn lsp_diagnostics(a: &Analysis, ws: &Workspace) -> Vec<Diagnostic> {
    a.diagnostics
        .iter()
        .map(|d| to_lsp_diagnostic(a, ws, d))
        .collect()
}

fn edit(a: &Analysis, e: &millpath_ide::TextEdit) -> TextEdit {
    TextEdit {
        range: range(&a.index, e.start, e.end),
        new_text: e.text.clone(),
    }
}

fn loc(l: &millpath_ide::Location) -> Option<Location> {
    Some(Location {
        uri: to_uri(&l.path)?,
        range: Range {
            start: pos(l.start),
            end: pos(l.end),
        },
    })
}

/// The machine settings of the client's initialization options (`millpath.toml` keys).
fn client_settings(v: Option<&Value>) -> (FileConfig, Option<u64>) {
    let Some(v) = v else {
        return (FileConfig::default(), None);
    };
    let debounce = v.get("debounceMs").and_then(Value::as_u64);
    let mut v = v.clone();
    if let Some(o) = v.as_object_mut() {
        o.remove("debounceMs");
    }
    (serde_json::from_value(v).unwrap_or_default(), debounce)
}

fn is_current(state: &Mutex<State>, path: &Path, generation: u64) -> bool {
    state
        .lock()
        .map(|s| s.generation.get(path) == Some(&generation))
        .unwrap_or(false)
}

fn content_modified() -> Error {
    Error {
        code: tower_lsp_server::jsonrpc::ErrorCode::ContentModified,
        message: "the document changed; ask again".into(),
        data: None,
    }
}

/// Runs a heavy handler body on the blocking pool; the handler future only awaits it, so
/// a `$/cancelRequest` drops the request at once (its result is discarded).
async fn blocking<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> Result<T> {
    match tokio::task::spawn_blocking(move || guarded(f)).await {
        Ok(r) => r,
        Err(_) => Err(Error::internal_error()),
    }
}

impl Backend {
    fn snapshot(&self) -> Workspace {
        self.state.lock().map(|s| s.ws.clone()).unwrap_or_default()
    }

    /// The analysis of the current version of a document, made once and shared: the
    /// diagnostics, hover, inlay hints, lenses, symbols and the preview all use it. Runs on
    /// the blocking pool; gives up between its stages when a newer change arrives.
    async fn analysis(&self, uri: &Uri) -> Result<(Arc<Analysis>, Arc<Workspace>)> {
        let path = to_path(uri).ok_or_else(|| Error::invalid_params("not a file URI"))?;
        let entry = {
            let mut st = self.state.lock().map_err(|_| Error::internal_error())?;
            match st.generation.get(&path).copied() {
                // not open: analysed afresh each time
                None => Arc::new(Entry {
                    generation: u64::MAX,
                    ws: Arc::new(st.ws.clone()),
                    cell: Default::default(),
                }),
                Some(g) => match st.entries.get(&path) {
                    Some(e) if e.generation == g => e.clone(),
                    _ => {
                        let e = Arc::new(Entry {
                            generation: g,
                            ws: Arc::new(st.ws.clone()),
                            cell: Default::default(),
                        });
                        st.entries.insert(path.clone(), e.clone());
                        e
                    }
                },
            }
        };
        // the analysis runs in a task of its own: a cancelled request does not abort it
        // for the others waiting on the same version
        let shared = entry.clone();
        let state = self.state.clone();
        let task_path = path.clone();
        let task = tokio::spawn(async move {
            let e = shared.clone();
            e.cell
                .get_or_init(|| {
                    let (state, ws, path, g) =
                        (state, shared.ws.clone(), task_path, shared.generation);
                    async move {
                        let st = state.clone();
                        let p = path.clone();
                        let prev = state.lock().ok().and_then(|s| s.last.get(&path).cloned());
                        let r = tokio::task::spawn_blocking(move || {
                            catch_unwind(AssertUnwindSafe(|| {
                                let cancelled = || g != u64::MAX && !is_current(&st, &p, g);
                                analyze_from(&ws, &p, prev.as_deref(), &cancelled)
                            }))
                        })
                        .await;
                        let a = match r {
                            Ok(Ok(Some(a))) => Arc::new(a),
                            Ok(Ok(None)) => return None,
                            // a panic: the error is reported by the caller
                            _ => return None,
                        };
                        if g != u64::MAX {
                            if let Ok(mut s) = state.lock() {
                                if s.generation.contains_key(&path) {
                                    s.last.insert(path, a.clone());
                                }
                            }
                        }
                        Some(a)
                    }
                })
                .await
                .clone()
        });
        let a = task.await.ok().flatten();
        match a {
            Some(a) => Ok((a, entry.ws.clone())),
            None if entry.generation != u64::MAX
                && !is_current(&self.state, &path, entry.generation) =>
            {
                Err(content_modified())
            }
            None => {
                let mut e = Error::internal_error();
                e.message = "millpath: internal error while analysing this file".into();
                Err(e)
            }
        }
    }

    /// A new generation of an open document (it or a file it depends on changed).
    fn bump(st: &mut State, path: &Path) -> Option<u64> {
        let g = st.generation.get_mut(path)?;
        *g += 1;
        st.entries.remove(path);
        Some(*g)
    }

    /// Open documents other than `changed` whose last analysis depends on it.
    fn dependents(st: &State, changed: &Path) -> Vec<PathBuf> {
        st.last
            .iter()
            .filter(|(p, a)| p.as_path() != changed && a.depends_on(changed))
            .map(|(p, _)| p.clone())
            .collect()
    }

    /// `changed` changed (buffer, disk, closed): re-analyse the open documents depending on
    /// it and republish their diagnostics.
    fn dependents_changed(&self, changed: &[PathBuf]) {
        let mut todo = Vec::new();
        if let Ok(mut st) = self.state.lock() {
            for c in changed {
                // an open drawing is read from the disk: its own change counts
                if !millpath_core::load::fs::is_text_file(c) && st.generation.contains_key(c) {
                    todo.push(c.clone());
                }
                for d in Self::dependents(&st, c) {
                    if !todo.contains(&d) {
                        todo.push(d);
                    }
                }
            }
            todo.retain(|d| Self::bump(&mut st, d).is_some());
        }
        for d in todo {
            self.publish_later(d);
        }
    }

    /// Debounced analysis and publication of the current generation of an open document;
    /// a newer change makes it stale (abandoned, never published).
    fn publish_later(&self, path: PathBuf) {
        let Some(uri) = to_uri(&path) else { return };
        // the client's version of exactly this generation
        let Ok((generation, debounce, version)) = self.state.lock().map(|s| {
            (
                s.generation.get(&path).copied().unwrap_or(0),
                s.debounce,
                s.versions.get(&path).copied(),
            )
        }) else {
            return;
        };
        let this = Backend {
            client: self.client.clone(),
            state: self.state.clone(),
        };
        tokio::spawn(async move {
            if !debounce.is_zero() {
                tokio::time::sleep(debounce).await;
            }
            if !is_current(&this.state, &path, generation) {
                return;
            }
            let diags = match this.analysis(&uri).await {
                Ok((a, ws)) => match blocking(move || lsp_diagnostics(&a, &ws)).await {
                    Ok(d) => d,
                    Err(_) => internal_error_diagnostic(),
                },
                Err(e) if e.code == tower_lsp_server::jsonrpc::ErrorCode::ContentModified => return,
                Err(_) => internal_error_diagnostic(),
            };
            if is_current(&this.state, &path, generation) {
                this.client.publish_diagnostics(uri, diags, version).await;
            }
        });
    }

    /// The document changed: a new generation, its diagnostics and its dependents'.
    fn changed(&self, path: PathBuf) {
        if let Ok(mut st) = self.state.lock() {
            Self::bump(&mut st, &path);
        }
        self.publish_later(path.clone());
        self.dependents_changed(&[path]);
    }

    async fn gcode_preview(&self, params: PreviewParams) -> Result<PreviewResult> {
        let (a, ws) = self.analysis(&params.text_document.uri).await?;
        let name = params.path;
        let pv = blocking(move || millpath_ide::preview_of(&a, &ws, name.as_deref()))
            .await?
            .map_err(|e| {
                let mut err = Error::invalid_request();
                err.message = e.into();
                err
            })?;
        Ok(PreviewResult {
            path: pv.path,
            gcode: pv.gcode,
            probing: pv.probing,
            z_txt: pv.z_txt,
            stats: pv.stats,
            errors: pv.errors,
        })
    }
}

impl Backend {
    async fn toolpath(&self, params: PreviewParams) -> Result<Value> {
        let path = to_path(&params.text_document.uri)
            .ok_or_else(|| Error::invalid_params("not a file URI"))?;
        let ws = self.snapshot();
        let name = params.path;
        blocking(move || millpath_ide::toolpath(&ws, &path, name.as_deref()))
            .await?
            .map_err(|e| {
                let mut err = Error::invalid_request();
                err.message = e.into();
                err
            })
    }
}

impl LanguageServer for Backend {
    async fn initialize(&self, params: InitializeParams) -> Result<InitializeResult> {
        let (client, debounce) = client_settings(params.initialization_options.as_ref());
        let utf8 = params
            .capabilities
            .general
            .as_ref()
            .and_then(|g| g.position_encodings.as_ref())
            .is_some_and(|e| e.contains(&PositionEncodingKind::UTF8));
        if let Ok(mut st) = self.state.lock() {
            st.ws.client = client;
            st.ws.utf8 = utf8;
            if let Some(ms) = debounce {
                st.debounce = Duration::from_millis(ms);
            }
            st.watch_files = params
                .capabilities
                .workspace
                .as_ref()
                .and_then(|w| w.did_change_watched_files.as_ref())
                .and_then(|d| d.dynamic_registration)
                .unwrap_or(false);
            let folders = params.workspace_folders.unwrap_or_default();
            for f in &folders {
                if let Some(p) = to_path(&f.uri) {
                    st.ws.roots.push(p);
                }
            }
            // older clients: rootUri, or the even older rootPath
            #[allow(deprecated)]
            if folders.is_empty() {
                let root = params
                    .root_uri
                    .as_ref()
                    .and_then(to_path)
                    .or_else(|| params.root_path.as_ref().map(PathBuf::from));
                if let Some(r) = root {
                    st.ws.roots.push(r);
                }
            }
        }
        Ok(InitializeResult {
            server_info: Some(ServerInfo {
                name: "millpath".into(),
                version: Some(env!("CARGO_PKG_VERSION").into()),
            }),
            capabilities: ServerCapabilities {
                position_encoding: Some(if utf8 {
                    PositionEncodingKind::UTF8
                } else {
                    PositionEncodingKind::UTF16
                }),
                text_document_sync: Some(TextDocumentSyncCapability::Options(
                    TextDocumentSyncOptions {
                        open_close: Some(true),
                        change: Some(TextDocumentSyncKind::INCREMENTAL),
                        save: Some(TextDocumentSyncSaveOptions::Supported(true)),
                        ..Default::default()
                    },
                )),
                workspace: Some(WorkspaceServerCapabilities {
                    workspace_folders: Some(WorkspaceFoldersServerCapabilities {
                        supported: Some(true),
                        change_notifications: Some(OneOf::Left(true)),
                    }),
                    file_operations: None,
                }),
                hover_provider: Some(HoverProviderCapability::Simple(true)),
                completion_provider: Some(CompletionOptions {
                    trigger_characters: Some(vec![">".into(), " ".into()]),
                    ..Default::default()
                }),
                definition_provider: Some(OneOf::Left(true)),
                references_provider: Some(OneOf::Left(true)),
                document_symbol_provider: Some(OneOf::Left(true)),
                workspace_symbol_provider: Some(OneOf::Left(true)),
                document_formatting_provider: Some(OneOf::Left(true)),
                code_action_provider: Some(CodeActionProviderCapability::Simple(true)),
                inlay_hint_provider: Some(OneOf::Left(true)),
                code_lens_provider: Some(CodeLensOptions {
                    resolve_provider: Some(false),
                }),
                execute_command_provider: Some(ExecuteCommandOptions {
                    commands: vec!["millpath.server.preview".into()],
                    ..Default::default()
                }),
                semantic_tokens_provider: Some(
                    SemanticTokensServerCapabilities::SemanticTokensOptions(
                        SemanticTokensOptions {
                            legend: SemanticTokensLegend {
                                token_types: millpath_ide::TOKEN_TYPES
                                    .iter()
                                    .map(|t| SemanticTokenType::new(t))
                                    .collect(),
                                token_modifiers: vec![],
                            },
                            full: Some(SemanticTokensFullOptions::Bool(true)),
                            range: Some(false),
                            ..Default::default()
                        },
                    ),
                ),
                ..ServerCapabilities::default()
            },
            offset_encoding: None,
        })
    }

    async fn initialized(&self, _: InitializedParams) {
        let watch = self.state.lock().map(|s| s.watch_files).unwrap_or(false);
        if !watch {
            return;
        }
        let client = self.client.clone();
        // not awaited here: the client answers while we go on
        tokio::spawn(async move {
            let watchers = ["**/*.{mpath,dxf,DXF}", "**/millpath.toml"]
                .iter()
                .map(|g| FileSystemWatcher {
                    glob_pattern: GlobPattern::String(g.to_string()),
                    kind: None,
                })
                .collect();
            let options = DidChangeWatchedFilesRegistrationOptions { watchers };
            let _ = client
                .register_capability(vec![Registration {
                    id: "millpath-watch".into(),
                    method: "workspace/didChangeWatchedFiles".into(),
                    register_options: serde_json::to_value(options).ok(),
                }])
                .await;
        });
    }

    async fn shutdown(&self) -> Result<()> {
        SHUT_DOWN.store(true, std::sync::atomic::Ordering::SeqCst);
        Ok(())
    }

    async fn did_open(&self, params: DidOpenTextDocumentParams) {
        let uri = params.text_document.uri;
        if params.text_document.language_id == "millpath" {
            if let Ok(mut b) = TEXT_BUFFERS.lock() {
                if !b.iter().any(|u| u == uri.as_str()) {
                    b.push(uri.as_str().to_string());
                }
            }
        }
        let Some(p) = to_path(&uri) else { return };
        // the same text as on disk changes nothing for the files depending on it
        let as_on_disk = std::fs::read_to_string(&p).is_ok_and(|t| t == params.text_document.text);
        if let Ok(mut st) = self.state.lock() {
            st.ws.overlays.insert(p.clone(), params.text_document.text);
            st.versions.insert(p.clone(), params.text_document.version);
            st.generation.entry(p.clone()).or_insert(0);
            Self::bump(&mut st, &p);
        }
        self.publish_later(p.clone());
        if !as_on_disk {
            self.dependents_changed(&[p]);
        }
    }

    async fn did_change(&self, params: DidChangeTextDocumentParams) {
        let uri = params.text_document.uri;
        let Some(p) = to_path(&uri) else { return };
        if let Ok(mut st) = self.state.lock() {
            let utf8 = st.ws.utf8;
            let mut text = st.ws.overlays.remove(&p).unwrap_or_default();
            for change in params.content_changes {
                match change.range {
                    Some(r) => apply_edit(&mut text, r, &change.text, utf8),
                    None => text = change.text,
                }
            }
            st.ws.overlays.insert(p.clone(), text);
            st.versions.insert(p.clone(), params.text_document.version);
        }
        self.changed(p);
    }

    async fn did_save(&self, params: DidSaveTextDocumentParams) {
        if let Some(p) = to_path(&params.text_document.uri) {
            self.dependents_changed(&[p]);
        }
    }

    async fn did_close(&self, params: DidCloseTextDocumentParams) {
        let uri = params.text_document.uri;
        if let (Some(p), Ok(mut st)) = (to_path(&uri), self.state.lock()) {
            st.ws.overlays.remove(&p);
            st.generation.remove(&p);
            st.versions.remove(&p);
            st.entries.remove(&p);
            st.last.remove(&p);
            drop(st);
            // its dependents now see the file on disk
            self.dependents_changed(&[p]);
        }
        if let Ok(mut b) = TEXT_BUFFERS.lock() {
            b.retain(|u| u != uri.as_str());
        }
        self.client.publish_diagnostics(uri, Vec::new(), None).await;
    }

    async fn did_change_watched_files(&self, params: DidChangeWatchedFilesParams) {
        let changed: Vec<PathBuf> = params
            .changes
            .iter()
            .filter_map(|c| to_path(&c.uri))
            .collect();
        self.dependents_changed(&changed);
    }

    async fn did_change_workspace_folders(&self, params: DidChangeWorkspaceFoldersParams) {
        if let Ok(mut st) = self.state.lock() {
            for f in &params.event.removed {
                if let Some(p) = to_path(&f.uri) {
                    st.ws.roots.retain(|r| *r != p);
                }
            }
            for f in &params.event.added {
                if let Some(p) = to_path(&f.uri) {
                    if !st.ws.roots.contains(&p) {
                        st.ws.roots.push(p);
                    }
                }
            }
        }
    }

    async fn hover(&self, params: HoverParams) -> Result<Option<Hover>> {
        let (a, ws) = self
            .analysis(&params.text_document_position_params.text_document.uri)
            .await?;
        let at = offset(&a, params.text_document_position_params.position);
        guarded(|| {
            millpath_ide::hover(&a, &ws, at).map(|h| Hover {
                contents: HoverContents::Markup(MarkupContent {
                    kind: MarkupKind::Markdown,
                    value: h.markdown,
                }),
                range: Some(range(&a.index, h.start, h.end)),
            })
        })
    }

    async fn completion(&self, params: CompletionParams) -> Result<Option<CompletionResponse>> {
        let (a, ws) = self
            .analysis(&params.text_document_position.text_document.uri)
            .await?;
        let at = offset(&a, params.text_document_position.position);
        guarded(|| {
            let items = millpath_ide::completion(&a, &ws, at)
                .into_iter()
                .map(|c| CompletionItem {
                    label: c.label,
                    detail: Some(c.detail),
                    insert_text: Some(c.insert),
                    ..Default::default()
                })
                .collect();
            Some(CompletionResponse::Array(items))
        })
    }

    async fn goto_definition(
        &self,
        params: GotoDefinitionParams,
    ) -> Result<Option<GotoDefinitionResponse>> {
        let (a, ws) = self
            .analysis(&params.text_document_position_params.text_document.uri)
            .await?;
        let at = offset(&a, params.text_document_position_params.position);
        guarded(|| {
            let locs: Vec<Location> = millpath_ide::definition(&a, &ws, at)
                .iter()
                .filter_map(loc)
                .collect();
            (!locs.is_empty()).then_some(GotoDefinitionResponse::Array(locs))
        })
    }

    async fn references(&self, params: ReferenceParams) -> Result<Option<Vec<Location>>> {
        let (a, ws) = self
            .analysis(&params.text_document_position.text_document.uri)
            .await?;
        let at = offset(&a, params.text_document_position.position);
        let with_declaration = params.context.include_declaration;
        guarded(|| {
            let mut out = Vec::new();
            if with_declaration {
                out.extend(millpath_ide::definition(&a, &ws, at).iter().filter_map(loc));
            }
            out.extend(millpath_ide::references(&a, &ws, at).iter().filter_map(loc));
            Some(out)
        })
    }

    async fn document_symbol(
        &self,
        params: DocumentSymbolParams,
    ) -> Result<Option<DocumentSymbolResponse>> {
        let (a, _) = self.analysis(&params.text_document.uri).await?;
        #[allow(deprecated)]
        fn conv(a: &Analysis, s: &millpath_ide::Symbol) -> DocumentSymbol {
            DocumentSymbol {
                name: s.name.clone(),
                detail: Some(s.detail.clone()),
                kind: if s.is_path {
                    SymbolKind::MODULE
                } else {
                    SymbolKind::FIELD
                },
                tags: None,
                deprecated: None,
                range: range(&a.index, s.start, s.end),
                selection_range: range(&a.index, s.start, s.end),
                children: Some(s.children.iter().map(|c| conv(a, c)).collect()),
            }
        }
        guarded(|| {
            Some(DocumentSymbolResponse::Nested(
                millpath_ide::document_symbols(&a)
                    .iter()
                    .map(|s| conv(&a, s))
                    .collect(),
            ))
        })
    }

    async fn symbol(
        &self,
        params: WorkspaceSymbolParams,
    ) -> Result<Option<WorkspaceSymbolResponse>> {
        let ws = self.snapshot();
        guarded(|| {
            let out: Vec<WorkspaceSymbol> = millpath_ide::workspace_symbols(&ws, &params.query)
                .into_iter()
                .filter_map(|(name, l)| {
                    Some(WorkspaceSymbol {
                        name,
                        kind: SymbolKind::MODULE,
                        tags: None,
                        container_name: None,
                        location: OneOf::Left(loc(&l)?),
                        data: None,
                    })
                })
                .collect();
            Some(WorkspaceSymbolResponse::Nested(out))
        })
    }

    async fn formatting(&self, params: DocumentFormattingParams) -> Result<Option<Vec<TextEdit>>> {
        let (a, _) = self.analysis(&params.text_document.uri).await?;
        guarded(|| {
            millpath_ide::format(&a).filter(|f| *f != a.src).map(|f| {
                vec![TextEdit {
                    range: range(&a.index, 0, a.src.len()),
                    new_text: f,
                }]
            })
        })
    }

    async fn code_action(&self, params: CodeActionParams) -> Result<Option<CodeActionResponse>> {
        let uri = params.text_document.uri.clone();
        let (a, _) = self.analysis(&uri).await?;
        let (s, e) = (offset(&a, params.range.start), offset(&a, params.range.end));
        guarded(|| {
            let actions = millpath_ide::code_actions(&a, s, e)
                .into_iter()
                .map(|act| {
                    let mut changes = HashMap::new();
                    changes.insert(uri.clone(), act.edits.iter().map(|x| edit(&a, x)).collect());
                    CodeActionOrCommand::CodeAction(CodeAction {
                        title: act.title,
                        kind: Some(CodeActionKind::QUICKFIX),
                        edit: Some(WorkspaceEdit {
                            changes: Some(changes),
                            ..Default::default()
                        }),
                        ..Default::default()
                    })
                })
                .collect();
            Some(actions)
        })
    }

    async fn inlay_hint(&self, params: InlayHintParams) -> Result<Option<Vec<InlayHint>>> {
        let (a, _) = self.analysis(&params.text_document.uri).await?;
        let (start, end) = (offset(&a, params.range.start), offset(&a, params.range.end));
        guarded(|| {
            Some(
                millpath_ide::inlay_hints_in(&a, start, end)
                    .into_iter()
                    .map(|h| InlayHint {
                        position: pos(a.index.pos(h.offset)),
                        label: InlayHintLabel::String(h.label),
                        kind: Some(InlayHintKind::PARAMETER),
                        text_edits: None,
                        tooltip: None,
                        padding_left: Some(true),
                        padding_right: None,
                        data: None,
                    })
                    .collect(),
            )
        })
    }

    async fn semantic_tokens_full(
        &self,
        params: SemanticTokensParams,
    ) -> Result<Option<SemanticTokensResult>> {
        let (a, _) = self.analysis(&params.text_document.uri).await?;
        guarded(|| {
            let mut data = Vec::new();
            let (mut line, mut col) = (0u32, 0u32);
            for t in millpath_ide::semantic_tokens(&a) {
                let s = a.index.pos(t.start);
                let e = a.index.pos(t.end);
                if e.line != s.line {
                    continue;
                }
                let delta_line = s.line - line;
                let delta_start = if delta_line == 0 { s.col - col } else { s.col };
                data.push(SemanticToken {
                    delta_line,
                    delta_start,
                    length: e.col - s.col,
                    token_type: t.kind,
                    token_modifiers_bitset: 0,
                });
                line = s.line;
                col = s.col;
            }
            Some(SemanticTokensResult::Tokens(SemanticTokens {
                result_id: None,
                data,
            }))
        })
    }

    async fn code_lens(&self, params: CodeLensParams) -> Result<Option<Vec<CodeLens>>> {
        let uri = params.text_document.uri;
        let (a, ws) = self.analysis(&uri).await?;
        blocking(move || {
            Some(
                millpath_ide::code_lenses(&a, &ws)
                    .into_iter()
                    .map(|l| {
                        let p = pos(a.index.pos(l.offset));
                        CodeLens {
                            range: Range { start: p, end: p },
                            command: Some(Command {
                                title: l.title,
                                command: "millpath.preview".into(),
                                arguments: Some(vec![
                                    serde_json::json!(uri.as_str()),
                                    serde_json::json!(l.path),
                                ]),
                            }),
                            data: None,
                        }
                    })
                    .collect(),
            )
        })
        .await
    }

    async fn execute_command(&self, params: ExecuteCommandParams) -> Result<Option<Value>> {
        if params.command != "millpath.server.preview" {
            return Err(Error::method_not_found());
        }
        let uri = params
            .arguments
            .first()
            .and_then(Value::as_str)
            .and_then(|s| s.parse::<Uri>().ok())
            .ok_or_else(|| Error::invalid_params("expected the document URI"))?;
        let path = params
            .arguments
            .get(1)
            .and_then(Value::as_str)
            .map(str::to_string);
        let r = self
            .gcode_preview(PreviewParams {
                text_document: TextDocumentIdentifier { uri },
                path,
            })
            .await?;
        Ok(serde_json::to_value(r).ok())
    }
}

/// The service, with the custom requests `millpath/gcodePreview` and `millpath/toolpath`.
pub fn service() -> (LspService<Backend>, tower_lsp_server::ClientSocket) {
    LspService::build(|client| Backend {
        client,
        state: Arc::new(Mutex::new(State {
            ws: Workspace::default(),
            generation: HashMap::new(),
            versions: HashMap::new(),
            entries: HashMap::new(),
            last: HashMap::new(),
            debounce: Duration::ZERO,
            watch_files: false,
        })),
    })
    .custom_method("millpath/gcodePreview", Backend::gcode_preview)
    .custom_method("millpath/toolpath", Backend::toolpath)
    .finish()
}

/// `shutdown` was received (the exit status of [`run_stdio`]).
static SHUT_DOWN: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Serves LSP over standard input and output until the client exits; the exit status is 0
/// after `shutdown`, 1 when the client exits (or the input ends) without it.
pub fn run_stdio() -> u8 {
    let Ok(rt) = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
    else {
        eprintln!("millpath lsp: cannot start the runtime");
        return 1;
    };
    rt.block_on(async {
        let (service, socket) = service();
        Server::new(tokio::io::stdin(), tokio::io::stdout(), socket)
            .serve(service)
            .await;
    });
    // blocking analyses still running are not waited for
    rt.shutdown_background();
    u8::from(!SHUT_DOWN.load(std::sync::atomic::Ordering::SeqCst))
}
