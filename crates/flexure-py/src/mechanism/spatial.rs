//! The analyses of a spatial mechanism (a file with `dimension = 3`) that
//! the door does not answer yet, in the shape of the planar ones:
//! `compliance` (6 × 6), `sweep` and `simulate`. Bodies' placements are
//! NumPy arrays: a position (3,), a rotation matrix (3, 3) and URDF's roll,
//! pitch, yaw (3,). The numbers are the library's; the stack level of every
//! warning is 2, the line that called `flexure.Mechanism`'s Python wrapper.

use crate::errors::{AccuracyWarning, ConvergenceError, StabilityWarning, to_py};
use crate::findings;
use crate::interrupt::interruptible;
use crate::strict::finite_answer;
use crate::warnings::warn;
use flexure::Error;

use flexure::estimate::Accuracy;
use flexure::mechanism::spatial::SpatialMechanism;
use flexure::mechanism::spatial::findings::{crossings_along, open_closures};
use flexure::mechanism::statics::{Solution, compliance};
use flexure::mechanism::sweep::{SpatialParameter, sweep as run_sweep};
use flexure::report::{BodyPose, Reported};
use flexure::solver::Settings;
use flexure::space::Spatial;
use nalgebra::Point3;
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Each moving body's placement at `q`: position, rotation by rows, and roll, pitch, yaw.
type Placement = ([f64; 3], [[f64; 3]; 3], [f64; 3]);

fn placements(m: &SpatialMechanism, q: &[f64]) -> Vec<Placement> {
    let poses = <Spatial as Reported>::poses(m, q);
    poses
        .into_iter()
        .skip(1)
        .filter_map(|p| match p {
            BodyPose::Spatial { x, y, z, roll, pitch, yaw, rotation } => {
                Some(([x, y, z], rotation, [roll, pitch, yaw]))
            }
            BodyPose::Planar { .. } => None,
        })
        .collect()
}

/// A sweep's rows as arrays: values (n,), bodies {name: {position (n, 3),
/// rotation (n, 3, 3), rpy (n, 3)}}, coordinates {joint: (n, k)}, energy (n,).
fn rows_dict<'py>(
    py: Python<'py>,
    m: &SpatialMechanism,
    rows: &[(f64, Solution<Spatial>)],
) -> PyResult<Bound<'py, PyDict>> {
    let n = rows.len();
    let out = PyDict::new(py);
    out.set_item("dimension", 3)?;
    out.set_item("values", PyArray1::from_vec(py, rows.iter().map(|r| r.0).collect()))?;
    let placed: Vec<Vec<Placement>> = rows.iter().map(|(_, s)| placements(m, &s.q)).collect();
    let bodies = PyDict::new(py);
    for (k, b) in m.bodies.iter().enumerate().skip(1) {
        let d = PyDict::new(py);
        let at = |r: usize| &placed[r][k - 1];
        d.set_item("position", Array2::from_shape_fn((n, 3), |(r, i)| at(r).0[i]).into_pyarray(py))?;
        d.set_item("rotation", Array3::from_shape_fn((n, 3, 3), |(r, i, j)| at(r).1[i][j]).into_pyarray(py))?;
        d.set_item("rpy", Array2::from_shape_fn((n, 3), |(r, i)| at(r).2[i]).into_pyarray(py))?;
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
    Ok(out)
}

