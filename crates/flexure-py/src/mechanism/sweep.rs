//! `Mechanism.sweep`: equilibria along one load, as `flexure solve --sweep`,
//! in both dimensions through the door ([`Model::sweep`]). The rows are the
//! library's table; the stack level of every warning is 2, the line that
//! called `flexure.Mechanism`'s Python wrapper.

use crate::errors::{AccuracyWarning, ConvergenceError, StabilityWarning, to_py};
use crate::findings;
use crate::interrupt::{clear_raised, raised_during, signalled};
use crate::simulate::bodies_dict;
use crate::strict::finite_answer;
use crate::warnings::{warn, warn_unestimated};
use flexure::Error;
use flexure::estimate::Accuracy;
use flexure::model::{Model, Swept};
use flexure::report::EstimateFailed;
use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::{PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Equilibria along `values` of the load `parameter` of `model`: see
/// `flexure.Mechanism.sweep`. With `frame` (a body's name and a point on it),
/// each row's compliance there. A sweep that stops raises ConvergenceError
/// (KeyboardInterrupt for Ctrl-C) whose `result` holds the rows reached,
/// with `stopped`.
pub fn sweep<'py>(
    py: Python<'py>,
    model: &Model,
    parameter: &str,
    values: &Bound<'py, PyAny>,
    target: &Accuracy,
    frame: Option<(&str, Vec<f64>)>,
) -> PyResult<Bound<'py, PyDict>> {
    crate::strict::no_bool("values", values)?;
    let values: Vec<f64> = values.extract().map_err(|_| {
        PyValueError::new_err(format!(
            "invalid values = {}: must be a sequence of numbers, the values of {parameter} to solve at in turn",
            values.repr().map(|r| r.to_string()).unwrap_or_default()
        ))
    })?;
    let max = 10_000;
    if values.is_empty() || values.len() > max {
        return Err(PyValueError::new_err(format!(
            "invalid values: {} given, a sweep takes from 1 to {max} values",
            values.len()
        )));
    }
    // As `interruptible`, but a Ctrl-C keeps the rows reached: the library ends the sweep
    // there with `stopped`, and the interrupt is raised carrying them.
    clear_raised();
    let compliance = frame.as_ref().map(|(body, at)| (*body, at.as_slice()));
    let out = py.detach(|| {
        flexure::solver::with_interrupt(signalled, || {
            let open = model.open_closures()?;
            Ok((open, model.sweep(parameter, &values, target, compliance)?))
        })
    });
    let raised = raised_during(py, || PyKeyboardInterrupt::new_err("Mechanism.sweep: interrupted"));
    let (result, swept) = match (out, raised) {
        (Ok((open, Ok(swept))), None) => (answer(py, model, parameter, &values, &open, &swept)?, swept),
        (Ok((open, Ok(swept))), Some(err)) if swept.stopped.is_some() => {
            // Interrupted within the sweep: the rows before it are kept on the exception.
            let result = answer(py, model, parameter, &values, &open, &swept)?;
            let err = if err.is_instance_of::<PyKeyboardInterrupt>(py) {
                PyKeyboardInterrupt::new_err(format!(
                    "Mechanism.sweep: interrupted after {} of {} values (kept in the exception's `result`)",
                    swept.rows.len(),
                    values.len()
                ))
            } else {
                err
            };
            err.value(py).setattr("result", result)?;
            return Err(err);
        }
        (_, Some(err)) => return Err(err),
        (Ok((_, Err(EstimateFailed { joint, error }))), None) => {
            // A row's report has no answer without every estimate: say whose failed, and why.
            warn_unestimated(py, &format!("Mechanism.sweep, flexure joint '{joint}'"), &error, 2)?;
            return Err(to_py(error));
        }
        // The library names both by the CLI's option, `--sweep PARAMETER=VALUES`: an error
        // about the parameter shows it as its value.
        (Err(Error::InvalidParameter { name: "sweep", value, reason }), None)
            if value.trim_matches('"') == parameter =>
        {
            return Err(PyValueError::new_err(format!("invalid parameter = {parameter:?}: {reason}")));
        }
        (Err(Error::InvalidParameter { name: "sweep", value, reason }), None) => {
            return Err(PyValueError::new_err(format!("invalid values: one is {value}: {reason}")));
        }
        (Err(e), None) => return Err(to_py(e)),
    };
    let Some((value, e)) = &swept.stopped else { return Ok(result) };
    let text = format!(
        "Mechanism.sweep: the sweep stopped at {parameter} = {value} after {} of {} values (kept in the exception's `result`), {}: {e}",
        swept.rows.len(),
        values.len(),
        flexure::mechanism::sweep::way_to(swept.rows.last().map(|r| r[0]))
    );
    let err = match e {
        Error::Interrupted { .. } | Error::InterruptedAt { .. } => PyKeyboardInterrupt::new_err(text),
        _ => {
            let err = ConvergenceError::new_err(text);
            if let Error::NoConvergence { residual, .. } | Error::ContinuationStalled { residual, .. } = e {
                err.value(py).setattr("residual", residual)?;
            }
            err
        }
    };
    err.value(py).setattr("result", &result)?;
    Err(err)
}

