//! Python as strict as the CLI: a float argument is a real number, never a
//! `bool` ([`Real`]), and no answer holds an infinity or a NaN ([`finite_answer`]),
//! as the CLI's `emit` refuses any non-finite number in an answer, naming the field.

use numpy::ndarray::Dimension;
use numpy::{PyArrayDyn, PyArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyList, PyTuple};

/// Whether `value` is a Python or NumPy boolean (NumPy's `bool_` is no subclass of `bool`).
pub fn is_bool(value: &Bound<'_, PyAny>) -> bool {
    value.is_instance_of::<PyBool>() || value.get_type().name().is_ok_and(|n| n == "bool" || n == "bool_")
}

/// A float argument that refuses `True` and `False`: Python would read them
/// as 1.0 and 0.0, so `thickness=True` would silently mean a metre. PyO3
/// names the argument in the `TypeError` (`argument 'fx': ...`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Real(pub f64);

impl std::fmt::Display for Real {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for Real {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> Result<Self, Self::Error> {
        if is_bool(&obj) {
            return Err(PyTypeError::new_err(format!("must be a real number, not a boolean ({})", obj.repr()?)));
        }
        Ok(Real(obj.extract::<f64>()?))
    }
}

/// `value`, refused when it (or, for a list or tuple, one of its items) is a boolean.
pub fn no_bool(name: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
    let bool_inside = if let Ok(list) = value.cast::<PyList>() {
        list.iter().any(|v| is_bool(&v) || no_bool(name, &v).is_err())
    } else if let Ok(tuple) = value.cast::<PyTuple>() {
        tuple.iter().any(|v| is_bool(&v) || no_bool(name, &v).is_err())
    } else {
        false
    };
    if is_bool(value) || bool_inside {
        return Err(PyTypeError::new_err(format!(
            "argument '{name}': must be real numbers, not booleans, got {}",
            value.repr()?
        )));
    }
    Ok(())
}

/// Refuses what NumPy would cast to float64 by dropping or inventing
/// meaning: a boolean array (0.0 and 1.0), a complex array (its imaginary
/// part dropped), an object array (whatever each object converts to), any
/// array of a kind other than integers and floats, and a `memoryview`
/// (whose format NumPy reinterprets), naming `name`.
pub fn real_array(name: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
    if value.is_instance_of::<pyo3::types::PyMemoryView>() {
        return Err(PyTypeError::new_err(format!(
            "argument '{name}': must be real numbers (a list, tuple or NumPy array), not a memoryview"
        )));
    }
    let kind = value.getattr("dtype").and_then(|d| d.getattr("kind")).and_then(|k| k.extract::<String>());
    match kind.as_deref() {
        Ok("b") => Err(PyTypeError::new_err(format!("argument '{name}': must be real numbers, not a boolean array"))),
        Ok("f" | "i" | "u") | Err(_) => Ok(()),
        Ok(k) => {
            let what = match k {
                "c" => "a complex array (its imaginary parts would be dropped)",
                "O" => "an object array",
                _ => "an array of that kind",
            };
            Err(PyTypeError::new_err(format!(
                "argument '{name}': must be real numbers (an integer or float array), not {what}; dtype {}",
                value.getattr("dtype")?.str()?
            )))
        }
    }
}

/// A whole-number argument (`count`, `max_steps`) that refuses `True` and
/// `False`, which Python would read as 1 and 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Whole(pub usize);

impl<'a, 'py> FromPyObject<'a, 'py> for Whole {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> Result<Self, Self::Error> {
        if is_bool(&obj) {
            return Err(PyTypeError::new_err(format!("must be a whole number, not a boolean ({})", obj.repr()?)));
        }
        Ok(Whole(obj.extract::<usize>()?))
    }
}

/// The path of the first number in `value` that is not finite (".key",
/// "[i]", "[i, j]" and "['field']" for a structured array's field), if any.
fn non_finite(value: &Bound<'_, PyAny>) -> PyResult<Option<String>> {
    if let Ok(x) = value.cast::<PyFloat>() {
        return Ok((!x.value().is_finite()).then(String::new));
    }
    if let Ok(d) = value.cast::<PyDict>() {
        for (k, v) in d.iter() {
            if let Some(p) = non_finite(&v)? {
                return Ok(Some(format!(".{k}{p}")));
            }
        }
        return Ok(None);
    }
    if let Ok(l) = value.cast::<PyList>() {
        for (i, v) in l.iter().enumerate() {
            if let Some(p) = non_finite(&v)? {
                return Ok(Some(format!("[{i}]{p}")));
            }
        }
        return Ok(None);
    }
    if let Ok(t) = value.cast::<PyTuple>() {
        for (i, v) in t.iter().enumerate() {
            if let Some(p) = non_finite(&v)? {
                return Ok(Some(format!("[{i}]{p}")));
            }
        }
        return Ok(None);
    }
    if let Ok(a) = value.cast::<PyArrayDyn<f64>>() {
        let read = a.readonly();
        let view = read.as_array();
        return Ok(view.indexed_iter().find(|(_, v)| !v.is_finite()).map(|(at, _)| {
            let at: Vec<String> = at.slice().iter().map(|i| i.to_string()).collect();
            format!("[{}]", at.join(", "))
        }));
    }
    // A structured array (Flexure.shape): each field in turn.
    if value.hasattr("dtype")? {
        let names = value.getattr("dtype")?.getattr("names")?;
        if !names.is_none() {
            for name in names.cast::<PyTuple>()?.iter() {
                let field = value.get_item(&name)?;
                if let Some(p) = non_finite(&field)? {
                    return Ok(Some(format!("['{name}']{p}")));
                }
            }
        }
    }
    Ok(None)
}

/// The error for a non-finite number at `path` of `what`'s answer.
pub fn refused(what: &str, path: &str) -> PyErr {
    let field = path.strip_prefix('.').unwrap_or(path);
    let place = if field.is_empty() { "the result".to_string() } else { format!("the result's field `{field}`") };
    PyValueError::new_err(format!(
        "{what}: {place} is not a finite number (NaN or infinite): the inputs are beyond what float64 holds \
         (the CLI refuses the same answer)"
    ))
}

/// `value`, refused with a `ValueError` naming the field when any number in
/// it is infinite or NaN (`what` names the call).
pub fn finite_answer(what: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
    match non_finite(value)? {
        Some(path) => Err(refused(what, &path)),
        None => Ok(()),
    }
}

/// A float answer, refused when it is not finite.
pub fn finite_number(what: &str, x: f64) -> PyResult<f64> {
    if x.is_finite() { Ok(x) } else { Err(refused(what, "")) }
}

/// Every number of `values`, refused when one is not finite (`what` names the call).
pub fn finite_slice(what: &str, values: &[f64]) -> PyResult<()> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(i) => Err(refused(what, &format!("[{i}]"))),
        None => Ok(()),
    }
}
