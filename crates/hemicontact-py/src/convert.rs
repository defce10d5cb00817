//! Python values ↔ TOML values, so that a scenario given as Python dicts and lists goes
//! through exactly the schema (and the error messages) of a scenario file.

use crate::errors::scenario_error;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// `path.key` or `key` at the top level.
fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// The TOML value of the Python value `obj` at the field `path` of the scenario `source`:
/// bool, int, float, str, dict (string keys), list or tuple, and anything with `tolist()`
/// (numpy arrays and scalars).
///
/// # Errors
/// `ScenarioError` naming the field for `None`, an int beyond 64 bits, a non-string key, or
/// a value of another type.
pub fn to_toml(obj: &Bound<'_, PyAny>, path: &str, source: &str) -> PyResult<toml::Value> {
    let py_type = || {
        obj.get_type()
            .name()
            .map_or_else(|_| "?".to_string(), |n| n.to_string())
    };
    if obj.is_none() {
        return Err(scenario_error(
            source,
            path,
            "None",
            "a value (leave the key out for its default)",
        ));
    }
    if let Ok(b) = obj.cast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if obj.is_instance_of::<PyInt>() {
        return obj.extract::<i64>().map(toml::Value::Integer).map_err(|_| {
            scenario_error(
                source,
                path,
                obj.to_string(),
                "an integer that fits in 64 bits",
            )
        });
    }
    if let Ok(f) = obj.cast::<PyFloat>() {
        return Ok(toml::Value::Float(f.value()));
    }
    if let Ok(s) = obj.cast::<PyString>() {
        return Ok(toml::Value::String(s.extract::<String>()?));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in d.iter() {
            let Ok(key) = k.cast::<PyString>() else {
                return Err(scenario_error(
                    source,
                    path,
                    format!("a key {}", k.repr().map_or("?".into(), |r| r.to_string())),
                    "string keys",
                ));
            };
            let key = key.extract::<String>()?;
            let value = to_toml(&v, &join(path, &key), source)?;
            table.insert(key, value);
        }
        return Ok(toml::Value::Table(table));
    }
    let items: Option<Vec<Bound<'_, PyAny>>> = if let Ok(l) = obj.cast::<PyList>() {
        Some(l.iter().collect())
    } else if let Ok(t) = obj.cast::<PyTuple>() {
        Some(t.iter().collect())
    } else {
        None
    };
    if let Some(items) = items {
        let values = items
            .iter()
            .enumerate()
            .map(|(i, v)| to_toml(v, &format!("{path}[{i}]"), source))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(values));
    }
    // numpy arrays and scalars.
    if obj.hasattr("tolist")? {
        let plain = obj.call_method0("tolist")?;
        if !plain.hasattr("tolist")? {
            return to_toml(&plain, path, source);
        }
    }
    Err(scenario_error(
        source,
        path,
        format!("a value of type {}", py_type()),
        "a bool, int, float, str, dict, list or tuple (or a numpy array)",
    ))
}

/// The Python value of a TOML value: dicts, lists, str, int, float and bool.
pub fn to_python<'py>(py: Python<'py>, value: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        toml::Value::String(s) => PyString::new(py, s).into_any(),
        toml::Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        toml::Value::Float(f) => PyFloat::new(py, *f).into_any(),
        toml::Value::Boolean(b) => PyBool::new(py, *b).to_owned().into_any(),
        toml::Value::Datetime(d) => PyString::new(py, &d.to_string()).into_any(),
        toml::Value::Array(a) => {
            let list = PyList::empty(py);
            for v in a {
                list.append(to_python(py, v)?)?;
            }
            list.into_any()
        }
        toml::Value::Table(t) => {
            let dict = PyDict::new(py);
            for (k, v) in t {
                dict.set_item(k, to_python(py, v)?)?;
            }
            dict.into_any()
        }
    })
}
