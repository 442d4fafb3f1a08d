//! `Mechanism.buckle` and `Mechanism.modes`, in both dimensions, through the
//! door ([`Model::buckle`], [`Model::modes`]): the library's answer with its
//! estimate, as `flexure buckle --json` and `flexure modes --json` print
//! them, vectors as NumPy arrays, and the warnings Python adds about them.

use crate::errors::StabilityWarning;
use crate::findings;
use crate::interrupt::interruptible;
use crate::strict::{finite_answer, finite_slice};
use crate::warnings::{sig, warn, warn_values};
use flexure::estimate::{Accuracy, ValueEstimate};
use flexure::model::Model;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `order` {joint: int (planar) or [n_twist, n_y, n_z] (spatial)} when a
/// flexure has `order = "auto"`: the orders the answer was found at, as the
/// CLI's (`buckle`, `modes`, `solve` and `sweep` alike).
pub(crate) fn insert_orders(py: Python<'_>, out: &Bound<'_, PyDict>, used: &Model) -> PyResult<()> {
    if used.auto_order() {
        let orders = PyDict::new(py);
        for (name, o) in used.orders().0 {
            match o.as_slice() {
                [one] => orders.set_item(name, one)?,
                all => orders.set_item(name, all.to_vec())?,
            }
        }
        out.set_item("order", orders)?;
    }
    Ok(())
}

/// What to do about an eigenvalue answer of `used` that misses its target.
fn order_hint(used: &Model) -> &'static str {
    if used.auto_order() {
        "the flexures of order = \"auto\" are at the cap of 64, or there are none left to raise: give the others order = \"auto\""
    } else {
        "give the flexures order = \"auto\" (or a higher order) in the mechanism file"
    }
}

/// The warning of a missed estimate `e` of `used`, after `what` and naming each value by `name`.
fn warn_missed(
    py: Python<'_>,
    (what, hint): (&str, &str),
    used: &Model,
    e: &ValueEstimate,
    target: &Accuracy,
    name: impl Fn(usize) -> String,
) -> PyResult<()> {
    warn_values(py, what, e, target, name, &used.reference_of(e), hint, 2)
}

/// Linear buckling about the unloaded configuration, as `flexure buckle --json`.
pub fn buckle<'py>(py: Python<'py>, model: &Model, target: &Accuracy) -> PyResult<Bound<'py, PyDict>> {
    let (open, found) = interruptible(py, || Ok((model.open_closures()?, model.buckle(target)?)))?;
    let (b, e, used) = (&found.answer, &found.estimate, &found.model);
    let out = crate::serialize::to_dict(py, b)?;
    let listed = findings::report(py, "Mechanism.buckle", &open, &findings::NO_CROSSINGS, 2)?;
    if !listed.is_empty() {
        out.set_item("findings", listed)?;
    }
    out.set_item("mode", PyArray1::from_vec(py, b.mode.clone()))?;
    out.set_item("dimension", model.dimension())?;
    // As the CLI's: the relative error, reference_load_factor, the reference orders by
    // joint, and where there is no estimate, `unestimated` and `reference_stable`.
    let d = PyDict::new(py);
    if let Some(Some(r)) = e.relative.first() {
        d.set_item("load_factor", *r)?;
    } else {
        d.set_item("unestimated", vec![1])?;
        d.set_item("reference_stable", e.reference_stable)?;
    }
    if let Some(r) = e.reference.first() {
        d.set_item("reference_load_factor", *r)?;
    }
    crate::modes::insert_reference_orders(py, &d, &used.flexure_names(), &e.reference_orders)?;
    out.set_item("error_estimate", d)?;
    out.set_item("flagged", e.flagged)?;
    insert_orders(py, &out, used)?;
    let name = |_| format!("the load factor {}", sig(b.load_factor));
    warn_missed(py, ("Mechanism.buckle", order_hint(used)), used, e, target, name)?;
    finite_answer("Mechanism.buckle", out.as_any())?;
    Ok(out)
}

/// Vibration modes about the loaded equilibrium, as `flexure modes --json`:
/// omega, frequency, quasi_static, shapes {joint: (modes, k)}, limit_fraction
/// after a snap-through, the estimate, and the closures open at rest.
pub fn modes<'py>(
    py: Python<'py>,
    model: &Model,
    count: Option<&Bound<'py, PyAny>>,
    target: &Accuracy,
) -> PyResult<Bound<'py, PyDict>> {
    let asked = crate::modes::wanted(count, model.dof(), "the mechanism")?;
    let (open, found) = interruptible(py, || Ok((model.open_closures()?, model.modes(asked, target)?)))?;
    let (modes, e, used) = (&found.answer, &found.estimate, &found.model);
    let out = PyDict::new(py);
    let listed = findings::report(py, "Mechanism.modes", &open, &findings::NO_CROSSINGS, 2)?;
    if !listed.is_empty() {
        out.set_item("findings", listed)?;
    }
    out.set_item("dimension", model.dimension())?;
    out.set_item("omega", PyArray1::from_vec(py, modes.omega.clone()))?;
    out.set_item("frequency", PyArray1::from_vec(py, modes.frequency.clone()))?;
    out.set_item("quasi_static", modes.quasi_static)?;
    finite_answer("Mechanism.modes", out.as_any())?;
    // After the check: the estimate's omega holds NaN where the reference pairs no mode.
    finite_slice("Mechanism.modes error_estimate reference_omega", &e.reference)?;
    finite_slice("Mechanism.modes shapes", modes.shapes.as_slice())?;
    let shapes = PyDict::new(py);
    for (name, range) in used.coordinates() {
        let a = Array2::from_shape_fn((modes.omega.len(), range.len()), |(k, i)| modes.shapes[(range.start + i, k)]);
        shapes.set_item(name, a.into_pyarray(py))?;
    }
    out.set_item("shapes", shapes)?;
    crate::modes::insert_estimate(py, &out, e, Some(&used.flexure_names()))?;
    insert_orders(py, &out, used)?;
    let name = |k: usize| format!("mode {} ({} rad/s)", k + 1, sig(modes.omega[k]));
    let hint = format!("{}, or ask fewer modes", order_hint(used));
    warn_missed(py, ("Mechanism.modes", &hint), used, e, target, name)?;
    if let Some(limit) = modes.limit {
        out.set_item("limit_fraction", limit)?;
        let text = format!(
            "Mechanism.modes: the loading path lost stability at {:.4} % of the load and snapped through: these are the modes about the stable equilibrium beyond it",
            100.0 * limit
        );
        warn(py, &py.get_type::<StabilityWarning>(), text, 2)?;
    }
    Ok(out)
}
