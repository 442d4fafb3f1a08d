//! `Mechanism.solve`'s report: the library's solve report
//! ([`solve_report`], what `flexure solve --json` prints), with coordinates
//! and shapes as NumPy arrays and each estimate's `flagged`, and the
//! warnings and findings Python adds about it.

use crate::error_estimate::estimate_dict;
use crate::errors::{StabilityWarning, to_py};
use crate::findings;
use crate::interrupt::interruptible;
use crate::serialize::to_dict;
use crate::stress::{safety_factor_of, shape_table};
use crate::strict;
use crate::warnings::{warn, warn_inaccurate, warn_unestimated};
use flexure::Error;
use flexure::estimate::Accuracy;
use flexure::mechanism::Mechanism;
use flexure::mechanism::file::ReportOptions;
use flexure::mechanism::statics::{Settings as MechanismSettings, solve as equilibrium};
use flexure::report::{EstimateFailed, solve_report};
use flexure::stress::Peak;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The equilibrium of `m` as `Mechanism.solve` documents it; `reports` holds
/// each flexure joint's `yield_strength` and `shape`, by name.
pub fn solve<'py>(
    py: Python<'py>,
    m: &Mechanism,
    reports: &[(String, ReportOptions)],
    target: &Accuracy,
) -> PyResult<Bound<'py, PyDict>> {
    let (s, report, open) = interruptible(py, || {
        let open = flexure::mechanism::findings::open_closures(m, &MechanismSettings::default())?;
        let s = equilibrium(m, &MechanismSettings::default())?;
        let report = match solve_report(m, &s, reports, target) {
            Err(EstimateFailed { error: e @ Error::Interrupted { .. }, .. }) => return Err(e),
            other => other,
        };
        Ok((s, report, open))
    })?;
    // Stack level 2: the line calling `flexure.Mechanism.solve`, past its Python wrapper.
    let what = |joint: &str| format!("Mechanism.solve, flexure joint '{joint}'");
    let r = report.map_err(|failed| {
        // The library's report has no answer without every estimate: say whose failed, and why.
        match warn_unestimated(py, &what(&failed.joint), &failed.error, 2) {
            Ok(()) => to_py(failed.error),
            Err(e) => e,
        }
    })?;
    let flexure_of = |name: &str| m.joints.iter().find(|j| j.name == name).and_then(|j| j.kind.flexure());
    let out = to_dict(py, &r)?;
    let coordinates = PyDict::new(py);
    for (name, q) in &r.coordinates.0 {
        coordinates.set_item(name, PyArray1::from_slice(py, q))?;
    }
    out.set_item("coordinates", coordinates)?;
    let estimates = PyDict::new(py);
    for (name, e) in &r.error_estimate.0 {
        if let Some(f) = flexure_of(name).filter(|_| e.flagged) {
            let hint = "raise the joint's order (and quadrature) in the mechanism file";
            warn_inaccurate(py, &what(name), f, e, target, hint, 2)?;
        }
        estimates.set_item(name, estimate_dict(py, e)?)?;
    }
    out.set_item("error_estimate", estimates)?;
    // The library gives each safety factor; a YieldWarning says which fall below 1.
    for (name, _) in &r.safety_factor.0 {
        let strength = reports.iter().find(|k| &k.0 == name).and_then(|k| k.1.yield_strength);
        if let (Some(p), Some(strength)) = (r.stress.get(name), strength) {
            safety_factor_of(py, Some(Peak { value: p.max, at: p.at }), strength, &what(name), 2)?;
        }
    }
    if !r.shape.is_empty() {
        let shapes = PyDict::new(py);
        for (name, points) in &r.shape.0 {
            let stressed = flexure_of(name).is_some_and(|f| f.section().modulus().is_some());
            shapes.set_item(name, shape_table(py, points, stressed)?)?;
        }
        out.set_item("shape", shapes)?;
    }
    let crossings = flexure::mechanism::findings::crossings(m, &s.q).into_iter().map(|c| (None, c)).collect::<Vec<_>>();
    let listed = findings::report(py, "Mechanism.solve", &open, &crossings, 2)?;
    if !listed.is_empty() {
        out.set_item("findings", listed)?;
    }
    if let Some(limit) = r.limit_fraction {
        // A snap-through: the stable answer beyond a limit load, which the caller must know of.
        let text = format!(
            "Mechanism.solve: the loading path lost stability at {:.4} % of the load and snapped through to this stable equilibrium",
            100.0 * limit
        );
        warn(py, &py.get_type::<StabilityWarning>(), text, 2)?;
    }
    if !r.stable {
        let text = "Mechanism.solve: the equilibrium is unstable (`stable` is False): its constrained stiffness is not positive definite, so a small disturbance moves it away".to_string();
        warn(py, &py.get_type::<StabilityWarning>(), text, 2)?;
    }
    strict::finite_answer("Mechanism.solve", out.as_any())?;
    Ok(out)
}
