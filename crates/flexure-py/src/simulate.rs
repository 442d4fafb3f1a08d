//! `Mechanism.simulate`: a mechanism file's motion as NumPy arrays.

use flexure::dynamics::integrate;
use flexure::dynamics::simulation::{SimulationSettings, Start, simulate};
use flexure::mechanism::Mechanism;
use numpy::IntoPyArray;
use numpy::ndarray::{Array1, Array2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The motion of `m` over `duration` (s), sampled every `every` (default
/// duration/100), at relative and absolute `tolerance`, from `start`
/// ("equilibrium" or "rest"), with a step budget of `max_steps` (default:
/// the library's, 1e6 plus 10 per sample), as a dict of arrays; runs
/// without the GIL.
pub fn motion<'py>(
    py: Python<'py>,
    m: &Mechanism,
    (duration, every): (f64, Option<f64>),
    tolerance: f64,
    start: &str,
    max_steps: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let start = match start {
        "equilibrium" => Start::Equilibrium,
        "rest" => Start::Rest,
        other => {
            return Err(PyValueError::new_err(format!("start = {other:?}: must be \"equilibrium\" or \"rest\"")));
        }
    };
    let motion = integrate::Settings {
        duration,
        every: every.unwrap_or(duration / 100.0),
        tolerance,
        absolute: tolerance,
        max_steps,
        ..Default::default()
    };
    let settings = SimulationSettings { motion, ..Default::default() };
    let (run, open) = crate::interrupt::interruptible(py, || {
        let open = flexure::mechanism::findings::open_closures(m, &settings.equilibrium)?;
        // Python raises on a run that stopped early, as before.
        let run = simulate(m, &settings, start)?;
        match &run.stopped {
            Some(e) => Err(e.clone()),
            None => Ok((run, open)),
        }
    })?;
    let crossings: Vec<(Option<f64>, _)> =
        flexure::mechanism::findings::crossings_along(m, (0..run.time.len()).map(|k| run.q(k)))
            .into_iter()
            .flat_map(|(k, cs)| cs.into_iter().map(move |c| (Some(k), c)))
            .map(|(k, c)| (k.map(|k| run.time[k]), c))
            .collect();
    let findings = crate::findings::report(py, "Mechanism.simulate", &open, &crossings, 2)?;
    let n = run.time.len();
    let bodies = PyDict::new(py);
    for b in &run.bodies {
        let d = PyDict::new(py);
        d.set_item("x", Array1::from_vec(b.x.clone()).into_pyarray(py))?;
        d.set_item("y", Array1::from_vec(b.y.clone()).into_pyarray(py))?;
        d.set_item("phi", Array1::from_vec(b.phi.clone()).into_pyarray(py))?;
        bodies.set_item(&b.name, d)?;
    }
    let (coordinates, velocities) = (PyDict::new(py), PyDict::new(py));
    for j in &m.joints {
        let k = j.kind.joint().dof();
        let q = Array2::from_shape_fn((n, k), |(s, i)| run.q(s)[j.offset + i]);
        let v = Array2::from_shape_fn((n, k), |(s, i)| run.v(s)[j.offset + i]);
        coordinates.set_item(&j.name, q.into_pyarray(py))?;
        velocities.set_item(&j.name, v.into_pyarray(py))?;
    }
    let out = PyDict::new(py);
    out.set_item("time", Array1::from_vec(run.trajectory.time).into_pyarray(py))?;
    out.set_item("bodies", bodies)?;
    out.set_item("coordinates", coordinates)?;
    out.set_item("velocities", velocities)?;
    out.set_item("steps", run.trajectory.steps)?;
    out.set_item("rejected", run.trajectory.rejected)?;
    out.set_item("violation", run.trajectory.violation)?;
    out.set_item("energy", Array1::from_vec(run.trajectory.energy).into_pyarray(py))?;
    if !findings.is_empty() {
        out.set_item("findings", findings)?;
    }
    Ok(out)
}
