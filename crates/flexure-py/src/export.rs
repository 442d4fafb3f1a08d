//! `Mechanism.export`: the mechanism as MJCF, SDFormat or URDF text, with its fit report.

use crate::errors::to_py;
use crate::interrupt::interruptible;
use crate::serialize::to_dict;
use crate::strict::Real;
use flexure::export::{Format, LoadRange, Options};
use flexure::prb::PrbKind;
use pyo3::exceptions::{PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

/// The load range: None (the file's loads from 0 to 1 at 12 fractions), a
/// string "F0:F1:N", or a sequence (F0, F1, N).
fn load_range(range: Option<&Bound<'_, PyAny>>) -> PyResult<LoadRange> {
    let Some(r) = range.filter(|r| !r.is_none()) else { return Ok(LoadRange::default()) };
    if let Ok(s) = r.cast::<PyString>() {
        return s.to_str()?.parse().map_err(to_py);
    }
    let bad = || {
        PyValueError::new_err(format!(
            "invalid range = {r}: must be \"F0:F1:N\" or (F0, F1, N), fractions of the file's loads"
        ))
    };
    let (from, to, count): (Real, Real, Bound<'_, PyAny>) = r.extract().map_err(|_| bad())?;
    if crate::strict::is_bool(&count) {
        return Err(bad());
    }
    let count: usize = count.extract().map_err(|_| bad())?;
    let r = LoadRange { from: from.0, to: to.0, count };
    r.validate().map_err(to_py)?;
    Ok(r)
}

/// The model as text and the fit report as a dict (`flexure export --json`'s
/// keys); each warning is also raised as a `UserWarning`.
#[allow(clippy::too_many_arguments)]
pub fn export<'py>(
    py: Python<'py>,
    m: &flexure::model::Model,
    to: &str,
    prb: &str,
    range: Option<&Bound<'py, PyAny>>,
    armature: Real,
    step: Real,
    name: &str,
) -> PyResult<(String, Bound<'py, PyDict>)> {
    let format: Format = to.parse().map_err(to_py)?;
    let prb: PrbKind = prb.parse().map_err(to_py)?;
    let range = load_range(range)?;
    let options =
        Options { format, prb, range, armature: armature.0, step: step.0, name: name.into(), ..Default::default() };
    let e = interruptible(py, || m.export(&options))?;
    for w in &e.warnings {
        crate::warnings::warn(py, &py.get_type::<PyUserWarning>(), w.clone(), 2)?;
    }
    let report = to_dict(py, &e.report)?;
    Ok((e.xml, report))
}
