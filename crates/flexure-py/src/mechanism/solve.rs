//! `Mechanism.solve`'s report, in both dimensions: the library's solve
//! report ([`flexure::report::solve_report`], what `flexure solve --json`
//! prints, through the door [`Model::solve`]), with coordinates, loads and
//! shapes as NumPy arrays and each estimate's `flagged`, and the warnings
//! and findings Python adds about it.

use crate::analyses::{MAX_FACTOR, limit_dict};
use crate::error_estimate::estimate_dict;
use crate::errors::{StabilityWarning, to_py};
use crate::findings;
use crate::interrupt::interruptible;
use crate::serialize::{to_dict, to_python};
use crate::stress::{safety_factor_of, shape_table};
use crate::strict;
use crate::warnings::{warn, warn_inaccurate, warn_unestimated};
use flexure::Error;
use flexure::estimate::Accuracy;
use flexure::model::Model;
use flexure::report::{BodyPose, CarriedLoad, EstimateFailed, Shape};
use flexure::stress::Peak;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// What to do about a flexure joint whose estimate misses the target:
/// raise its order, unless it has `order = "auto"` and stopped at the cap
/// (`capped`), as the CLI says.
fn order_hint(joint: &str, capped: &[String]) -> String {
    if capped.iter().any(|c| c == joint) {
        CAPPED.into()
    } else {
        "raise the joint's order (and quadrature) in the mechanism file".into()
    }
}

/// What a flexure of `order = "auto"` that still misses at the cap says.
pub(super) const CAPPED: &str =
    "order = \"auto\" raised it to the cap of 64 and it still misses: loosen the accuracy or reduce the load";

/// The equilibrium of `model` as `Mechanism.solve` documents it, with its
/// stability limit (`limit`, as `flexure solve --limit`).
pub fn solve<'py>(py: Python<'py>, model: &Model, target: &Accuracy, limit: bool) -> PyResult<Bound<'py, PyDict>> {
    let (solved, open, stability_limit) = interruptible(py, || {
        let open = model.open_closures()?;
        let solved = model.solve(target, None)?;
        if let Err(EstimateFailed { error: e @ (Error::Interrupted { .. } | Error::InterruptedAt { .. }), .. }) =
            solved.report
        {
            return Err(e);
        }
        // At the orders the answer was found with.
        let stability_limit = limit.then(|| solved.model.stability_limit(MAX_FACTOR)).transpose()?;
        Ok((solved, open, stability_limit))
    })?;
    // Stack level 2: the line calling `flexure.Mechanism.solve`, past its Python wrapper.
    let what = |joint: &str| format!("Mechanism.solve, flexure joint '{joint}'");
    let r = solved.report.map_err(|failed| {
        // The library's report has no answer without every estimate: say whose failed, and why.
        match warn_unestimated(py, &what(&failed.joint), &failed.error, 2) {
            Ok(()) => to_py(failed.error),
            Err(e) => e,
        }
    })?;
    let out = to_dict(py, &r)?;
    let arrays = |named: &[(String, Vec<f64>)]| -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (name, v) in named {
            d.set_item(name, PyArray1::from_slice(py, v))?;
        }
        Ok(d)
    };
    out.set_item("coordinates", arrays(&r.coordinates.0)?)?;
    // A spatial body's rotation matrix as an array (3, 3).
    let bodies = PyDict::new(py);
    for (name, pose) in &r.bodies.0 {
        let d = to_dict(py, pose)?;
        if let BodyPose::Spatial { rotation, .. } = pose {
            d.set_item("rotation", Array2::from_shape_fn((3, 3), |(i, j)| rotation[i][j]).into_pyarray(py))?;
        }
        bodies.set_item(name, d)?;
    }
    out.set_item("bodies", bodies)?;
    out.set_item("multipliers", PyArray1::from_slice(py, &r.multipliers))?;
    let loads = PyDict::new(py);
    for (name, load) in &r.load.0 {
        if let CarriedLoad::Spatial(l) = load {
            // A spatial wrench's parts as arrays (3,); a planar one's are numbers.
            let d = PyDict::new(py);
            d.set_item("moment", PyArray1::from_slice(py, &l.moment))?;
            d.set_item("force", PyArray1::from_slice(py, &l.force))?;
            loads.set_item(name, d)?;
        } else {
            loads.set_item(name, to_python(py, load)?)?;
        }
    }
    out.set_item("load", loads)?;
    super::eigen::insert_orders(py, &out, &solved.model)?;
    let estimates = PyDict::new(py);
    for (name, e) in &r.error_estimate.0 {
        if e.flagged {
            let hint = order_hint(name, &solved.capped);
            let length = model.flexure_length(name).unwrap_or(f64::NAN);
            warn_inaccurate(py, &what(name), length, e, target, &hint, 2)?;
        }
        estimates.set_item(name, estimate_dict(py, e)?)?;
    }
    out.set_item("error_estimate", estimates)?;
    // The library gives each safety factor; a YieldWarning says which fall below 1.
    for (name, _) in &r.safety_factor.0 {
        if let (Some(p), Some(strength)) = (r.stress.get(name), model.yield_strength(name)) {
            safety_factor_of(py, Some(Peak { value: p.max, at: p.at }), strength, &what(name), 2)?;
        }
    }
    if !r.shape.is_empty() {
        let shapes = PyDict::new(py);
        for (name, points) in &r.shape.0 {
            match points {
                Shape::Planar(points) => {
                    let stressed = r.stress.get(name).is_some();
                    shapes.set_item(name, shape_table(py, points, stressed)?)?;
                }
                Shape::Spatial(_) => shapes.set_item(name, to_python(py, points)?)?,
            }
        }
        out.set_item("shape", shapes)?;
    }
    let crossings: Vec<_> = solved.crossings.into_iter().map(|c| (None, c)).collect();
    let listed = findings::report(py, "Mechanism.solve", &open, &crossings, 2)?;
    if !listed.is_empty() {
        out.set_item("findings", listed)?;
    }
    if let Some(l) = &stability_limit {
        out.set_item("stability_limit", limit_dict(py, l, "Mechanism.solve(limit=True)", 2)?)?;
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
