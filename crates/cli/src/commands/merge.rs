//! `millpath merge BASE OURS THEIRS [PATH]`: git's merge driver (`%O %A %B %P`) for drawings
//! and MillPath texts. The result replaces OURS (git reads it back); exit 0 merged, 1 a
//! conflict, 2 an input that cannot be read. A conflicting `.mpath` gets git's markers in
//! OURS; a conflicting drawing stays byte for byte as it was and the merged text with the
//! markers goes beside it (`PATH` with `.merge.mpath`). The merge itself is
//! `millpath_history::merge`.

use crate::args::{lang_of, patterns_for, settings_for, MachineArgs};
use crate::{report, write};
use millpath_core::diag::FileRef;
use millpath_core::{args, Diagnostic, InputMode, Lang, Msg, Origin, Settings};
use millpath_history::merge::drawing::{merge_drawings, DrawingMerge, OtherChanges, Version};
use millpath_history::merge::{broken_paths_at, merge_texts, Conflict, ConflictKind, TextMerge};
use std::path::Path;

/// The largest version the driver reads (a drawing of a million elements is far smaller).
const MAX_BYTES: u64 = 256 << 20;

pub fn run(base: &Path, ours: &Path, theirs: &Path, path: Option<&Path>, m: &MachineArgs) -> u8 {
    let name = path.unwrap_or(ours);
    let lang = lang_of(m, Some(name));
    let (patterns, _) = match patterns_for(m, name) {
        Ok(p) => p,
        Err(e) => {
            eprintln!(
                "{}: {e}",
                report::severity_word(millpath_core::Severity::Error, lang)
            );
            return 2;
        }
    };
    let mut settings = settings_for(m, Some(name), false).unwrap_or_default();
    settings.lang = lang;
    // git passes an empty base when both sides added the file; a missing one reads alike
    let read = |p: &Path, may_be_missing: bool| -> Result<Vec<u8>, u8> {
        match std::fs::metadata(p) {
            Ok(md) if md.len() > MAX_BYTES => Err(fail(
                Msg::CannotRead,
                p,
                args![p.display(), format!("larger than {} MiB", MAX_BYTES >> 20)],
                lang,
            )),
            Err(e) if may_be_missing && e.kind() == std::io::ErrorKind::NotFound => Ok(Vec::new()),
            _ => {
                std::fs::read(p).map_err(|e| fail(Msg::CannotRead, p, args![p.display(), e], lang))
            }
        }
    };
    let bytes = (|| Ok::<_, u8>((read(base, true)?, read(ours, false)?, read(theirs, false)?)))();
    let Ok((b, o, t)) = bytes else {
        return 2;
    };
    // where the text stands for the compile check: the drawing's place in the work tree
    // (git's `%P`), where its subpaths and millpath.toml are
    let at = path.map(|p| {
        dunce::canonicalize(
            p.parent()
                .filter(|d| !d.as_os_str().is_empty())
                .unwrap_or(Path::new(".")),
        )
        .map(|d| d.join(p.file_name().unwrap_or_default()))
        .unwrap_or_else(|_| p.to_path_buf())
        .with_extension("mpath")
    });
    let is_drawing = name
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("dxf"));
    if is_drawing {
        let input = if m.extended {
            InputMode::Extended
        } else {
            InputMode::Reference
        };
        let (vb, vo, vt) = (
            Version {
                bytes: &b,
                file: FileRef::new(base.to_path_buf()),
            },
            Version {
                bytes: &o,
                file: FileRef::new(ours.to_path_buf()),
            },
            Version {
                bytes: &t,
                file: FileRef::new(theirs.to_path_buf()),
            },
        );
        match merge_drawings(&vb, &vo, &vt, &patterns, input, &settings, at.as_deref()) {
            Err(diags) => {
                diags
                    .iter()
                    .for_each(|d| eprintln!("{}", report::human(d, lang)));
                2
            }
            Ok(DrawingMerge::Merged(None)) => 0,
            Ok(DrawingMerge::Merged(Some(dxf))) => write_ours(ours, &dxf, lang),
            Ok(DrawingMerge::Conflict {
                text,
                other,
                broken,
            }) => {
                // our drawing is left as it is; the merged text goes beside it
                let beside = name.with_extension("merge.mpath");
                if let Err(e) = write::write_atomic_bytes(&beside, text.text.as_bytes()) {
                    return fail(Msg::CannotWrite, &beside, args![beside.display(), e], lang);
                }
                report_conflicts(name, &beside, &text, &other, &broken, lang);
                1
            }
        }
    } else {
        merge_text_files(
            name,
            [(&b, base), (&o, ours), (&t, theirs)],
            ours,
            &settings,
            at.as_deref(),
            lang,
        )
    }
}

