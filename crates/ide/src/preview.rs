//! The G-code preview of a path, as `millpath compile` writes it.
//!
//! The G-code preview (= `compile`, computed once per analysis: `preview_of`); a refused path gives
//! no G-code and its reasons in `errors` (a missing path names the file's paths);
//! `preview_until`/`preview_of_until` stop inside the emitter when asked (`emit::generate_until`),
//! a stopped preview is not remembered.

use crate::preview_files::Preview;
use crate::{Analysis, Workspace};
use millpath_core::emit::{generate_until, Controller, Output};
use millpath_core::{Lang, Session};
use std::path::Path;

/// A path built as `millpath compile` builds it, with the errors of the build.
pub(crate) struct TopModel {
    pub model: std::sync::Arc<millpath_core::model::Model>,
    pub lang: Lang,
    pub sweep_speed: f64,
    pub controller: Controller,
    pub errors: Vec<String>,
    /// `[[clamp]]` boxes of the settings (drawn by the toolpath view).
    pub clamps: Vec<millpath_verify::Clamp>,
    /// The cut part's cell edge (mm) asked for.
    pub cut_cell: Option<f64>,
}

/// Builds `name` (default: the first path of the file) with the file's settings; the
/// session asks `stop` (a cancelled request ends the work early; the caller asks `stop`
/// again before using the result).
pub(crate) fn top_model_until(
    ws: &Workspace,
    path: &Path,
    name: Option<&str>,
    stop: &dyn Fn() -> bool,
) -> Result<TopModel, String> {
    top_model_from(ws, path, None, name, stop)
}

/// [`top_model_until`] that takes the document's paths from its analysis (`analysed`)
/// instead of reading and parsing the file again. Only an analysis without errors in the
/// document is taken (a path `compile` refuses for an error of the text is refused alike
/// by the fresh read); the caller checks that (`Analysis::has_errors`).
pub(crate) fn top_model_from(
    ws: &Workspace,
    path: &Path,
    analysed: Option<&Analysis>,
    name: Option<&str>,
    stop: &dyn Fn() -> bool,
) -> Result<TopModel, String> {
    let ds = ws.settings_for(path);
    let missing = ds.missing_message();
    let lang = ds.settings.lang;
    let sweep_speed = ds.settings.sweep_speed;
    let fs = ws.fs();
    let joined = |e: &[millpath_core::Diagnostic]| {
        e.iter()
            .map(|d| d.message(lang))
            .collect::<Vec<_>>()
            .join("; ")
    };
    let mut session = Session::new(ds.settings, &fs).map_err(|e| joined(&e))?;
    session.stop = Some(stop);
    // the analysis's walks: a path walked once serves its build and its hover rows
    session.traversals = analysed.map(|a| &a.traversals);
    let names = match analysed {
        Some(a) => session.add_shared_paths(path, a.paths.clone()),
        None => session.load_file(path),
    };
    let name = match name {
        Some(n) => n.to_string(),
        None => names.first().cloned().ok_or(match lang {
            Lang::En => "no path in this file",
            Lang::De => "kein Pfad in dieser Datei",
        })?,
    };
    match session.build_top(&name) {
        Ok(Some(model)) => Ok(TopModel {
            // the drawing's own height map (K) as compile takes it
            controller: Controller::for_model(&session.settings, &model),
            clamps: session.settings.clamps.clone(),
            cut_cell: session.settings.cut_cell,
            model,
            lang,
            sweep_speed,
            // not silent: `millpath compile` would refuse without them
            errors: missing
                .into_iter()
                .chain(messages(&session, lang))
                .collect(),
        }),
        Ok(None) => Err(not_built(&session, &names, &name, lang)),
        Err(abort) => Err(abort.message(lang)),
    }
}

