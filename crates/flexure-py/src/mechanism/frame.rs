//! A frame on a body, as Python names it: the body by name, and a point in
//! its frame with as many coordinates as the mechanism's dimension.

use flexure::model::Model;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The body named `name` of `model`, or a ValueError listing the bodies.
pub fn body_named(model: &Model, name: &str) -> PyResult<usize> {
    model.body(name).ok_or_else(|| {
        let names: Vec<String> = model.body_names().iter().map(|b| format!("{b:?}")).collect();
        PyValueError::new_err(format!(
            "body = {name:?}: names no body of the mechanism (its bodies: {})",
            names.join(", ")
        ))
    })
}

/// A point in a body's frame (m; `None`: its origin), of the model's
/// dimension, each coordinate finite and within 1e6 m (the library's bound
/// on lengths), else a ValueError naming `at`.
pub fn point(at: Option<&Bound<'_, PyAny>>, dimension: u8) -> PyResult<Vec<f64>> {
    let n = usize::from(dimension);
    let Some(at) = at.filter(|a| !a.is_none()) else { return Ok(vec![0.0; n]) };
    let bad = |why: &str| {
        PyValueError::new_err(format!(
            "invalid at = {}: {why}",
            at.repr().map(|r| r.to_string()).unwrap_or_else(|_| "an object without repr".into())
        ))
    };
    let count = match dimension {
        2 => "must be two numbers (x, y), a point in the body's frame (m)",
        _ => {
            "must be three numbers (x, y, z), a point in the body's frame (m): the mechanism is spatial (dimension = 3)"
        }
    };
    crate::strict::no_bool("at", at)?;
    let v: Vec<f64> = at.extract().map_err(|_| bad(count))?;
    if v.len() != n {
        return Err(bad(count));
    }
    let max = flexure::flexure::LENGTH_RANGE.1;
    if !v.iter().all(|c| c.is_finite() && c.abs() <= max) {
        return Err(bad(&format!("each coordinate must be a finite number of magnitude at most {max:e} m")));
    }
    Ok(v)
}
