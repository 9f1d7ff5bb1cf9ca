//! `millpath adjust-z`: NAME_Clean.gcode and the measured NAME_Z.txt to NAME_Milling.gcode.

use crate::{report, write};
use millpath_core::diag::{Diagnostic, Diags, Msg, Origin};
use millpath_core::probe::adjustz;
use millpath_core::Lang;
use millpath_post::Post;
use std::path::{Path, PathBuf};

/// `post`: the post the programs were written with (a height map's moves are written in
/// its words).
pub fn run(
    max: f64,
    x: Option<&str>,
    lang: Lang,
    files: &[String],
    reference_lines: bool,
    post: &Post,
) -> u8 {
    run_set(max, x, lang, files, reference_lines, None, post)
}

/// The post the programs were written with: `--post`, else `post =` (or `dialect =`) of the
/// millpath.toml compile read for them (the nearest above the first program). The
/// `reference` writes no height maps, so without either (or with it) a set is taken in
/// `linuxcnc`'s words, the follower's own before the posts. The error names the option or
/// the file.
pub fn post_of(
    option: Option<&str>,
    first: Option<&Path>,
    lang: Lang,
) -> Result<std::sync::Arc<Post>, String> {
    use millpath_core::Dialect;
    let read = |p: &Path| std::fs::read_to_string(p).map_err(|e| e.to_string());
    let select = |name: &str, base: &Path| {
        millpath_core::emit::dialect::select_post(name, base, &read, lang)
            .map(|(dialect, post)| post.unwrap_or_else(|| dialect.shared_post()))
    };
    let chosen = match (option, first.and_then(crate::config::find)) {
        (Some(name), _) => select(name, Path::new("")).map_err(|e| format!("--post: {e}"))?,
        (None, None) => Dialect::LinuxCnc.shared_post(),
        (None, Some(path)) => {
            let cfg = crate::config::load_in(&path, lang)?;
            match (&cfg.post, cfg.dialect) {
                (Some(name), _) => select(name, &cfg.base_dir)
                    .map_err(|e| format!("{}: post: {e}", path.display()))?,
                (None, Some(dialect)) => dialect.shared_post(),
                (None, None) => Dialect::LinuxCnc.shared_post(),
            }
        }
    };
    Ok(
        if std::sync::Arc::ptr_eq(&chosen, &Dialect::Reference.shared_post()) {
            Dialect::LinuxCnc.shared_post()
        } else {
            chosen
        },
    )
}

/// `adjust-z --probe-log LOG`: the measured heights of the one program come from the log.
pub fn run_with_log(
    max: f64,
    log: &str,
    tolerance: f64,
    lang: Lang,
    files: &[String],
    post: &Post,
) -> u8 {
    let fail = |d: Diagnostic| {
        eprintln!("{}", report::human(&d, lang));
        2
    };
    if files.len() != 1 {
        let d = Diagnostic::error(
            Msg::ProbeLogOneProgram,
            Origin::Options,
            millpath_core::args![files.len()],
        );
        return fail(d);
    }
    if let Some(d) = adjustz::check_tolerance(tolerance, &tolerance.to_string()) {
        return fail(d);
    }
    run_set(max, None, lang, files, false, Some((log, tolerance)), post)
}

/// A probe log, read only when it is not larger than [`adjustz::MAX_LOG_BYTES`]; UTF-16 with
/// a mark is decoded, bytes that are not UTF-8 (a console's odd characters) become U+FFFD.
/// Also `verify --surface`'s reader.
pub(crate) fn read_log(path: &str, diags: &mut Diags) -> Option<String> {
    use std::io::Read;
    let limit = adjustz::MAX_LOG_BYTES as u64;
    let mut bytes = Vec::new();
    let read = std::fs::File::open(path).and_then(|f| f.take(limit + 1).read_to_end(&mut bytes));
    if let Err(e) = read {
        diags.error(
            Msg::CannotRead,
            Origin::Input,
            millpath_core::args![path, e],
        );
        return None;
    }
    if bytes.len() as u64 > limit {
        let origin = Origin::FileLine {
            file: path.into(),
            line: 1,
        };
        let limit = format!("{} bytes", adjustz::MAX_LOG_BYTES);
        diags.error(Msg::ProbeLogTooLarge, origin, millpath_core::args![limit]);
        return None;
    }
    match millpath_core::load::text_file::text_of(bytes) {
        Ok(text) => Some(text),
        Err(e) => {
            diags.error(
                Msg::CannotRead,
                Origin::Input,
                millpath_core::args![path, e],
            );
            None
        }
    }
}

