//! Initialization (capabilities, position encoding, roots), registration of the file watchers, shutdown.
//!
//! Initialize (capabilities, `positionEncoding`, roots), watcher registration, shutdown.

use crate::conv::*;
use crate::state::*;
use std::path::PathBuf;
use std::time::Duration;
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;

pub(crate) async fn initialize(b: &Backend, params: InitializeParams) -> Result<InitializeResult> {
    let (client, debounce) = client_settings(params.initialization_options.as_ref());
    let utf8 = params
        .capabilities
        .general
        .as_ref()
        .and_then(|g| g.position_encodings.as_ref())
        .is_some_and(|e| e.contains(&PositionEncodingKind::UTF8));
    if let Ok(mut st) = b.state.lock() {
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
        // a client that pulls diagnostics gets none pushed (VS Code would show both)
        st.results.pull = params
            .capabilities
            .text_document
            .as_ref()
            .is_some_and(|t| t.diagnostic.is_some());
        st.results.refresh = params
            .capabilities
            .workspace
            .as_ref()
            .and_then(|w| w.diagnostics.as_ref())
            .and_then(|d| d.refresh_support)
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
                // `"`: a post name in millpath.toml
                trigger_characters: Some(vec![">".into(), " ".into(), "\"".into()]),
                ..Default::default()
            }),
            definition_provider: Some(OneOf::Left(true)),
            references_provider: Some(OneOf::Left(true)),
            document_symbol_provider: Some(OneOf::Left(true)),
            workspace_symbol_provider: Some(OneOf::Left(true)),
            document_formatting_provider: Some(OneOf::Left(true)),
            document_range_formatting_provider: Some(OneOf::Left(true)),
            document_highlight_provider: Some(OneOf::Left(true)),
            document_link_provider: Some(DocumentLinkOptions {
                resolve_provider: Some(false),
                work_done_progress_options: Default::default(),
            }),
            rename_provider: Some(OneOf::Right(RenameOptions {
                prepare_provider: Some(true),
                work_done_progress_options: Default::default(),
            })),
            folding_range_provider: Some(FoldingRangeProviderCapability::Simple(true)),
            selection_range_provider: Some(SelectionRangeProviderCapability::Simple(true)),
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
                SemanticTokensServerCapabilities::SemanticTokensOptions(SemanticTokensOptions {
                    legend: SemanticTokensLegend {
                        token_types: millpath_ide::TOKEN_TYPES
                            .iter()
                            .map(|t| SemanticTokenType::new(t))
                            .collect(),
                        token_modifiers: vec![],
                    },
                    full: Some(SemanticTokensFullOptions::Delta { delta: Some(true) }),
                    range: Some(true),
                    ..Default::default()
                }),
            ),
            call_hierarchy_provider: Some(CallHierarchyServerCapability::Simple(true)),
            diagnostic_provider: Some(DiagnosticServerCapabilities::Options(DiagnosticOptions {
                identifier: Some("millpath".into()),
                inter_file_dependencies: true,
                workspace_diagnostics: true,
                work_done_progress_options: Default::default(),
            })),
            ..ServerCapabilities::default()
        },
        offset_encoding: None,
    })
}

pub(crate) async fn initialized(b: &Backend) {
    let watch = b.state.lock().map(|s| s.watch_files).unwrap_or(false);
    if !watch {
        return;
    }
    let client = b.client.clone();
    // not awaited here: the client answers while we go on
    tokio::spawn(async move {
        // `*.toml`: millpath.toml and the post files it names
        let watchers = ["**/*.{mpath,dxf,DXF}", "**/*.toml"]
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

/// `shutdown` was received (the exit status of [`crate::run_stdio`]).
pub(crate) static SHUT_DOWN: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

pub(crate) async fn shutdown(_: &Backend) -> Result<()> {
    SHUT_DOWN.store(true, std::sync::atomic::Ordering::SeqCst);
    Ok(())
}
