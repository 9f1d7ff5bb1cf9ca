//! The temporary files this process has beside a user's outputs (a staged program, a
//! temporary of an atomic write), so that an interrupted run removes them: the command
//! line's signal handler calls [`remove_all_and_hold`] and ends the process. Creating one
//! and the renames that put a set in place ([`commit`]) hold the same lock, so a signal
//! never lands between a file's creation and its registration, nor in the middle of a set
//! being put in place (the folder keeps the old set or the new one).

use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn live() -> MutexGuard<'static, Vec<PathBuf>> {
    // a panic elsewhere while it was held leaves the list as it was: still right
    LIVE.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The registered temporaries while a set is put in place ([`commit`]).
pub struct Live<'a>(&'a mut Vec<PathBuf>);

impl Live<'_> {
    /// `path` is no temporary any more (renamed into place, or removed).
    pub fn forget(&mut self, path: &Path) {
        self.0.retain(|p| p != path);
    }

    /// Removes the temporary `path` and forgets it.
    pub fn remove(&mut self, path: &Path) {
        let _ = std::fs::remove_file(path);
        self.forget(path);
    }
}

/// Creates (truncates) the temporary file `path`, registered before anyone can see it.
pub fn create(path: &Path) -> std::io::Result<File> {
    let mut list = live();
    let file = File::create(path)?;
    list.push(path.to_path_buf());
    Ok(file)
}

/// Removes the temporary `path` (if it is there) and forgets it.
pub fn remove(path: &Path) {
    Live(&mut live()).remove(path);
}

/// Runs `f` (the renames that put files in place) with the list held: a signal that comes
/// meanwhile is handled once `f` is done.
pub fn commit<T>(f: impl FnOnce(&mut Live) -> T) -> T {
    f(&mut Live(&mut live()))
}

/// Whether `path` is a temporary of this process (a sweep of stale files leaves it).
pub fn is_live(path: &Path) -> bool {
    live().iter().any(|p| p == path)
}

/// Removes every registered temporary and keeps the list held, so that no other thread
/// makes a new one: for the end of the process (a signal, a panic).
pub fn remove_all_and_hold() -> MutexGuard<'static, Vec<PathBuf>> {
    let mut list = live();
    for p in list.drain(..) {
        let _ = std::fs::remove_file(p);
    }
    list
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registered_files_are_removed_and_committed_ones_stay() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join(".a.1.tmp"), dir.path().join(".b.1.tmp"));
        create(&a).unwrap();
        create(&b).unwrap();
        assert!(is_live(&a) && is_live(&b));
        commit(|live| {
            std::fs::rename(&b, dir.path().join("b")).unwrap();
            live.forget(&b);
        });
        // (not `remove_all_and_hold`: other tests of this process stage files meanwhile)
        remove(&a);
        assert!(!a.exists() && !is_live(&a));
        assert!(dir.path().join("b").exists());
        // a file that cannot be created is not registered
        assert!(create(&dir.path().join("missing/x")).is_err());
        assert!(!is_live(&dir.path().join("missing/x")));
    }
}
