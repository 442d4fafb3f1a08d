//! An answer's estimated error as Python sees it: one dict shape, built here
//! alone, for every answer that carries one (`Flexure.error_estimate`,
//! `deflect`'s warnings aside, `tendon`, `connect`, and each flexure joint of
//! `Mechanism.solve`).

use flexure::Error;
use flexure::estimate::{self, ErrorEstimate};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// An estimate as a dict: position (m), angle (rad), curvature (1/m, the peak curvature
/// change's), stress (Pa, the peak stress's; only with a thickness), flagged, reference ("model",
/// or "elastica" at order 64, where reference_order and reference_quadrature are 0),
/// reference_order, reference_quadrature.
pub fn estimate_dict<'py>(py: Python<'py>, e: &ErrorEstimate) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("position", e.position)?;
    d.set_item("angle", e.angle)?;
    d.set_item("curvature", e.curvature)?;
    if let Some(stress) = e.stress {
        d.set_item("stress", stress)?;
    }
    d.set_item("flagged", e.flagged)?;
    d.set_item("reference", if e.exact { "elastica" } else { "model" })?;
    d.set_item("reference_order", e.reference_order)?;
    d.set_item("reference_quadrature", e.reference_quadrature)?;
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
