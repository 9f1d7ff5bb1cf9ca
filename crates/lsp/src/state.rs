//! The server's state: open documents, their generations and shared analyses, the
//! dependency graph between files, and the publication of diagnostics.
//!
//! `Backend` and its state: generations, the shared analysis per version (made on the analysis
//! thread, `worker.rs`; the one it replaces freed there after it, not on the way to the
//! diagnostics), the dependency graph, debounced publication, `blocking`/`guarded`.

use crate::conv::*;
use millpath_core::load::config::FileConfig;
use millpath_ide::{analyze_from, Analysis, Workspace};
use serde_json::Value;
use std::collections::HashMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tower_lsp_server::jsonrpc::{Error, Result};
use tower_lsp_server::ls_types::*;
use tower_lsp_server::Client;

/// One analysis of one version of an open document, shared by every request about it.
pub(crate) struct Entry {
    pub(crate) generation: u64,
    pub(crate) ws: Arc<Workspace>,
    pub(crate) cell: tokio::sync::OnceCell<Option<Arc<Analysis>>>,
}

pub(crate) struct State {
    pub(crate) ws: Workspace,
    /// Bumped on every change of an open document (or of a file it depends on); an analysis
    /// of an older generation is abandoned and never published.
    pub(crate) generation: HashMap<PathBuf, u64>,
    /// The client's version of each open document (sent back with its diagnostics).
    pub(crate) versions: HashMap<PathBuf, i32>,
    /// The URI each open document was opened under, spelled as the client spelled it
    /// (`Z%3A` or `z:`, percent-encoded letters …): its diagnostics go back under it.
    pub(crate) uris: HashMap<PathBuf, Uri>,
    /// The analysis of the current (or last requested) generation of each open document.
    pub(crate) entries: HashMap<PathBuf, Arc<Entry>>,
    /// The last completed analysis of each open document: its dependencies (which files it
    /// read for its subpaths, which folders it searched) form the dependency graph.
    pub(crate) last: HashMap<PathBuf, Arc<Analysis>>,
    pub(crate) debounce: Duration,
    /// The client can register `workspace/didChangeWatchedFiles` dynamically.
    pub(crate) watch_files: bool,
    /// Semantic tokens and pulled diagnostics kept between requests; pull or push.
    pub(crate) results: crate::results::Results,
}

pub struct Backend {
    pub(crate) client: Client,
    pub(crate) state: Arc<Mutex<State>>,
}

/// Runs a handler body, turning a panic into an error answer (the server goes on).
pub(crate) fn guarded<T>(f: impl FnOnce() -> T) -> Result<T> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|_| {
        let mut e = Error::internal_error();
        e.message = "millpath: internal error while answering this request".into();
        e
    })
}

/// The machine settings of the client's initialization options (`millpath.toml` keys).
pub(crate) fn client_settings(v: Option<&Value>) -> (FileConfig, Option<u64>) {
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

pub(crate) fn is_current(state: &Mutex<State>, path: &Path, generation: u64) -> bool {
    state
        .lock()
        .map(|s| s.generation.get(path) == Some(&generation))
        .unwrap_or(false)
}

pub(crate) fn content_modified() -> Error {
    Error {
        code: tower_lsp_server::jsonrpc::ErrorCode::ContentModified,
        message: "the document changed; ask again".into(),
        data: None,
    }
}

/// At most this many diagnostics are converted on the publishing task itself.
const CONVERT_AT_ONCE: usize = 64;

/// The analysis' diagnostics are few and point into its own file only.
fn converts_at_once(a: &Analysis) -> bool {
    a.diagnostics.len() <= CONVERT_AT_ONCE && a.diagnostics.iter().all(|d| d.related.is_empty())
}

/// Runs a heavy handler body on the blocking pool; the handler future only awaits it, so
/// a `$/cancelRequest` drops the request at once (its result is discarded).
pub(crate) async fn blocking<T: Send + 'static>(
    f: impl FnOnce() -> T + Send + 'static,
) -> Result<T> {
    match tokio::task::spawn_blocking(move || guarded(f)).await {
        Ok(r) => r,
        Err(_) => Err(Error::internal_error()),
    }
}

impl Backend {
    pub(crate) fn snapshot(&self) -> Workspace {
        self.state.lock().map(|s| s.ws.clone()).unwrap_or_default()
    }

