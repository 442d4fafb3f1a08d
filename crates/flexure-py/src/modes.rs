//! Vibration modes about the loaded equilibrium: of one flexure with a tip
//! body (`Flexure.modes`), of a mechanism (`Mechanism.modes`), and the exact
//! beam's frequencies (`flexure.exact.frequencies`).

use crate::{Flexure, StabilityWarning, count, finite, interruptible, tip_load, warn};
use flexure::dynamics::{self, Body, Modes};
use flexure::mechanism::statics::Settings;
use flexure::reference::vibration;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Modes returned when `count` is None (fewer if the model has fewer coordinates).
const DEFAULT_COUNT: usize = 3;

/// The tip body from `tip_mass`, `tip_inertia` and `tip_com`, each checked
/// by its own name; None when none is given.
pub fn tip_body(mass: Option<f64>, inertia: Option<f64>, com: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Body>> {
    let com = com.filter(|c| !c.is_none());
    if mass.is_none() && inertia.is_none() && com.is_none() {
        return Ok(None);
    }
    for (name, v) in [("tip_mass", mass), ("tip_inertia", inertia)] {
        if let Some(v) = v
            && !(v.is_finite() && v >= 0.0)
        {
            return Err(PyValueError::new_err(format!(
                "invalid {name} = {v}: must be a finite number, zero or greater"
            )));
        }
    }
    let (x, y) = match com {
        None => (0.0, 0.0),
        Some(c) => match c.extract::<Vec<f64>>() {
            Ok(v) if v.len() == 2 => (v[0], v[1]),
            _ => {
                return Err(PyValueError::new_err(format!(
                    "invalid tip_com = {}: must be two numbers (x, y), the tip body's centre of mass in the tip frame (m)",
                    c.repr()?
                )));
            }
        },
    };
    finite("tip_com[0]", x)?;
    finite("tip_com[1]", y)?;
    Ok(Some(Body { mass: mass.unwrap_or(0.0), inertia: inertia.unwrap_or(0.0), com: [x, y] }))
}

/// `count` (None: at most [`DEFAULT_COUNT`]) held to `coordinates`.
pub fn wanted(value: Option<&Bound<'_, PyAny>>, coordinates: usize, what: &str) -> PyResult<usize> {
    let Some(value) = value.filter(|v| !v.is_none()) else { return Ok(DEFAULT_COUNT.min(coordinates)) };
    let k = count("count", value, coordinates)?;
    if (1..=coordinates).contains(&k) {
        Ok(k)
    } else {
        Err(PyValueError::new_err(format!(
            "invalid count = {k}: must be from 1 to {coordinates}: {what} has {coordinates} coordinates, so at most that many modes"
        )))
    }
}

/// omega, frequency and quasi_static of `modes`, into `out`.
fn put_frequencies(py: Python<'_>, out: &Bound<'_, PyDict>, modes: &Modes) -> PyResult<()> {
    out.set_item("omega", PyArray1::from_vec(py, modes.omega.clone()))?;
    out.set_item("frequency", PyArray1::from_vec(py, modes.frequency.clone()))?;
    out.set_item("quasi_static", modes.quasi_static)?;
    Ok(())
}

/// The modes of one flexure under a tip load, with an optional tip body.
pub fn flexure_modes<'py>(
    py: Python<'py>,
    f: &flexure::Flexure,
    count: Option<&Bound<'py, PyAny>>,
    body: Option<Body>,
    (moment, fx, fy): (f64, f64, f64),
) -> PyResult<Bound<'py, PyDict>> {
    let load = tip_load(moment, fx, fy)?;
    let asked = wanted(count, f.order(), "a flexure of this order")?;
    let modes = interruptible(py, || dynamics::modes(f, &load, body.as_ref(), asked))?;
    let out = PyDict::new(py);
    put_frequencies(py, &out, &modes)?;
    let (n, k) = (modes.shapes.nrows(), modes.omega.len());
    out.set_item("shapes", Array2::from_shape_fn((k, n), |(m, i)| modes.shapes[(i, m)]).into_pyarray(py))?;
    Ok(out)
}

/// The modes of a mechanism about its loaded equilibrium; a loading path
/// that snapped through warns StabilityWarning (stack level 2: past the
/// Python wrapper).
pub fn mechanism_modes<'py>(
    py: Python<'py>,
    m: &flexure::mechanism::Mechanism,
    count: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let asked = wanted(count, m.dof(), "the mechanism")?;
    let modes = interruptible(py, || dynamics::mechanism::modes(m, &Settings::default(), asked))?;
    let out = PyDict::new(py);
    put_frequencies(py, &out, &modes)?;
    let shapes = PyDict::new(py);
    for j in m.joints.iter().filter(|j| j.kind.joint().dof() > 0) {
        let d = j.kind.joint().dof();
        let a = Array2::from_shape_fn((modes.omega.len(), d), |(k, i)| modes.shapes[(j.offset + i, k)]);
        shapes.set_item(&j.name, a.into_pyarray(py))?;
    }
    out.set_item("shapes", shapes)?;
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

/// The exact natural frequencies of `flexure` as a straight Euler–Bernoulli
/// beam with rotary inertia (EI(s), mass per length μ(s), ρI(s)), clamped at
/// its root, carrying an optional tip body, under an axial `compression` (N;
/// negative for tension), by shooting on the frequency: a dict of omega
/// (rad/s), frequency (Hz), beta_l (the scaled frequency, βL for a uniform
/// beam) and mass_per_length (the reference μ̄ of beta_l, kg/m).
#[pyfunction]
#[pyo3(signature = (flexure, count=None, compression=0.0, tip_mass=None, tip_inertia=None, tip_com=None))]
pub fn exact_frequencies<'py>(
    py: Python<'py>,
    flexure: &Flexure,
    count: Option<&Bound<'py, PyAny>>,
    compression: f64,
    tip_mass: Option<f64>,
    tip_inertia: Option<f64>,
    tip_com: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let f = &flexure.inner;
    if let Some(k) = f.rest().iter().find(|&&k| k != 0.0) {
        return Err(PyValueError::new_err(format!(
            "invalid rest: a rest curvature coefficient is {k}: the exact frequencies are those of a straight beam"
        )));
    }
    let compression = finite("compression", compression)?;
    let body = tip_body(tip_mass, tip_inertia, tip_com)?;
    let asked = match count.filter(|c| !c.is_none()) {
        None => DEFAULT_COUNT,
        Some(c) => match crate::count("count", c, 64)? {
            k @ 1..=64 => k,
            k => return Err(PyValueError::new_err(format!("invalid count = {k}: must be from 1 to 64"))),
        },
    };
    let v = interruptible(py, || vibration::frequencies(f, body.as_ref(), compression, asked, &Default::default()))?;
    let out = PyDict::new(py);
    out.set_item("omega", PyArray1::from_vec(py, v.omega))?;
    out.set_item("frequency", PyArray1::from_vec(py, v.frequency))?;
    out.set_item("beta_l", PyArray1::from_vec(py, v.scaled))?;
    out.set_item("mass_per_length", v.mass_per_length)?;
    Ok(out)
}
