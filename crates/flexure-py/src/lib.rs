//! Python bindings: a thin layer over the flexure library.
//!
//! Inputs accept anything array-like; outputs are float64 NumPy arrays.
//! Bad input raises `ValueError` naming the parameter; a solver that does
//! not converge raises `flexure.ConvergenceError` with its residual; an
//! equilibrium that is found but unstable warns with `flexure.StabilityWarning`;
//! an answer whose estimated error misses its accuracy target warns with
//! `flexure.AccuracyWarning`; a peak bending stress beyond the flexure's
//! yield strength warns with `flexure.YieldWarning`.
//!
//! One file per concept: the classes `Flexure` (`joint`: construction and
//! queries; its `kinematics` and `statics`) and `Mechanism` (`mechanism/`);
//! the analyses, modes, exact references, stresses and simulations they
//! answer; and beneath them the exceptions (`errors`), warnings, accuracy
//! targets, error estimates, interruption and conversions they share
//! (`serialize`: the library's `Serialize` results as Python objects).

mod accuracy;
mod analyses;
mod convert;
mod coordinates;
mod error_estimate;
mod errors;
mod exact;
mod export;
mod findings;
mod interrupt;
mod joint;
mod kinematics;
mod mechanism;
mod modes;
mod one_flexure;
mod section;
mod serialize;
mod simulate;
mod spatial;
mod statics;
mod stress;
mod strict;
mod warnings;

use errors::{AccuracyWarning, ConvergenceError, IntersectionWarning, PreloadWarning, StabilityWarning, YieldWarning};
use pyo3::prelude::*;

#[pymodule]
fn _flexure(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<joint::Flexure>()?;
    m.add_class::<spatial::SpatialFlexure>()?;
    m.add_class::<mechanism::Mechanism>()?;
    m.add_class::<exact::Elastica>()?;
    m.add_function(wrap_pyfunction!(exact::exact_elastica, m)?)?;
    m.add_function(wrap_pyfunction!(exact::exact_compliance, m)?)?;
    m.add_function(wrap_pyfunction!(exact::exact_buckling_load, m)?)?;
    m.add_function(wrap_pyfunction!(exact::exact_flexure, m)?)?;
    m.add_function(wrap_pyfunction!(exact::exact_frequencies, m)?)?;
    m.add_function(wrap_pyfunction!(interrupt::ctrl_c_at_poll, m)?)?;
    m.add("ConvergenceError", m.py().get_type::<ConvergenceError>())?;
    m.add("StabilityWarning", m.py().get_type::<StabilityWarning>())?;
    m.add("AccuracyWarning", m.py().get_type::<AccuracyWarning>())?;
    m.add("YieldWarning", m.py().get_type::<YieldWarning>())?;
    m.add("PreloadWarning", m.py().get_type::<PreloadWarning>())?;
    m.add("IntersectionWarning", m.py().get_type::<IntersectionWarning>())?;
    Ok(())
}
