//! An interrupted run leaves no temporary file: Ctrl-C, SIGTERM or SIGHUP (Windows: Ctrl-C,
//! Ctrl-Break, closing the console) removes the files registered in core's `temporaries.rs`
//! and ends the process with status 130; so does a panic (then with the panic's status).
//! A run killed without a chance to clean up (SIGKILL, power loss) leaves its files to the
//! next compile of the same outputs (`stale.rs`).

use millpath_core::temporaries;

/// The status of a run ended by an interrupt (128 + SIGINT, as shells report Ctrl-C).
pub const INTERRUPTED: i32 = 130;

/// Installs the handler for the commands that write files. A signal the run was started
/// with ignored stays ignored (`nohup`, a background job of a script).
pub fn install() {
    let ignored = ignored_now();
    // an error (a handler set already) leaves the default: the process ends at once
    let _ = ctrlc::set_handler(|| {
        let _held = temporaries::remove_all_and_hold();
        exit_now(INTERRUPTED);
    });
    ignore_again(&ignored);
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        drop(temporaries::remove_all_and_hold());
        default(info);
    }));
}

/// The signals of the handler that are ignored now.
#[cfg(target_os = "linux")]
fn ignored_now() -> Vec<libc::c_int> {
    [libc::SIGINT, libc::SIGTERM, libc::SIGHUP]
        .into_iter()
        .filter(|&sig| {
            // SAFETY: reads the disposition of `sig` into a zeroed struct of our own
            unsafe {
                let mut old: libc::sigaction = std::mem::zeroed();
                libc::sigaction(sig, std::ptr::null(), &mut old) == 0
                    && old.sa_sigaction == libc::SIG_IGN
            }
        })
        .collect()
}

#[cfg(target_os = "linux")]
fn ignore_again(signals: &[libc::c_int]) {
    for &sig in signals {
        // SAFETY: sets the disposition of one signal to "ignore"
        unsafe {
            libc::signal(sig, libc::SIG_IGN);
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn ignored_now() -> Vec<i32> {
    Vec::new()
}

#[cfg(not(target_os = "linux"))]
fn ignore_again(_: &[i32]) {}

/// Ends the process without waiting for other threads (the compile still running).
fn exit_now(code: i32) -> ! {
    #[cfg(target_os = "linux")]
    {
        use std::io::Write;
        let _ = std::io::stderr().lock().flush();
        // SAFETY: `_exit` takes a plain integer and ends the process; the files it leaves
        // open are the temporaries just removed and the user's outputs, which are only
        // renamed (never written in place).
        unsafe { libc::_exit(code) }
    }
    #[cfg(not(target_os = "linux"))]
    std::process::exit(code)
}
