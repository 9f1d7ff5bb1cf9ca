//! Temporary files of an earlier run that was killed before it could remove them (SIGKILL,
//! a power loss; an interrupt removes its own, `interrupt.rs`): `compile` sweeps those of
//! the outputs it is about to write. A file is taken only when it is provably ours and
//! dead: its name is one `core::stage::sibling` gives an output of this compile
//! (`.NAME.PID.stage1`, `..NAME.PID.stage1.PID.stage2`, `.NAME.PID.tmp`), and the process
//! PID is not running (or is this one, which has not made it): asked of the system on Unix
//! (kill 0) and on Windows (OpenProcess). An old output moved aside
//! (`.NAME.PID.old`) is the user's previous file: it is never swept.

use millpath_core::temporaries;
use std::collections::HashMap;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// The folders read so far in this run: each folder's temporary-looking names, listed once.
#[derive(Default)]
pub struct Sweeper {
    listed: HashMap<PathBuf, Vec<OsString>>,
}

impl Sweeper {
    /// Removes the dead temporaries of `output` (the file a compile is about to write).
    /// Returns how many were removed.
    pub fn sweep(&mut self, output: &Path) -> usize {
        let dir = output
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let Some(name) = output.file_name().and_then(|n| n.to_str()) else {
            return 0;
        };
        let names = self.listed.entry(dir.to_path_buf()).or_insert_with(|| {
            std::fs::read_dir(dir)
                .map(|entries| {
                    entries
                        .filter_map(Result::ok)
                        .map(|e| e.file_name())
                        .filter(|n| n.to_str().is_some_and(looks_temporary))
                        .collect()
                })
                .unwrap_or_default()
        });
        let mut removed = 0;
        names.retain(|n| {
            let Some(pid) = n.to_str().and_then(|n| temporary_of(n, name)) else {
                return true;
            };
            let path = dir.join(n);
            if !dead(pid, &path) {
                return true;
            }
            let gone = std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file())
                && std::fs::remove_file(&path).is_ok();
            removed += usize::from(gone);
            !gone
        });
        removed
    }
}

/// A name `sibling` could have given a temporary (listed once, matched per output later).
fn looks_temporary(name: &str) -> bool {
    name.starts_with('.')
        && (name.ends_with(".stage1") || name.ends_with(".stage2") || name.ends_with(".tmp"))
}

/// The process id in `name` when it is a temporary of the output `output_name`.
fn temporary_of(name: &str, output_name: &str) -> Option<u32> {
    let digits = |s: &str| -> Option<u32> {
        (!s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()))
            .then(|| s.parse().ok())
            .flatten()
    };
    // .NAME.PID.stage1 / .NAME.PID.tmp
    if let Some(rest) = name
        .strip_prefix('.')
        .and_then(|r| r.strip_prefix(output_name))
        .and_then(|r| r.strip_prefix('.'))
    {
        if let Some(pid) = rest
            .strip_suffix(".stage1")
            .or_else(|| rest.strip_suffix(".tmp"))
            .and_then(digits)
        {
            return Some(pid);
        }
    }
    // ..NAME.PID.stage1.PID.stage2 (the staged file with the set's digest stamped in)
    let rest = name
        .strip_prefix("..")?
        .strip_prefix(output_name)?
        .strip_prefix('.')?
        .strip_suffix(".stage2")?;
    let (first, second) = rest.split_once(".stage1.")?;
    let pid = digits(first)?;
    (digits(second)? == pid).then_some(pid)
}

/// Whether the process `pid` that made `path` is gone (unknown counts as alive).
fn dead(pid: u32, path: &Path) -> bool {
    if pid == std::process::id() {
        // a process id used again (containers start at the same few): not made by this run
        return !temporaries::is_live(path);
    }
    running(pid) == Some(false)
}

/// Whether a process `pid` runs now; `None` where it cannot be told.
#[cfg(unix)]
fn running(pid: u32) -> Option<bool> {
    let pid = libc::pid_t::try_from(pid).ok()?;
    if pid <= 0 {
        return None;
    }
    // SAFETY: signal 0 only asks whether the process exists (no signal is sent)
    let answer = unsafe { libc::kill(pid, 0) };
    if answer == 0 {
        return Some(true);
    }
    match std::io::Error::last_os_error().raw_os_error() {
        Some(libc::ESRCH) => Some(false),
        // EPERM: it runs, as another user
        _ => Some(true),
    }
}

