//! The MillPath language server (`millpath lsp`): LSP over stdio with tower-lsp-server.
//! All answers come from `millpath-ide`; this crate converts between LSP types and plain
//! data, debounces analyses, drops stale ones and keeps running when a handler fails.

use millpath_core::diag::{Diagnostic as CoreDiagnostic, Origin, Severity};
use millpath_core::load::config::FileConfig;
use millpath_ide::features;
use millpath_ide::{analyze, Analysis, LineIndex, Pos, Workspace};
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

struct State {
    ws: Workspace,
    /// Bumped on every change; an analysis publishes only if it is still the latest.
    generation: HashMap<Uri, u64>,
    debounce: Duration,
}

pub struct Backend {
    client: Client,
    state: Arc<Mutex<State>>,
}

/// Buffers opened with the language id `millpath` whose file name is not `*.mpath`.
static TEXT_BUFFERS: Mutex<Vec<String>> = Mutex::new(Vec::new());

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
        return Some(
            std::env::temp_dir()
                .join("millpath-buffers")
                .join(format!("{name}.mpath")),
        );
    }
    let p = uri.to_file_path()?.into_owned();
    Some(if text && !millpath_core::load::fs::is_text_file(&p) {
        p.with_extension(format!(
            "{}.mpath",
            p.extension().and_then(|e| e.to_str()).unwrap_or("")
        ))
    } else {
        p
    })
}

fn to_uri(path: &Path) -> Option<Uri> {
    Uri::from_file_path(path)
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
        _ => Range::default(),
    }
}

