//! The analysis thread: every analysis of an open document, and the freeing of the one it
//! replaces, runs on one long-lived thread, in order.
//!
//! Why not tokio's blocking pool: the allocator (mimalloc) keeps a heap per thread, and an
//! analysis made on whichever pool thread was idle, its predecessor freed on another, found
//! none of the pages the last analysis had used: each keystroke in a 20,000-element document
//! faulted in fresh memory (about 1,100 page faults, many of them 2 MiB huge pages zeroed
//! by the kernel), which cost as much as the analysis itself. On one thread the next analysis
//! reuses the pages the previous one gave back. A stale analysis gives up between its stages
//! (`Backend::analysis`), so the queue behind it stays short.
//!
//! The freeing stays in this queue although a keystroke's analysis can wait behind it (1 to 8
//! ms at 20,000 elements): freed on a thread of its own (even at nice 19), the next analysis
//! found the pages still taken and faulted in fresh ones; the latency bench, 8 runs each on a
//! busy computer: one long chain 10.5 → 13.5 ms median, short chains unchanged.

use std::sync::mpsc::{channel, Sender};
use std::sync::{Mutex, OnceLock};

type Job = Box<dyn FnOnce() + Send>;

/// The thread's queue; `None` when the thread could not be started.
fn queue() -> Option<&'static Mutex<Sender<Job>>> {
    static QUEUE: OnceLock<Option<Mutex<Sender<Job>>>> = OnceLock::new();
    QUEUE
        .get_or_init(|| {
            let (tx, rx) = channel::<Job>();
            std::thread::Builder::new()
                .name("millpath-analysis".into())
                .spawn(move || {
                    // ends when the process does (the queue is never dropped)
                    for job in rx {
                        job();
                    }
                })
                .ok()
                .map(|_| Mutex::new(tx))
        })
        .as_ref()
}

/// Runs `f` on the analysis thread after the jobs before it; `None` when it panicked (or the
/// thread is gone). Without the thread, on tokio's blocking pool.
pub(crate) async fn run<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> Option<T> {
    let (tx, rx) = tokio::sync::oneshot::channel();
    let job: Job = Box::new(move || {
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
        // the waiting request may have been dropped (cancelled): nothing to tell
        let _ = tx.send(r.ok());
    });
    let sent = match queue().map(|q| q.lock()) {
        Some(Ok(q)) => q.send(job).map_err(|e| e.0),
        _ => Err(job),
    };
    if let Err(job) = sent {
        tokio::task::spawn_blocking(job).await.ok()?;
    }
    rx.await.ok().flatten()
}

/// Frees `value` on the analysis thread, after the jobs before it (not on the way to an
/// answer, and where its pages are reused).
pub(crate) fn drop_later<T: Send + 'static>(value: T) {
    let job: Job = Box::new(move || drop(value));
    let sent = match queue().map(|q| q.lock()) {
        Some(Ok(q)) => q.send(job).map_err(|e| e.0),
        _ => Err(job),
    };
    if let Err(job) = sent {
        tokio::task::spawn_blocking(job);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test]
    async fn jobs_run_in_order_on_one_thread_and_a_panic_is_none() {
        let first = run(|| std::thread::current().id()).await.unwrap();
        let (a, b) = tokio::join!(
            run(|| std::thread::current().id()),
            run(|| std::thread::current().id())
        );
        assert_eq!(Some(first), a);
        assert_eq!(Some(first), b);
        let order = std::sync::Arc::new(Mutex::new(Vec::new()));
        let o = order.clone();
        drop_later(DropMark(o.clone(), 1));
        run(move || o.lock().unwrap().push(2)).await.unwrap();
        assert_eq!(*order.lock().unwrap(), vec![1, 2]);
        assert_eq!(run(|| -> u8 { panic!("a test panic") }).await, None);
        // the thread goes on after a panic
        assert_eq!(run(|| 7).await, Some(7));
    }

    struct DropMark(std::sync::Arc<Mutex<Vec<u8>>>, u8);
    impl Drop for DropMark {
        fn drop(&mut self) {
            self.0.lock().unwrap().push(self.1);
        }
    }
}
