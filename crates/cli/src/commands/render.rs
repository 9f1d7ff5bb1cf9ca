//! `millpath render`: a path's toolpath as an HTML page, an SVG or a PNG.

use crate::args::{lang_of, settings_for, MachineArgs};
use crate::commands::check::check_file;
use crate::output::{emit, print_human};
use crate::{png, report, write};
use millpath_core::complete_input;
use millpath_core::diag::{Diagnostic, Msg, Origin, Severity};
use millpath_core::Lang;
use std::path::{Path, PathBuf};

pub fn run(
    m: &MachineArgs,
    file: &Path,
    path: Option<&str>,
    (html, svg, png): (Option<PathBuf>, Option<PathBuf>, Option<PathBuf>),
    surface: Option<&str>,
    (cut, cut_cell): (bool, Option<f64>),
) -> u8 {
    let file = complete_input(&file.to_string_lossy());
    let abs = dunce::canonicalize(&file).unwrap_or_else(|_| file.clone());
    // like `compile`: options over millpath.toml (or --config), no drawing with placeholder
    // machine settings
    let settings = match settings_for(m, Some(&file), true) {
        Ok(mut s) => {
            if cut_cell.is_some() {
                s.cut_cell = cut_cell;
                s.option_keys.push("cut_cell");
            }
            s
        }
        Err(e) => {
            eprintln!(
                "{}: {e}",
                report::severity_word(Severity::Error, lang_of(m, Some(&file)))
            );
            return 2;
        }
    };
    let ws = millpath_ide::Workspace {
        fixed: Some(settings.clone()),
        ..Default::default()
    };
    let lang = settings.lang;
    let mut data = match millpath_ide::toolpath(&ws, &abs, path) {
        Ok(d) => d,
        Err(e) => {
            // say why: a missing or unreadable file, a file that is not a drawing, syntax
            // errors — not only that no path was found
            if let Err(err) = std::fs::read(&file) {
                let d = Diagnostic::error(
                    Msg::CannotRead,
                    Origin::File(millpath_core::diag::FileRef::new(file.clone())),
                    millpath_core::args![file.display(), err],
                );
                eprintln!("{}", report::human(&d, lang));
                return 1;
            }
            let mut check = settings.clone();
            check.check = true;
            let errors: Vec<Diagnostic> = check_file(&check, &file)
                .ok()
                .map(|c| report::tidy(c.diags))
                .unwrap_or_default()
                .into_iter()
                .filter(|d| d.severity == Severity::Error)
                .collect();
            if errors.is_empty() {
                eprintln!(
                    "{}: {}: {e}",
                    report::severity_word(Severity::Error, lang),
                    file.display()
                );
            } else {
                print_human(&errors, lang);
            }
            return 1;
        }
    };
    // the measured surface under the moves, its heights against the drawing's top T
    if let Some(file) = surface {
        let top = data["stock"]["top"].as_f64().unwrap_or(0.0);
        let tol = millpath_core::probe::adjustz::DEFAULT_TOLERANCE;
        let map = crate::surface_file::read(file, lang)
            .and_then(|s| s.map(top, tol, lang).map_err(|e| vec![e]));
        match map {
            Ok(map) => millpath_ide::with_surface(&mut data, &map),
            Err(lines) => {
                for l in lines {
                    eprintln!("{l}");
                }
                return 2;
            }
        }
    }
    let writing = match lang {
        Lang::En => "Writing",
        Lang::De => "Schreiben von",
    };
    // `--svg part.mpath` for `--svg part.svg`: the drawing is not replaced by its picture
    let outputs = [
        (html.as_deref(), "HTML"),
        (svg.as_deref(), "SVG"),
        (png.as_deref(), "PNG"),
    ];
    if crate::output::output_is_input(&outputs, std::slice::from_ref(&abs), lang) {
        return 1;
    }
    let html = html.or_else(|| {
        (svg.is_none() && png.is_none()).then(|| {
            PathBuf::from(format!(
                "{}_toolpath.html",
                file.with_extension("").display()
            ))
        })
    });
    let mut status = 0;
    if let Some(out) = html {
        eprintln!("---- {writing} {}", out.display());
        status |= emit(Some(&out), &millpath_ide::toolpath_html(&data), lang);
    }
    if let Some(out) = svg {
        eprintln!("---- {writing} {}", out.display());
        status |= emit(Some(&out), &millpath_ide::toolpath_svg(&data, cut), lang);
    }
    if let Some(out) = png {
        eprintln!("---- {writing} {}", out.display());
        let written = png::svg_to_png(&millpath_ide::toolpath_svg(&data, cut))
            .and_then(|bytes| write::write_atomic_bytes(&out, &bytes).map_err(|e| e.to_string()));
        if let Err(e) = written {
            eprintln!(
                "{}: {}: {}",
                report::severity_word(Severity::Error, lang),
                out.display(),
                millpath_core::diag::os_error_text(&e, lang)
            );
            status |= 1;
        }
    }
    status
}
