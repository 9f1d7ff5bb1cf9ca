//! Pull diagnostics: `textDocument/diagnostic` (the document's analysis, `unchanged` while
//! its result id still matches) and `workspace/diagnostic` (`millpath check`'s findings for
//! every drawing of the workspace folders, open or not, text and DXF; a drawing is analysed
//! again only when something it read changed).
//!
//! `textDocument/diagnostic` (`unchanged` while the result id matches) and `workspace/diagnostic`:
//! every drawing of the workspace checked (`ide::workspace_check`), again only when its inputs'
//! fingerprint changed.

use crate::cancel;
use crate::conv::*;
use crate::results::{diagnostics_id, Pulled};
use crate::state::*;
use millpath_ide::workspace_check::{check_file, workspace_drawings, FileCheck, Inputs};
use std::collections::HashMap;
use std::path::PathBuf;
use tower_lsp_server::jsonrpc::{ErrorCode, Result};
use tower_lsp_server::ls_types::*;

/// Analyses asked again when a newer edit made the one awaited stale (the client asks anew
/// after an edit anyway; an error would blank its list for a moment).
const STALE_RETRIES: usize = 20;

pub(crate) async fn diagnostic(
    b: &Backend,
    params: DocumentDiagnosticParams,
) -> Result<DocumentDiagnosticReportResult> {
    let uri = params.text_document.uri;
    let mut tries = 0;
    let (a, ws) = loop {
        match b.analysis(&uri).await {
            Err(e) if e.code == ErrorCode::ContentModified && tries < STALE_RETRIES => tries += 1,
            r => break r?,
        }
    };
    let items = blocking(move || lsp_diagnostics(&a, &ws)).await?;
    let id = diagnostics_id(&items);
    let report = if params.previous_result_id.as_deref() == Some(id.as_str()) {
        DocumentDiagnosticReport::Unchanged(RelatedUnchangedDocumentDiagnosticReport {
            related_documents: None,
            unchanged_document_diagnostic_report: UnchangedDocumentDiagnosticReport {
                result_id: id,
            },
        })
    } else {
        DocumentDiagnosticReport::Full(RelatedFullDocumentDiagnosticReport {
            related_documents: None,
            full_document_diagnostic_report: FullDocumentDiagnosticReport {
                result_id: Some(id),
                items,
            },
        })
    };
    Ok(DocumentDiagnosticReportResult::Report(report))
}

pub(crate) async fn workspace_diagnostic(
    b: &Backend,
    params: WorkspaceDiagnosticParams,
) -> Result<WorkspaceDiagnosticReportResult> {
    let previous: HashMap<PathBuf, String> = params
        .previous_result_ids
        .into_iter()
        .filter_map(|p| Some((to_path(&p.uri)?, p.value)))
        .collect();
    let (ws, versions, cache) = {
        let mut st = b
            .state
            .lock()
            .map_err(|_| tower_lsp_server::jsonrpc::Error::internal_error())?;
        (
            st.ws.clone(),
            st.versions.clone(),
            std::mem::take(&mut st.results.pulled),
        )
    };
    let (_guard, cancelled) = cancel::on_drop();
    let work = cancelled.clone();
    let (items, cache) =
        blocking(move || pull_all(&ws, &versions, &previous, cache, &work)).await?;
    if cancelled.get() {
        return Err(cancel::request_cancelled());
    }
    if let Ok(mut st) = b.state.lock() {
        st.results.pulled = cache;
    }
    Ok(WorkspaceDiagnosticReportResult::Report(
        WorkspaceDiagnosticReport { items },
    ))
}

/// Every drawing's report; the remembered answers updated (drawings gone are forgotten).
fn pull_all(
    ws: &millpath_ide::Workspace,
    versions: &HashMap<PathBuf, i32>,
    previous: &HashMap<PathBuf, String>,
    mut cache: HashMap<PathBuf, Pulled>,
    cancelled: &cancel::Cancelled,
) -> (
    Vec<WorkspaceDocumentDiagnosticReport>,
    HashMap<PathBuf, Pulled>,
) {
    let files = workspace_drawings(ws).files;
    let mut listings = HashMap::new();
    let mut out = Vec::new();
    let mut kept = HashMap::new();
    for f in files {
        if cancelled.get() {
            break;
        }
        let Some(uri) = to_uri(&f) else { continue };
        let cached = cache
            .remove(&f)
            .filter(|p| p.inputs.fingerprint(ws, &mut listings) == p.fingerprint);
        let pulled = match cached {
            Some(p) => p,
            None => match check_file(ws, &f, &|| cancelled.get()) {
                None => break,
                Some(FileCheck::Analysed(a)) => {
                    let items = lsp_diagnostics(&a, ws);
                    let inputs = Inputs::of(&a);
                    Pulled {
                        fingerprint: inputs.fingerprint(ws, &mut listings),
                        inputs,
                        result_id: diagnostics_id(&items),
                        items,
                    }
                }
                Some(FileCheck::Unreadable(d)) => {
                    let lang = ws.settings_for(&f).settings.lang;
                    let items = vec![Diagnostic {
                        severity: Some(DiagnosticSeverity::ERROR),
                        code: Some(NumberOrString::String(d.msg.code())),
                        source: Some("millpath".into()),
                        message: d.message(lang),
                        ..Default::default()
                    }];
                    // never remembered: a file made readable again keeps its stamp
                    Pulled {
                        fingerprint: 0,
                        inputs: Inputs::default(),
                        result_id: diagnostics_id(&items),
                        items,
                    }
                }
            },
        };
        let version = versions.get(&f).map(|v| i64::from(*v));
        let report = if previous.get(&f) == Some(&pulled.result_id) {
            WorkspaceDocumentDiagnosticReport::Unchanged(
                WorkspaceUnchangedDocumentDiagnosticReport {
                    uri,
                    version,
                    unchanged_document_diagnostic_report: UnchangedDocumentDiagnosticReport {
                        result_id: pulled.result_id.clone(),
                    },
                },
            )
        } else {
            WorkspaceDocumentDiagnosticReport::Full(WorkspaceFullDocumentDiagnosticReport {
                uri,
                version,
                full_document_diagnostic_report: FullDocumentDiagnosticReport {
                    result_id: Some(pulled.result_id.clone()),
                    items: pulled.items.clone(),
                },
            })
        };
        out.push(report);
        if !pulled.inputs.files.is_empty() {
            kept.insert(f, pulled);
        }
    }
    (out, kept)
}
