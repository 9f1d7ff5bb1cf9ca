//! Results remembered between requests: semantic tokens per document (for deltas), pulled
//! diagnostics per drawing (for `unchanged` reports without a new analysis), and what the
//! client said about pulling diagnostics.
//!
//! What is kept between requests: the last semantic tokens per document (≤ 64), the pulled
//! diagnostics per drawing, whether the client pulls (then nothing is pushed; a dependency's change
//! sends `workspace/diagnostic/refresh`).

use millpath_ide::workspace_check::Inputs;
use millpath_ide::RelToken;
use std::collections::HashMap;
use std::path::PathBuf;
use tower_lsp_server::ls_types::Diagnostic;

/// Documents whose last semantic tokens are kept (the oldest result is dropped beyond).
const MAX_TOKEN_RESULTS: usize = 64;

#[derive(Default)]
pub(crate) struct Results {
    /// Per document URI: the last result id sent and its tokens.
    tokens: HashMap<String, (u64, Vec<RelToken>)>,
    next_id: u64,
    /// Per drawing: the last workspace pull's answer and what it was made from.
    pub(crate) pulled: HashMap<PathBuf, Pulled>,
    /// The client pulls diagnostics (`textDocument.diagnostic`): nothing is pushed then.
    pub(crate) pull: bool,
    /// The client takes `workspace/diagnostic/refresh`.
    pub(crate) refresh: bool,
}

/// One drawing's pulled diagnostics.
#[derive(Clone)]
pub(crate) struct Pulled {
    pub(crate) inputs: Inputs,
    pub(crate) fingerprint: u64,
    pub(crate) result_id: String,
    pub(crate) items: Vec<Diagnostic>,
}

impl Results {
    /// Remembers the tokens sent for `uri`; returns their result id.
    pub(crate) fn keep_tokens(&mut self, uri: &str, data: Vec<RelToken>) -> String {
        self.next_id += 1;
        if self.tokens.len() >= MAX_TOKEN_RESULTS && !self.tokens.contains_key(uri) {
            let oldest = self
                .tokens
                .iter()
                .min_by_key(|(_, (id, _))| *id)
                .map(|(u, _)| u.clone());
            if let Some(u) = oldest {
                self.tokens.remove(&u);
            }
        }
        self.tokens.insert(uri.to_string(), (self.next_id, data));
        self.next_id.to_string()
    }

    /// The tokens last sent for `uri` under `result_id`.
    pub(crate) fn tokens(&self, uri: &str, result_id: &str) -> Option<&[RelToken]> {
        self.tokens
            .get(uri)
            .filter(|(id, _)| id.to_string() == result_id)
            .map(|(_, d)| d.as_slice())
    }
}

/// A result id for a list of diagnostics: equal lists, equal ids.
pub(crate) fn diagnostics_id(items: &[Diagnostic]) -> String {
    use std::hash::{Hash, Hasher};
    let mut h = std::hash::DefaultHasher::new();
    serde_json::to_string(items)
        .unwrap_or_default()
        .hash(&mut h);
    format!("{:016x}", h.finish())
}
