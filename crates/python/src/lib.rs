//! millpath as a Python module (`millpath._native`, PyO3, abi3 for CPython 3.9 and later):
//! the command line's compile, check, conversions and checker over texts and bytes held in
//! memory, the same crates and code paths as the command line. This file only converts
//! between Python and Rust values; the work is in `run.rs`, `convert.rs`,
//! `check_program.rs`, the settings in `settings.rs` and `values.rs`. The Python package
//! (`python/millpath`) wraps the plain dicts returned here in classes and adds the builder.
//!
//! Every failure is a `millpath.MillpathError` (a `ValueError`) with the located message;
//! the work runs without the GIL.

mod check_program;
mod convert;
mod run;
mod settings;
mod values;

use millpath_core::load::fs::MAX_FILE_BYTES;
use millpath_core::{Lang, MemFileSystem};
use pyo3::create_exception;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyString};

create_exception!(
    millpath,
    MillpathError,
    PyValueError,
    "A millpath error: the located message of malformed input or unusable settings."
);

fn lang_of(lang: &str) -> Lang {
    Lang::from_name(lang)
}

fn error(message: impl Into<String>) -> PyErr {
    MillpathError::new_err(message.into())
}

/// A text or the bytes of a file (`str` as UTF-8), refused over the command line's bound.
fn bytes_of(v: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<u8>> {
    let bytes = if let Ok(s) = v.cast::<PyString>() {
        s.extract::<String>()?.into_bytes()
    } else if let Ok(b) = v.cast::<PyBytes>() {
        b.as_bytes().to_vec()
    } else {
        return Err(PyTypeError::new_err(format!(
            "{what}: expected str or bytes, got {}",
            v.get_type().name()?
        )));
    };
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(error(format!(
            "{what}: larger than {} MiB",
            MAX_FILE_BYTES >> 20
        )));
    }
    Ok(bytes)
}

fn diag_dict<'py>(py: Python<'py>, d: &run::Diag) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("code", &d.code)?;
    out.set_item("name", &d.name)?;
    out.set_item("severity", d.severity)?;
    out.set_item("message", &d.message)?;
    out.set_item("file", &d.file)?;
    out.set_item("line", d.line)?;
    out.set_item("column", d.column)?;
    out.set_item("located", &d.located)?;
    Ok(out)
}

/// Compiles or checks one drawing: `_run(source, file_name, settings, files, check)` →
/// `{files, diagnostics, statistics, removed_volume, info}`.
#[pyfunction]
#[pyo3(signature = (source, file_name, settings=None, files=None, check=false))]
fn _run<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    file_name: &str,
    settings: Option<&Bound<'py, PyDict>>,
    files: Option<&Bound<'py, PyDict>>,
    check: bool,
) -> PyResult<Bound<'py, PyDict>> {
    if file_name.is_empty() || file_name.contains('\0') {
        return Err(error(
            "file_name: a file name is needed (e.g. \"part.mpath\")",
        ));
    }
    let mut memory = MemFileSystem::default();
    if let Some(files) = files {
        for (name, content) in files.iter() {
            let name: String = name
                .extract()
                .map_err(|_| PyTypeError::new_err("files: keys must be str (file names)"))?;
            memory.add(
                name.clone(),
                bytes_of(&content, &format!("files[{name:?}]"))?,
            );
        }
    }
    memory.add(file_name, bytes_of(source, "source")?);
    let toml_text = settings.map(values::settings_text).transpose()?;
    let outcome = py.detach(|| {
        run::run(&run::Request {
            file_name,
            files: &memory,
            settings: toml_text.as_deref(),
            check,
        })
    });
    let outcome = outcome.map_err(|m| error(m.join("\n")))?;
    let out = PyDict::new(py);
    let files = PyDict::new(py);
    for (name, text) in &outcome.files {
        files.set_item(name, text)?;
    }
    out.set_item("files", files)?;
    let diags = PyList::empty(py);
    for d in &outcome.diagnostics {
        diags.append(diag_dict(py, d)?)?;
    }
    out.set_item("diagnostics", diags)?;
    let stats = PyList::empty(py);
    for s in &outcome.statistics {
        let d = PyDict::new(py);
        d.set_item("path", &s.path)?;
        d.set_item("lines", &s.lines)?;
        d.set_item("seconds", s.seconds)?;
        d.set_item("time", &s.time)?;
        stats.append(d)?;
    }
    out.set_item("statistics", stats)?;
    out.set_item("removed_volume", outcome.removed_volume)?;
    out.set_item("info", &outcome.info)?;
    Ok(out)
}