/// The `.mpath` merge: each version decoded and parsed (a version that does not parse is an
/// error located in it), merged, written to OURS, markers and all.
fn merge_text_files(
    name: &Path,
    versions: [(&[u8], &Path); 3],
    ours: &Path,
    settings: &Settings,
    at: Option<&Path>,
    lang: Lang,
) -> u8 {
    let mut texts = Vec::new();
    for (bytes, p) in versions {
        let Ok(decoded) = millpath_core::load::text_file::decode(bytes) else {
            return fail(Msg::TextNulBytes, p, args![p.display()], lang);
        };
        let text = decoded.text.into_owned();
        if let Err(diags) =
            millpath_core::convert::format_text(&text, &FileRef::new(p.to_path_buf()))
        {
            diags
                .iter()
                .for_each(|d| eprintln!("{}", report::human(d, lang)));
            return 2;
        }
        texts.push(text);
    }
    let merged = merge_texts(&texts[0], &texts[1], &texts[2]);
    let broken = if merged.conflicts.is_empty() {
        broken_paths_at(&texts[1], &texts[2], &merged.text, settings, at)
    } else {
        Vec::new()
    };
    let code = write_ours(ours, merged.text.as_bytes(), lang);
    if code != 0 {
        return code;
    }
    if merged.conflicts.is_empty() && broken.is_empty() {
        return 0;
    }
    report_conflicts(name, name, &merged, &OtherChanges::new(), &broken, lang);
    1
}

fn write_ours(ours: &Path, bytes: &[u8], lang: Lang) -> u8 {
    match write::write_atomic_bytes(ours, bytes) {
        Ok(()) => 0,
        Err(e) => fail(Msg::CannotWrite, ours, args![ours.display(), e], lang),
    }
}

/// One message per kind of conflict, each located at the file git merges.
fn report_conflicts(
    name: &Path,
    written: &Path,
    text: &TextMerge,
    other: &OtherChanges,
    broken: &[String],
    lang: Lang,
) {
    let at = || Origin::File(FileRef::new(name.to_path_buf()));
    let mut diags = Vec::new();
    if !text.conflicts.is_empty() {
        let list: Vec<String> = text.conflicts.iter().map(|c| describe(c, lang)).collect();
        diags.push(Diagnostic::error(
            Msg::MergeConflicts,
            at(),
            args![
                name.display(),
                text.conflicts.len(),
                written.display(),
                list.join("; ")
            ],
        ));
    }
    if !other.is_empty() {
        diags.push(Diagnostic::error(
            Msg::MergeOtherContent,
            at(),
            args![
                name.display(),
                describe_other(other, lang),
                written.display()
            ],
        ));
    }
    if !broken.is_empty() {
        diags.push(Diagnostic::error(
            Msg::MergeBreaksCompile,
            at(),
            args![name.display(), broken.join(", "), written.display()],
        ));
    }
    diags
        .iter()
        .for_each(|d| eprintln!("{}", report::human(d, lang)));
}

/// `path 2001.1P, line 7, mill (5, 0) -> (25, 0): changed on both sides`.
fn describe(c: &Conflict, lang: Lang) -> String {
    let what = match (c.kind, lang) {
        (ConflictKind::BothChanged, Lang::En) => "changed on both sides",
        (ConflictKind::BothChanged, Lang::De) => "auf beiden Seiten geändert",
        (ConflictKind::AddedBoth, Lang::En) => "added on both sides, differently",
        (ConflictKind::AddedBoth, Lang::De) => "auf beiden Seiten verschieden hinzugefügt",
        (ConflictKind::DeletedByOurs, Lang::En) => "deleted on our side, changed on theirs",
        (ConflictKind::DeletedByOurs, Lang::De) => "auf unserer Seite gelöscht, auf ihrer geändert",
        (ConflictKind::DeletedByTheirs, Lang::En) => "changed on our side, deleted on theirs",
        (ConflictKind::DeletedByTheirs, Lang::De) => {
            "auf unserer Seite geändert, auf ihrer gelöscht"
        }
    };
    let (path, line) = match lang {
        Lang::En => ("path", "line"),
        Lang::De => ("Pfad", "Zeile"),
    };
    let mut s = format!("{path} {}, {line} {}", c.path, c.line);
    if let Some(e) = &c.element {
        s.push_str(&format!(", {e}"));
    }
    format!("{s}: {what}")
}

/// `layer BEMASSUNG: 1 INSERT added, 2 LINE removed, DIMENSION changed`.
fn describe_other(other: &OtherChanges, lang: Lang) -> String {
    let (layer, added, removed, changed) = match lang {
        Lang::En => ("layer", "added", "removed", "changed"),
        Lang::De => ("Layer", "hinzugefügt", "entfernt", "geändert"),
    };
    other
        .iter()
        .map(|((l, kind), n)| match n {
            0 => format!("{layer} {l}: {kind} {changed}"),
            n if *n > 0 => format!("{layer} {l}: {n} {kind} {added}"),
            n => format!("{layer} {l}: {} {kind} {removed}", -n),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn fail(msg: Msg, path: &Path, a: Vec<String>, lang: Lang) -> u8 {
    let d = Diagnostic::error(msg, Origin::File(FileRef::new(path.to_path_buf())), a);
    eprintln!("{}", report::human(&d, lang));
    2
}