/// Equilibria along `values` of one load of a spatial mechanism, as
/// `flexure solve --sweep` on a spatial file: see `flexure.Mechanism.sweep`.
/// With `frame` (a body, and a point on it), each row's 6 × 6 compliance there.
pub fn sweep<'py>(
    py: Python<'py>,
    m: &SpatialMechanism,
    parameter: &str,
    values: &Bound<'py, PyAny>,
    target: &Accuracy,
    frame: Option<(usize, Vec<f64>)>,
) -> PyResult<Bound<'py, PyDict>> {
    let frame = frame.map(|(body, p)| (body, Point3::new(p[0], p[1], p[2])));
    let p = SpatialParameter::parse(m, parameter).map_err(|e| match e {
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
    let (out, estimated, compliances, open) = interruptible(py, || {
        let open = open_closures(m, &Settings::default())?;
        let out = match run_sweep(m, &p, &values, &Settings::default()) {
            Err(Error::InvalidParameter { name: "sweep", value, reason }) => {
                return Err(Error::InvalidParameter { name: "values", value, reason });
            }
            other => other?,
        };
        let mut estimated = Vec::with_capacity(out.rows.len());
        for (v, s) in &out.rows {
            let errors = match flexure::estimate::spatial_mechanism::flexure_errors(m, s, target) {
                Err(e @ Error::Interrupted { .. }) => return Err(e),
                other => other.ok(),
            };
            // A row is flagged when an estimate misses the target or could not be made.
            let flagged = errors.is_none_or(|es| es.iter().flatten().any(|e| e.flagged));
            estimated.push((*v, flagged));
        }
        let compliances = match frame {
            Some((b, at)) => {
                Some(out.rows.iter().map(|(_, s)| compliance(m, s, b, at)).collect::<flexure::Result<Vec<_>>>()?)
            }
            None => None,
        };
        Ok((out, estimated, compliances, open))
    })?;
    let result = rows_dict(py, m, &out.rows)?;
    let crossings: Vec<_> = crossings_along(m, out.rows.iter().map(|r| r.1.q.as_slice()))
        .into_iter()
        .flat_map(|(k, cs)| cs.into_iter().map(move |c| (Some(k), c)))
        .map(|(k, c)| (k.map(|k| out.rows[k].0), c))
        .collect();
    let listed = findings::report_along(py, "Mechanism.sweep", &open, &crossings, ("value", parameter, ""), 2)?;
    if !listed.is_empty() {
        result.set_item("findings", listed)?;
    }
    if let Some(cs) = &compliances {
        let a = Array3::from_shape_fn((cs.len(), 6, 6), |(k, i, j)| cs[k][(i, j)]);
        result.set_item("compliance", a.into_pyarray(py))?;
    }
    if let Some(l) = &out.stability_limit {
        result.set_item("stability_limit", crate::serialize::to_dict(py, l)?)?;
        let text = format!(
            "Mechanism.sweep: stability is lost at {parameter} = {} ({:.4} % along the sweep)",
            l.value,
            100.0 * l.fraction
        );
        warn(py, &py.get_type::<StabilityWarning>(), text, 2)?;
    }
    let flagged: Vec<f64> = estimated.iter().filter(|(_, f)| *f).map(|(v, _)| *v).collect();
    if !flagged.is_empty() {
        let text = format!(
            "Mechanism.sweep: at {} of the swept values a flexure joint's estimated error misses the accuracy target (or could not be estimated; listed in `flagged`); raise its orders",
            flagged.len()
        );
        warn(py, &py.get_type::<AccuracyWarning>(), text, 2)?;
    }
    result.set_item("flagged", PyArray1::from_vec(py, flagged))?;
    finite_answer("Mechanism.sweep", result.as_any())?;
    if let Some((value, e)) = &out.stopped {
        let text = format!(
            "the sweep stopped at {parameter} = {value} after {} of {} values: {e}",
            out.rows.len(),
            values.len()
        );
        let d = PyDict::new(py);
        d.set_item("value", value)?;
        d.set_item("error", &text)?;
        result.set_item("stopped", d)?;
        let err = match e {
            Error::Interrupted { .. } | Error::InterruptedAt { .. } => {
                pyo3::exceptions::PyKeyboardInterrupt::new_err(format!("Mechanism.sweep: {text}"))
            }
            _ => ConvergenceError::new_err(format!("Mechanism.sweep: {text} (kept in the exception's `result`)")),
        };
        err.value(py).setattr("result", &result)?;
        return Err(err);
    }
    Ok(result)
}