/// Whether a process `pid` runs now (Windows). Only a clear "no such process" is `false`:
/// OpenProcess refuses an id no process has with ERROR_INVALID_PARAMETER; a process object
/// still open somewhere after its process ended answers an exit code other than
/// STILL_ACTIVE. Any other answer (access denied: it runs, as another user) counts as
/// running, and so does a process that exited with code 259 (STILL_ACTIVE): its file stays.
/// An id given again to another process also counts as running: only a dead file is taken.
#[cfg(windows)]
fn running(pid: u32) -> Option<bool> {
    use windows_sys::Win32::Foundation::{
        CloseHandle, GetLastError, ERROR_INVALID_PARAMETER, STILL_ACTIVE,
    };
    use windows_sys::Win32::System::Threading::{
        GetExitCodeProcess, OpenProcess, PROCESS_QUERY_LIMITED_INFORMATION,
    };
    if pid == 0 {
        // the System Idle Process
        return None;
    }
    // SAFETY: plain Win32 calls with no pointers but the exit code's, which lives here; the
    // handle is closed before returning
    unsafe {
        let handle = OpenProcess(PROCESS_QUERY_LIMITED_INFORMATION, 0, pid);
        if handle.is_null() {
            return Some(GetLastError() != ERROR_INVALID_PARAMETER);
        }
        let mut code = 0u32;
        let asked = GetExitCodeProcess(handle, &mut code);
        CloseHandle(handle);
        if asked == 0 {
            return Some(true);
        }
        Some(code == STILL_ACTIVE as u32)
    }
}

/// Elsewhere only this process's own leftovers are swept (see [`dead`]).
#[cfg(not(any(unix, windows)))]
fn running(_pid: u32) -> Option<bool> {
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_our_names_of_that_output() {
        let o = "1000_Milling.gcode";
        assert_eq!(temporary_of(".1000_Milling.gcode.42.stage1", o), Some(42));
        assert_eq!(temporary_of(".1000_Milling.gcode.42.tmp", o), Some(42));
        assert_eq!(
            temporary_of("..1000_Milling.gcode.42.stage1.42.stage2", o),
            Some(42)
        );
        for other in [
            ".1000_Milling.gcode.42.old",
            ".1000_Milling.gcode.x42.stage1",
            ".1000_Milling.gcode..stage1",
            ".11000_Milling.gcode.42.stage1",
            ".1000_Milling.gcode.42.43.stage1",
            "..1000_Milling.gcode.42.stage1.43.stage2",
            "1000_Milling.gcode.42.stage1",
            ".1000_Milling.gcode.99999999999.tmp",
        ] {
            assert_eq!(temporary_of(other, o), None, "{other}");
        }
    }

    // Windows: tests/windows/cli.sh, under Wine
    #[cfg(unix)]
    #[test]
    fn dead_leftovers_go_and_live_ones_stay() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("7_Milling.gcode");
        let me = std::process::id();
        // a process that ran and ended: its id is free (until the system gives it again)
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let gone = child.id();
        child.wait().unwrap();
        let names = [
            format!(".7_Milling.gcode.{gone}.stage1"),
            format!("..7_Milling.gcode.{gone}.stage1.{gone}.stage2"),
            format!(".7_Milling.gcode.{me}.tmp"),
            format!(".7_Milling.gcode.{gone}.old"),
            format!(".8_Milling.gcode.{gone}.stage1"),
            ".7_Milling.gcode.1.tmp".to_string(),
        ];
        for n in &names {
            std::fs::write(dir.path().join(n), "x").unwrap();
        }
        // one of this run's own, registered
        let ours = dir.path().join(format!(".7_Milling.gcode.{me}.stage1"));
        temporaries::create(&ours).unwrap();
        assert_eq!(Sweeper::default().sweep(&out), 3);
        let left: Vec<bool> = names.iter().map(|n| dir.path().join(n).exists()).collect();
        // the old output, another output's file and pid 1's (running) stay
        assert_eq!(left, [false, false, false, true, true, true]);
        assert!(ours.exists());
        temporaries::remove(&ours);
    }
}
