//! The worker threads of `check`: a rayon pool whose main thread is one of the workers, and
//! whose other workers start on a CPU of their own.
//!
//! Why the placement: a scheduler may pack a new thread onto the busy CPU of its parent and
//! leave the idle one asleep until load balancing moves it. On the 2-vCPU VM this project is
//! measured on, a new thread first ran after 50 µs half of the time and after 2.4–3.4 ms the
//! other half; started on the other CPU, always within 60–210 µs. A `check` of 38 drawings
//! takes 4 ms of work, so a late second worker did nothing but cost. Each worker is pointed at
//! an idle CPU only to start: once running, it gets back the process's whole CPU set and the
//! scheduler places it freely.

use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::Arc;

/// A worker's start: spawned, pointed at its CPU, running.
const NEW: u8 = 0;
const POINTED: u8 = 1;
const STARTED: u8 = 2;

/// Builds the pool for `check`: as many workers as CPUs, the calling thread the first of
/// them, each with the main thread's usual 8 MiB stack (a drawing checks on a worker exactly
/// as it would on the main thread).
pub fn check_pool() -> Result<rayon::ThreadPool, rayon::ThreadPoolBuildError> {
    let start = placement::Start::here();
    rayon::ThreadPoolBuilder::new()
        .stack_size(8 << 20)
        .use_current_thread()
        .spawn_handler(move |worker| {
            let mut b = std::thread::Builder::new();
            if let Some(name) = worker.name() {
                b = b.name(name.to_owned());
            }
            if let Some(size) = worker.stack_size() {
                b = b.stack_size(size);
            }
            // Who comes second lets the worker go: the worker itself when it starts after
            // being pointed, else this thread right after pointing it (it already runs).
            let state = Arc::new(AtomicU8::new(NEW));
            let (worker_state, cpus) = (state.clone(), start.clone());
            let index = worker.index();
            let handle = b.spawn(move || {
                if worker_state.swap(STARTED, Ordering::SeqCst) == POINTED {
                    cpus.release_current();
                }
                worker.run()
            })?;
            if start.point(&handle, index) && state.swap(POINTED, Ordering::SeqCst) == STARTED {
                start.release(&handle);
            }
            Ok(())
        })
        .build()
}

#[cfg(target_os = "linux")]
mod placement {
    use std::os::unix::thread::JoinHandleExt;

    fn set_affinity<T>(handle: &std::thread::JoinHandle<T>, set: &libc::cpu_set_t) -> bool {
        // SAFETY: the set is ours and its size is passed; the thread is alive while we hold
        // its JoinHandle, so its pthread_t is valid.
        // (std's pthread handle is an integer; musl's pthread_t a pointer: the static Linux
        // release build)
        #[allow(clippy::unnecessary_cast, trivial_numeric_casts)]
        let thread = handle.as_pthread_t() as libc::pthread_t;
        unsafe {
            libc::pthread_setaffinity_np(thread, std::mem::size_of::<libc::cpu_set_t>(), set) == 0
        }
    }

    /// The process's CPU set and the CPU the pool was built on.
    #[derive(Clone)]
    pub struct Start {
        allowed: Option<libc::cpu_set_t>,
        home: Option<usize>,
    }

    impl Start {
        pub fn here() -> Start {
            // SAFETY: `set` is a plain bit set that sched_getaffinity fills (its size is
            // passed); sched_getcpu takes nothing and returns a number or -1.
            let (allowed, home) = unsafe {
                let mut set: libc::cpu_set_t = std::mem::zeroed();
                let ok =
                    libc::sched_getaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &mut set);
                (
                    (ok == 0).then_some(set),
                    usize::try_from(libc::sched_getcpu()).ok(),
                )
            };
            Start { allowed, home }
        }

        /// Points worker `index` (1, 2, … : 0 is the calling thread) at the index-th allowed
        /// CPU after the home CPU; whether it did (else the scheduler places the worker).
        pub fn point<T>(&self, handle: &std::thread::JoinHandle<T>, index: usize) -> bool {
            let (Some(allowed), Some(home)) = (self.allowed, self.home) else {
                return false;
            };
            let max = 8 * std::mem::size_of::<libc::cpu_set_t>();
            // SAFETY: CPU_ISSET reads a bit of a set we own, for an index below its size.
            let cpus: Vec<usize> = (0..max)
                .filter(|&c| unsafe { libc::CPU_ISSET(c, &allowed) })
                .collect();
            let Some(at) = cpus.iter().position(|&c| c == home) else {
                return false;
            };
            let target = cpus[(at + index) % cpus.len()];
            // SAFETY: `one` is a zeroed bit set with one bit set below its size.
            let one = unsafe {
                let mut one: libc::cpu_set_t = std::mem::zeroed();
                libc::CPU_SET(target, &mut one);
                one
            };
            set_affinity(handle, &one)
        }

        /// Gives a worker the whole CPU set back.
        pub fn release<T>(&self, handle: &std::thread::JoinHandle<T>) {
            if let Some(allowed) = &self.allowed {
                set_affinity(handle, allowed);
            }
        }

        /// Gives the calling (just started) worker the whole CPU set back.
        pub fn release_current(&self) {
            if let Some(allowed) = &self.allowed {
                // SAFETY: the set is ours and its size is passed; 0 is the calling thread.
                unsafe {
                    libc::sched_setaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), allowed);
                }
            }
        }
    }
}

#[cfg(not(target_os = "linux"))]
mod placement {
    /// Elsewhere the scheduler places the workers.
    #[derive(Clone)]
    pub struct Start;

    impl Start {
        pub fn here() -> Start {
            Start
        }
        pub fn point<T>(&self, _: &std::thread::JoinHandle<T>, _: usize) -> bool {
            false
        }
        pub fn release<T>(&self, _: &std::thread::JoinHandle<T>) {}
        pub fn release_current(&self) {}
    }
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    /// The CPUs the calling thread may run on.
    fn allowed_now() -> Vec<usize> {
        // SAFETY: as in `Start::here`: a bit set we own, its size passed, bits read in range.
        unsafe {
            let mut set: libc::cpu_set_t = std::mem::zeroed();
            assert_eq!(
                libc::sched_getaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &mut set),
                0
            );
            (0..8 * std::mem::size_of::<libc::cpu_set_t>())
                .filter(|&c| libc::CPU_ISSET(c, &set))
                .collect()
        }
    }

    /// Pointed at a CPU only to start: every worker, once running, may run anywhere the
    /// process may, and the pool does its work in order.
    #[test]
    fn workers_run_with_the_whole_cpu_set() {
        use rayon::prelude::*;
        let whole = allowed_now();
        let pool = super::check_pool().unwrap();
        assert_eq!(pool.current_num_threads(), rayon::current_num_threads());
        let seen = pool.broadcast(|_| allowed_now());
        assert_eq!(seen.len(), pool.current_num_threads());
        assert!(
            seen.iter().all(|s| *s == whole),
            "{seen:?} against {whole:?}"
        );
        let squares: Vec<u64> =
            pool.install(|| (0..1000u64).into_par_iter().map(|i| i * i).collect());
        assert_eq!(squares, (0..1000u64).map(|i| i * i).collect::<Vec<_>>());
        assert_eq!(allowed_now(), whole, "the calling thread keeps its set");
    }
}
