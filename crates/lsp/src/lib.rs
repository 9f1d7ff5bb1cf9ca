//! The MillPath language server (`millpath lsp`): LSP over stdio with tower-lsp-server.
//! All answers come from `millpath-ide`; this crate converts between LSP types and plain
//! data (`conv`), keeps the open documents and their shared analyses (`state`), and has one
//! file per group of handlers (`handlers/`), each turning a request into an ide call.
//!
//! - **One analysis per document version.** Every change bumps the document's generation;
//!   the `Arc<Analysis>` of the current generation is made once (on the analysis thread, `worker.rs`, in
//!   a `OnceCell`) and shared by the diagnostics, hover, inlay hints, lenses, symbols, actions
//!   and the preview. An analysis whose generation is no longer current gives up between its
//!   stages (inside the compiler: between elements and passes) and is never published;
//!   requests about it answer ContentModified.
//! - **Cancellation.** Handlers await the shared analysis or run heavy work with
//!   `spawn_blocking`, so tower-lsp-server can drop them on `$/cancelRequest` (answer
//!   -32800); the lenses, the preview and the workspace pull also stop their work then
//!   (`cancel.rs`, the emitter's `stop`).
//! - **Cross-file.** The last analysis of each open document knows the files it read and the
//!   folders it searched (the dependency graph: embedding → the file that defines the
//!   subpath, `millpath.toml`). A change of a buffer, closing it, `didSave`, or
//!   `workspace/didChangeWatchedFiles` (registered dynamically for `**/*.{mpath,dxf,DXF}` and
//!   `**/*.toml`, settings and post files, when the client allows it) re-analyses and republishes the open
//!   documents that depend on the file. Opening a buffer equal to the disk changes nothing
//!   for them. Open DXF drawings are read from the disk (an editor's text of them is
//!   decoded).
//! - **Sync and positions.** Incremental sync (UTF-16 or UTF-8 ranges, `positionEncoding`
//!   negotiated: utf-8 when offered); workspace folders, else `rootUri`, else `rootPath`;
//!   `didChangeWorkspaceFolders`.
//! - No debounce by default (`debounceMs` init option); diagnostics carry the version they
//!   were computed for; every handler runs under `catch_unwind`; `exit` without `shutdown`
//!   ends with status 1. Custom requests `millpath/gcodePreview`, `millpath/toolpath`.
//! - **Commands.** The code lenses' command is `millpath.preview`, a client-side command of
//!   the editors (VS Code's extension, the Neovim plugin's `vim.lsp.commands` handler) that
//!   opens the preview; the server's own `workspace/executeCommand` is
//!   `millpath.server.preview` (returns the preview), a different name because
//!   vscode-languageclient registers every advertised command as a VS Code command. A
//!   non-`file:` URI (`untitled:`) and a buffer opened with the language id `millpath` get a
//!   made-up `*.mpath` path (`to_path`): text, never a drawing to load.
//!
//! - **TOML documents.** `millpath.toml` and post files are analysed by `ide::analyze_toml`
//!   (the post loader's located errors); completion and hover there are the post names'
//!   (`ide::settings_completion`, `ide::settings_hover`).
//!
//! The `LanguageServer` impl (one line per method, delegating to `handlers/`), `service()` with the
//! custom requests, `run_stdio` and the exit status.

mod cancel;
mod conv;
mod handlers;
mod results;
mod state;
mod worker;

pub use conv::apply_edit;
pub use handlers::preview::{PreviewParams, PreviewResult};
use millpath_ide::Workspace;
use serde_json::Value;
use state::Backend;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tower_lsp_server::jsonrpc::Result;
use tower_lsp_server::ls_types::*;
use tower_lsp_server::{LanguageServer, LspService, Server};

impl LanguageServer for Backend {
    async fn initialize(&self, params: InitializeParams) -> Result<InitializeResult> {
        handlers::lifecycle::initialize(self, params).await
    }

    async fn initialized(&self, _: InitializedParams) {
        handlers::lifecycle::initialized(self).await
    }

    async fn shutdown(&self) -> Result<()> {
        handlers::lifecycle::shutdown(self).await
    }

    async fn did_open(&self, params: DidOpenTextDocumentParams) {
        handlers::sync::did_open(self, params).await
    }

    async fn did_change(&self, params: DidChangeTextDocumentParams) {
        handlers::sync::did_change(self, params).await
    }

    async fn did_save(&self, params: DidSaveTextDocumentParams) {
        handlers::sync::did_save(self, params).await
    }

    async fn did_close(&self, params: DidCloseTextDocumentParams) {
        handlers::sync::did_close(self, params).await
    }

    async fn did_change_watched_files(&self, params: DidChangeWatchedFilesParams) {
        handlers::sync::did_change_watched_files(self, params).await
    }

    async fn did_change_workspace_folders(&self, params: DidChangeWorkspaceFoldersParams) {
        handlers::sync::did_change_workspace_folders(self, params).await
    }

    async fn hover(&self, params: HoverParams) -> Result<Option<Hover>> {
        handlers::hover::hover(self, params).await
    }

    async fn completion(&self, params: CompletionParams) -> Result<Option<CompletionResponse>> {
        handlers::completion::completion(self, params).await
    }

    async fn goto_definition(
        &self,
        params: GotoDefinitionParams,
    ) -> Result<Option<GotoDefinitionResponse>> {
        handlers::navigation::goto_definition(self, params).await
    }

