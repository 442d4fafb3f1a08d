//! The library's findings (`flexure::mechanism::findings`) in Python: a
//! list of dicts under `findings`, each warning raised as `PreloadWarning`
//! (a closure open at rest) or `IntersectionWarning` (parts that cross);
//! a closure with `preload = true` is listed as a note, without a warning.

use crate::errors::{IntersectionWarning, PreloadWarning};
use crate::warnings::warn;
use flexure::mechanism::findings::{Crossing, OpenClosure, Severity};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

fn closure_dict<'py>(py: Python<'py>, c: &OpenClosure) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("kind", "open_closure")?;
    d.set_item("severity", if c.severity() == Severity::Note { "note" } else { "warning" })?;
    d.set_item("closure", &c.what)?;
    d.set_item("place", &c.place)?;
    d.set_item("gap_m", c.gap)?;
    d.set_item("gap_rad", c.turn)?;
    d.set_item("preload_force_n", c.force)?;
    d.set_item("preload_moment_n_m", c.moment)?;
    d.set_item("preload", c.preload)?;
    d.set_item("message", c.message())?;
    Ok(d)
}

fn crossing_dict<'py, P: AsRef<[f64]>>(py: Python<'py>, c: &Crossing<P>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("kind", "crossing")?;
    d.set_item("severity", "warning")?;
    d.set_item("parts", (c.names[0].as_str(), c.names[1].as_str()))?;
    d.set_item("at", PyTuple::new(py, c.at.as_ref())?)?;
    d.set_item("s_a", c.s[0])?;
    d.set_item("s_b", c.s[1])?;
    d.set_item("points", c.points)?;
    d.set_item("message", c.message())?;
    Ok(d)
}

/// No crossings (for an analysis that has no shapes to look at: buckling, modes).
pub const NO_CROSSINGS: [(Option<f64>, Crossing); 0] = [];

/// The open closures and crossings as a list, each warning raised
/// (`what` names the call, `stacklevel` as [`warn`]); a crossing found at
/// a sample of a series carries its `time`, warned once per pair of parts.
pub fn report<'py, P: AsRef<[f64]>>(
    py: Python<'py>,
    what: &str,
    open: &[OpenClosure],
    crossings: &[(Option<f64>, Crossing<P>)],
    stacklevel: i32,
) -> PyResult<Bound<'py, PyList>> {
    report_along(py, what, open, crossings, ("time", "t", " s"), stacklevel)
}

/// [`report`], a crossing's place in the series under `key` and, in the
/// warning, as `label = value unit` (a simulation's `time`, `t`, ` s`; a
/// sweep's `value`, its parameter, no unit).
pub fn report_along<'py, P: AsRef<[f64]>>(
    py: Python<'py>,
    what: &str,
    open: &[OpenClosure],
    crossings: &[(Option<f64>, Crossing<P>)],
    (key, label, unit): (&str, &str, &str),
    stacklevel: i32,
) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for c in open {
        if c.severity() == Severity::Warning {
            warn(py, &py.get_type::<PreloadWarning>(), format!("{what}: {}", c.message()), stacklevel)?;
        }
        list.append(closure_dict(py, c)?)?;
    }
    let mut told: Vec<&[String; 2]> = Vec::new();
    for (time, c) in crossings {
        if !told.contains(&&c.names) {
            told.push(&c.names);
            let when = time.map_or(String::new(), |t| format!(" (first at {label} = {t}{unit})"));
            warn(py, &py.get_type::<IntersectionWarning>(), format!("{what}{when}: {}", c.message()), stacklevel)?;
        }
        let d = crossing_dict(py, c)?;
        if let Some(t) = time {
            d.set_item(key, t)?;
        }
        list.append(d)?;
    }
    Ok(list)
}
