//! `compile` over a `_Z.txt` the machinist filled in (issue 31): the file stays as it is when
//! the new set names the same probes; otherwise it is kept beside as `NAME_Z.1.txt` (the
//! next free number: an earlier one is never replaced), and the new `_Z.txt` gets the
//! values of the probe points that did not change. Core's `adjustz::plan_new_z` decides;
//! this reads the old files and keeps the old one.

use millpath_core::diag::{Diagnostic, FileRef, Msg, Origin};
use millpath_core::probe::adjustz::{self, Aside, OldZ, Unreadable, ZPlan};
use std::io::{BufRead, Read};
use std::path::{Path, PathBuf};

/// What compile writes in place of the old `_Z.txt`.
pub enum ZWrite {
    /// The set as compile made it: the old file holds nothing the new one does not.
    AsIs,
    /// The old file stays exactly as it is and the new one is not written: it holds the
    /// measured values of the same probes.
    Keep,
    /// The old file is kept as `side` (already there); the new `_Z.txt` is `content`;
    /// `said` is the warning that says so.
    Replace {
        content: String,
        side: PathBuf,
        said: Diagnostic,
    },
}

/// Largest old `_Z.txt` or probing program read (a `_Z.txt` of 4000 grid points is 160 KB);
/// a larger one is kept aside unread.
const MAX_READ: u64 = 64 << 20;
/// Side files tried: `NAME_Z.1.txt` … `NAME_Z.999.txt`.
const MAX_SIDE: usize = 999;

/// At most [`MAX_READ`] bytes of `path`.
fn read_bounded(path: &Path) -> Result<Vec<u8>, Unreadable> {
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_READ + 1).read_to_end(&mut bytes))
        .map_err(|e| Unreadable::Io(e.to_string()))?;
    if bytes.len() as u64 > MAX_READ {
        return Err(Unreadable::TooLarge(MAX_READ >> 20));
    }
    Ok(bytes)
}

/// The probe points of the old probing program beside `z`, when it carries the digest of
/// the old `_Z.txt` (`z_bytes`) with the old `_Clean.gcode`. When both old programs carry
/// the new set's digest `ours` and the old `_Z.txt` names the new one's probes, that is
/// the same set, and the old `_Clean.gcode` (it may be large) is not read again.
fn old_points(
    prefix: &str,
    z_bytes: &[u8],
    new_z: &str,
    ours: Option<&str>,
) -> Option<Vec<adjustz::ProbePoint>> {
    let probing = read_bounded(Path::new(&format!("{prefix}_Probing.gcode"))).ok()?;
    let probing = String::from_utf8(probing).ok()?;
    let stored = adjustz::stored_digest(&probing)?;
    let z = millpath_core::load::text_file::decode(z_bytes).ok()?;
    let clean = format!("{prefix}_Clean.gcode");
    let clean_head = millpath_core::stage::file_head(Path::new(&clean), 3);
    let same_set = ours == Some(stored)
        && adjustz::stored_digest(&clean_head) == Some(stored)
        && adjustz::set_digest(&z.text, "") == adjustz::set_digest(new_z, "");
    if same_set {
        return Some(adjustz::probe_points(&probing));
    }
    let clean = std::fs::File::open(clean).ok()?;
    let mut failed = false;
    let lines = std::io::BufReader::new(clean)
        .lines()
        .map_while(|l| l.map_err(|_| failed = true).ok());
    let digest = adjustz::set_digest_lines(&z.text, lines);
    (!failed && digest == stored).then(|| adjustz::probe_points(&probing))
}

/// `NAME_Z.N.txt` beside `z` for the first free N.
fn free_side(z: &Path) -> Option<PathBuf> {
    let name = z.file_name()?.to_string_lossy();
    let stem = name.strip_suffix(".txt").unwrap_or(&name);
    (1..=MAX_SIDE)
        .map(|n| z.with_file_name(format!("{stem}.{n}.txt")))
        .find(|p| std::fs::symlink_metadata(p).is_err())
}

/// Keeps the file `z` as `side` too: a second name for the same file (its bytes, owner and
/// permissions as they are, even when it cannot be read), or else a copy of `bytes`.
fn keep_as(z: &Path, side: &Path, bytes: Option<&[u8]>) -> std::io::Result<()> {
    let linked = std::fs::hard_link(z, side);
    match (linked, bytes) {
        (Ok(()), _) => Ok(()),
        (Err(e), None) => Err(e),
        (Err(_), Some(b)) => {
            use std::io::Write;
            let mut f = std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(side)?;
            f.write_all(b).and_then(|()| f.sync_all()).inspect_err(|_| {
                let _ = std::fs::remove_file(side);
            })
        }
    }
}

