//! `millpath verify`: the independent G-code checker (crates/verify) over files.

use millpath_verify::{verify_on_surface, Dialect, Lang, Options, Report, Severity};
use serde_json::json;
use std::path::PathBuf;

/// An operating-system error in the message language.
fn os_text(e: &std::io::Error, lang: Lang) -> String {
    let lang = match lang {
        Lang::En => millpath_core::Lang::En,
        Lang::De => millpath_core::Lang::De,
    };
    millpath_core::diag::os_error_text(&e.to_string(), lang)
}

/// Larger files are refused unread.
const MAX_FILE_BYTES: u64 = 256 << 20;

pub struct Args {
    pub dialect: Dialect,
    pub top: Option<f64>,
    pub tool: Option<f64>,
    pub bottom: Option<f64>,
    pub lang: Lang,
    pub json: bool,
    /// `--surface FILE` and `--tolerance`.
    pub surface: Option<(String, f64)>,
    /// `--clamp NAME,XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX`.
    pub clamps: Vec<String>,
    /// `--config FILE`: its `[[clamp]]` boxes.
    pub config: Option<PathBuf>,
    pub files: Vec<PathBuf>,
}

fn core_lang(lang: Lang) -> millpath_core::Lang {
    match lang {
        Lang::En => millpath_core::Lang::En,
        Lang::De => millpath_core::Lang::De,
    }
}

/// The surface of `--surface` for one program: its nominal top from its own comments, else
/// `--top`.
fn surface_for(
    s: &crate::surface_file::Surface,
    (file, tol): (&str, f64),
    text: &str,
    a: &Args,
) -> Result<millpath_verify::HeightMap, String> {
    let Some(top) = millpath_verify::program_top(text).or(a.top) else {
        return Err(match a.lang {
            Lang::En => format!("--surface {file}: the nominal top T the heights are measured against is unknown: the program has no (MILLPATH-SURFACE …) or (MILLPATH-STOCK …) comment; give --top"),
            Lang::De => format!("--surface {file}: die Soll-Oberkante T, gegen die die Höhen gemessen sind, ist unbekannt: das Programm hat keinen Kommentar (MILLPATH-SURFACE …) oder (MILLPATH-STOCK …); --top angeben"),
        });
    };
    s.map(top, tol, core_lang(a.lang))
}

fn read(path: &PathBuf, lang: Lang) -> Result<String, String> {
    let de = lang == Lang::De;
    let os = |e: std::io::Error| os_text(&e, lang);
    let meta = std::fs::metadata(path).map_err(os)?;
    if meta.len() > MAX_FILE_BYTES {
        return Err(if de {
            format!("größer als {} MiB", MAX_FILE_BYTES >> 20)
        } else {
            format!("larger than {} MiB", MAX_FILE_BYTES >> 20)
        });
    }
    let bytes = std::fs::read(path).map_err(os)?;
    Ok(program_text(bytes))
}

/// A program's text as the checker reads it: UTF-16 with a mark (Notepad's "Unicode") is
/// decoded, its mark kept, so that the checker says the controller cannot take the file
/// (as it says of a UTF-8 mark); other bytes as UTF-8, the rest as U+FFFD.
fn program_text(bytes: Vec<u8>) -> String {
    use millpath_core::load::text_file::{decode, Encoding};
    match decode(&bytes) {
        Ok(d) if matches!(d.encoding, Encoding::Utf16Le | Encoding::Utf16Be) => {
            format!("\u{feff}{}", d.text)
        }
        _ => String::from_utf8(bytes)
            .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned()),
    }
}

fn summary(report: &Report, lang: Lang) -> String {
    let e = report.count(Severity::Error);
    let w = report.count(Severity::Warning);
    let stock = match &report.stock {
        Some(s) => match lang {
            Lang::En => format!(
                "; removed volume {:.1} mm³ (T={:.3}, O={:.3}, grid {}×{} of {:.3} mm)",
                report.removed_volume_mm3, s.top, s.tool_diameter, s.nx, s.ny, s.cell
            ),
            Lang::De => format!(
                "; abgetragenes Volumen {:.1} mm³ (T={:.3}, O={:.3}, Raster {}×{} zu {:.3} mm)",
                report.removed_volume_mm3, s.top, s.tool_diameter, s.nx, s.ny, s.cell
            ),
        },
        None => String::new(),
    };
    let surface = match &report.surface {
        Some(m) => {
            let (nx, ny) = (m.xs().len(), m.ys().len());
            match lang {
                Lang::En => format!("; on a height map of {nx}×{ny} points"),
                Lang::De => format!("; auf einer Höhenkarte von {nx}×{ny} Punkten"),
            }
        }
        None => String::new(),
    };
    match lang {
        Lang::En => format!(
            "{} lines, {} moves: {e} error(s), {w} warning(s){stock}{surface}",
            report.lines, report.moves
        ),
        Lang::De => format!(
            "{} Zeilen, {} Bewegungen: {e} Fehler, {w} Warnung(en){stock}{surface}",
            report.lines, report.moves
        ),
    }
}

