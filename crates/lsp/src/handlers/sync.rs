//! Document and workspace synchronisation: open buffers, incremental changes, saves, watched files, folders.

use crate::conv::*;
use crate::state::*;
use std::path::PathBuf;
use tower_lsp_server::ls_types::*;

pub(crate) async fn did_open(b: &Backend, params: DidOpenTextDocumentParams) {
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
    let as_on_disk = std::fs::read(&p).is_ok_and(|b| {
        millpath_core::load::text_file::decode(&b)
            .is_ok_and(|d| d.text == params.text_document.text.as_str())
    });
    if let Ok(mut st) = b.state.lock() {
        st.ws.overlays.insert(p.clone(), params.text_document.text);
        st.versions.insert(p.clone(), params.text_document.version);
        st.uris.insert(p.clone(), uri.clone());
        st.generation.entry(p.clone()).or_insert(0);
        Backend::bump(&mut st, &p);
    }
    b.publish_later(p.clone());
    if !as_on_disk {
        b.dependents_changed(&[p]);
    }
}

pub(crate) async fn did_change(b: &Backend, params: DidChangeTextDocumentParams) {
    let uri = params.text_document.uri;
    let Some(p) = to_path(&uri) else { return };
    if let Ok(mut st) = b.state.lock() {
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
    b.changed(p);
}

pub(crate) async fn did_save(b: &Backend, params: DidSaveTextDocumentParams) {
    if let Some(p) = to_path(&params.text_document.uri) {
        b.dependents_changed(&[p]);
    }
}

pub(crate) async fn did_close(b: &Backend, params: DidCloseTextDocumentParams) {
    let uri = params.text_document.uri;
    if let (Some(p), Ok(mut st)) = (to_path(&uri), b.state.lock()) {
        st.ws.overlays.remove(&p);
        st.generation.remove(&p);
        st.versions.remove(&p);
        st.uris.remove(&p);
        st.entries.remove(&p);
        st.last.remove(&p);
        drop(st);
        // its dependents now see the file on disk
        b.dependents_changed(&[p]);
    }
    if let Ok(mut b) = TEXT_BUFFERS.lock() {
        b.retain(|u| u != uri.as_str());
    }
    b.client.publish_diagnostics(uri, Vec::new(), None).await;
}

pub(crate) async fn did_change_watched_files(b: &Backend, params: DidChangeWatchedFilesParams) {
    let changed: Vec<PathBuf> = params
        .changes
        .iter()
        .filter_map(|c| to_path(&c.uri))
        .collect();
    b.dependents_changed(&changed);
}

pub(crate) async fn did_change_workspace_folders(
    b: &Backend,
    params: DidChangeWorkspaceFoldersParams,
) {
    if let Ok(mut st) = b.state.lock() {
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
