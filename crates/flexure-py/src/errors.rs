//! The package's exceptions and warning categories, and the library's
//! [`Error`] as a Python exception.

use flexure::Error;
use pyo3::create_exception;
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyUserWarning, PyValueError};
use pyo3::prelude::*;

create_exception!(
    _flexure,
    ConvergenceError,
    PyRuntimeError,
    "A solver stopped before meeting its tolerance; `residual` holds its last residual."
);

create_exception!(
    _flexure,
    StabilityWarning,
    PyUserWarning,
    "An equilibrium was found but is unstable: a small disturbance would move the flexure away from it."
);

create_exception!(
    _flexure,
    AccuracyWarning,
    PyUserWarning,
    "A model answer's estimated error misses its accuracy target (by default 1 % of the length and 1 degree)."
);

create_exception!(
    _flexure,
    YieldWarning,
    PyUserWarning,
    "A flexure's peak bending stress exceeds its yield strength: the safety factor is below 1."
);

create_exception!(
    _flexure,
    PreloadWarning,
    PyUserWarning,
    "A weld or pin of a mechanism is open at rest: closing it preloads the mechanism before any load acts (say `preload = true` in it if that is meant)."
);

create_exception!(
    _flexure,
    IntersectionWarning,
    PyUserWarning,
    "Two parts of a solved mechanism (flexures, links) cross: parts touch only geoms, not each other, so the shape passes through itself."
);

/// The library's error as a Python exception.
pub fn to_py(e: Error) -> PyErr {
    match e {
        Error::NoConvergence { residual, .. } | Error::ContinuationStalled { residual, .. } => {
            let err = ConvergenceError::new_err(e.to_string());
            Python::attach(|py| {
                let _ = err.value(py).setattr("residual", residual);
            });
            err
        }
        Error::Unstable { load_fraction, .. } => {
            let err = ConvergenceError::new_err(e.to_string());
            Python::attach(|py| {
                let _ = err.value(py).setattr("load_fraction", load_fraction);
            });
            err
        }
        Error::IntegrationStalled { time, .. } => {
            let err = ConvergenceError::new_err(e.to_string());
            Python::attach(|py| {
                let _ = err.value(py).setattr("time", time);
            });
            err
        }
        Error::Interrupted { .. } | Error::InterruptedAt { .. } => PyKeyboardInterrupt::new_err(e.to_string()),
        other => PyValueError::new_err(other.to_string()),
    }
}
