//! Vibration modes about the loaded equilibrium: of one flexure with a tip
//! body (`Flexure.modes`), of a mechanism (`Mechanism.modes`), and the exact
//! beam's frequencies (`flexure.exact.frequencies`).

use crate::convert::{count, finite};
use crate::interrupt::interruptible;
use crate::warnings::{sig, warn_values};
use flexure::dynamics::{self, Modes};
use flexure::estimate::{self, Accuracy, ValueEstimate};
use flexure::inertia::RigidInertia;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Modes returned when `count` is None (fewer if the model has fewer coordinates).
pub const DEFAULT_COUNT: usize = 3;

/// The tip body from `tip_mass`, `tip_inertia` and `tip_com`, each checked
/// by its own name; None when none is given.
pub fn tip_body(
    mass: Option<f64>,
    inertia: Option<f64>,
    com: Option<&Bound<'_, PyAny>>,
) -> PyResult<Option<RigidInertia>> {
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
    Ok(Some(RigidInertia { mass: mass.unwrap_or(0.0), inertia: inertia.unwrap_or(0.0), com: [x, y] }))
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
fn insert_frequencies(py: Python<'_>, out: &Bound<'_, PyDict>, modes: &Modes) -> PyResult<()> {
    out.set_item("omega", PyArray1::from_vec(py, modes.omega.clone()))?;
    out.set_item("frequency", PyArray1::from_vec(py, modes.frequency.clone()))?;
    out.set_item("quasi_static", modes.quasi_static)?;
    Ok(())
}

/// `reference_order` and `reference_quadrature` into `d`, each {joint: int}
/// for the flexure joints `names` of a mechanism's estimate.
pub fn insert_reference_orders(
    py: Python<'_>,
    d: &Bound<'_, PyDict>,
    names: &[String],
    reference_orders: &[(usize, usize)],
) -> PyResult<()> {
    let (orders, points) = (PyDict::new(py), PyDict::new(py));
    for (name, (o, q)) in names.iter().zip(reference_orders) {
        orders.set_item(name, o)?;
        points.set_item(name, q)?;
    }
    d.set_item("reference_order", orders)?;
    d.set_item("reference_quadrature", points)
}

/// `error_estimate`: a dict of omega (each mode's estimated relative error,
/// NaN where the reference pairs none), reference_omega, reference_order and
/// reference_quadrature (ints for one flexure, {joint: int} for a mechanism
/// of `names`), reference_stable and flagged; into `out`.
pub(crate) fn insert_estimate(
    py: Python<'_>,
    out: &Bound<'_, PyDict>,
    e: &ValueEstimate,
    names: Option<&[String]>,
) -> PyResult<()> {
    let d = PyDict::new(py);
    let relative: Vec<f64> = e.relative.iter().map(|r| r.unwrap_or(f64::NAN)).collect();
    d.set_item("omega", PyArray1::from_vec(py, relative))?;
    d.set_item("reference_omega", PyArray1::from_vec(py, e.reference.clone()))?;
    match names {
        None => {
            let (order, points) = e.reference_orders.first().copied().unwrap_or((0, 0));
            d.set_item("reference_order", order)?;
            d.set_item("reference_quadrature", points)?;
        }
        Some(names) => insert_reference_orders(py, &d, names, &e.reference_orders)?,
    }
    d.set_item("reference_stable", e.reference_stable)?;
    d.set_item("flagged", e.flagged)?;
    out.set_item("error_estimate", d)
}

/// The modes of one flexure under a tip load, with an optional tip body,
/// and their estimate (a miss of `target` warns `AccuracyWarning`).
pub fn flexure_modes<'py>(
    py: Python<'py>,
    f: &flexure::Flexure,
    count: Option<&Bound<'py, PyAny>>,
    body: Option<RigidInertia>,
    load: flexure::TipLoad,
    target: &Accuracy,
) -> PyResult<Bound<'py, PyDict>> {
    let asked = wanted(count, f.order(), "a flexure of this order")?;
    let (modes, e) = interruptible(py, || {
        let modes = dynamics::modes(f, &load, body.as_ref(), asked)?;
        let e = estimate::modes_error(f, &load, body.as_ref(), &modes, target)?;
        Ok((modes, e))
    })?;
    let out = PyDict::new(py);
    insert_frequencies(py, &out, &modes)?;
    // Checked before the estimate, whose omega holds NaN where the reference pairs no mode.
    crate::strict::finite_answer("Flexure.modes", out.as_any())?;
    crate::strict::finite_slice("Flexure.modes error_estimate reference_omega", &e.reference)?;
    insert_estimate(py, &out, &e, None)?;
    let (order, points) = e.reference_orders[0];
    let reference = format!("order {order} with {points} quadrature points");
    let name = |k: usize| format!("mode {} ({} rad/s)", k + 1, sig(modes.omega[k]));
    let hint = "build the flexure with a higher order, or ask fewer modes";
    warn_values(py, "Flexure.modes", &e, target, name, &reference, hint, 1)?;
    crate::strict::finite_slice("Flexure.modes shapes", modes.shapes.as_slice())?;
    let (n, k) = (modes.shapes.nrows(), modes.omega.len());
    out.set_item("shapes", Array2::from_shape_fn((k, n), |(m, i)| modes.shapes[(i, m)]).into_pyarray(py))?;
    Ok(out)
}
