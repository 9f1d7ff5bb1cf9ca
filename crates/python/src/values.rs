//! Python values → TOML values: the `settings` dict becomes the text of a `millpath.toml`,
//! read by the same parser as the file (its errors name the key and the line).

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// Nesting deeper than any setting has (`[machine]` → `max_velocity` → a list): refused.
const MAX_DEPTH: usize = 8;
/// More entries than any setting has (clamps included): refused.
const MAX_ENTRIES: usize = 100_000;

/// The TOML text of a settings dict (keys whose value is `None` are left out).
pub fn settings_text(d: &Bound<'_, PyDict>) -> PyResult<String> {
    let toml::Value::Table(t) = value(d.as_any(), 0, "settings")? else {
        return Err(PyTypeError::new_err("settings: expected a dict"));
    };
    toml::to_string(&t).map_err(|e| PyTypeError::new_err(format!("settings: {e}")))
}

fn value(v: &Bound<'_, PyAny>, depth: usize, at: &str) -> PyResult<toml::Value> {
    if depth > MAX_DEPTH {
        return Err(PyTypeError::new_err(format!("{at}: nested too deeply")));
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return match v.extract::<i64>() {
            Ok(i) => Ok(toml::Value::Integer(i)),
            // beyond 64 bits: as the number it is (the settings' checks refuse it)
            Err(_) => Ok(toml::Value::Float(
                v.extract::<f64>().unwrap_or(f64::INFINITY),
            )),
        };
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract()?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let n = v.len()?;
        if n > MAX_ENTRIES {
            return Err(PyTypeError::new_err(format!(
                "{at}: more than {MAX_ENTRIES} entries"
            )));
        }
        let mut out = Vec::with_capacity(n);
        for (i, item) in v.try_iter()?.enumerate() {
            out.push(value(&item?, depth + 1, &format!("{at}[{i}]"))?);
        }
        return Ok(toml::Value::Array(out));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        if d.len() > MAX_ENTRIES {
            return Err(PyTypeError::new_err(format!(
                "{at}: more than {MAX_ENTRIES} entries"
            )));
        }
        let mut t = toml::Table::new();
        for (k, item) in d.iter() {
            let Ok(key) = k.extract::<String>() else {
                return Err(PyTypeError::new_err(format!("{at}: keys must be str")));
            };
            if item.is_none() {
                continue;
            }
            let inner = value(&item, depth + 1, &format!("{at}[{key:?}]"))?;
            t.insert(key, inner);
        }
        return Ok(toml::Value::Table(t));
    }
    Err(PyTypeError::new_err(format!(
        "{at}: {} is no settings value (bool, int, float, str, list, dict)",
        v.get_type().name()?
    )))
}
