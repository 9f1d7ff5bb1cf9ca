//! The keep-out boxes of `millpath verify`: `--clamp NAME,XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX`,
//! `--config FILE`, or the `[[clamp]]` of the millpath.toml nearest each program, with the
//! bounds `compile` applies (`millpath_core::load::clamps::errors`).

use millpath_core::Lang;
use millpath_verify::Clamp;
use std::path::{Path, PathBuf};

/// The boxes given for every program; `None`: none given, each program's millpath.toml
/// decides. Errors as printable lines.
pub fn given(
    options: &[String],
    config: Option<&Path>,
    lang: Lang,
) -> Result<Option<Vec<Clamp>>, Vec<String>> {
    let mut clamps = Vec::new();
    let mut file = None;
    if let Some(p) = config {
        clamps = from_file(p, lang)?;
        file = Some(p.to_path_buf());
    }
    for o in options {
        clamps.push(parse(o, lang).map_err(|e| vec![e])?);
    }
    if options.is_empty() && config.is_none() {
        return Ok(None);
    }
    check(&clamps, file.as_ref(), lang)?;
    Ok(Some(clamps))
}

/// The `[[clamp]]` boxes of the millpath.toml nearest `program` (none without one).
pub fn nearest(program: &Path, lang: Lang) -> Result<Vec<Clamp>, Vec<String>> {
    let Some(p) = crate::config::find(program) else {
        return Ok(Vec::new());
    };
    let clamps = from_file(&p, lang)?;
    check(&clamps, Some(&p), lang)?;
    Ok(clamps)
}

fn from_file(p: &Path, lang: Lang) -> Result<Vec<Clamp>, Vec<String>> {
    let cfg = crate::config::load_in(p, lang).map_err(|e| vec![e])?;
    Ok(millpath_core::load::clamps::clamps(&cfg.clamp))
}

fn check(clamps: &[Clamp], file: Option<&PathBuf>, lang: Lang) -> Result<(), Vec<String>> {
    let errors = millpath_core::load::clamps::errors(clamps, file);
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors
            .iter()
            .map(|d| crate::report::human(d, lang))
            .collect())
    }
}

/// `NAME,XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX` (the name may be empty: `clamp N` is not known
/// here, so it becomes the option's text).
fn parse(text: &str, lang: Lang) -> Result<Clamp, String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let numbers: Option<Vec<f64>> = parts
        .get(1..)
        .filter(|p| p.len() == 6)
        .and_then(|p| p.iter().map(|v| v.parse::<f64>().ok()).collect());
    match numbers {
        Some(v) => Ok(Clamp {
            name: if parts[0].is_empty() {
                text.to_string()
            } else {
                parts[0].to_string()
            },
            min: [v[0], v[1], v[2]],
            max: [v[3], v[4], v[5]],
        }),
        None => Err(match lang {
            Lang::En => {
                format!("error: --clamp {text}: expected NAME,XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm)")
            }
            Lang::De => {
                format!("Fehler: --clamp {text}: erwartet NAME,XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm)")
            }
        }),
    }
}
