//! Atomic output: a G-code file is either complete or not there at all.
//!
//! Atomic output files; `write_set`: a drawing's files all or none (temporaries, or core's staged
//! program as it is, old files moved aside, put back on a failure part-way); a rename refused
//! because another program holds the file open (Windows: a G-code sender) is tried again for a
//! second, then reported as `HELD_OPEN` naming the file.
//! Temporaries are registered (core's `temporaries.rs`), so an interrupted run leaves none.

use millpath_core::stage::sibling;
use millpath_core::temporaries;
use std::io::Write;
use std::path::Path;
use std::time::Duration;

/// What a rename answers when another program holds the file open: on Windows a G-code
/// sender or an editor keeps the program open without letting others delete it, and a
/// rename onto it or away from it fails. Shown in `Cannot write FILE: …` (German in
/// `diag::os_error_text`).
pub const HELD_OPEN: &str =
    "another program has the file open (a G-code sender or an editor?): close it there and run again";

/// Why a read-only file is not replaced (German in `diag::os_error_text`): the user made
/// it so on purpose (a proven program, a measured `_Z.txt`), and a replacement would be
/// writable again.
pub const READ_ONLY: &str = "read-only: not replaced (make it writable to replace it)";

/// `Err` naming [`READ_ONLY`] when `path` is a read-only file (Unix: no write bit; Windows:
/// the read-only attribute); root, who could write it, is refused alike.
fn refuse_read_only(path: &Path) -> std::io::Result<()> {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_file() && m.permissions().readonly() => Err(std::io::Error::new(
            std::io::ErrorKind::PermissionDenied,
            READ_ONLY,
        )),
        _ => Ok(()),
    }
}

/// Why a read-only output of an earlier run is not removed (German in `diag::os_error_text`).
pub const READ_ONLY_KEPT: &str = "read-only: not removed (make it writable to remove it)";

/// Removes a user's file that an earlier run wrote (an output a new one no longer stands
/// behind), unless it is read-only ([`READ_ONLY_KEPT`]).
pub fn remove_output(path: &Path) -> std::io::Result<()> {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_file() && m.permissions().readonly() => Err(std::io::Error::new(
            std::io::ErrorKind::PermissionDenied,
            READ_ONLY_KEPT,
        )),
        _ => std::fs::remove_file(path),
    }
}

/// Whether `e` says that another program holds the file open (Windows: sharing or lock
/// violation; access denied on an existing plain file that is not read-only).
fn held_open(e: &std::io::Error, target: &Path) -> bool {
    const SHARING_VIOLATION: i32 = 32;
    const LOCK_VIOLATION: i32 = 33;
    const ACCESS_DENIED: i32 = 5;
    if !cfg!(windows) {
        return false;
    }
    match e.raw_os_error() {
        Some(SHARING_VIOLATION | LOCK_VIOLATION) => true,
        Some(ACCESS_DENIED) => std::fs::metadata(target)
            .map(|m| m.is_file() && !m.permissions().readonly())
            .unwrap_or(false),
        _ => false,
    }
}

/// `std::fs::rename`, tried again a few times (a second in all) while the user's `file` is
/// held open: virus scanners and indexers hold a file for a moment. A program that keeps it
/// open gets [`HELD_OPEN`] naming the reason, the OS error kept in the text.
fn rename(from: &Path, to: &Path, file: &Path) -> std::io::Result<()> {
    rename_with(from, to, file, held_open, Duration::from_millis(100))
}

/// [`rename`] with the test for a held file and the pause as parameters (unit tests).
fn rename_with(
    from: &Path,
    to: &Path,
    file: &Path,
    is_held: fn(&std::io::Error, &Path) -> bool,
    pause: Duration,
) -> std::io::Result<()> {
    const TRIES: u32 = 10;
    let mut tries = 0;
    loop {
        match std::fs::rename(from, to) {
            Ok(()) => return Ok(()),
            Err(e) if is_held(&e, file) => {
                tries += 1;
                if tries >= TRIES {
                    return Err(std::io::Error::new(e.kind(), format!("{HELD_OPEN} ({e})")));
                }
                std::thread::sleep(pause);
            }
            Err(e) => return Err(e),
        }
    }
}

/// Writes `content` to a temporary file beside `path` and renames it into place.
pub fn write_atomic(path: &Path, content: &str) -> std::io::Result<()> {
    write_atomic_bytes(path, content.as_bytes())
}

/// [`write_atomic`] for bytes (pictures).
pub fn write_atomic_bytes(path: &Path, content: &[u8]) -> std::io::Result<()> {
    let target = link_target(path);
    let path = target.as_deref().unwrap_or(path);
    refuse_read_only(path)?;
    let tmp = sibling(path, "tmp");
    let result = (|| {
        let mut f = temporaries::create(&tmp)?;
        f.write_all(content)?;
        f.sync_all()
    })();
    temporaries::commit(|live| {
        let result = result.and_then(|()| rename(&tmp, path, path));
        match result {
            Ok(()) => live.forget(&tmp),
            Err(_) => live.remove(&tmp),
        }
        result
    })
}

