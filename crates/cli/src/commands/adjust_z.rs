//! `millpath adjust-z`: NAME_Clean.gcode and the measured NAME_Z.txt to NAME_Milling.gcode.

use crate::{report, write};
use millpath_core::diag::{Diagnostic, Diags, Msg, Origin};
use millpath_core::probe::adjustz;
use millpath_core::Lang;
use std::path::{Path, PathBuf};

pub fn run(max: f64, x: Option<&str>, lang: Lang, files: &[String], reference_lines: bool) -> u8 {
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
        std::fs::read_to_string(path)
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
        let probing = std::fs::read_to_string(&probing_path).ok();
        let set = |name, text| adjustz::SetFile { name, text };
        if let Some(content) = adjustz::adjust_set(
            set(&clean_path, &clean),
            set(&z_path, &z_text),
            probing.as_deref().map(|p| set(&probing_path, p)),
            max,
            opt,
            &mut diags,
        ) {
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
            remove_stale_milling(milling, &[clean_path, z_path], &mut diags);
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
