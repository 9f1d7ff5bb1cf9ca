//! One file per group of LSP handlers; each converts the request, asks `millpath-ide` and
//! converts the answer.

pub(crate) mod call_hierarchy;
pub(crate) mod code_actions;
pub(crate) mod code_lens;
pub(crate) mod completion;
pub(crate) mod folding;
pub(crate) mod formatting;
pub(crate) mod hover;
pub(crate) mod inlay_hints;
pub(crate) mod lifecycle;
pub(crate) mod navigation;
pub(crate) mod preview;
pub(crate) mod pull_diagnostics;
pub(crate) mod rename;
pub(crate) mod semantic_tokens;
pub(crate) mod symbols;
pub(crate) mod sync;
