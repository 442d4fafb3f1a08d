//! `Mechanism.simulate`: a mechanism file's motion as NumPy arrays, in both
//! dimensions through the door ([`Model::simulate`]).

use crate::errors::AccuracyWarning;
use crate::warnings::warn;
use flexure::dynamics::integrate;
use flexure::dynamics::simulation::{SimulationSettings, Start};
use flexure::estimate::Accuracy;
use flexure::model::{Model, MotionEstimate};
use flexure::report::BodyPose;
use numpy::IntoPyArray;
use numpy::ndarray::{Array1, Array2, Array3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The motion of `model` over `duration` (s), sampled every `every` (default
/// duration/100), at relative and absolute `tolerance`, from `start`
/// ("equilibrium" or "rest"), with a step budget of `max_steps` (default:
/// the library's, 1e6 plus 10 per sample), as a dict of arrays: each body's
/// pose keys one array each (planar x, y, phi; spatial x, y, z, roll, pitch,
/// yaw, and rotation (N, 3, 3)), with `contacts` (a list per sample) and
/// `changes` where it has geoms, as `flexure simulate --json`, with its
/// `error_estimate` against a run at a tenth of the tolerance and `flagged`
/// (`AccuracyWarning` when it misses `target`); runs without the GIL.
pub fn motion<'py>(
    py: Python<'py>,
    model: &Model,
    (duration, every): (f64, Option<f64>),
    tolerance: f64,
    (start, max_steps): (&str, Option<usize>),
    target: &Accuracy,
) -> PyResult<Bound<'py, PyDict>> {
    let start = match start {
        "equilibrium" => Start::Equilibrium,
        "rest" => Start::Rest,
        other => {
            return Err(PyValueError::new_err(format!("start = {other:?}: must be \"equilibrium\" or \"rest\"")));
        }
    };
    let motion = integrate::MotionSettings {
        duration,
        every: every.unwrap_or(duration / 100.0),
        tolerance,
        absolute: tolerance,
        max_steps,
        ..Default::default()
    };
    let settings = SimulationSettings { motion, ..Default::default() };
    let (run, open, estimate) = crate::interrupt::interruptible(py, || {
        let open = model.open_closures()?;
        // Python raises on a run that stopped early, as before.
        let run = model.simulate(&settings, start)?;
        if let Some(e) = &run.stopped {
            return Err(e.clone());
        }
        let estimate = model.motion_error(&settings, start, &run, target);
        Ok((run, open, estimate))
    })?;
    let t = &run.trajectory;
    let crossings: Vec<(Option<f64>, _)> =
        run.crossings.iter().flat_map(|(k, cs)| cs.iter().map(move |c| (Some(t.time[*k]), c.clone()))).collect();
    let findings = crate::findings::report(py, "Mechanism.simulate", &open, &crossings, 2)?;
    let n = t.time.len();
    let bodies = bodies_dict(py, &run.bodies)?;
    let (coordinates, velocities) = (PyDict::new(py), PyDict::new(py));
    for (name, range) in model.joints() {
        let q = Array2::from_shape_fn((n, range.len()), |(s, i)| t.q(s)[range.start + i]);
        let v = Array2::from_shape_fn((n, range.len()), |(s, i)| t.v(s)[range.start + i]);
        coordinates.set_item(&name, q.into_pyarray(py))?;
        velocities.set_item(&name, v.into_pyarray(py))?;
    }
    let out = PyDict::new(py);
    out.set_item("dimension", model.dimension())?;
    out.set_item("time", Array1::from_vec(t.time.clone()).into_pyarray(py))?;
    out.set_item("bodies", bodies)?;
    out.set_item("coordinates", coordinates)?;
    out.set_item("velocities", velocities)?;
    out.set_item("steps", t.steps)?;
    out.set_item("rejected", t.rejected)?;
    out.set_item("violation", t.violation)?;
    out.set_item("energy", Array1::from_vec(t.energy.clone()).into_pyarray(py))?;
    if !run.contacts.is_empty() {
        out.set_item("contacts", crate::serialize::to_python(py, &run.contacts)?)?;
        out.set_item("changes", crate::serialize::to_python(py, &run.changes)?)?;
    }
    if !findings.is_empty() {
        out.set_item("findings", findings)?;
    }
    insert_motion_error(py, &out, estimate, target)?;
    Ok(out)
}

/// `error_estimate` (left out when it could not be made) and `flagged`,
/// warning `AccuracyWarning` when the estimate misses `target`, is
/// incomplete or could not be made, as `flexure simulate` warns.
fn insert_motion_error(
    py: Python<'_>,
    out: &Bound<'_, PyDict>,
    estimate: flexure::Result<MotionEstimate>,
    target: &Accuracy,
) -> PyResult<()> {
    let warning = |text: String| warn(py, &py.get_type::<AccuracyWarning>(), text, 2);
    match estimate {
        Ok(e) => {
            if !e.complete {
                warning(format!(
                    "Mechanism.simulate: the error estimate's reference run stopped after {} samples: it covers those only",
                    e.samples
                ))?;
            } else if e.flagged {
                warning(format!(
                    "Mechanism.simulate: estimated error {:.3e} m (tolerance {:.3e} m) and {:.3e} rad (tolerance {:.3e} rad), largest at t = {:e} s, misses accuracy: lower tolerance",
                    e.position, e.position_tolerance, e.angle, target.angle, e.at
                ))?;
            }
            let d = PyDict::new(py);
            d.set_item("position", e.position)?;
            d.set_item("angle", e.angle)?;
            d.set_item("at", e.at)?;
            d.set_item("reference_tolerance", e.reference_tolerance)?;
            d.set_item("samples", e.samples)?;
            d.set_item("complete", e.complete)?;
            d.set_item("position_tolerance", e.position_tolerance)?;
            out.set_item("error_estimate", d)?;
            out.set_item("flagged", e.flagged)
        }
        Err(e) => {
            warning(format!("Mechanism.simulate: no error estimate: {e}"))?;
            out.set_item("flagged", true)
        }
    }
}

/// Each body's poses as arrays, one per pose key (planar x, y, phi; spatial
/// x, y, z, roll, pitch, yaw, and rotation (N, 3, 3)): what `simulate` and
/// `sweep` answer for their samples or rows, as the CLI's columns name them.
pub fn bodies_dict<'py>(py: Python<'py>, bodies: &[(String, Vec<BodyPose>)]) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    for (name, poses) in bodies {
        let d = PyDict::new(py);
        if let Some(first) = poses.first() {
            let values: Vec<Vec<f64>> = poses.iter().map(BodyPose::coordinates).collect();
            for (c, key) in first.columns().iter().enumerate() {
                d.set_item(*key, Array1::from_iter(values.iter().map(|v| v[c])).into_pyarray(py))?;
            }
            if let BodyPose::Spatial { .. } = first {
                let r: Vec<[[f64; 3]; 3]> = poses.iter().map(BodyPose::rotation).collect();
                let n = r.len();
                d.set_item("rotation", Array3::from_shape_fn((n, 3, 3), |(s, i, j)| r[s][i][j]).into_pyarray(py))?;
            }
        }
        out.set_item(name, d)?;
    }
    Ok(out)
}