/// `pathdxf2gcode` over a `_Z.txt` the machinist filled in: it writes the reference's file
/// (the values empty, byte for byte the reference's), so the old one is kept beside first as
/// `NAME_Z.N.txt`. `Ok(None)`: nothing to keep (no file, the same text, or every line
/// unfilled, `#51=`); `Ok(Some(side))`: kept there; `Err`: it could not be kept (nothing of
/// the drawing may be written then).
pub fn keep_filled_for_reference(z: &Path, new_z: &str) -> Result<Option<PathBuf>, Diagnostic> {
    if !std::fs::metadata(z).is_ok_and(|m| m.is_file()) {
        return Ok(None);
    }
    let bytes = read_bounded(z).ok();
    let text = bytes
        .as_deref()
        .and_then(|b| millpath_core::load::text_file::decode(b).ok())
        .map(|d| d.text.replace("\r\n", "\n"));
    // unreadable, or any line that is more than `… #n=`: a value, or not a _Z.txt line
    let filled = text.as_deref().is_none_or(|t| {
        t.lines()
            .map(str::trim_end)
            .any(|l| !l.is_empty() && !l.ends_with('='))
    });
    if !filled || text.as_deref() == Some(new_z) {
        return Ok(None);
    }
    let side = free_side(z);
    let kept = match &side {
        Some(s) => keep_as(z, s, bytes.as_deref()).map_err(|e| e.to_string()),
        None => Err(format!("{MAX_SIDE} earlier copies")),
    };
    let side = side.unwrap_or_else(|| z.with_extension("N.txt"));
    match kept {
        Ok(()) => Ok(Some(side)),
        Err(e) => Err(Diagnostic::error(
            Msg::ZCannotKeepAside,
            Origin::File(FileRef::new(z.to_path_buf())),
            millpath_core::args![z.display(), side.display(), e],
        )),
    }
}

/// What to write for the `_Z.txt` at `z` (compile's new one: `new_z`, its probing program
/// `new_probing`). `Err`: the old file may hold measured values and could not be kept beside;
/// nothing of the set may be written. `ours`: the new set's digest; `lang`: the words of an
/// unreadable file's reason.
pub fn prepare(
    z: &Path,
    new_z: &str,
    new_probing: &str,
    ours: Option<&str>,
    lang: millpath_core::Lang,
) -> Result<ZWrite, Diagnostic> {
    // nothing there, or something no write can replace (a folder: the set write says so)
    if !std::fs::metadata(z).is_ok_and(|m| m.is_file()) {
        return Ok(ZWrite::AsIs);
    }
    let bytes = read_bounded(z);
    let prefix = z.to_string_lossy();
    let prefix = prefix.strip_suffix("_Z.txt").unwrap_or(&prefix).to_string();
    // the old set's files are read only when its values are to be compared
    let points = || old_points(&prefix, bytes.as_deref().ok()?, new_z, ours);
    let clean_head =
        millpath_core::stage::file_head(Path::new(&format!("{prefix}_Clean.gcode")), 3);
    let old = OldZ {
        bytes: bytes.as_deref().map_err(Clone::clone),
        points: &points,
        same_set: ours.is_some() && adjustz::stored_digest(&clean_head) == ours,
    };
    let plan = adjustz::plan_new_z(&old, new_z, new_probing);
    let (content, why) = match plan {
        ZPlan::Write => return Ok(ZWrite::AsIs),
        ZPlan::Keep { .. } => return Ok(ZWrite::Keep),
        ZPlan::Aside { content, why } => (content, why),
    };
    let origin = Origin::File(FileRef::new(z.to_path_buf()));
    let side = free_side(z);
    let kept = match &side {
        Some(s) => keep_as(z, s, bytes.as_deref().ok()).map_err(|e| e.to_string()),
        None => Err(match lang {
            millpath_core::Lang::En => format!("{MAX_SIDE} earlier copies"),
            millpath_core::Lang::De => format!("{MAX_SIDE} frühere Kopien"),
        }),
    };
    let side_name = side.clone().unwrap_or_else(|| z.with_extension("N.txt"));
    if let Err(e) = kept {
        return Err(Diagnostic::error(
            Msg::ZCannotKeepAside,
            origin,
            millpath_core::args![z.display(), side_name.display(), e],
        ));
    }
    let (zs, ss) = (z.display(), side_name.display());
    let said = match why {
        Aside::Compared {
            values,
            carried,
            unfilled,
        } => Diagnostic::warning(
            Msg::ZKeptAside,
            origin,
            millpath_core::args![zs, ss, values, carried, unfilled],
        ),
        Aside::Unchecked { values } => Diagnostic::warning(
            Msg::ZKeptAsideUnchecked,
            origin,
            millpath_core::args![zs, ss, values],
        ),
        Aside::Unreadable(u) => Diagnostic::warning(
            Msg::ZKeptAsideUnreadable,
            origin,
            millpath_core::args![zs, ss, u.describe(lang)],
        ),
    };
    Ok(ZWrite::Replace {
        content,
        side: side_name,
        said,
    })
}
