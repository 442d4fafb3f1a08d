//! The library's results as Python objects, from their `serde::Serialize`
//! output: what the CLI prints as JSON, Python returns as dicts, lists,
//! floats, ints, strings, booleans and `None`, with the same keys in the
//! same order. The bindings re-derive nothing; where an answer's type is a
//! NumPy array (coordinates, shapes), its caller converts that key.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde_json::Value;

/// `value` serialized, as a Python object (see the module docs). JSON has
/// no infinity or NaN: `serde_json` writes one as null, which arrives here
/// as `None`, past [`crate::strict::finite_answer`]; the library's results
/// are finite or an error, as the CLI's JSON relies on too.
pub fn to_python<'py>(py: Python<'py>, value: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let v = serde_json::to_value(value).map_err(|e| PyValueError::new_err(e.to_string()))?;
    from_json(py, &v)
}

/// A JSON value as a Python object; its depth is that of the library's
/// result types, a handful of levels.
pub fn from_json<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        // Counts stay ints (reference_order); every other number is a float.
        Value::Number(n) => match (n.as_u64(), n.as_i64()) {
            (Some(u), _) => u.into_pyobject(py)?.into_any(),
            (None, Some(i)) => i.into_pyobject(py)?.into_any(),
            _ => n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any(),
        },
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(from_json(py, item)?)?;
            }
            list.into_any()
        }
        Value::Object(map) => {
            let d = PyDict::new(py);
            for (k, item) in map {
                d.set_item(k, from_json(py, item)?)?;
            }
            d.into_any()
        }
    })
}

/// `value` serialized, as a Python dict: for the library's result structs.
pub fn to_dict<'py>(py: Python<'py>, value: &impl serde::Serialize) -> PyResult<Bound<'py, PyDict>> {
    Ok(to_python(py, value)?.cast_into::<PyDict>()?)
}
