//! A measured surface from a file (`verify --surface`, `render --surface`): a probe log as
//! adjust-z reads it (LinuxCNC PROBEOPEN, GRBL `[PRB:…]`, bCNC `x y z`), a filled-in `_Z.txt`
//! (each point's XY in its comment) or a program holding a `(MILLPATH-SURFACE …)` record.
//! The points become a [`HeightMap`] once the nominal top T is known (each program's own).
//!
//! `verify --surface` / `render --surface`: a probe log (core's readers), a filled-in `_Z.txt` (XY
//! from its comments) or a program's `MILLPATH-SURFACE` record → `HeightMap` with the program's T;
//! located EN/DE errors, reads bounded like probe logs.

use crate::report;
use millpath_core::diag::{Diags, Msg, Origin};
use millpath_core::probe::adjustz::{self, LogFormat};
use millpath_core::Lang;
use millpath_verify::{HeightMap, SurfaceProblem};

/// The measurements of a surface file, each with its line.
pub enum Surface {
    Points {
        file: String,
        points: Vec<(f64, f64, f64, usize)>,
    },
    /// A program's record: its own T.
    Record(HeightMap),
}

fn located(file: &str, line: Option<usize>) -> String {
    match line {
        Some(l) => format!("{file}:{l}"),
        None => file.to_string(),
    }
}

fn error_word(lang: Lang) -> &'static str {
    match lang {
        Lang::En => "error",
        Lang::De => "Fehler",
    }
}

/// The `[x y]` of a `_Z.txt` comment `([3.000 -2.000]/T=3.000) #1000=…`.
fn z_line_xy(line: &str) -> Option<(f64, f64)> {
    let inner = line.split_once('[')?.1.split_once(']')?.0;
    let mut w = inner.split_whitespace().map(|v| {
        v.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && v.abs() <= adjustz::LIMIT)
    });
    match (w.next(), w.next(), w.next()) {
        (Some(Some(x)), Some(Some(y)), None) => Some((x, y)),
        _ => None,
    }
}

/// Reads `path` (bounded like adjust-z's probe logs); `Err` holds the lines to print, each
/// located at the file and line.
pub fn read(path: &str, lang: Lang) -> Result<Surface, Vec<String>> {
    let mut diags = Diags::default();
    let printed = |diags: &Diags| {
        diags
            .list
            .iter()
            .map(|d| report::human(d, lang))
            .collect::<Vec<_>>()
    };
    let Some(text) = crate::commands::adjust_z::read_log(path, &mut diags) else {
        return Err(printed(&diags));
    };
    // a program with its record (an adjusted NAME_Milling.gcode)
    match HeightMap::read_comments(text.lines().take(adjustz::MAX_LOG_LINES)) {
        Some(Ok(map)) => return Ok(Surface::Record(map)),
        Some(Err((line, p))) => {
            return Err(vec![format!(
                "{}: {}: {}",
                located(path, Some(line)),
                error_word(lang),
                p.message(verify_lang(lang))
            )])
        }
        None => {}
    }
    let points: Vec<(f64, f64, f64, usize)> = match adjustz::detect(&text) {
        None => {
            let first = text.lines().position(|l| !l.trim().is_empty());
            let at = Origin::FileLine {
                file: path.into(),
                line: first.map_or(1, |i| i + 1),
            };
            diags.error(Msg::ProbeLogUnknownFormat, at, vec![]);
            return Err(printed(&diags));
        }
        Some(LogFormat::ZFile) => {
            let lines: Vec<&str> = text.lines().collect();
            let mut out = Vec::new();
            for z in adjustz::parse_z_file(&text, path, &mut diags) {
                let line = lines.get(z.line - 1).copied().unwrap_or("");
                match z_line_xy(line) {
                    Some((x, y)) => out.push((x, y, z.value, z.line)),
                    None => {
                        return Err(vec![format!(
                            "{}: {}: {}",
                            located(path, Some(z.line)),
                            error_word(lang),
                            match lang {
                                Lang::En => "no probe point [x y] in this line's comment",
                                Lang::De => "kein Antastpunkt [x y] im Kommentar dieser Zeile",
                            }
                        )])
                    }
                }
            }
            out
        }
        Some(format) => adjustz::read_measurements(&text, path, format, &mut diags)
            .into_iter()
            .map(|m| (m.x, m.y, m.z, m.line))
            .collect(),
    };
    if diags.has_errors() {
        return Err(printed(&diags));
    }
    if points.is_empty() {
        return Err(vec![format!(
            "{path}: {}: {}",
            error_word(lang),
            match lang {
                Lang::En => "no measurements in this file",
                Lang::De => "keine Messungen in dieser Datei",
            }
        )]);
    }
    Ok(Surface::Points {
        file: path.to_string(),
        points,
    })
}

fn verify_lang(lang: Lang) -> millpath_verify::Lang {
    match lang {
        Lang::En => millpath_verify::Lang::En,
        Lang::De => millpath_verify::Lang::De,
    }
}

impl Surface {
    /// The map with nominal top `top` (a record keeps its own); `tol`: XY distance within
    /// which measurements count as one grid line.
    pub fn map(&self, top: f64, tol: f64, lang: Lang) -> Result<HeightMap, String> {
        let (file, points) = match self {
            Surface::Record(m) => return Ok(m.clone()),
            Surface::Points { file, points } => (file, points),
        };
        let xyz: Vec<(f64, f64, f64)> = points.iter().map(|p| (p.0, p.1, p.2)).collect();
        HeightMap::from_points(&xyz, top, tol).map_err(|p| {
            // a second height names the measurement's line
            let line = match p {
                SurfaceProblem::Duplicate { x, y } => points
                    .iter()
                    .filter(|q| (q.0 - x).abs() <= tol && (q.1 - y).abs() <= tol)
                    .nth(1)
                    .map(|q| q.3),
                _ => None,
            };
            let why = match lang {
                Lang::En => "the measurements do not form a full grid of probe points",
                Lang::De => "die Messungen bilden kein volles Raster von Antastpunkten",
            };
            format!(
                "{}: {}: {why}: {}",
                located(file, line),
                error_word(lang),
                p.message(verify_lang(lang))
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn z_txt_comments_give_their_xy() {
        assert_eq!(
            z_line_xy("([3.000 -2.000]/T=3.000) #1000=3.05"),
            Some((3.0, -2.0))
        );
        assert_eq!(z_line_xy("(x/T=3.000) #1000=3.05"), None);
        assert_eq!(z_line_xy("([NaN 1]/T=3) #1=1"), None);
        assert_eq!(z_line_xy("([1 2 3]/T=3) #1=1"), None);
    }
}