/// The file a symbolic link `path` points to (`None`: not a link, or a link to nothing): a
/// file written in place through a link (`fmt` of a linked `.mpath`, `text2dxf --into` a
/// drawing linked from a library) changes that file and keeps the link, as an editor does;
/// a rename onto the link would replace the link by a copy and leave the file unchanged.
fn link_target(path: &Path) -> Option<std::path::PathBuf> {
    let meta = std::fs::symlink_metadata(path).ok()?;
    if !meta.file_type().is_symlink() {
        return None;
    }
    dunce::canonicalize(path).ok()
}

/// What one file of a set holds: a text, or a temporary file it was written to already
/// (core's staged program).
#[derive(Clone, Copy)]
pub enum Content<'a> {
    Text(&'a str),
    Staged(&'a Path),
}

/// Writes the files of one drawing all or none: every content into a temporary file first,
/// then the old files moved aside and the new ones renamed into place. When any step fails,
/// the new files are taken away and the old ones put back, so the folder holds the old set
/// or the new one, never a mix; a read-only file among the old ones keeps them all. `Err`
/// names the file that failed.
pub fn write_set(files: &[(&Path, Content)]) -> Result<(), (std::path::PathBuf, std::io::Error)> {
    if let Some((path, e)) = files
        .iter()
        .find_map(|(path, _)| refuse_read_only(path).err().map(|e| (path, e)))
    {
        for (_, content) in files {
            if let Content::Staged(staged) = content {
                temporaries::remove(staged);
            }
        }
        return Err((path.to_path_buf(), e));
    }
    let mut temps = Vec::new();
    let cleanup = |temps: &[std::path::PathBuf]| {
        for t in temps {
            temporaries::remove(t);
        }
    };
    for (path, content) in files {
        let (tmp, result) = match content {
            Content::Text(text) => {
                let tmp = sibling(path, "tmp");
                let result = (|| {
                    let mut f = temporaries::create(&tmp)?;
                    f.write_all(text.as_bytes())?;
                    f.sync_all()
                })();
                (tmp, result)
            }
            // written as it was generated (and synced): only renamed
            Content::Staged(staged) => (staged.to_path_buf(), Ok(())),
        };
        temps.push(tmp);
        if let Err(e) = result {
            cleanup(&temps);
            return Err((path.to_path_buf(), e));
        }
    }
    // the renames with the temporaries held: an interrupt waits until the folder holds
    // the old set or the new one
    temporaries::commit(|live| put_in_place(files, &temps, live))
}

/// The second half of [`write_set`]: the old files moved aside, the new ones renamed into
/// place (or every step undone).
fn put_in_place(
    files: &[(&Path, Content)],
    temps: &[std::path::PathBuf],
    live: &mut temporaries::Live,
) -> Result<(), (std::path::PathBuf, std::io::Error)> {
    // (target, its old file moved aside, new file in place)
    let mut done: Vec<(&Path, Option<std::path::PathBuf>, bool)> = Vec::new();
    let mut failure = None;
    for ((path, _), tmp) in files.iter().zip(temps) {
        let old = sibling(path, "old");
        let kept = if let Ok(meta) = std::fs::symlink_metadata(path) {
            // a folder in the way is never moved: the set is not written
            let moved = if meta.is_dir() {
                Err(std::io::Error::new(
                    std::io::ErrorKind::IsADirectory,
                    "is a directory",
                ))
            } else {
                rename(path, &old, path)
            };
            if let Err(e) = moved {
                failure = Some((path.to_path_buf(), e));
                break;
            }
            Some(old)
        } else {
            None
        };
        done.push((path, kept, false));
        if let Err(e) = rename(tmp, path, path) {
            failure = Some((path.to_path_buf(), e));
            break;
        }
        if let Some(last) = done.last_mut() {
            last.2 = true;
        }
    }
    match failure {
        None => {
            for (_, kept, _) in &done {
                if let Some(old) = kept {
                    let _ = std::fs::remove_file(old);
                }
            }
            for t in temps {
                live.forget(t);
            }
            Ok(())
        }
        Some(err) => {
            // back to the old set, newest step first
            for (path, kept, placed) in done.iter().rev() {
                if *placed {
                    let _ = std::fs::remove_file(path);
                }
                if let Some(old) = kept {
                    let _ = rename(old, path, path);
                }
            }
            for t in temps {
                live.remove(t);
            }
            Err(err)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_whole_files_and_leaves_no_temporaries() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a_Milling.gcode");
        write_atomic(&p, "G00\n").unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "G00\n");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        assert!(write_atomic(&dir.path().join("missing/x.gcode"), "x").is_err());
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_file_that_stays_held_gives_the_reason_after_the_retries() {
        // Wine shows the real case (tests/windows/cli.sh holds a file open with a Windows
        // program); here the retry loop and its message, with every failure taken as held
        let dir = tempfile::tempdir().unwrap();
        let (from, to) = (dir.path().join("missing.tmp"), dir.path().join("x.gcode"));
        let start = std::time::Instant::now();
        let err = rename_with(&from, &to, &to, |_, _| true, Duration::from_millis(5)).unwrap_err();
        assert!(start.elapsed() >= Duration::from_millis(45), "no retries");
        let text = err.to_string();
        assert!(text.starts_with(HELD_OPEN), "{text}");
        assert!(text.contains("os error 2"), "{text}");
        // an error that is not a held file comes back at once, as it is
        let err = rename_with(&from, &to, &to, |_, _| false, Duration::from_secs(60)).unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::NotFound);
    }

    #[test]
    fn a_set_is_written_whole() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("x_Z.txt"), dir.path().join("x_Clean.gcode"));
        std::fs::write(&a, "old z").unwrap();
        write_set(&[
            (&a, Content::Text("new z")),
            (&b, Content::Text("new clean")),
        ])
        .unwrap();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "new z");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "new clean");
        assert_eq!(names(dir.path()), ["x_Clean.gcode", "x_Z.txt"]);
    }

    #[test]
    fn a_read_only_file_keeps_the_whole_set_and_its_staged_program_goes() {
        let dir = tempfile::tempdir().unwrap();
        let p = |n: &str| dir.path().join(n);
        let (a, b, c) = (p("x_Probing.gcode"), p("x_Z.txt"), p("x_Clean.gcode"));
        for f in [&a, &b, &c] {
            std::fs::write(f, "old").unwrap();
        }
        let mut ro = std::fs::metadata(&b).unwrap().permissions();
        ro.set_readonly(true);
        std::fs::set_permissions(&b, ro).unwrap();
        let staged = sibling(&c, "stage1");
        temporaries::create(&staged).unwrap();
        let (failed, e) = write_set(&[
            (&a, Content::Text("new")),
            (&b, Content::Text("new")),
            (&c, Content::Staged(&staged)),
        ])
        .unwrap_err();
        assert_eq!((failed, e.to_string()), (b.clone(), READ_ONLY.to_string()));
        for f in [&a, &b, &c] {
            assert_eq!(std::fs::read_to_string(f).unwrap(), "old");
        }
        assert!(std::fs::metadata(&b).unwrap().permissions().readonly());
        assert_eq!(
            names(dir.path()),
            ["x_Clean.gcode", "x_Probing.gcode", "x_Z.txt"]
        );
        assert!(!temporaries::is_live(&staged));
        // alone too, and not removed as outdated
        assert_eq!(write_atomic(&b, "new").unwrap_err().to_string(), READ_ONLY);
        assert_eq!(remove_output(&b).unwrap_err().to_string(), READ_ONLY_KEPT);
        assert!(b.exists());
    }

    #[test]
    fn a_failure_part_way_brings_the_old_set_back() {
        // the third target is a directory (not empty): the rename onto it fails even for
        // root, after the first two files were already replaced
        let dir = tempfile::tempdir().unwrap();
        let p = |n: &str| dir.path().join(n);
        std::fs::write(p("x_Probing.gcode"), "old probing").unwrap();
        std::fs::write(p("x_Z.txt"), "old z").unwrap();
        std::fs::create_dir(p("x_Clean.gcode")).unwrap();
        std::fs::write(p("x_Clean.gcode/keep"), "").unwrap();
        let (a, b, c) = (p("x_Probing.gcode"), p("x_Z.txt"), p("x_Clean.gcode"));
        let err = write_set(&[
            (&a, Content::Text("new probing")),
            (&b, Content::Text("new z")),
            (&c, Content::Text("new clean")),
        ]);
        let (failed, _) = err.unwrap_err();
        assert_eq!(failed, c);
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old probing");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "old z");
        assert!(c.join("keep").exists());
        assert_eq!(
            names(dir.path()),
            ["x_Clean.gcode", "x_Probing.gcode", "x_Z.txt"]
        );
        // a new file of a failed set is taken away again
        std::fs::remove_file(&a).unwrap();
        assert!(write_set(&[
            (&a, Content::Text("new probing")),
            (&c, Content::Text("new clean"))
        ])
        .is_err());
        assert!(!a.exists());
        assert_eq!(names(dir.path()), ["x_Clean.gcode", "x_Z.txt"]);
    }
}