/// The answer of a sweep, its warnings given: values (n,), bodies (each
/// pose key an (n,) array; a spatial body's rotation (n, 3, 3)), coordinates
/// {joint: (n, k)}, energy (n,), stress {flexure joint with a section: (n,)},
/// normal_force {contact.GEOM.PART: (n,)} and contacts (a list per row)
/// where a part may touch a geom, compliance (n, k, k) if asked for,
/// `stability_limit`, `flagged`, `findings` and `stopped`.
fn answer<'py>(
    py: Python<'py>,
    model: &Model,
    parameter: &str,
    values: &[f64],
    open: &[flexure::mechanism::findings::OpenClosure],
    swept: &Swept,
) -> PyResult<Bound<'py, PyDict>> {
    let n = swept.rows.len();
    let column = |name: &str| swept.columns.iter().position(|c| c == name);
    let values_at = |c: usize| Array1::from_iter(swept.rows.iter().map(|r| r[c]));
    let result = PyDict::new(py);
    result.set_item("dimension", model.dimension())?;
    result.set_item("values", values_at(0).into_pyarray(py))?;
    result.set_item("bodies", bodies_dict(py, &swept.bodies)?)?;
    let coordinates = PyDict::new(py);
    // The coordinates of the model the rows were found with: an `order = "auto"` flexure's raised.
    for (name, range) in swept.model.joints() {
        let a = Array2::from_shape_fn((n, range.len()), |(r, i)| swept.q[r][range.start + i]);
        coordinates.set_item(&name, a.into_pyarray(py))?;
    }
    result.set_item("coordinates", coordinates)?;
    let energy = column("energy").expect("a sweep's table has an energy column");
    result.set_item("energy", values_at(energy).into_pyarray(py))?;
    let stress = PyDict::new(py);
    for (c, name) in swept.columns.iter().enumerate() {
        if let Some(joint) = name.strip_suffix(".stress") {
            stress.set_item(joint, values_at(c).into_pyarray(py))?;
        }
    }
    if !stress.is_empty() {
        result.set_item("stress", stress)?;
    }
    // Where a part may touch a geom: each pair's push by row, and each row's
    // contacts as `solve` lists them (as `simulate`'s, one list per row).
    let normal_force = PyDict::new(py);
    for (c, name) in swept.columns.iter().enumerate() {
        if let Some(pair) = name.strip_suffix(".normal_force").filter(|p| p.starts_with("contact.")) {
            normal_force.set_item(pair, values_at(c).into_pyarray(py))?;
        }
    }
    if !normal_force.is_empty() {
        result.set_item("normal_force", normal_force)?;
    }
    if let Some(contacts) = &swept.contacts {
        result.set_item("contacts", crate::serialize::to_python(py, contacts)?)?;
    }
    if let Some(first) = swept.columns.iter().position(|c| c.starts_with("compliance.")) {
        let k = (swept.columns.len() - first).isqrt();
        let a = Array3::from_shape_fn((n, k, k), |(r, i, j)| swept.rows[r][first + i * k + j]);
        result.set_item("compliance", a.into_pyarray(py))?;
    }
    if let Some(l) = &swept.stability_limit {
        result.set_item("stability_limit", crate::serialize::to_dict(py, l)?)?;
        let beyond = match values.len() - n {
            0 => "the path snapped through to stable states beyond it".to_string(),
            1 => "the last value has no stable equilibrium reachable by loading and is left out".to_string(),
            k => format!("the last {k} values have no stable equilibrium reachable by loading and are left out"),
        };
        let text = format!(
            "Mechanism.sweep: stability is lost at {parameter} = {} ({:.4} % along the sweep); {beyond}",
            l.value,
            100.0 * l.fraction
        );
        warn(py, &py.get_type::<StabilityWarning>(), text, 2)?;
    }
    super::eigen::insert_orders(py, &result, &swept.model)?;
    if !swept.flagged.is_empty() {
        let hint = match swept.capped.as_slice() {
            [] => "raise its order".to_string(),
            capped => format!("flexure joints {capped:?}: {}", super::solve::CAPPED),
        };
        let text = format!(
            "Mechanism.sweep: at {} of the swept values a flexure joint's estimated error misses the accuracy target (listed in `flagged`); {hint}",
            swept.flagged.len()
        );
        warn(py, &py.get_type::<AccuracyWarning>(), text, 2)?;
    }
    result.set_item("flagged", PyArray1::from_slice(py, &swept.flagged))?;
    let crossings: Vec<_> = (swept.crossings.iter())
        .flat_map(|(k, cs)| cs.iter().map(move |c| (Some(swept.rows[*k][0]), c.clone())))
        .collect();
    let listed = findings::report_along(py, "Mechanism.sweep", open, &crossings, ("value", parameter, ""), 2)?;
    if !listed.is_empty() {
        result.set_item("findings", listed)?;
    }
    if let Some((value, e)) = &swept.stopped {
        let d = PyDict::new(py);
        d.set_item("value", value)?;
        d.set_item(
            "error",
            format!(
                "the sweep stopped at {parameter} = {value} after {n} of {} values, {}: {e}",
                values.len(),
                flexure::mechanism::sweep::way_to(swept.rows.last().map(|r| r[0]))
            ),
        )?;
        result.set_item("stopped", d)?;
    }
    finite_answer("Mechanism.sweep", result.as_any())?;
    Ok(result)
}