/// Why `name` gave no model: its errors, or that the file has no such path (naming the
/// paths it has, and the one that differs only in case).
fn not_built(session: &Session, names: &[String], name: &str, lang: Lang) -> String {
    let why = messages(session, lang);
    if !why.is_empty() {
        return match lang {
            Lang::En => format!("path {name} cannot be built: {}", why.join("; ")),
            Lang::De => format!("Pfad {name} kann nicht erzeugt werden: {}", why.join("; ")),
        };
    }
    let list = if names.is_empty() {
        "-".to_string()
    } else {
        names.join(", ")
    };
    let case = names.iter().find(|n| n.eq_ignore_ascii_case(name));
    match (lang, case) {
        (Lang::En, Some(c)) => {
            format!("no path {name} in this file; did you mean {c}? (names are case-sensitive)")
        }
        (Lang::De, Some(c)) => format!(
            "kein Pfad {name} in dieser Datei; war {c} gemeint? (Groß- und Kleinschreibung zählt)"
        ),
        (Lang::En, None) => format!("no path {name} in this file; its paths: {list}"),
        (Lang::De, None) => format!("kein Pfad {name} in dieser Datei; ihre Pfade: {list}"),
    }
}

/// Preview of `name` (default: the first path of the document). A path that `millpath
/// compile` would refuse gives no G-code and its reasons in `errors` (the editors show them
/// instead); `Err` is kept for the signature's callers and never returned.
pub fn preview(ws: &Workspace, path: &Path, name: Option<&str>) -> Result<Preview, String> {
    preview_until(ws, path, name, &|| false).unwrap_or_else(|| Err("cancelled".into()))
}

/// [`preview`] that gives up (`None`) when `stop()` turns true: asked between building and
/// generating, and by the emitter every few hundred elements or passes.
pub fn preview_until(
    ws: &Workspace,
    path: &Path,
    name: Option<&str>,
    stop: &dyn Fn() -> bool,
) -> Option<Result<Preview, String>> {
    let refused = |errors: Vec<String>| Preview {
        path: name.unwrap_or_default().to_string(),
        gcode: String::new(),
        probing: None,
        z_txt: None,
        stats: Vec::new(),
        time: String::new(),
        errors,
    };
    let TopModel {
        model,
        lang,
        sweep_speed,
        controller,
        errors,
        ..
    } = match top_model_until(ws, path, name, stop) {
        _ if stop() => return None,
        Ok(t) => t,
        Err(e) => return Some(Ok(refused(vec![e]))),
    };
    let name = model.name().to_string();
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let g = match generate_until(
        &model,
        &file_name,
        &millpath_core::banner(),
        sweep_speed,
        lang,
        &controller,
        Some(stop),
    ) {
        _ if stop() => return None,
        Ok(g) => g,
        Err(e) => {
            let mut all = errors;
            all.extend(e.iter().map(|d| d.message(lang)));
            let mut r = refused(all);
            r.path = name;
            return Some(Ok(r));
        }
    };
    let stats = g.stats.lines(lang).to_vec();
    let time = millpath_core::emit::stats::hms(g.stats.seconds());
    Some(Ok(match g.output {
        Output::Milling(gcode) => Preview {
            path: name,
            gcode,
            probing: None,
            z_txt: None,
            stats,
            time,
            errors,
        },
        Output::Probing {
            probing,
            z_txt,
            clean,
        } => Preview {
            path: name,
            gcode: clean,
            probing: Some(probing),
            z_txt: Some(z_txt),
            stats,
            time,
            errors,
        },
    }))
}

pub(crate) fn messages(session: &Session, lang: Lang) -> Vec<String> {
    session
        .diags
        .list
        .iter()
        .filter(|d| d.severity == millpath_core::Severity::Error)
        .map(|d| d.reference_line(lang))
        .collect()
}

/// [`preview`] computed once per analysis: `ws` must be the workspace `a` was made from.
pub fn preview_of(a: &Analysis, ws: &Workspace, name: Option<&str>) -> Result<Preview, String> {
    preview_of_until(a, ws, name, &|| false).unwrap_or_else(|| Err("cancelled".into()))
}

/// [`preview_of`] that gives up (`None`, nothing remembered) when `stop()` turns true.
pub fn preview_of_until(
    a: &Analysis,
    ws: &Workspace,
    name: Option<&str>,
    stop: &dyn Fn() -> bool,
) -> Option<Result<Preview, String>> {
    let key = name.map(str::to_string);
    if let Some(p) = a.previews.lock().ok().and_then(|c| c.get(&key).cloned()) {
        return Some(p);
    }
    let p = preview_until(ws, &a.path, name, stop)?;
    if let Ok(mut c) = a.previews.lock() {
        c.insert(key, p.clone());
    }
    Some(p)
}
