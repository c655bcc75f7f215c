//! Python values → the library's scene inputs: a scene given as a file path or as a dict (the
//! TOML file's tables), `set` overrides given as a dict or as `"key=value"` strings, and the
//! values of a sweep's varied keys.

use pdamp::scene::{parse_assignment, SceneSource};
use pdamp::sweep::Vary;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use crate::errors;

/// A Python value as a TOML value: bool, int, float (also `inf`), str, dict (a table),
/// list/tuple (an array); numpy scalars through `__index__` / `__float__`. `key` names the
/// value in the error of an unsupported type (e.g. `None`).
pub fn toml_value(obj: &Bound<'_, PyAny>, key: &str) -> PyResult<toml::Value> {
    if obj.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(obj.extract()?));
    }
    if obj.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(obj.extract()?));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(obj.extract()?));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        return Ok(toml::Value::Table(toml_table(d, key)?));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let items = obj
            .try_iter()?
            .enumerate()
            .map(|(i, item)| toml_value(&item?, &format!("{key}[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    // numpy integer and float scalars (np.int64 is not an int subclass)
    if obj.hasattr("__index__")? {
        return Ok(toml::Value::Integer(obj.extract()?));
    }
    if obj.hasattr("__float__")? {
        return Ok(toml::Value::Float(obj.extract()?));
    }
    Err(PyTypeError::new_err(format!(
        "{key} = {}: a scene value must be a bool, int, float, str, list or dict, not {}",
        obj.repr()?,
        obj.get_type().name()?
    )))
}

/// A Python dict as a TOML table (keys must be strings).
fn toml_table(d: &Bound<'_, PyDict>, prefix: &str) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (k, v) in d.iter() {
        let k: String = k.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "{}: scene keys must be strings, not {}",
                if prefix.is_empty() { "scene" } else { prefix },
                k.repr().map(|r| r.to_string()).unwrap_or_default()
            ))
        })?;
        let path = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        table.insert(k, toml_value(&v, &path)?);
    }
    Ok(table)
}

/// The scene: a dict (the tables of a scene file) or the path of a scene file (`str` or
/// `os.PathLike`).
///
/// # Errors
/// `OSError` for a file that cannot be read; `pdamp.SceneError` for malformed TOML; `TypeError`
/// for anything else.
pub fn scene_source(scene: &Bound<'_, PyAny>) -> PyResult<SceneSource> {
    if let Ok(d) = scene.cast::<PyDict>() {
        let text = toml::to_string(&toml_table(d, "")?)
            .map_err(|e| errors::SceneError::new_err(format!("scene dict: {e}")))?;
        return SceneSource::parse(&text).map_err(errors::scene);
    }
    let path: std::path::PathBuf = scene.extract().map_err(|_| {
        PyTypeError::new_err(
            "scene must be the path of a scene file (str or os.PathLike) or a dict",
        )
    })?;
    let text = std::fs::read_to_string(&path)
        .map_err(|e| errors::io(&path, format!("cannot read the scene file: {e}")))?;
    SceneSource::parse(&text)
        .map_err(|e| errors::SceneError::new_err(format!("in {}: {e}", path.display())))
}

/// Overrides as `(dotted key, value)` pairs, in order: `None`, a dict `{"run.periods": 20}`
/// (`None` as a value removes the key, like `--set run.dt=`), or a list of `"key=value"`
/// strings (the CLI's `--set` syntax).
pub fn overrides(set: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<(String, toml::Value)>> {
    let Some(set) = set.filter(|s| !s.is_none()) else {
        return Ok(Vec::new());
    };
    if let Ok(d) = set.cast::<PyDict>() {
        return d
            .iter()
            .map(|(k, v)| {
                let key: String = k.extract()?;
                let value = if v.is_none() {
                    toml::Value::String(String::new())
                } else {
                    toml_value(&v, &key)?
                };
                Ok((key, value))
            })
            .collect();
    }
    if set.is_instance_of::<PyString>() {
        return Err(PyTypeError::new_err(
            "set must be a dict {\"key\": value} or a list of \"key=value\" strings, not one string",
        ));
    }
    set.try_iter()?
        .map(|a| {
            let a: String = a?.extract()?;
            parse_assignment(&a).map_err(errors::scene)
        })
        .collect()
}

/// The varied keys of a sweep, from `(key, values)` pairs: `values` is a list of values or a
/// range string `"START:STOP:STEP"` / `"a,b,c"` (the CLI's `--vary` syntax).
pub fn varies(vary: &[(String, Bound<'_, PyAny>)]) -> PyResult<Vec<Vary>> {
    vary.iter()
        .map(|(key, values)| {
            if let Ok(spec) = values.extract::<String>() {
                return Vary::parse(&format!("{key}={spec}")).map_err(errors::scene);
            }
            let values = values
                .try_iter()?
                .map(|v| toml_value(&v?, key))
                .collect::<PyResult<Vec<_>>>()?;
            if values.is_empty() {
                return Err(errors::SceneError::new_err(format!(
                    "{key}: the list of values to sweep is empty"
                )));
            }
            Ok(Vary {
                key: key.clone(),
                values,
            })
        })
        .collect()
}