fn location(origin: &Origin, ws: &Workspace) -> Option<Location> {
    match origin {
        Origin::Span {
            file, start, end, ..
        } => {
            let text = ws.text(&file.path)?;
            let idx = LineIndex::new(&text);
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

fn edit(a: &Analysis, e: &features::TextEdit) -> TextEdit {
    TextEdit {
        range: range(&a.index, e.start, e.end),
        new_text: e.text.clone(),
    }
}

fn loc(l: &features::Location) -> Option<Location> {
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

impl Backend {
    fn snapshot(&self) -> Workspace {
        self.state.lock().map(|s| s.ws.clone()).unwrap_or_default()
    }

    fn analysis(&self, uri: &Uri) -> Result<(Analysis, Workspace)> {
        let path = to_path(uri).ok_or_else(|| Error::invalid_params("not a file URI"))?;
        let ws = self.snapshot();
        let a = guarded(|| analyze(&ws, &path))?;
        Ok((a, ws))
    }

    /// Debounced analysis and publication; a newer change makes this one stale.
    async fn schedule(&self, uri: Uri) {
        let (generation, debounce) = {
            let Ok(mut st) = self.state.lock() else {
                return;
            };
            let g = st.generation.entry(uri.clone()).or_insert(0);
            *g += 1;
            (*g, st.debounce)
        };
        let state = self.state.clone();
        let client = self.client.clone();
        tokio::spawn(async move {
            tokio::time::sleep(debounce).await;
            let current = |st: &Arc<Mutex<State>>| {
                st.lock()
                    .map(|s| s.generation.get(&uri) == Some(&generation))
                    .unwrap_or(false)
            };
            if !current(&state) {
                return;
            }
            let Some(path) = to_path(&uri) else { return };
            let ws = match state.lock() {
                Ok(s) => s.ws.clone(),
                Err(_) => return,
            };
            let result = tokio::task::spawn_blocking(move || {
                catch_unwind(AssertUnwindSafe(|| {
                    let a = analyze(&ws, &path);
                    lsp_diagnostics(&a, &ws)
                }))
            })
            .await;
            let diags = match result {
                Ok(Ok(d)) => d,
                _ => vec![Diagnostic {
                    message: "millpath: internal error while analysing this file".into(),
                    severity: Some(DiagnosticSeverity::ERROR),
                    ..Default::default()
                }],
            };
            if current(&state) {
                client.publish_diagnostics(uri, diags, None).await;
            }
        });
    }

    async fn gcode_preview(&self, params: PreviewParams) -> Result<PreviewResult> {
        let path = to_path(&params.text_document.uri)
            .ok_or_else(|| Error::invalid_params("not a file URI"))?;
        let ws = self.snapshot();
        let pv =
            guarded(|| features::preview(&ws, &path, params.path.as_deref()))?.map_err(|e| {
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
        guarded(|| features::toolpath(&ws, &path, params.path.as_deref()))?.map_err(|e| {
            let mut err = Error::invalid_request();
            err.message = e.into();
            err
        })
    }
}

impl LanguageServer for Backend {
    async fn initialize(&self, params: InitializeParams) -> Result<InitializeResult> {
        let (client, debounce) = client_settings(params.initialization_options.as_ref());
        if let Ok(mut st) = self.state.lock() {
            st.ws.client = client;
            if let Some(ms) = debounce {
                st.debounce = Duration::from_millis(ms);
            }
            for f in params.workspace_folders.unwrap_or_default() {
                if let Some(p) = to_path(&f.uri) {
                    st.ws.roots.push(p);
                }
            }
        }
        Ok(InitializeResult {
            server_info: Some(ServerInfo {
                name: "millpath".into(),
                version: Some(env!("CARGO_PKG_VERSION").into()),
            }),
            capabilities: ServerCapabilities {
                text_document_sync: Some(TextDocumentSyncCapability::Kind(
                    TextDocumentSyncKind::FULL,
                )),
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
                                token_types: features::TOKEN_TYPES
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

    async fn shutdown(&self) -> Result<()> {
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
        if let (Some(p), Ok(mut st)) = (to_path(&uri), self.state.lock()) {
            st.ws.overlays.insert(p, params.text_document.text);
        }
        self.schedule(uri).await;
    }

    async fn did_change(&self, params: DidChangeTextDocumentParams) {
        let uri = params.text_document.uri;
        if let (Some(p), Some(change), Ok(mut st)) = (
            to_path(&uri),
            params.content_changes.into_iter().last(),
            self.state.lock(),
        ) {
            st.ws.overlays.insert(p, change.text);
        }
        self.schedule(uri).await;
    }

    async fn did_close(&self, params: DidCloseTextDocumentParams) {
        let uri = params.text_document.uri;
        if let (Some(p), Ok(mut st)) = (to_path(&uri), self.state.lock()) {
            st.ws.overlays.remove(&p);
            st.generation.remove(&uri);
        }
        if let Ok(mut b) = TEXT_BUFFERS.lock() {
            b.retain(|u| u != uri.as_str());
        }
        self.client.publish_diagnostics(uri, Vec::new(), None).await;
    }

    async fn hover(&self, params: HoverParams) -> Result<Option<Hover>> {
        let (a, ws) = self.analysis(&params.text_document_position_params.text_document.uri)?;
        let at = offset(&a, params.text_document_position_params.position);
        guarded(|| {
            features::hover(&a, &ws, at).map(|h| Hover {
                contents: HoverContents::Markup(MarkupContent {
                    kind: MarkupKind::Markdown,
                    value: h.markdown,
                }),
                range: Some(range(&a.index, h.start, h.end)),
            })
        })
    }

    async fn completion(&self, params: CompletionParams) -> Result<Option<CompletionResponse>> {
        let (a, ws) = self.analysis(&params.text_document_position.text_document.uri)?;
        let at = offset(&a, params.text_document_position.position);
        guarded(|| {
            let items = features::completion(&a, &ws, at)
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
        let (a, ws) = self.analysis(&params.text_document_position_params.text_document.uri)?;
        let at = offset(&a, params.text_document_position_params.position);
        guarded(|| {
            let locs: Vec<Location> = features::definition(&a, &ws, at)
                .iter()
                .filter_map(loc)
                .collect();
            (!locs.is_empty()).then_some(GotoDefinitionResponse::Array(locs))
        })
    }

    async fn references(&self, params: ReferenceParams) -> Result<Option<Vec<Location>>> {
        let (a, ws) = self.analysis(&params.text_document_position.text_document.uri)?;
        let at = offset(&a, params.text_document_position.position);
        guarded(|| {
            Some(
                features::references(&a, &ws, at)
                    .iter()
                    .filter_map(loc)
                    .collect(),
            )
        })
    }

    async fn document_symbol(
        &self,
        params: DocumentSymbolParams,
    ) -> Result<Option<DocumentSymbolResponse>> {
        let (a, _) = self.analysis(&params.text_document.uri)?;
        #[allow(deprecated)]
        fn conv(a: &Analysis, s: &features::Symbol) -> DocumentSymbol {
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
                features::document_symbols(&a)
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
            let out: Vec<WorkspaceSymbol> = features::workspace_symbols(&ws, &params.query)
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
        let (a, _) = self.analysis(&params.text_document.uri)?;
        guarded(|| {
            features::format(&a).filter(|f| *f != a.src).map(|f| {
                vec![TextEdit {
                    range: range(&a.index, 0, a.src.len()),
                    new_text: f,
                }]
            })
        })
    }

    async fn code_action(&self, params: CodeActionParams) -> Result<Option<CodeActionResponse>> {
        let uri = params.text_document.uri.clone();
        let (a, _) = self.analysis(&uri)?;
        let (s, e) = (offset(&a, params.range.start), offset(&a, params.range.end));
        guarded(|| {
            let actions = features::code_actions(&a, s, e)
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
        let (a, _) = self.analysis(&params.text_document.uri)?;
        guarded(|| {
            Some(
                features::inlay_hints(&a)
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
        let (a, _) = self.analysis(&params.text_document.uri)?;
        guarded(|| {
            let mut data = Vec::new();
            let (mut line, mut col) = (0u32, 0u32);
            for t in features::semantic_tokens(&a) {
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
        let (a, ws) = self.analysis(&uri)?;
        guarded(|| {
            Some(
                features::code_lenses(&a, &ws)
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
            debounce: Duration::from_millis(10),
        })),
    })
    .custom_method("millpath/gcodePreview", Backend::gcode_preview)
    .custom_method("millpath/toolpath", Backend::toolpath)
    .finish()
}

/// Serves LSP over standard input and output until the client exits.
pub fn run_stdio() {
    let Ok(rt) = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
    else {
        eprintln!("millpath lsp: cannot start the runtime");
        return;
    };
    rt.block_on(async {
        let (service, socket) = service();
        Server::new(tokio::io::stdin(), tokio::io::stdout(), socket)
            .serve(service)
            .await;
    });
}