    async fn references(&self, params: ReferenceParams) -> Result<Option<Vec<Location>>> {
        handlers::navigation::references(self, params).await
    }

    async fn document_symbol(
        &self,
        params: DocumentSymbolParams,
    ) -> Result<Option<DocumentSymbolResponse>> {
        handlers::symbols::document_symbol(self, params).await
    }

    async fn symbol(
        &self,
        params: WorkspaceSymbolParams,
    ) -> Result<Option<WorkspaceSymbolResponse>> {
        handlers::symbols::symbol(self, params).await
    }

    async fn formatting(&self, params: DocumentFormattingParams) -> Result<Option<Vec<TextEdit>>> {
        handlers::formatting::formatting(self, params).await
    }

    async fn code_action(&self, params: CodeActionParams) -> Result<Option<CodeActionResponse>> {
        handlers::code_actions::code_action(self, params).await
    }

    async fn inlay_hint(&self, params: InlayHintParams) -> Result<Option<Vec<InlayHint>>> {
        handlers::inlay_hints::inlay_hint(self, params).await
    }

    async fn semantic_tokens_full(
        &self,
        params: SemanticTokensParams,
    ) -> Result<Option<SemanticTokensResult>> {
        handlers::semantic_tokens::semantic_tokens_full(self, params).await
    }

    async fn semantic_tokens_full_delta(
        &self,
        params: SemanticTokensDeltaParams,
    ) -> Result<Option<SemanticTokensFullDeltaResult>> {
        handlers::semantic_tokens::semantic_tokens_full_delta(self, params).await
    }

    async fn semantic_tokens_range(
        &self,
        params: SemanticTokensRangeParams,
    ) -> Result<Option<SemanticTokensRangeResult>> {
        handlers::semantic_tokens::semantic_tokens_range(self, params).await
    }

    async fn diagnostic(
        &self,
        params: DocumentDiagnosticParams,
    ) -> Result<DocumentDiagnosticReportResult> {
        handlers::pull_diagnostics::diagnostic(self, params).await
    }

    async fn workspace_diagnostic(
        &self,
        params: WorkspaceDiagnosticParams,
    ) -> Result<WorkspaceDiagnosticReportResult> {
        handlers::pull_diagnostics::workspace_diagnostic(self, params).await
    }

    async fn prepare_call_hierarchy(
        &self,
        params: CallHierarchyPrepareParams,
    ) -> Result<Option<Vec<CallHierarchyItem>>> {
        handlers::call_hierarchy::prepare_call_hierarchy(self, params).await
    }

    async fn incoming_calls(
        &self,
        params: CallHierarchyIncomingCallsParams,
    ) -> Result<Option<Vec<CallHierarchyIncomingCall>>> {
        handlers::call_hierarchy::incoming_calls(self, params).await
    }

    async fn outgoing_calls(
        &self,
        params: CallHierarchyOutgoingCallsParams,
    ) -> Result<Option<Vec<CallHierarchyOutgoingCall>>> {
        handlers::call_hierarchy::outgoing_calls(self, params).await
    }

    async fn code_lens(&self, params: CodeLensParams) -> Result<Option<Vec<CodeLens>>> {
        handlers::code_lens::code_lens(self, params).await
    }

    async fn execute_command(&self, params: ExecuteCommandParams) -> Result<Option<Value>> {
        handlers::code_lens::execute_command(self, params).await
    }

    async fn document_highlight(
        &self,
        params: DocumentHighlightParams,
    ) -> Result<Option<Vec<DocumentHighlight>>> {
        handlers::navigation::document_highlight(self, params).await
    }

    async fn document_link(&self, params: DocumentLinkParams) -> Result<Option<Vec<DocumentLink>>> {
        handlers::navigation::document_link(self, params).await
    }

    async fn range_formatting(
        &self,
        params: DocumentRangeFormattingParams,
    ) -> Result<Option<Vec<TextEdit>>> {
        handlers::formatting::range_formatting(self, params).await
    }

    async fn prepare_rename(
        &self,
        params: TextDocumentPositionParams,
    ) -> Result<Option<PrepareRenameResponse>> {
        handlers::rename::prepare_rename(self, params).await
    }

    async fn rename(&self, params: RenameParams) -> Result<Option<WorkspaceEdit>> {
        handlers::rename::rename(self, params).await
    }

    async fn folding_range(&self, params: FoldingRangeParams) -> Result<Option<Vec<FoldingRange>>> {
        handlers::folding::folding_range(self, params).await
    }

    async fn selection_range(
        &self,
        params: SelectionRangeParams,
    ) -> Result<Option<Vec<SelectionRange>>> {
        handlers::folding::selection_range(self, params).await
    }
}

/// The service, with the custom requests `millpath/gcodePreview` and `millpath/toolpath`.
pub fn service() -> (LspService<Backend>, tower_lsp_server::ClientSocket) {
    LspService::build(|client| Backend {
        client,
        state: Arc::new(Mutex::new(state::State {
            ws: Workspace::default(),
            generation: HashMap::new(),
            versions: HashMap::new(),
            uris: HashMap::new(),
            entries: HashMap::new(),
            last: HashMap::new(),
            debounce: Duration::ZERO,
            watch_files: false,
            results: Default::default(),
        })),
    })
    .custom_method("millpath/gcodePreview", Backend::gcode_preview)
    .custom_method("millpath/toolpath", Backend::toolpath)
    .finish()
}

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
    u8::from(!handlers::lifecycle::SHUT_DOWN.load(std::sync::atomic::Ordering::SeqCst))
}
