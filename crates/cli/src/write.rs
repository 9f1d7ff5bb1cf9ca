//! Atomic output: a G-code file is either complete or not there at all.

use std::io::Write;
use std::path::Path;

/// Writes `content` to a temporary file beside `path` and renames it into place.
pub fn write_atomic(path: &Path, content: &str) -> std::io::Result<()> {
    write_atomic_bytes(path, content.as_bytes())
}

/// [`write_atomic`] for bytes (pictures).
pub fn write_atomic_bytes(path: &Path, content: &[u8]) -> std::io::Result<()> {
    let tmp = sibling(path, "tmp");
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(content)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// A sibling of `path` named `.NAME.<pid>.<what>`, for temporaries and kept old files.
fn sibling(path: &Path, what: &str) -> std::path::PathBuf {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    dir.join(format!(".{name}.{}.{what}", std::process::id()))
}

/// Writes the files of one drawing all or none: every content into a temporary file first,
/// then the old files moved aside and the new ones renamed into place. When any step fails,
/// the new files are taken away and the old ones put back, so the folder holds the old set
/// or the new one, never a mix. `Err` names the file that failed.
pub fn write_set(files: &[(&Path, &str)]) -> Result<(), (std::path::PathBuf, std::io::Error)> {
    let mut temps = Vec::new();
    let cleanup = |temps: &[std::path::PathBuf]| {
        for t in temps {
            let _ = std::fs::remove_file(t);
        }
    };
    for (path, content) in files {
        let tmp = sibling(path, "tmp");
        let result = (|| {
            let mut f = std::fs::File::create(&tmp)?;
            f.write_all(content.as_bytes())?;
            f.sync_all()
        })();
        temps.push(tmp);
        if let Err(e) = result {
            cleanup(&temps);
            return Err((path.to_path_buf(), e));
        }
    }
    // (target, its old file moved aside, new file in place)
    let mut done: Vec<(&Path, Option<std::path::PathBuf>, bool)> = Vec::new();
    let mut failure = None;
    for ((path, _), tmp) in files.iter().zip(&temps) {
        let old = sibling(path, "old");
        let kept = if let Ok(meta) = std::fs::symlink_metadata(path) {
            // a folder in the way is never moved: the set is not written
            let moved = if meta.is_dir() {
                Err(std::io::Error::new(
                    std::io::ErrorKind::IsADirectory,
                    "is a directory",
                ))
            } else {
                std::fs::rename(path, &old)
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
        if let Err(e) = std::fs::rename(tmp, path) {
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
            Ok(())
        }
        Some(err) => {
            // back to the old set, newest step first
            for (path, kept, placed) in done.iter().rev() {
                if *placed {
                    let _ = std::fs::remove_file(path);
                }
                if let Some(old) = kept {
                    let _ = std::fs::rename(old, path);
                }
            }
            cleanup(&temps);
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
    fn a_set_is_written_whole() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("x_Z.txt"), dir.path().join("x_Clean.gcode"));
        std::fs::write(&a, "old z").unwrap();
        write_set(&[(&a, "new z"), (&b, "new clean")]).unwrap();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "new z");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "new clean");
        assert_eq!(names(dir.path()), ["x_Clean.gcode", "x_Z.txt"]);
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
        let err = write_set(&[(&a, "new probing"), (&b, "new z"), (&c, "new clean")]);
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
        assert!(write_set(&[(&a, "new probing"), (&c, "new clean")]).is_err());
        assert!(!a.exists());
        assert_eq!(names(dir.path()), ["x_Clean.gcode", "x_Z.txt"]);
    }
}