/// `dxf2text(data, file_name, extended, lang)` → `(text, [diagnostic dicts])`.
#[pyfunction]
#[pyo3(signature = (data, file_name="drawing.dxf", extended=false, lang="en"))]
fn dxf2text<'py>(
    py: Python<'py>,
    data: &Bound<'py, PyAny>,
    file_name: &str,
    extended: bool,
    lang: &str,
) -> PyResult<(String, Bound<'py, PyList>)> {
    let bytes = bytes_of(data, "data")?;
    let lang = lang_of(lang);
    let (text, diags) = py
        .detach(|| convert::dxf2text(&bytes, file_name, extended, lang))
        .map_err(error)?;
    let list = PyList::empty(py);
    for d in &diags {
        list.append(diag_dict(py, &run::diag(d, lang))?)?;
    }
    Ok((text, list))
}

/// `text2dxf(text, into, file_name, lang)` → the DXF's bytes.
#[pyfunction]
#[pyo3(signature = (text, into=None, file_name="drawing.mpath", lang="en"))]
fn text2dxf<'py>(
    py: Python<'py>,
    text: &str,
    into: Option<&Bound<'py, PyAny>>,
    file_name: &str,
    lang: &str,
) -> PyResult<Bound<'py, PyBytes>> {
    let into = into.map(|b| bytes_of(b, "into")).transpose()?;
    let lang = lang_of(lang);
    let dxf = py
        .detach(|| convert::text2dxf(text, file_name, into.as_deref(), lang))
        .map_err(error)?;
    Ok(PyBytes::new(py, &dxf))
}

/// `format(text, file_name, lang)` → the canonical text.
#[pyfunction]
#[pyo3(signature = (text, file_name="drawing.mpath", lang="en"))]
fn format(py: Python<'_>, text: &str, file_name: &str, lang: &str) -> PyResult<String> {
    let lang = lang_of(lang);
    py.detach(|| convert::format(text, file_name, lang))
        .map_err(error)
}

/// A keep-out box from Python: name, (xmin, ymin, zmin), (xmax, ymax, zmax).
type ClampBox = (String, [f64; 3], [f64; 3]);

/// `verify(gcode, dialect_or_post, clamps, lang)` → `{lines, moves, errors, warnings,
/// removed_volume, findings: [{line, severity, code, message, text}]}`; clamps as
/// `(name, (xmin, ymin, zmin), (xmax, ymax, zmax))`.
#[pyfunction]
#[pyo3(signature = (gcode, dialect_or_post, clamps=None, lang="en"))]
fn verify<'py>(
    py: Python<'py>,
    gcode: &str,
    dialect_or_post: &str,
    clamps: Option<Vec<ClampBox>>,
    lang: &str,
) -> PyResult<Bound<'py, PyDict>> {
    use millpath_verify::Severity;
    if gcode.len() as u64 > MAX_FILE_BYTES {
        return Err(error(format!(
            "gcode: larger than {} MiB",
            MAX_FILE_BYTES >> 20
        )));
    }
    let clamps = clamps.unwrap_or_default();
    if clamps.len() > millpath_verify::MAX_CLAMPS {
        return Err(error(format!(
            "clamps: more than {}",
            millpath_verify::MAX_CLAMPS
        )));
    }
    let clamps = clamps
        .into_iter()
        .map(|(name, min, max)| millpath_verify::Clamp { name, min, max })
        .collect();
    let core_lang = lang_of(lang);
    let vlang = match core_lang {
        Lang::De => millpath_verify::Lang::De,
        Lang::En => millpath_verify::Lang::En,
    };
    let report = py
        .detach(|| check_program::verify(gcode, dialect_or_post, clamps, core_lang))
        .map_err(error)?;
    let out = PyDict::new(py);
    out.set_item("lines", report.lines)?;
    out.set_item("moves", report.moves)?;
    out.set_item("errors", report.count(Severity::Error))?;
    out.set_item("warnings", report.count(Severity::Warning))?;
    out.set_item(
        "removed_volume",
        report.stock.map(|_| report.removed_volume_mm3),
    )?;
    let findings = PyList::empty(py);
    for f in &report.findings {
        let d = PyDict::new(py);
        d.set_item("line", f.line)?;
        d.set_item("severity", f.severity.word(millpath_verify::Lang::En))?;
        d.set_item("code", f.code())?;
        d.set_item("message", f.message(vlang))?;
        d.set_item("text", &f.text)?;
        findings.append(d)?;
    }
    out.set_item("findings", findings)?;
    Ok(out)
}

/// The version banner written into every program (`millpath V.x.y.z`).
#[pyfunction]
fn banner() -> String {
    millpath_core::banner()
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("MillpathError", m.py().get_type::<MillpathError>())?;
    m.add_function(wrap_pyfunction!(_run, m)?)?;
    m.add_function(wrap_pyfunction!(dxf2text, m)?)?;
    m.add_function(wrap_pyfunction!(text2dxf, m)?)?;
    m.add_function(wrap_pyfunction!(format, m)?)?;
    m.add_function(wrap_pyfunction!(verify, m)?)?;
    m.add_function(wrap_pyfunction!(banner, m)?)?;
    Ok(())
}