fn run_set(
    max: f64,
    x: Option<&str>,
    lang: Lang,
    files: &[String],
    reference_lines: bool,
    log: Option<(&str, f64)>,
    post: &Post,
) -> u8 {
    let print = |d: &Diagnostic| {
        if reference_lines {
            eprintln!("{}", d.reference_line(lang));
        } else {
            eprintln!("{}", report::human(d, lang));
        }
    };
    let opt = if reference_lines {
        adjustz::MaxOption::Slash
    } else {
        adjustz::MaxOption::Long
    };
    // `--max NaN` or `inf` would switch the limit off: an option error, like a missing /m
    if let Some(d) = adjustz::check_max(max, &max.to_string(), opt) {
        print(&d);
        return 2;
    }
    let mut diags = Diags::default();
    let show = x.and_then(|p| regex::Regex::new(p).ok());
    let verb = |en: &str, de: &str| {
        if lang == Lang::De {
            de.to_string()
        } else {
            en.to_string()
        }
    };
    let read = |path: &str, diags: &mut Diags| {
        eprintln!("---- {} {path}", verb("Reading", "Einlesen von"));
        crate::read::text(path)
            .map_err(|e| {
                diags.error(
                    Msg::CannotRead,
                    Origin::Input,
                    millpath_core::args![path, e],
                );
            })
            .ok()
    };
    let mut planned = Vec::new();
    // every part: its inputs and its output, written or not
    let mut parts: Vec<(String, String, PathBuf)> = Vec::new();
    for f in files {
        let base = adjustz::base_path(f);
        let z_path = format!("{base}_Z.txt");
        let clean_path = format!("{base}_Clean.gcode");
        let milling = PathBuf::from(format!("{base}_Milling.gcode"));
        parts.push((z_path.clone(), clean_path.clone(), milling.clone()));
        let z_text = read(&z_path, &mut diags);
        let clean = read(&clean_path, &mut diags);
        let (Some(z_text), Some(clean)) = (z_text, clean) else {
            continue;
        };
        if let Some(re) = &show {
            for line in clean.lines().filter(|l| re.is_match(l)) {
                eprintln!("---- {line}");
            }
        }
        // the probing program that measured the values, when it is beside them
        let probing_path = format!("{base}_Probing.gcode");
        let probing = crate::read::text(&probing_path).ok();
        let set = |name, text| adjustz::SetFile { name, text };
        let probing = probing.as_deref().map(|p| set(&probing_path, p));
        let content = match log {
            Some((log_path, tol)) => {
                eprintln!("---- {} {log_path}", verb("Reading", "Einlesen von"));
                let Some(log_text) = read_log(log_path, &mut diags) else {
                    continue;
                };
                adjustz::adjust_with_log(
                    [set(&clean_path, &clean), set(&z_path, &z_text)],
                    probing,
                    set(log_path, &log_text),
                    tol,
                    max,
                    post,
                    &mut diags,
                )
            }
            None => adjustz::adjust_set(
                set(&clean_path, &clean),
                set(&z_path, &z_text),
                probing,
                max,
                opt,
                post,
                &mut diags,
            ),
        };
        if let Some(content) = content {
            planned.push((milling, content));
        }
    }
    // nothing is written when any file had an error
    let mut written = Vec::new();
    if !diags.has_errors() {
        for (path, content) in planned {
            eprintln!(
                "---- {} {}",
                verb("Writing", "Schreiben von"),
                path.display()
            );
            if let Some((moves, pieces)) = adjustz::split_summary(&content) {
                eprintln!(
                    "{}",
                    verb(
                        &format!("  Following the measured surface: {moves} moves split into {pieces} pieces"),
                        &format!("  Der gemessenen Oberfläche folgen: {moves} Wege in {pieces} Teile geteilt"),
                    )
                );
            }
            match write::write_atomic(&path, &content) {
                Ok(()) => written.push(path),
                Err(e) => diags.error(
                    Msg::CannotWrite,
                    Origin::Options,
                    millpath_core::args![path.display(), e],
                ),
            }
        }
    }
    // a refusal must not leave an older _Milling.gcode looking like the result
    for (z_path, clean_path, milling) in &parts {
        if !written.contains(milling) {
            let mut inputs = vec![clean_path, z_path];
            let log_path = log.map(|(l, _)| l.to_string());
            inputs.extend(log_path.as_ref());
            remove_stale_milling(milling, &inputs, &mut diags);
        }
    }
    for d in &diags.list {
        print(d);
    }
    u8::from(diags.has_errors())
}

/// Removes `milling` when it is not newer than one of its existing `inputs` (it was not made
/// from them), with a warning; an unknown modification time counts as not newer.
fn remove_stale_milling(milling: &Path, inputs: &[&String], diags: &mut Diags) {
    let modified = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified());
    if !milling.is_file() {
        return;
    }
    let own = modified(milling).ok();
    let newer_input = inputs.iter().find(|input| {
        let path = Path::new(input.as_str());
        path.is_file()
            && match (own, modified(path)) {
                (Some(own), Ok(t)) => t >= own,
                _ => true,
            }
    });
    let Some(input) = newer_input else {
        return;
    };
    let said = Diagnostic::warning(
        Msg::StaleMillingRemoved,
        Origin::Input,
        millpath_core::args![milling.display(), input],
    );
    crate::output::remove_with(milling, said, diags);
}
