//! Python values in, NumPy arrays out: finite numbers, counts, tip loads,
//! arc lengths along a flexure, and matrices.

use crate::stress;
use crate::strict::Real;
use crate::warnings::deprecated;
use flexure::TipLoad;
use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, IntoPyArray, PyArray2, PyArrayLikeDyn};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyInt;

/// A pair of NumPy matrices, as `hessians` returns.
pub type MatrixPair<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>);

pub fn matrix(m: &nalgebra::DMatrix<f64>) -> Array2<f64> {
    Array2::from_shape_fn((m.nrows(), m.ncols()), |(i, j)| m[(i, j)])
}

pub fn finite(name: &str, v: f64) -> PyResult<f64> {
    if v.is_finite() { Ok(v) } else { Err(PyValueError::new_err(format!("{name} = {v}: must be a finite number"))) }
}

/// A tip load of finite components.
pub fn tip_load(moment: Real, fx: Real, fy: Real) -> PyResult<TipLoad> {
    Ok(TipLoad { moment: finite("moment", moment.0)?, fx: finite("fx", fx.0)?, fy: finite("fy", fy.0)? })
}

/// A count such as `order` from any Python integer: one that does not fit a
/// `usize` (negative, or past 2^64) is a `ValueError` naming `name` and the
/// bound, not an `OverflowError`. The library checks the bound itself.
pub fn count(name: &str, value: &Bound<'_, PyAny>, max: usize) -> PyResult<usize> {
    // True and False are Python integers, but no count.
    if crate::strict::is_bool(value) {
        return Err(PyTypeError::new_err(format!(
            "argument '{name}': must be a whole number, not a boolean ({})",
            value.repr()?
        )));
    }
    match value.extract::<usize>() {
        Ok(v) => Ok(v),
        // Integers (also NumPy's, through __index__) out of usize's range.
        Err(_) if value.is_instance_of::<PyInt>() || value.hasattr("__index__").unwrap_or(false) => {
            Err(PyValueError::new_err(format!("invalid {name} = {value}: must be from 1 to {max}")))
        }
        Err(e) => Err(PyTypeError::new_err(format!("argument '{name}': {}", e.value(value.py())))),
    }
}

/// The number of points `k` of a shape, from 2 to [`stress::MAX_SHAPE`].
pub fn shape_points(value: &Bound<'_, PyAny>) -> PyResult<usize> {
    let max = stress::MAX_SHAPE;
    match value.extract::<usize>() {
        Ok(k) if (2..=max).contains(&k) => Ok(k),
        Ok(_) => Err(PyValueError::new_err(format!(
            "invalid k = {value}: must be from 2 to {max} points (the ends included)"
        ))),
        Err(_) if value.is_instance_of::<PyInt>() || value.hasattr("__index__").unwrap_or(false) => Err(
            PyValueError::new_err(format!("invalid k = {value}: must be from 2 to {max} points (the ends included)")),
        ),
        Err(e) => Err(PyTypeError::new_err(format!("argument 'k': {}", e.value(value.py())))),
    }
}

/// Evaluates `g` at arc length `s` (m) on a flexure of length `l`: a float
/// for a number, an array of the same shape for an array; every `s` must lie
/// in [0, L].
pub fn along<'py>(
    py: Python<'py>,
    l: f64,
    s: &Bound<'py, PyAny>,
    g: impl Fn(f64) -> f64,
) -> PyResult<Bound<'py, PyAny>> {
    let check = |v: f64| {
        if v.is_finite() && (0.0..=l).contains(&v) {
            Ok(v)
        } else {
            Err(PyValueError::new_err(format!("s = {v}: must lie along the flexure, in [0, L] = [0, {l}] m")))
        }
    };
    if let Ok(v) = s.extract::<f64>() {
        return Ok(g(check(v)?).into_pyobject(py)?.into_any());
    }
    let array: PyArrayLikeDyn<'py, f64, AllowTypeChange> = s.extract().map_err(|e: PyErr| {
        if e.is_instance_of::<PyTypeError>(py) {
            PyTypeError::new_err(format!("argument 's': {}", e.value(py)))
        } else {
            e
        }
    })?;
    let values = array.as_array().map(|&v| v).to_owned();
    for &v in &values {
        check(v)?;
    }
    Ok(values.mapv(g).into_pyarray(py).into_any())
}

/// A finite float argument named `name`.
pub fn real(name: &str, v: Real) -> PyResult<f64> {
    finite(name, v.0)
}

/// The rest curvature coefficients κ given as `kappa`, or as `rest`, its deprecated
/// name (which warns `DeprecationWarning`), with the keyword the caller used, for
/// messages; both at once is a `ValueError`.
pub fn kappa<'a, 'py>(
    py: Python<'py>,
    kappa: Option<&'a Bound<'py, PyAny>>,
    rest: Option<&'a Bound<'py, PyAny>>,
    stacklevel: i32,
) -> PyResult<Option<(&'static str, &'a Bound<'py, PyAny>)>> {
    match (kappa, rest) {
        (Some(_), Some(_)) => Err(PyValueError::new_err(
            "kappa and rest given together: rest is kappa's deprecated name, the rest curvature coefficients; give kappa alone",
        )),
        (None, Some(r)) => {
            deprecated(py, "rest", "kappa", stacklevel)?;
            Ok(Some(("rest", r)))
        }
        (k, None) => Ok(k.map(|k| ("kappa", k))),
    }
}
