//! The output files one `compile` run has written, by drawing. A path's `R` value is part
//! of its output names (`a.dxf` with `R_X` writes `a_X_Milling.gcode`, as `a_X.dxf` without
//! one does; an `R` with `/..` leads into another folder), and it is known only once the
//! drawing is compiled: a later drawing of the run whose outputs have a name an earlier one
//! wrote is not written, so that no program silently replaces another's. Names compare as
//! the file system does (case ignored on Windows and macOS); one drawing named twice is no
//! such pair.

use millpath_core::Origin;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The drawing that wrote an output.
#[derive(Debug, Clone, PartialEq)]
pub struct Writer {
    /// As the command line (or the folder's listing) named it.
    pub input: PathBuf,
    /// Its path's start marker (where its `R` is given).
    pub start: Option<Origin>,
    canonical: PathBuf,
}

/// Output file (its [`key`]) → the drawing that wrote it.
#[derive(Default)]
pub struct Claims(HashMap<PathBuf, Writer>);

impl Claims {
    /// The first of `outputs` that another drawing of this run wrote, with that drawing.
    pub fn taken<'a>(
        &self,
        input: &Path,
        outputs: impl IntoIterator<Item = &'a Path>,
    ) -> Option<(&'a Path, &Writer)> {
        let me = canonical(input);
        outputs.into_iter().find_map(|o| {
            self.0
                .get(&key(o))
                .filter(|w| w.canonical != me)
                .map(|w| (o, w))
        })
    }

    /// `input` (its path's start marker at `start`) wrote `outputs`.
    pub fn claim<'a>(
        &mut self,
        input: &Path,
        start: Option<Origin>,
        outputs: impl IntoIterator<Item = &'a Path>,
    ) {
        let writer = Writer {
            input: input.to_path_buf(),
            start,
            canonical: canonical(input),
        };
        for o in outputs {
            self.0.insert(key(o), writer.clone());
        }
    }
}

/// The file as the file system finds it: its folder resolved (`..`, links), the name as
/// written (in lower case where names ignore case).
fn key(file: &Path) -> PathBuf {
    let name = file.file_name().map(|n| n.to_string_lossy().into_owned());
    let name = match name {
        Some(n) if cfg!(any(windows, target_os = "macos")) => n.to_lowercase(),
        Some(n) => n,
        None => return file.to_path_buf(),
    };
    let dir = match file.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    dunce::canonicalize(dir)
        .unwrap_or_else(|_| dir.to_path_buf())
        .join(name)
}

fn canonical(input: &Path) -> PathBuf {
    dunce::canonicalize(input).unwrap_or_else(|_| input.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_name_another_drawing_wrote_is_taken_but_not_by_the_same_drawing() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        for f in ["a.mpath", "a_X.mpath"] {
            std::fs::write(d.join(f), "").unwrap();
        }
        std::fs::create_dir(d.join("sub")).unwrap();
        let mut claims = Claims::default();
        let out = d.join("a_X_Milling.gcode");
        claims.claim(&d.join("a.mpath"), None, [out.as_path()]);
        let other = d.join("a_X.mpath");
        let (file, by) = claims.taken(&other, [out.as_path()]).unwrap();
        assert_eq!(
            (file, by.input.as_path()),
            (out.as_path(), d.join("a.mpath").as_path())
        );
        // the same folder reached another way
        let around = d.join("sub/../a_X_Milling.gcode");
        assert!(claims.taken(&other, [around.as_path()]).is_some());
        // the drawing itself, named another way
        let again = d.join("sub/../a.mpath");
        assert!(claims.taken(&again, [out.as_path()]).is_none());
        assert!(claims
            .taken(&other, [d.join("a_Milling.gcode").as_path()])
            .is_none());
    }
}
