//! What `flexure solve` and `flexure buckle` answer on a mechanism file, in
//! Python, beside the solve itself (`solve.rs`): linear buckling (`Mechanism.buckle`), the compliance of a frame on a body
//! (`Mechanism.compliance`, as `solve --compliance BODY --at X,Y`) and
//! sweeps of one load (`Mechanism.sweep`, as `solve --sweep`). The numbers
//! are the library's; the stack level of every warning is 2, the line that
//! called `flexure.Mechanism`'s Python wrapper.

use crate::errors::{AccuracyWarning, ConvergenceError, StabilityWarning, to_py};
use crate::findings;
use crate::interrupt::{clear_raised, raised_during, signalled};
use crate::strict::finite_answer;
use crate::warnings::warn;
use flexure::Error;
use flexure::estimate::{self, Accuracy, ErrorEstimate};
use flexure::mechanism::Mechanism;
use flexure::mechanism::statics::{Settings, Solution, body_frames, compliance};
use flexure::mechanism::sweep::{Parameter, sweep as run_sweep};
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::{PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A sweep's rows as arrays: values (n,), bodies {name: {x, y, phi}} (the
/// ground left out), coordinates {joint: (n, k)}, energy (n,) and stress
/// {flexure joint with a thickness: (n,) peak stress (Pa)}.
fn rows_dict<'py>(py: Python<'py>, m: &Mechanism, rows: &[(f64, Solution)]) -> PyResult<Bound<'py, PyDict>> {
    let n = rows.len();
    let out = PyDict::new(py);
    out.set_item("values", PyArray1::from_vec(py, rows.iter().map(|r| r.0).collect()))?;
    let frames: Vec<_> = rows.iter().map(|(_, s)| body_frames(m, s)).collect();
    let bodies = PyDict::new(py);
    for (k, b) in m.bodies.iter().enumerate().skip(1) {
        let d = PyDict::new(py);
        d.set_item("x", Array1::from_iter(frames.iter().map(|f| f.bodies[k].x)).into_pyarray(py))?;
        d.set_item("y", Array1::from_iter(frames.iter().map(|f| f.bodies[k].y)).into_pyarray(py))?;
        d.set_item("phi", Array1::from_iter(frames.iter().map(|f| f.bodies[k].phi)).into_pyarray(py))?;
        bodies.set_item(&b.name, d)?;
    }
    out.set_item("bodies", bodies)?;
    let coordinates = PyDict::new(py);
    for j in &m.joints {
        let d = j.kind.joint().dof();
        let a = Array2::from_shape_fn((n, d), |(r, i)| rows[r].1.q[j.offset + i]);
        coordinates.set_item(&j.name, a.into_pyarray(py))?;
    }
    out.set_item("coordinates", coordinates)?;
    out.set_item("energy", PyArray1::from_vec(py, rows.iter().map(|r| r.1.energy).collect()))?;
    let stress = PyDict::new(py);
    for j in &m.joints {
        if let Some(f) = j.kind.flexure()
            && f.section().modulus().is_some()
        {
            let peaks = rows.iter().map(|(_, s)| {
                flexure::stress::peak_stress(f, &s.q[j.offset..j.offset + f.order()]).map_or(0.0, |p| p.value)
            });
            stress.set_item(&j.name, Array1::from_iter(peaks).into_pyarray(py))?;
        }
    }
    if !stress.is_empty() {
        out.set_item("stress", stress)?;
    }
    Ok(out)
}

