//! Cancellation that reaches into the work: a request's future holds a [`CancelOnDrop`];
//! tower-lsp-server drops the future on `$/cancelRequest`, which raises the flag the
//! blocking work asks (the compile of a preview or of the lenses' statistics stops within a
//! few hundred elements).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

pub(crate) struct CancelOnDrop(Arc<AtomicBool>);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// A guard for the request's future and the flag for its work.
pub(crate) fn on_drop() -> (CancelOnDrop, Cancelled) {
    let flag = Arc::new(AtomicBool::new(false));
    (CancelOnDrop(flag.clone()), Cancelled(flag))
}

/// The work's side: whether the request was dropped.
#[derive(Clone)]
pub(crate) struct Cancelled(Arc<AtomicBool>);

impl Cancelled {
    pub(crate) fn get(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

pub(crate) fn request_cancelled() -> tower_lsp_server::jsonrpc::Error {
    tower_lsp_server::jsonrpc::Error::request_cancelled()
}