    /// The analysis of the current version of a document, made once and shared: the
    /// diagnostics, hover, inlay hints, lenses, symbols and the preview all use it. Runs on
    /// the analysis thread (`worker.rs`); gives up between its stages when a newer change arrives.
    pub(crate) async fn analysis(&self, uri: &Uri) -> Result<(Arc<Analysis>, Arc<Workspace>)> {
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
                        let work = move || {
                            let cancelled = || g != u64::MAX && !is_current(&st, &p, g);
                            // queued behind a newer change: not started at all
                            if cancelled() {
                                return None;
                            }
                            if millpath_ide::is_toml(&p) {
                                // millpath.toml or a post file: its own checks
                                return Some(millpath_ide::analyze_toml(&ws, &p));
                            }
                            analyze_from(&ws, &p, prev.as_deref(), &cancelled)
                        };
                        // an open document's on the analysis thread, where the previous
                        // one's pages are; a file that is not open (it cannot go stale)
                        // not in the queue before them
                        let r = if g != u64::MAX {
                            crate::worker::run(work).await
                        } else {
                            blocking(work).await.ok()
                        };
                        let a = match r {
                            Some(Some(a)) => Arc::new(a),
                            // stale (given up), or a panic: the error is reported by the caller
                            _ => return None,
                        };
                        if g != u64::MAX {
                            let replaced = state.lock().ok().and_then(|mut s| {
                                s.generation
                                    .contains_key(&path)
                                    .then(|| s.last.insert(path, a.clone()))
                                    .flatten()
                            });
                            // freeing a large analysis takes a millisecond or more: not on
                            // the way to the diagnostics
                            if let Some(old) = replaced {
                                crate::worker::drop_later(old);
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
    pub(crate) fn bump(st: &mut State, path: &Path) -> Option<u64> {
        let g = st.generation.get_mut(path)?;
        *g += 1;
        st.entries.remove(path);
        Some(*g)
    }

    /// Open documents other than `changed` whose last analysis depends on it.
    pub(crate) fn dependents(st: &State, changed: &Path) -> Vec<PathBuf> {
        st.last
            .iter()
            .filter(|(p, a)| p.as_path() != changed && a.depends_on(changed))
            .map(|(p, _)| p.clone())
            .collect()
    }

    /// `changed` changed (buffer, disk, closed): re-analyse the open documents depending on
    /// it and republish their diagnostics.
    pub(crate) fn dependents_changed(&self, changed: &[PathBuf]) {
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
            // a client that pulls is told to pull again
            if st.results.pull && st.results.refresh && !todo.is_empty() {
                let client = self.client.clone();
                tokio::spawn(async move { client.workspace_diagnostic_refresh().await });
            }
        }
        for d in todo {
            self.publish_later(d);
        }
    }

    /// Debounced analysis and publication of the current generation of an open document;
    /// a newer change makes it stale (abandoned, never published).
    pub(crate) fn publish_later(&self, path: PathBuf) {
        // the client's version of exactly this generation, under the client's URI
        let Ok((generation, debounce, version, pull, opened)) = self.state.lock().map(|s| {
            (
                s.generation.get(&path).copied().unwrap_or(0),
                s.debounce,
                s.versions.get(&path).copied(),
                s.results.pull,
                s.uris.get(&path).cloned(),
            )
        }) else {
            return;
        };
        let Some(uri) = opened.or_else(|| to_uri(&path)) else {
            return;
        };
        // the client asks for them (`textDocument/diagnostic`)
        if pull {
            return;
        }
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
                // a few diagnostics of this file alone are converted at once (a hop to the
                // blocking pool costs more than that on a busy computer); many, or ones that
                // point into other files (their lines read), on the blocking pool
                Ok((a, ws)) if converts_at_once(&a) => match guarded(|| lsp_diagnostics(&a, &ws)) {
                    Ok(d) => d,
                    Err(_) => internal_error_diagnostic(),
                },
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
    pub(crate) fn changed(&self, path: PathBuf) {
        if let Ok(mut st) = self.state.lock() {
            Self::bump(&mut st, &path);
        }
        self.publish_later(path.clone());
        self.dependents_changed(&[path]);
    }
}