/// Equilibria along `values` of one load, as `solve --sweep PARAMETER=...`:
/// see `flexure.Mechanism.sweep`. A sweep that stops raises
/// ConvergenceError (KeyboardInterrupt for Ctrl-C) whose `result` holds
/// the rows reached, with `stopped`.
pub fn sweep<'py>(
    py: Python<'py>,
    m: &Mechanism,
    parameter: &str,
    values: &Bound<'py, PyAny>,
    target: &Accuracy,
    frame: Option<(usize, Vec<f64>)>,
) -> PyResult<Bound<'py, PyDict>> {
    // The compliance of a frame at every row, as `solve --sweep ... --compliance BODY --at X,Y`.
    let frame = frame.map(|(body, p)| (body, [p[0], p[1]]));
    // The library names a sweep's parameter and values `sweep` (the CLI's option): Python's are
    // `parameter` and `values`.
    let p = Parameter::parse(m, parameter).map_err(|e| match e {
        Error::InvalidParameter { value, reason, .. } => {
            PyValueError::new_err(format!("invalid parameter = {value}: {reason}"))
        }
        other => to_py(other),
    })?;
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
    let settings = Settings::default();
    // As `interruptible`, but a Ctrl-C keeps the rows reached: the library ends the sweep
    // there with `stopped`, and the interrupt is raised carrying them.
    clear_raised();
    let out = py.detach(|| {
        flexure::solver::with_interrupt(signalled, || {
            let open = flexure::mechanism::findings::open_closures(m, &settings)?;
            let out = run_sweep(m, &p, &values, &settings)?;
            let mut estimated = Vec::new();
            for (v, s) in &out.rows {
                let mut one = Vec::new();
                for j in &m.joints {
                    if let Some(f) = j.kind.flexure() {
                        let alpha = &s.q[j.offset..j.offset + f.order()];
                        one.push(match estimate::joint_error(f, alpha, target) {
                            Err(e @ Error::Interrupted { .. }) => return Err(e),
                            other => other.ok(),
                        });
                    }
                }
                estimated.push((*v, one));
            }
            let compliances = match frame {
                Some((b, at)) => Some(
                    out.rows
                        .iter()
                        .map(|(_, s)| compliance(m, s, b, at.into()))
                        .collect::<flexure::Result<Vec<_>>>()?,
                ),
                None => None,
            };
            Ok((open, out, estimated, compliances))
        })
    });
    let raised = raised_during(py, || PyKeyboardInterrupt::new_err("Mechanism.sweep: interrupted"));
    let put_compliance = |result: &Bound<'py, PyDict>, cs: &Option<Vec<nalgebra::Matrix3<f64>>>| match cs {
        Some(cs) => {
            let a = numpy::ndarray::Array3::from_shape_fn((cs.len(), 3, 3), |(k, i, j)| cs[k][(i, j)]);
            result.set_item("compliance", a.into_pyarray(py))
        }
        None => Ok(()),
    };
    let (open, out, estimated, compliances) = match (out, raised) {
        (Ok(found), None) => found,
        (Ok((open, out, estimated, compliances)), Some(err)) if out.stopped.is_some() => {
            // Interrupted within the sweep: the rows before it are kept on the exception.
            let found = (open, out, estimated);
            let result = answer(py, m, parameter, &values, &found)?;
            put_compliance(&result, &compliances)?;
            let err = if err.is_instance_of::<PyKeyboardInterrupt>(py) {
                PyKeyboardInterrupt::new_err(format!(
                    "Mechanism.sweep: interrupted after {} of {} values (kept in the exception's `result`)",
                    found.1.rows.len(),
                    values.len()
                ))
            } else {
                err
            };
            err.value(py).setattr("result", result)?;
            return Err(err);
        }
        (_, Some(err)) => return Err(err),
        (Err(Error::InvalidParameter { name: "sweep", value, reason }), None) => {
            return Err(PyValueError::new_err(format!("invalid values: one is {value}: {reason}")));
        }
        (Err(e), None) => return Err(to_py(e)),
    };
    let result = answer(py, m, parameter, &values, &(open, out.clone(), estimated))?;
    put_compliance(&result, &compliances)?;
    if let Some((value, e)) = &out.stopped {
        let text = format!(
            "Mechanism.sweep: the sweep stopped at {parameter} = {value} after {} of {} values (kept in the exception's `result`): {e}",
            out.rows.len(),
            values.len()
        );
        let err = match e {
            Error::Interrupted { .. } => PyKeyboardInterrupt::new_err(text),
            _ => {
                let err = ConvergenceError::new_err(text);
                if let Error::NoConvergence { residual, .. } | Error::ContinuationStalled { residual, .. } = e {
                    err.value(py).setattr("residual", residual)?;
                }
                err
            }
        };
        err.value(py).setattr("result", &result)?;
        return Err(err);
    }
    Ok(result)
}

/// The answer of a sweep, its warnings given: the rows, `stability_limit`,
/// `flagged` (the values at which a joint's estimate misses the target),
/// `findings` and `stopped`.
#[allow(clippy::type_complexity)]
fn answer<'py>(
    py: Python<'py>,
    m: &Mechanism,
    parameter: &str,
    values: &[f64],
    (open, out, estimated): &(
        Vec<flexure::mechanism::findings::OpenClosure>,
        flexure::mechanism::sweep::Sweep,
        Vec<(f64, Vec<Option<ErrorEstimate>>)>,
    ),
) -> PyResult<Bound<'py, PyDict>> {
    let result = rows_dict(py, m, &out.rows)?;
    if let Some(l) = &out.stability_limit {
        result.set_item("stability_limit", crate::serialize::to_dict(py, l)?)?;
        let beyond = match values.len() - out.rows.len() {
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
    let flagged: Vec<f64> = estimated
        .iter()
        .filter(|(_, es)| es.iter().any(|e| e.as_ref().is_none_or(|e| e.flagged)))
        .map(|(v, _)| *v)
        .collect();
    if !flagged.is_empty() {
        let text = format!(
            "Mechanism.sweep: at {} of the swept values a flexure joint's estimated error misses the accuracy target (or could not be estimated; listed in `flagged`); raise its order",
            flagged.len()
        );
        warn(py, &py.get_type::<AccuracyWarning>(), text, 2)?;
    }
    result.set_item("flagged", PyArray1::from_vec(py, flagged))?;
    let crossings: Vec<_> = flexure::mechanism::findings::crossings_along(m, out.rows.iter().map(|r| r.1.q.as_slice()))
        .into_iter()
        .flat_map(|(k, cs)| cs.into_iter().map(move |c| (Some(out.rows[k].0), c)))
        .collect();
    let listed = findings::report_along(py, "Mechanism.sweep", open, &crossings, ("value", parameter, ""), 2)?;
    if !listed.is_empty() {
        result.set_item("findings", listed)?;
    }
    if let Some((value, e)) = &out.stopped {
        let d = PyDict::new(py);
        d.set_item("value", value)?;
        d.set_item(
            "error",
            format!(
                "the sweep stopped at {parameter} = {value} after {} of {} values: {e}",
                out.rows.len(),
                values.len()
            ),
        )?;
        result.set_item("stopped", d)?;
    }
    finite_answer("Mechanism.sweep", result.as_any())?;
    Ok(result)
}
