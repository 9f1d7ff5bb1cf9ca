//! The analysis thread: every analysis of an open document runs on one long-lived thread, in
//! order; the analysis it replaces is freed on a second one.
//!
//! Why not tokio's blocking pool: the allocator (mimalloc) keeps a heap per thread, and an
//! analysis made on whichever pool thread was idle, its predecessor freed on another, found
//! none of the pages the last analysis had used: each keystroke in a 20,000-element document
//! faulted in fresh memory (about 1,100 page faults, many of them 2 MiB huge pages zeroed
//! by the kernel), which cost as much as the analysis itself. On one thread the next analysis
//! reuses the pages the previous one gave back. A stale analysis gives up between its stages
//! (`Backend::analysis`), so the queue behind it stays short.
//!
//! Why the freeing thread: freed in the analysis thread's queue, the previous analysis (1 to 8
//! ms at 20,000 elements) sat in front of the next keystroke's analysis whenever the keystroke
//! came before it was done (seen with timestamps at every hop). mimalloc returns a block freed
//! on another thread to the heap that allocated it, so the analysis thread still reuses its
//! pages (the server's page faults over the latency bench: 402–417 before, 425–464 after).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{channel, Sender};
use std::sync::{Mutex, OnceLock};

type Job = Box<dyn FnOnce() + Send>;

/// A long-lived thread running the jobs sent to its queue in order; `None` when it could not
/// be started.
fn start(name: &str) -> Option<Mutex<Sender<Job>>> {
    let (tx, rx) = channel::<Job>();
    std::thread::Builder::new()
        .name(name.into())
        .spawn(move || {
            // ends when the process does (the queue is never dropped)
            for job in rx {
                job();
            }
        })
        .ok()
        .map(|_| Mutex::new(tx))
}

/// Sends `job` to a thread's queue; the job back when the thread is gone.
fn send(queue: Option<&Mutex<Sender<Job>>>, job: Job) -> Result<(), Job> {
    match queue.map(|q| q.lock()) {
        Some(Ok(q)) => q.send(job).map_err(|e| e.0),
        _ => Err(job),
    }
}

/// Runs `f` on the analysis thread after the jobs before it; `None` when it panicked (or the
/// thread is gone). Without the thread, on tokio's blocking pool.
pub(crate) async fn run<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> Option<T> {
    static ANALYSIS: OnceLock<Option<Mutex<Sender<Job>>>> = OnceLock::new();
    let (tx, rx) = tokio::sync::oneshot::channel();
    let job: Job = Box::new(move || {
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
        // the waiting request may have been dropped (cancelled): nothing to tell
        let _ = tx.send(r.ok());
    });
    let queue = ANALYSIS.get_or_init(|| start("millpath-analysis")).as_ref();
    if let Err(job) = send(queue, job) {
        tokio::task::spawn_blocking(job).await.ok()?;
    }
    rx.await.ok().flatten()
}

/// Values waiting on the freeing thread at most: beyond them (the thread starved on a busy
/// computer while analyses go on), the caller frees its value itself, so replaced analyses
/// never pile up in memory.
const MAX_WAITING_TO_FREE: usize = 4;

/// Frees `value` on the freeing thread, after the values sent before it and beside the next
/// analysis (not in front of it).
pub(crate) fn drop_later<T: Send + 'static>(value: T) {
    static FREEING: OnceLock<Option<Mutex<Sender<Job>>>> = OnceLock::new();
    static WAITING: AtomicUsize = AtomicUsize::new(0);
    if WAITING.load(Ordering::Acquire) >= MAX_WAITING_TO_FREE {
        drop(value);
        return;
    }
    WAITING.fetch_add(1, Ordering::AcqRel);
    let job: Job = Box::new(move || {
        // a panicking Drop must not end the thread
        let _ = std::panic::catch_unwind(std::panic::AssertUnwindSafe(move || drop(value)));
        WAITING.fetch_sub(1, Ordering::AcqRel);
    });
    let queue = FREEING.get_or_init(|| start("millpath-free")).as_ref();
    if let Err(job) = send(queue, job) {
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
        assert_eq!(run(|| -> u8 { panic!("a test panic") }).await, None);
        // the thread goes on after a panic
        assert_eq!(run(|| 7).await, Some(7));
    }

    #[tokio::test]
    async fn a_value_freed_later_does_not_hold_up_the_next_analysis() {
        let analysis_thread = run(|| std::thread::current().id()).await.unwrap();
        // a value whose freeing waits until the analysis after it has run
        let (go, wait) = std::sync::mpsc::channel::<()>();
        let (freed_tx, freed_rx) = std::sync::mpsc::channel();
        drop_later(SlowDrop(Some(wait), freed_tx));
        let next = tokio::time::timeout(std::time::Duration::from_secs(20), run(|| 2)).await;
        assert_eq!(next, Ok(Some(2)), "the analysis waited for the freeing");
        go.send(()).unwrap();
        let freed_on = freed_rx
            .recv_timeout(std::time::Duration::from_secs(20))
            .unwrap();
        assert_ne!(freed_on, analysis_thread);
    }

    #[test]
    fn values_waiting_to_be_freed_are_bounded() {
        let (freed_tx, freed_rx) = std::sync::mpsc::channel();
        let mut gates = Vec::new();
        let me = std::thread::current().id();
        let mut inline = None;
        // the freeing thread blocked by the first values: a later one is freed at once, here
        for k in 0..=MAX_WAITING_TO_FREE + 1 {
            let (go, wait) = std::sync::mpsc::channel::<()>();
            gates.push(go);
            drop_later(SlowDrop(Some(wait), freed_tx.clone()));
            if freed_rx.try_recv() == Ok(me) {
                inline = Some(k);
                break;
            }
        }
        for g in gates {
            let _ = g.send(());
        }
        assert!(
            inline.is_some_and(|k| k <= MAX_WAITING_TO_FREE),
            "no value freed by the caller: {inline:?}"
        );
    }

    struct SlowDrop(
        Option<std::sync::mpsc::Receiver<()>>,
        std::sync::mpsc::Sender<std::thread::ThreadId>,
    );
    impl Drop for SlowDrop {
        fn drop(&mut self) {
            // only the freeing thread waits for its gate (a value the caller frees does not)
            let freeing = std::thread::current().name() == Some("millpath-free");
            if let Some(w) = self.0.take().filter(|_| freeing) {
                let _ = w.recv_timeout(std::time::Duration::from_secs(20));
            }
            let _ = self.1.send(std::thread::current().id());
        }
    }
}
