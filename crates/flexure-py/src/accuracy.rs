//! The `accuracy` and `order` arguments: the target an answer's estimated
//! error is held to, and whether the order is raised until it is met.

use crate::strict;
use flexure::estimate::Accuracy;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Reads `accuracy` = (position as a fraction of L, angle in rad[, peak
/// stress or curvature as a fraction of the peak]); the paper's 1 % of L
/// and 1°, and 1 % of the peak, when it is `None`.
pub fn accuracy(value: Option<&Bound<'_, PyAny>>) -> PyResult<Accuracy> {
    let Some(v) = value.filter(|v| !v.is_none()) else {
        return Ok(Accuracy::default());
    };
    let shape = || {
        PyValueError::new_err(format!(
            "accuracy must be a pair (position as a fraction of L, angle in rad) or a triple adding the peak stress as a fraction of the peak, such as (0.01, 0.0175) or (0.01, 0.0175, 0.02), got {}",
            v.repr().map(|r| r.to_string()).unwrap_or_else(|_| "an object without repr".into())
        ))
    };
    strict::no_bool("accuracy", v)?;
    // A str is a sequence too, but never a pair of numbers: pyo3 refuses it as a Vec.
    let pair: Vec<f64> = v.extract().map_err(|_| shape())?;
    let (position, angle, stress) = match pair[..] {
        [position, angle] => (position, angle, Accuracy::default().stress),
        [position, angle, stress] => (position, angle, stress),
        _ => return Err(shape()),
    };
    for (what, x) in [("position fraction of L", position), ("angle (rad)", angle), ("peak fraction", stress)] {
        if !(x.is_finite() && x > 0.0) {
            let given = pair.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(", ");
            return Err(PyValueError::new_err(format!(
                "accuracy = ({given}): its {what} is {x}, and must be a finite number greater than zero"
            )));
        }
    }
    Ok(Accuracy { position, angle, stress, ..Default::default() })
}

/// Reads the `accuracy` of a buckling load or frequency: a fraction of the
/// value (1 % when `None`).
pub fn eigen_accuracy(value: Option<&Bound<'_, PyAny>>) -> PyResult<Accuracy> {
    let Some(v) = value.filter(|v| !v.is_none()) else {
        return Ok(Accuracy::default());
    };
    let bad = || {
        PyValueError::new_err(format!(
            "accuracy must be one finite number greater than zero, the relative error a buckling load or frequency may have (0.01 is 1 %), got {}",
            v.repr().map(|r| r.to_string()).unwrap_or_else(|_| "an object without repr".into())
        ))
    };
    strict::no_bool("accuracy", v)?;
    let x: f64 = v.extract().map_err(|_| bad())?;
    if !(x.is_finite() && x > 0.0) {
        return Err(bad());
    }
    Ok(Accuracy { eigenvalue: x, ..Default::default() })
}

/// Reads `order`: None for the flexure's own, or "auto" to raise it until the estimate meets the target.
pub fn auto_order(order: Option<&Bound<'_, PyAny>>) -> PyResult<bool> {
    match order.filter(|o| !o.is_none()) {
        None => Ok(false),
        Some(o) if o.extract::<String>().is_ok_and(|s| s == "auto") => Ok(true),
        Some(o) => Err(PyValueError::new_err(format!(
            "order must be None or \"auto\", got {}: a flexure's own order is set when it is built",
            o.repr()?
        ))),
    }
}