/// Exit status 1 when any finding is an error (or a file cannot be read).
pub fn run(a: &Args) -> u8 {
    // boxes given for every program (--clamp, --config); else each program's millpath.toml
    let given = match crate::verify_clamps::given(&a.clamps, a.config.as_deref(), core_lang(a.lang))
    {
        Ok(c) => c,
        Err(lines) => {
            lines.iter().for_each(|l| eprintln!("{l}"));
            return 2;
        }
    };
    let mut options = Options {
        dialect: a.dialect,
        top: a.top,
        tool: a.tool,
        bottom: a.bottom,
        ..Default::default()
    };
    for (name, v) in [("--top", a.top), ("--tool", a.tool), ("--bottom", a.bottom)] {
        if let Some(v) = v {
            if !v.is_finite() || v.abs() > millpath_verify::MAX_MAGNITUDE {
                match a.lang {
                    Lang::En => eprintln!("error: {name} {v}: not a usable number"),
                    Lang::De => eprintln!("Fehler: {name} {v}: keine brauchbare Zahl"),
                }
                return 2;
            }
        }
    }
    if a.tool.is_some_and(|o| o <= 0.0) {
        match a.lang {
            Lang::En => eprintln!("error: --tool must be > 0"),
            Lang::De => eprintln!("Fehler: --tool muss > 0 sein"),
        }
        return 2;
    }
    let surface = match &a.surface {
        Some((file, tol)) => {
            if let Some(d) = millpath_core::probe::adjustz::check_tolerance(*tol, &tol.to_string())
            {
                eprintln!("{}", crate::report::human(&d, core_lang(a.lang)));
                return 2;
            }
            match crate::surface_file::read(file, core_lang(a.lang)) {
                Ok(s) => Some((s, (file.as_str(), *tol))),
                Err(lines) => {
                    for l in lines {
                        eprintln!("{l}");
                    }
                    return 2;
                }
            }
        }
        None => None,
    };
    let mut failed = false;
    let mut errors = 0;
    let mut warnings = 0;
    let mut files_json = Vec::new();
    for path in &a.files {
        let shown = path.display().to_string();
        let text = match read(path, a.lang) {
            Ok(t) => t,
            Err(e) => {
                failed = true;
                errors += 1;
                if a.json {
                    files_json.push(json!({ "file": shown, "error": e }));
                } else {
                    let verb = match a.lang {
                        Lang::En => "cannot read",
                        Lang::De => "kann nicht gelesen werden",
                    };
                    outln!("{shown}: {}: {verb}: {e}", Severity::Error.word(a.lang));
                }
                continue;
            }
        };
        let map = match &surface {
            Some((s, at)) => match surface_for(s, *at, &text, a) {
                Ok(m) => Some(m),
                Err(e) => {
                    eprintln!("{}", e);
                    return 2;
                }
            },
            None => None,
        };
        options.clamps = match &given {
            Some(c) => c.clone(),
            None => match crate::verify_clamps::nearest(path, core_lang(a.lang)) {
                Ok(c) => c,
                Err(lines) => {
                    lines.iter().for_each(|l| eprintln!("{l}"));
                    return 2;
                }
            },
        };
        let report = verify_on_surface(&text, &options, map.as_ref());
        failed |= report.has_errors();
        errors += report.count(Severity::Error);
        warnings += report.count(Severity::Warning);
        if a.json {
            files_json.push(json!({
                "file": shown,
                "lines": report.lines,
                "moves": report.moves,
                "errors": report.count(Severity::Error),
                "warnings": report.count(Severity::Warning),
                "removed_volume_mm3": report.stock.map(|_| report.removed_volume_mm3),
                "stock": report.stock.map(|s| json!({
                    "top": s.top, "tool_diameter": s.tool_diameter, "cell": s.cell,
                    "nx": s.nx, "ny": s.ny, "x0": s.x0, "y0": s.y0,
                })),
                "bottom": report.params.bottom,
                "clamps": options.clamps.iter().map(|c| json!({ "name": c.name, "min": c.min, "max": c.max })).collect::<Vec<_>>(),
                "surface": report.surface.as_ref().map(|m| json!({
                    "nx": m.xs().len(), "ny": m.ys().len(), "top": m.top(),
                    "from": a.surface.as_ref().map(|s| s.0.clone()),
                })),
                "findings": report.findings.iter().map(|f| json!({
                    "line": f.line,
                    "severity": f.severity.word(Lang::En),
                    "code": f.code(),
                    "message": f.message(a.lang),
                    "text": f.text,
                })).collect::<Vec<_>>(),
            }));
            continue;
        }
        for f in &report.findings {
            let place = match f.line {
                Some(l) => format!("{shown}:{l}"),
                None => shown.clone(),
            };
            outln!(
                "{place}: {}: {}",
                f.severity.word(a.lang),
                f.message(a.lang)
            );
            if !f.text.is_empty() {
                outln!("    | {}", f.text);
            }
        }
        eprintln!("{shown}: {}", summary(&report, a.lang));
    }
    if a.json {
        outln!(
            "{}",
            serde_json::to_string_pretty(&json!({
                "dialect": a.dialect.name(),
                "files": files_json,
                "errors": errors,
                "warnings": warnings,
            }))
            .unwrap_or_default()
        );
    } else if a.files.len() > 1 {
        eprintln!(
            "{}",
            match a.lang {
                Lang::En => format!(
                    "verified {} file(s): {errors} error(s), {warnings} warning(s)",
                    a.files.len()
                ),
                Lang::De => format!(
                    "{} Datei(en) geprüft: {errors} Fehler, {warnings} Warnung(en)",
                    a.files.len()
                ),
            }
        );
    }
    u8::from(failed)
}
