//! An answer's estimated error as Python sees it: one dict shape, built here
//! alone, for every answer that carries one (`Flexure.error_estimate`,
//! `deflect`'s warnings aside, `tendon`, `connect`, and each flexure joint of
//! `Mechanism.solve`).

use flexure::Error;
use flexure::estimate::{self, ErrorEstimate};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// An estimate as a dict: the library's serialization of [`ErrorEstimate`], as the
/// CLI prints it (position (m), angle (rad), stress (Pa, the peak stress's; only with
/// a thickness), curvature (1/m, the peak curvature change's), reference_order,
/// reference_quadrature, reference ("model", or "elastica" at order 64, where
/// reference_order and reference_quadrature are 0)), plus `flagged`, which Python's
/// answers promise: whether it misses the accuracy target.
pub fn estimate_dict<'py>(py: Python<'py>, e: &ErrorEstimate) -> PyResult<Bound<'py, PyDict>> {
    let d = crate::serialize::to_dict(py, e)?;
    d.set_item("flagged", e.flagged)?;
    Ok(d)
}

thread_local! {
    /// The reusable estimator of `Flexure.deflect` (its reference model built once per flexure).
    pub static ESTIMATOR: std::cell::RefCell<estimate::Estimator> = std::cell::RefCell::new(estimate::Estimator::new());
}

/// An estimate's result, with an interruption passed on as the solve's error
/// (the answer is not returned) and any other failure kept for a warning.
pub type Estimated = std::result::Result<ErrorEstimate, Error>;

pub fn interrupted_or(e: flexure::Result<ErrorEstimate>) -> flexure::Result<Estimated> {
    match e {
        Err(e @ Error::Interrupted { .. }) => Err(e),
        other => Ok(other),
    }
}
