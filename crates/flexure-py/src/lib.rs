//! Python bindings: a thin layer over the flexure library.
//!
//! Inputs accept anything array-like; outputs are float64 NumPy arrays.
//! Bad input raises `ValueError` naming the parameter; a solver that does
//! not converge raises `flexure.ConvergenceError` with its residual; an
//! equilibrium that is found but unstable warns with `flexure.StabilityWarning`;
//! an answer whose estimated error misses its accuracy target warns with
//! `flexure.AccuracyWarning`; a peak bending stress beyond the flexure's
//! yield strength warns with `flexure.YieldWarning`.

use flexure::estimate::{self, Accuracy, ErrorEstimate};
use flexure::kinematics::par_poses_root_tip;
use flexure::mechanism::JointKind;
use flexure::mechanism::file::{Report, from_toml, reports};
use flexure::mechanism::statics::{Settings as MechanismSettings, body_frames, solve};
use flexure::{
    Error, Kinematics, Level, Pose, Statics, TipConstraint, TipLoad, buckling_load, compliance_tip,
    compliance_tip_rest, deflect, energy, update_kinematics,
};
use numpy::ndarray::{Array1, Array2};
use numpy::{AllowTypeChange, IntoPyArray, PyArray1, PyArray2, PyArrayLikeDyn, PyArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyTypeError, PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyInt, PyTuple};
use std::time::{Duration, Instant};

mod analyses;
mod coordinates;
mod exact;
mod findings;
mod mechanism;
mod modes;
mod section;
mod simulate;
mod stress;
mod strict;
use coordinates::{Coordinates, single, vector};
use strict::Real;

create_exception!(
    _flexure,
    ConvergenceError,
    PyRuntimeError,
    "A solver stopped before meeting its tolerance; `residual` holds its last residual."
);

create_exception!(
    _flexure,
    StabilityWarning,
    PyUserWarning,
    "An equilibrium was found but is unstable: a small disturbance would move the flexure away from it."
);

create_exception!(
    _flexure,
    AccuracyWarning,
    PyUserWarning,
    "A model answer's estimated error misses its accuracy target (by default 1 % of the length and 1 degree)."
);

create_exception!(
    _flexure,
    YieldWarning,
    PyUserWarning,
    "A flexure's peak bending stress exceeds its yield strength: the safety factor is below 1."
);

create_exception!(
    _flexure,
    PreloadWarning,
    PyUserWarning,
    "A weld or pin of a mechanism is open at rest: closing it preloads the mechanism before any load acts (say `preload = true` in it if that is meant)."
);

create_exception!(
    _flexure,
    IntersectionWarning,
    PyUserWarning,
    "Two parts of a solved mechanism (flexures, links) cross: the model has no contact, so the shape passes through itself."
);

/// Warns `text` as `category` (`stacklevel` 1: the Python line that called the binding).
fn warn(py: Python<'_>, category: &Bound<'_, pyo3::types::PyType>, text: String, stacklevel: i32) -> PyResult<()> {
    // Built from fixed text, numbers and names; a NUL in a name is dropped rather than losing the warning.
    let message = std::ffi::CString::new(text.replace('\0', "")).unwrap_or_default();
    PyErr::warn(py, category.as_any(), &message, stacklevel)
}

/// Warns that the equilibrium `solver` found under `load` is unstable, and `why`.
fn warn_unstable(py: Python<'_>, solver: &str, load: &TipLoad, why: &str, stacklevel: i32) -> PyResult<()> {
    let (m, fx, fy) = (load.moment, load.fx, load.fy);
    let text = format!("{solver}: the equilibrium under (moment, fx, fy) = ({m}, {fx}, {fy}) is unstable: {why}");
    warn(py, &py.get_type::<StabilityWarning>(), text, stacklevel)
}

/// `x` to 3 significant digits, without trailing zeros; in exponent form when very small or large.
fn sig(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let e = x.abs().log10().floor() as i32;
    if !(-4..6).contains(&e) {
        return format!("{x:.2e}");
    }
    let plain = format!("{:.*}", (2 - e).max(0) as usize, x);
    if plain.contains('.') { plain.trim_end_matches('0').trim_end_matches('.').to_string() } else { plain }
}

/// Reads `accuracy` = (position as a fraction of L, angle in rad[, peak
/// stress or curvature as a fraction of the peak]); the paper's 1 % of L
/// and 1°, and 1 % of the peak, when it is `None`.
fn accuracy(value: Option<&Bound<'_, PyAny>>) -> PyResult<Accuracy> {
    let Some(v) = value.filter(|v| !v.is_none()) else {
        return Ok(Accuracy::default());
    };
    let shape = || {
        PyValueError::new_err(format!(
            "accuracy must be a pair (position as a fraction of L, angle in rad) or a triple adding the peak stress as a fraction of the peak, such as (0.01, 0.0175) or (0.01, 0.0175, 0.02), got {}",
            v.repr().map(|r| r.to_string()).unwrap_or_else(|_| "an object without repr".into())
        ))
    };
    strict::no_bool("accuracy", v)?;
    // A str is a sequence too, but never a pair of numbers: pyo3 refuses it as a Vec.
    let pair: Vec<f64> = v.extract().map_err(|_| shape())?;
    let (position, angle, stress) = match pair[..] {
        [position, angle] => (position, angle, Accuracy::default().stress),
        [position, angle, stress] => (position, angle, stress),
        _ => return Err(shape()),
    };
    for (what, x) in [("position fraction of L", position), ("angle (rad)", angle), ("peak fraction", stress)] {
        if !(x.is_finite() && x > 0.0) {
            let given = pair.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(", ");
            return Err(PyValueError::new_err(format!(
                "accuracy = ({given}): its {what} is {x}, and must be a finite number greater than zero"
            )));
        }
    }
    Ok(Accuracy { position, angle, stress, ..Default::default() })
}

/// Reads the `accuracy` of a buckling load or frequency: a fraction of the
/// value (1 % when `None`).
fn eigen_accuracy(value: Option<&Bound<'_, PyAny>>) -> PyResult<Accuracy> {
    let Some(v) = value.filter(|v| !v.is_none()) else {
        return Ok(Accuracy::default());
    };
    let bad = || {
        PyValueError::new_err(format!(
            "accuracy must be one finite number greater than zero, the relative error a buckling load or frequency may have (0.01 is 1 %), got {}",
            v.repr().map(|r| r.to_string()).unwrap_or_else(|_| "an object without repr".into())
        ))
    };
    strict::no_bool("accuracy", v)?;
    let x: f64 = v.extract().map_err(|_| bad())?;
    if !(x.is_finite() && x > 0.0) {
        return Err(bad());
    }
    Ok(Accuracy { eigenvalue: x, ..Default::default() })
}

/// Warns `AccuracyWarning` for each value of `e` that misses `target`:
/// `name(k)` names the value, `reference` the reference model.
#[allow(clippy::too_many_arguments)]
fn warn_values(
    py: Python<'_>,
    what: &str,
    e: &estimate::ValueEstimate,
    target: &Accuracy,
    name: impl Fn(usize) -> String,
    reference: &str,
    hint: &str,
    stacklevel: i32,
) -> PyResult<()> {
    if !e.flagged {
        return Ok(());
    }
    let goal = sig(100.0 * target.eigenvalue);
    let parts: Vec<String> = e
        .missed(target)
        .into_iter()
        .map(|k| match e.relative[k] {
            Some(r) => format!("{}: estimated error {} % misses the target of {goal} %", name(k), sig(100.0 * r)),
            None if !e.reference_stable => format!(
                "{}: no estimate, the reference model is unstable under this load (it buckles below it), so the answer is not to be trusted",
                name(k)
            ),
            None => format!("{}: no estimate, the reference model resolves no such mode", name(k)),
        })
        .collect();
    let text = format!("{what}: {} (estimated against {reference}); {hint}", parts.join("; "));
    warn(py, &py.get_type::<AccuracyWarning>(), text, stacklevel)
}

/// Warns that an answer of `f` misses `target` by the estimate `e`; `what`
/// names the answer, `hint` says what to do about it.
fn warn_inaccurate(
    py: Python<'_>,
    what: &str,
    f: &flexure::Flexure,
    e: &ErrorEstimate,
    target: &Accuracy,
    hint: &str,
    stacklevel: i32,
) -> PyResult<()> {
    let peak = if e.stress.is_some() { "peak stress" } else { "peak curvature" };
    let reference = if e.exact {
        "the exact elastica, order 64 being the highest".to_string()
    } else {
        format!("order {} with {} quadrature points", e.reference_order, e.reference_quadrature)
    };
    let text = format!(
        "{what}: estimated error {} m ({} % of L) in position, {}° in angle and {} % in {peak} misses the target of \
         {} % of L, {}° and {} % (estimated against {reference}); {hint}",
        sig(e.position),
        sig(100.0 * e.position / f.length()),
        sig(e.angle.to_degrees()),
        sig(100.0 * e.peak),
        sig(100.0 * target.position),
        sig(target.angle.to_degrees()),
        sig(100.0 * target.stress),
    );
    warn(py, &py.get_type::<AccuracyWarning>(), text, stacklevel)
}

/// Warns that the error of `what` could not be estimated, and why.
fn warn_unestimated(py: Python<'_>, what: &str, why: &Error, stacklevel: i32) -> PyResult<()> {
    let text = format!("{what}: the error could not be estimated, so the answer's accuracy is unknown: {why}");
    warn(py, &py.get_type::<AccuracyWarning>(), text, stacklevel)
}

/// An estimate as a dict: position (m), angle (rad), flagged, reference ("model", or "elastica" at
/// order 64, where reference_order and reference_quadrature are 0), reference_order, reference_quadrature.
fn estimate_dict<'py>(py: Python<'py>, e: &ErrorEstimate) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("position", e.position)?;
    d.set_item("angle", e.angle)?;
    d.set_item("curvature", e.curvature)?;
    if let Some(stress) = e.stress {
        d.set_item("stress", stress)?;
    }
    d.set_item("flagged", e.flagged)?;
    d.set_item("reference", if e.exact { "elastica" } else { "model" })?;
    d.set_item("reference_order", e.reference_order)?;
    d.set_item("reference_quadrature", e.reference_quadrature)?;
    Ok(d)
}

thread_local! {
    /// The reusable estimator of `Flexure.deflect` (its reference model built once per flexure).
    static ESTIMATOR: std::cell::RefCell<estimate::Estimator> = std::cell::RefCell::new(estimate::Estimator::new());
}

/// An estimate's result, with an interruption passed on as the solve's error
/// (the answer is not returned) and any other failure kept for a warning.
type Estimated = std::result::Result<ErrorEstimate, Error>;

fn interrupted_or(e: flexure::Result<ErrorEstimate>) -> flexure::Result<Estimated> {
    match e {
        Err(e @ Error::Interrupted { .. }) => Err(e),
        other => Ok(other),
    }
}

/// The library's error as a Python exception.
fn to_py(e: Error) -> PyErr {
    match e {
        Error::NoConvergence { residual, .. } | Error::ContinuationStalled { residual, .. } => {
            let err = ConvergenceError::new_err(e.to_string());
            Python::attach(|py| {
                let _ = err.value(py).setattr("residual", residual);
            });
            err
        }
        Error::Unstable { load_fraction, .. } => {
            let err = ConvergenceError::new_err(e.to_string());
            Python::attach(|py| {
                let _ = err.value(py).setattr("load_fraction", load_fraction);
            });
            err
        }
        Error::IntegrationStalled { time, .. } => {
            let err = ConvergenceError::new_err(e.to_string());
            Python::attach(|py| {
                let _ = err.value(py).setattr("time", time);
            });
            err
        }
        Error::Interrupted { .. } | Error::InterruptedAt { .. } => PyKeyboardInterrupt::new_err(e.to_string()),
        other => PyValueError::new_err(other.to_string()),
    }
}

thread_local! {
    /// What a Python signal handler raised while an interruptible call ran on this thread.
    static RAISED: std::cell::RefCell<Option<PyErr>> = const { std::cell::RefCell::new(None) };
    /// When the interrupt check next runs Python's handlers.
    static NEXT_POLL: std::cell::Cell<Option<Instant>> = const { std::cell::Cell::new(None) };
}

/// How often a running solve hands control to Python's signal handlers:
/// taking the GIL at every Newton iteration would double the cost of a
/// small solve, and 10 ms is well below what a person pressing Ctrl-C notices.
const POLL: Duration = Duration::from_millis(10);

/// The solvers' interrupt check: at most every [`POLL`], runs Python's signal
/// handlers (only on the main thread; Ctrl-C's raises `KeyboardInterrupt`)
/// and keeps what they raised for [`interruptible`] to raise.
fn signalled() -> bool {
    let now = Instant::now();
    if NEXT_POLL.with(|t| t.get()).is_some_and(|next| now < next) {
        return false;
    }
    NEXT_POLL.with(|t| t.set(Some(now + POLL)));
    Python::attach(|py| match py.check_signals() {
        Ok(()) => false,
        Err(e) => {
            RAISED.with(|r| *r.borrow_mut() = Some(e));
            true
        }
    })
}

/// Starts an interruptible call: forgets what a handler raised before, and
/// first polls after [`POLL`], so a quick call never takes the GIL back.
fn clear_raised() {
    RAISED.with(|r| r.borrow_mut().take());
    NEXT_POLL.with(|t| t.set(Some(Instant::now() + POLL)));
}

/// What a signal handler raised during the work, if anything; a plain
/// `KeyboardInterrupt` is replaced by `interrupted`, which says how far the
/// work got.
fn raised_during(py: Python<'_>, interrupted: impl FnOnce() -> PyErr) -> Option<PyErr> {
    let raised = RAISED.with(|r| r.borrow_mut().take())?;
    if raised.is_instance_of::<PyKeyboardInterrupt>(py) { Some(interrupted()) } else { Some(raised) }
}

/// Runs a solve without the GIL, polling Python's signal handlers at every
/// continuation step and Newton iteration ([`flexure::solver::with_interrupt`]):
/// Ctrl-C stops it with `KeyboardInterrupt` saying the load fraction reached,
/// and an exception raised by any other handler propagates as it is.
fn interruptible<T: Send>(py: Python<'_>, work: impl FnOnce() -> flexure::Result<T> + Send) -> PyResult<T> {
    clear_raised();
    let out = py.detach(|| flexure::solver::with_interrupt(signalled, work));
    let message = match &out {
        Err(e @ (Error::Interrupted { .. } | Error::InterruptedAt { .. })) => e.to_string(),
        _ => "interrupted".to_string(),
    };
    // A handler that raised wins even over a result: Python would have raised it.
    match raised_during(py, || PyKeyboardInterrupt::new_err(message)) {
        Some(err) => Err(err),
        None => out.map_err(to_py),
    }
}

/// A pair of NumPy matrices, as `hessians` returns.
type MatrixPair<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>);

fn matrix(m: &nalgebra::DMatrix<f64>) -> Array2<f64> {
    Array2::from_shape_fn((m.nrows(), m.ncols()), |(i, j)| m[(i, j)])
}

/// A planar flexure joint of the Smooth Curvature Model (SI units, radians).
///
/// Flexure(length, ei, order, quadrature, rest, *, modulus, width, thickness, poisson,
/// notch, density, mass_per_length, yield_strength). Give `ei` (N·m²), or `modulus` (Pa)
/// with `width` and `thickness` (m) and an optional `poisson`. `ei`, `width`, `thickness`
/// and `mass_per_length` may vary along the flexure, over t = s/L from the root (0) to the
/// tip (1): a number; a pair (root, tip), a linear taper; or a table of [t, value] rows
/// (an (m, 2) array or a list of pairs; t starts at 0, ends at 1 and increases strictly),
/// linear between rows. `notch=(R, h)` cuts two circular cut-outs of radius R centred on
/// the flexure, leaving thickness h at its middle. `density` (kg/m³) or `mass_per_length`
/// (kg/m) gives the mass per length, for dynamics. `yield_strength` S (Pa, with a
/// thickness) gives `safety_factor` S/σmax, and `deflect` warns `YieldWarning` below 1.
///
/// Read-only: `length`, `ei` (the mean for a non-uniform section), `order`, `quadrature`,
/// `rest`, `modulus` (E′, None without a thickness), `yield_strength`, `uniform`; along
/// the flexure at s (m, a number or an array): `ei_at`, `thickness_at`, `width_at`,
/// `mass_per_length_at`. At coordinates alpha: `stress` {max, at} (None without a
/// thickness), `peak_curvature` {max, at}, `safety_factor`, and `shape(alpha, k)`, a
/// structured array of fields s, x, y, phi, curvature and (with a thickness) stress.
#[pyclass(frozen, module = "flexure")]
struct Flexure {
    inner: flexure::Flexure,
    /// Yield strength $S$ (Pa), for the safety factor; only with a thickness.
    yield_strength: Option<f64>,
}

fn finite(name: &str, v: f64) -> PyResult<f64> {
    if v.is_finite() { Ok(v) } else { Err(PyValueError::new_err(format!("{name} = {v}: must be a finite number"))) }
}

/// A tip load of finite components.
fn tip_load(moment: Real, fx: Real, fy: Real) -> PyResult<TipLoad> {
    Ok(TipLoad { moment: finite("moment", moment.0)?, fx: finite("fx", fx.0)?, fy: finite("fy", fy.0)? })
}

/// A count such as `order` from any Python integer: one that does not fit a
/// `usize` (negative, or past 2^64) is a `ValueError` naming `name` and the
/// bound, not an `OverflowError`. The library checks the bound itself.
fn count(name: &str, value: &Bound<'_, PyAny>, max: usize) -> PyResult<usize> {
    match value.extract::<usize>() {
        Ok(v) => Ok(v),
        // Integers (also NumPy's, through __index__) out of usize's range.
        Err(_) if value.is_instance_of::<PyInt>() || value.hasattr("__index__").unwrap_or(false) => {
            Err(PyValueError::new_err(format!("invalid {name} = {value}: must be from 1 to {max}")))
        }
        Err(e) => Err(PyTypeError::new_err(format!("argument '{name}': {}", e.value(value.py())))),
    }
}

/// The number of points `k` of a shape, from 2 to [`stress::MAX_SHAPE`].
fn shape_points(value: &Bound<'_, PyAny>) -> PyResult<usize> {
    let max = stress::MAX_SHAPE;
    match value.extract::<usize>() {
        Ok(k) if (2..=max).contains(&k) => Ok(k),
        Ok(_) => Err(PyValueError::new_err(format!(
            "invalid k = {value}: must be from 2 to {max} points (the ends included)"
        ))),
        Err(_) if value.is_instance_of::<PyInt>() || value.hasattr("__index__").unwrap_or(false) => Err(
            PyValueError::new_err(format!("invalid k = {value}: must be from 2 to {max} points (the ends included)")),
        ),
        Err(e) => Err(PyTypeError::new_err(format!("argument 'k': {}", e.value(value.py())))),
    }
}

/// Evaluates `g` at arc length `s` (m) on `f`: a float for a number, an
/// array of the same shape for an array; every `s` must lie in [0, L].
fn along<'py>(
    py: Python<'py>,
    f: &flexure::Flexure,
    s: &Bound<'py, PyAny>,
    g: impl Fn(f64) -> f64,
) -> PyResult<Bound<'py, PyAny>> {
    let l = f.length();
    let check = |v: f64| {
        if v.is_finite() && (0.0..=l).contains(&v) {
            Ok(v)
        } else {
            Err(PyValueError::new_err(format!("s = {v}: must lie along the flexure, in [0, L] = [0, {l}] m")))
        }
    };
    if let Ok(v) = s.extract::<f64>() {
        return Ok(g(check(v)?).into_pyobject(py)?.into_any());
    }
    let array: PyArrayLikeDyn<'py, f64, AllowTypeChange> = s.extract().map_err(|e: PyErr| {
        if e.is_instance_of::<PyTypeError>(py) {
            PyTypeError::new_err(format!("argument 's': {}", e.value(py)))
        } else {
            e
        }
    })?;
    let values = array.as_array().map(|&v| v).to_owned();
    for &v in &values {
        check(v)?;
    }
    Ok(values.mapv(g).into_pyarray(py).into_any())
}

/// A peak stress or curvature of `f` at `alpha`, as a dict, when it has one:
/// `stress` with a thickness, else `curvature_max`.
fn peak_item<'py>(
    py: Python<'py>,
    f: &flexure::Flexure,
    alpha: &[f64],
) -> PyResult<(&'static str, Bound<'py, PyDict>)> {
    match flexure::stress::peak_stress(f, alpha) {
        Some(p) => Ok(("stress", stress::peak_dict(py, &p)?)),
        None => Ok(("curvature_max", stress::peak_dict(py, &flexure::stress::peak_curvature(f, alpha))?)),
    }
}

/// The stiffness $K = \nabla\nabla U - F_x\nabla\nabla x - F_y\nabla\nabla y$
/// (Eq. 32) at `alpha`, with the kinematics there (Hessian level).
fn loaded_stiffness(f: &flexure::Flexure, alpha: &[f64], load: &TipLoad) -> (Kinematics<f64>, nalgebra::DMatrix<f64>) {
    let mut k = Kinematics::new(f);
    update_kinematics(f, alpha, &mut k, Level::Hessian);
    let mut stiffness = -(&k.hessian_root_tip_x * load.fx + &k.hessian_root_tip_y * load.fy);
    for i in 0..f.order() {
        for j in 0..f.order() {
            stiffness[(i, j)] += flexure::energy::stiffness(f, i, j);
        }
    }
    (k, stiffness)
}

/// Reads `order`: None for the flexure's own, or "auto" to raise it until the estimate meets the target.
fn auto_order(order: Option<&Bound<'_, PyAny>>) -> PyResult<bool> {
    match order.filter(|o| !o.is_none()) {
        None => Ok(false),
        Some(o) if o.extract::<String>().is_ok_and(|s| s == "auto") => Ok(true),
        Some(o) => Err(PyValueError::new_err(format!(
            "order must be None or \"auto\", got {}: a flexure's own order is set when it is built",
            o.repr()?
        ))),
    }
}

/// A finite float argument named `name`.
fn real(name: &str, v: Real) -> PyResult<f64> {
    finite(name, v.0)
}

#[pymethods]
impl Flexure {
    /// Flexure(length=1.0, ei=None, order=3, quadrature=None, rest=None, *, modulus=None, width=None, thickness=None, poisson=None, notch=None, density=None, mass_per_length=None, yield_strength=None)
    #[new]
    #[pyo3(
        signature = (length=Real(1.0), ei=None, order=None, quadrature=None, rest=None, *, modulus=None, width=None, thickness=None, poisson=None, notch=None, density=None, mass_per_length=None, yield_strength=None),
        text_signature = "(length=1.0, ei=None, order=3, quadrature=None, rest=None, *, modulus=None, width=None, thickness=None, poisson=None, notch=None, density=None, mass_per_length=None, yield_strength=None)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn new(
        length: Real,
        ei: Option<&Bound<'_, PyAny>>,
        order: Option<&Bound<'_, PyAny>>,
        quadrature: Option<&Bound<'_, PyAny>>,
        rest: Option<&Bound<'_, PyAny>>,
        modulus: Option<Real>,
        width: Option<&Bound<'_, PyAny>>,
        thickness: Option<&Bound<'_, PyAny>>,
        poisson: Option<Real>,
        notch: Option<&Bound<'_, PyAny>>,
        density: Option<Real>,
        mass_per_length: Option<&Bound<'_, PyAny>>,
        yield_strength: Option<Real>,
    ) -> PyResult<Self> {
        let (length, yield_strength) = (length.0, yield_strength.map(|s| s.0));
        let (ei, section) = section::read(&section::Arguments {
            ei,
            modulus: modulus.map(|v| v.0),
            width,
            thickness,
            poisson: poisson.map(|v| v.0),
            notch,
            density: density.map(|v| v.0),
            mass_per_length,
        })?;
        let order = order.map(|o| count("order", o, flexure::joint::MAX_ORDER)).transpose()?.unwrap_or(3);
        let mut f = flexure::Flexure::new(length, ei, order).map_err(to_py)?;
        if let Some(s) = section {
            f = f.with_section(s).map_err(to_py)?;
        }
        if let Some(q) = quadrature {
            f = f.with_quadrature(count("quadrature", q, flexure::quadrature::MAX_POINTS)?).map_err(to_py)?;
        }
        if let Some(r) = rest {
            f = f.with_rest(&vector("rest", &coordinates::array_like("rest", r)?, Some(order))?).map_err(to_py)?;
        }
        if let Some(s) = yield_strength {
            if !(s.is_finite() && s > 0.0) {
                return Err(PyValueError::new_err(format!(
                    "invalid yield_strength = {s}: must be a finite number greater than zero (Pa)"
                )));
            }
            if f.section().modulus().is_none() {
                return Err(PyValueError::new_err(format!(
                    "invalid yield_strength = {s}: needs a thickness to give a stress: give modulus, width and thickness (a flexure given by ei alone has no stress)"
                )));
            }
        }
        Ok(Self { inner: f, yield_strength })
    }

    /// Length L (m).
    #[getter]
    fn length(&self) -> f64 {
        self.inner.length()
    }
    /// Bending stiffness EI (N·m²); for a non-uniform section, its mean (1/L)∫EI ds.
    #[getter]
    fn ei(&self) -> f64 {
        self.inner.ei()
    }
    /// Order N.
    #[getter]
    fn order(&self) -> usize {
        self.inner.order()
    }
    /// Gauss–Legendre points.
    #[getter]
    fn quadrature(&self) -> usize {
        self.inner.quadrature_points()
    }
    /// Rest coefficients κ, shape (N,).
    #[getter]
    fn rest<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.inner.rest().to_vec())
    }
    /// Effective modulus E′ (Pa; E/(1−ν²) with a Poisson ratio), or None for a flexure given by ei (no stress).
    #[getter]
    fn modulus(&self) -> Option<f64> {
        self.inner.section().modulus()
    }
    /// Yield strength S (Pa), or None.
    #[getter]
    fn yield_strength(&self) -> Option<f64> {
        self.yield_strength
    }
    /// Whether EI is the same all along the flexure.
    #[getter]
    fn uniform(&self) -> bool {
        self.inner.section().is_uniform()
    }

    /// Bending stiffness EI(s) (N·m²) at arc length s (m) from the root: a float, or an array like s.
    fn ei_at<'py>(&self, py: Python<'py>, s: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        along(py, &self.inner, s, |s| self.inner.ei_at(s))
    }
    /// Thickness h(s) (m), notch included, at arc length s (m); None for a flexure given by ei.
    fn thickness_at<'py>(&self, py: Python<'py>, s: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let (f, l) = (&self.inner, self.inner.length());
        let section = f.section();
        if section.thickness(0.0, l).is_none() {
            return Ok(None);
        }
        along(py, f, s, |s| section.thickness(s / l, l).unwrap_or(0.0)).map(Some)
    }
    /// Width b(s) (m) at arc length s (m); None for a flexure given by ei.
    fn width_at<'py>(&self, py: Python<'py>, s: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let (f, l) = (&self.inner, self.inner.length());
        let section = f.section();
        if section.width(0.0).is_none() {
            return Ok(None);
        }
        along(py, f, s, |s| section.width(s / l).unwrap_or(0.0)).map(Some)
    }
    /// Mass per length μ(s) (kg/m) at arc length s (m); None without density or mass_per_length.
    fn mass_per_length_at<'py>(&self, py: Python<'py>, s: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let (f, l) = (&self.inner, self.inner.length());
        let section = f.section();
        if section.mass_per_length(0.0, l).is_none() {
            return Ok(None);
        }
        along(py, f, s, |s| section.mass_per_length(s / l, l).unwrap_or(0.0)).map(Some)
    }

    /// Peak bending stress at alpha (N,): {"max": σmax (Pa), "at": s (m from the root)},
    /// σ(s) = E′ h(s)/2 |ω̂(s) − ω̂₀(s)|; None for a flexure given by ei (no thickness).
    fn stress<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let a = single(self.inner.order(), alpha)?;
        let d = flexure::stress::peak_stress(&self.inner, &a).map(|p| stress::peak_dict(py, &p)).transpose()?;
        if let Some(d) = &d {
            strict::finite_answer("stress", d.as_any())?;
        }
        Ok(d)
    }

    /// Largest change of curvature from rest at alpha (N,): {"max": |ω̂ − ω̂₀| (1/m), "at": s (m)}.
    fn peak_curvature<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
        let a = single(self.inner.order(), alpha)?;
        let d = stress::peak_dict(py, &flexure::stress::peak_curvature(&self.inner, &a))?;
        strict::finite_answer("peak_curvature", d.as_any())?;
        Ok(d)
    }

    /// Safety factor S/σmax at alpha (N,) against the yield strength (inf while unstressed);
    /// below 1 it warns YieldWarning naming the yield strength.
    fn safety_factor(&self, py: Python<'_>, alpha: &Bound<'_, PyAny>) -> PyResult<f64> {
        let Some(s) = self.yield_strength else {
            return Err(PyValueError::new_err(
                "safety_factor needs the flexure's yield_strength: build it with Flexure(..., yield_strength=S)",
            ));
        };
        let a = single(self.inner.order(), alpha)?;
        Ok(stress::safety_factor(py, &self.inner, &a, s, "safety_factor", 1)?.map_or(f64::INFINITY, |(_, f)| f))
    }

    /// The deformed flexure at alpha (N,) at k points evenly spaced in arc length, ends included,
    /// in its root frame: a structured array of fields s, x, y, phi (m, m, m, rad), curvature
    /// (1/m, total) and, with a thickness, stress (Pa).
    fn shape<'py>(
        &self,
        py: Python<'py>,
        alpha: &Bound<'py, PyAny>,
        k: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let a = single(self.inner.order(), alpha)?;
        let out = stress::shape(py, &self.inner, &a, shape_points(k)?)?;
        strict::finite_answer("shape", &out)?;
        Ok(out)
    }

    /// Tip pose [phi, x, y] for alpha of shape (N,); (n, 3) for shape (n, N), computed in parallel without the GIL.
    fn pose<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let f = &self.inner;
        let (count, rows) = match coordinates::read(f.order(), alpha)? {
            Coordinates::One(a) => {
                let p = <[f64; 3]>::from(flexure::pose_root_tip(f, &a));
                strict::finite_slice("pose", &p)?;
                return Ok(PyArray1::from_slice(py, &p).into_any());
            }
            Coordinates::Many { count, rows } => (count, rows),
        };
        let n = f.order();
        // Written in place: a fresh C-ordered (count, 3) array, one [phi, x, y] row per pose.
        let out = PyArray2::<f64>::zeros(py, [count, 3], false);
        let mut written = out.readwrite();
        let poses = written.as_slice_mut().map_err(|e| PyRuntimeError::new_err(format!("pose: {e}")))?;
        let poses = poses.as_chunks_mut::<3>().0;
        let alphas = rows.as_slice();
        // Chunks of about 2^24 node evaluations (milliseconds), between which Ctrl-C is polled.
        let rows_per_chunk = ((1usize << 24) / (n * f.quadrature_points())).max(1);
        clear_raised();
        let done = py
            .detach(|| {
                let mut done = 0;
                for (a, p) in alphas.chunks(rows_per_chunk * n).zip(poses.chunks_mut(rows_per_chunk)) {
                    if signalled() {
                        break;
                    }
                    par_poses_root_tip(f, a, p)?;
                    done += p.len();
                }
                Ok(done)
            })
            .map_err(to_py)?;
        let interrupted = || PyKeyboardInterrupt::new_err(format!("pose: interrupted after {done} of {count} rows"));
        if let Some(err) = raised_during(py, interrupted) {
            return Err(err);
        }
        strict::finite_slice("pose", written.as_slice().unwrap_or(&[]))?;
        drop(written);
        Ok(out.into_any())
    }

    /// Jacobian of the tip pose, shape (3, N), rows phi, x, y (Eqs. 19–21).
    fn jacobian<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let a = single(self.inner.order(), alpha)?;
        let mut k = Kinematics::new(&self.inner);
        update_kinematics(&self.inner, &a, &mut k, Level::Jacobian);
        strict::finite_slice("jacobian", k.jacobian_root_tip.as_slice())?;
        Ok(matrix(&k.jacobian_root_tip).into_pyarray(py))
    }

    /// Hessians (Hx, Hy) of the tip's x and y, each (N, N) (Eqs. 30–31).
    fn hessians<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<MatrixPair<'py>> {
        let a = single(self.inner.order(), alpha)?;
        let mut k = Kinematics::new(&self.inner);
        update_kinematics(&self.inner, &a, &mut k, Level::Hessian);
        strict::finite_slice("hessians", k.hessian_root_tip_x.as_slice())?;
        strict::finite_slice("hessians", k.hessian_root_tip_y.as_slice())?;
        Ok((matrix(&k.hessian_root_tip_x).into_pyarray(py), matrix(&k.hessian_root_tip_y).into_pyarray(py)))
    }

    /// Homogeneous transform of the tip in the root frame, (4, 4) (Eq. 7).
    fn transform<'py>(&self, py: Python<'py>, alpha: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let a = single(self.inner.order(), alpha)?;
        let g = flexure::pose_root_tip(&self.inner, &a).transform();
        strict::finite_slice("transform", g.as_slice())?;
        Ok(Array2::from_shape_fn((4, 4), |(i, j)| g[(i, j)]).into_pyarray(py))
    }

    /// Bending energy U(alpha) in joules (Eq. 9).
    fn energy(&self, alpha: &Bound<'_, PyAny>) -> PyResult<f64> {
        strict::finite_number("energy", energy(&self.inner, &single(self.inner.order(), alpha)?))
    }

    /// Equilibrium coordinates alpha (N,) under a tip moment and force in the root frame (Eq. 22),
    /// with its error estimated against a refined model: a miss of `accuracy` (position as a
    /// fraction of L, angle in rad; default 1 % and 1°) warns `AccuracyWarning`. With
    /// `order="auto"`, raises the order until the target is met and returns `(flexure_used, alpha)`.
    /// With a yield strength, a peak stress beyond it warns `YieldWarning`.
    #[pyo3(signature = (moment=Real(0.0), fx=Real(0.0), fy=Real(0.0), *, accuracy=None, order=None))]
    fn deflect<'py>(
        &self,
        py: Python<'py>,
        moment: Real,
        fx: Real,
        fy: Real,
        accuracy: Option<&Bound<'py, PyAny>>,
        order: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let load = tip_load(moment, fx, fy)?;
        let target = self::accuracy(accuracy)?;
        let auto = match order.filter(|o| !o.is_none()) {
            None => false,
            Some(o) if o.extract::<String>().is_ok_and(|s| s == "auto") => true,
            Some(o) => {
                return Err(PyValueError::new_err(format!(
                    "order must be None or \"auto\", got {}: a flexure's own order is set when it is built",
                    o.repr()?
                )));
            }
        };
        let f = &self.inner;
        if auto {
            // The library refuses `order` when even its highest order misses the target.
            let found = interruptible(py, || match estimate::deflect_auto(f, &load, &target) {
                Ok((used, alpha, _)) => Ok(Ok((used, alpha))),
                // Its value says by how much the last order misses, and against what.
                Err(Error::InvalidParameter { name: "order", value, .. }) => Ok(Err(value)),
                Err(e) => Err(e),
            })?;
            let (used, alpha) = match found {
                Ok(found) => found,
                Err(value) => {
                    let by = value.strip_prefix("auto ").unwrap_or("");
                    return Err(PyValueError::new_err(format!(
                        "order=\"auto\": even order {} misses the target of {} % of L and {}° under (moment, fx, fy) = ({moment}, {fx}, {fy}) {by}: loosen accuracy or reduce the load",
                        flexure::joint::MAX_ORDER,
                        sig(100.0 * target.position),
                        sig(target.angle.to_degrees())
                    )));
                }
            };
            let (_, stiffness) = loaded_stiffness(&used, &alpha, &load);
            if !flexure::linalg::is_positive_definite(&stiffness) {
                let why = "its stiffness is not positive definite (the load is past a buckling load)";
                warn_unstable(py, "deflect", &load, why, 1)?;
            }
            if let Some(s) = self.yield_strength {
                stress::safety_factor(py, &used, &alpha, s, "deflect", 1)?;
            }
            strict::finite_slice("deflect", &alpha)?;
            let used = Py::new(py, Flexure { inner: used, yield_strength: self.yield_strength })?;
            let alpha = PyArray1::from_vec(py, alpha);
            return Ok(PyTuple::new(py, [used.into_any(), alpha.into_any().unbind()])?.into_any());
        }
        let (alpha, stable, estimated) = interruptible(py, || {
            let mut data = Statics::new(f);
            let eq = deflect(f, &load, &mut data, &Default::default())?;
            let alpha = data.alpha().to_vec();
            // One estimator per thread: its reference model is rebuilt only for another flexure.
            let estimated = ESTIMATOR.with_borrow_mut(|est| est.deflect_error(f, &load, &alpha, &target));
            Ok((alpha, eq.stable, interrupted_or(estimated)?))
        })?;
        if !stable {
            let why = "its stiffness is not positive definite (the load is past a buckling load)";
            warn_unstable(py, "deflect", &load, why, 1)?;
        }
        match estimated {
            Ok(e) if e.flagged => {
                let hint = "use deflect(..., order=\"auto\") to raise the order until the target is met";
                warn_inaccurate(py, "deflect", f, &e, &target, hint, 1)?
            }
            Ok(_) => {}
            Err(why) => warn_unestimated(py, "deflect", &why, 1)?,
        }
        if let Some(s) = self.yield_strength {
            stress::safety_factor(py, f, &alpha, s, "deflect", 1)?;
        }
        strict::finite_slice("deflect", &alpha)?;
        Ok(PyArray1::from_vec(py, alpha).into_any())
    }

    /// The estimated error of `alpha` as the equilibrium under a tip load, against a refined
    /// model: a dict of position (m), angle (rad), flagged (whether it misses `accuracy`),
    /// reference_order and reference_quadrature.
    #[pyo3(signature = (alpha, moment=Real(0.0), fx=Real(0.0), fy=Real(0.0), accuracy=None))]
    fn error_estimate<'py>(
        &self,
        py: Python<'py>,
        alpha: &Bound<'py, PyAny>,
        moment: Real,
        fx: Real,
        fy: Real,
        accuracy: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let a = single(self.inner.order(), alpha)?;
        let load = tip_load(moment, fx, fy)?;
        let target = self::accuracy(accuracy)?;
        let f = &self.inner;
        let e = interruptible(py, || estimate::deflect_error(f, &load, &a, &target))?;
        let d = estimate_dict(py, &e)?;
        strict::finite_answer("error_estimate", d.as_any())?;
        Ok(d)
    }

    /// Generalized stiffness (N, N) at alpha under a tip load:
    /// K = ∇∇U − Fx∇∇x − Fy∇∇y (Eq. 32; the moment adds nothing, φ_tip being linear in alpha).
    #[pyo3(signature = (alpha, moment=Real(0.0), fx=Real(0.0), fy=Real(0.0)))]
    fn stiffness<'py>(
        &self,
        py: Python<'py>,
        alpha: &Bound<'py, PyAny>,
        moment: Real,
        fx: Real,
        fy: Real,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let load = tip_load(moment, fx, fy)?;
        let (_, k) = loaded_stiffness(&self.inner, &single(self.inner.order(), alpha)?, &load);
        strict::finite_slice("stiffness", k.as_slice())?;
        Ok(matrix(&k).into_pyarray(py))
    }

    /// Tip compliance (3, 3), order (phi, x, y), at alpha under a tip load: C = J K⁻¹ Jᵀ with the
    /// loaded stiffness K of Eq. 32 (Eq. 36 at a loaded equilibrium). At an equilibrium alpha for
    /// that load (from `deflect`) it is the response d(pose)/d(moment, fx, fy) to a small extra load.
    #[pyo3(signature = (alpha, moment=Real(0.0), fx=Real(0.0), fy=Real(0.0)))]
    fn compliance<'py>(
        &self,
        py: Python<'py>,
        alpha: &Bound<'py, PyAny>,
        moment: Real,
        fx: Real,
        fy: Real,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let load = tip_load(moment, fx, fy)?;
        let (k, stiffness) = loaded_stiffness(&self.inner, &single(self.inner.order(), alpha)?, &load);
        let c = compliance_tip(&k, &stiffness).map_err(to_py)?;
        strict::finite_slice("compliance", c.as_slice())?;
        Ok(Array2::from_shape_fn((3, 3), |(i, j)| c[(i, j)]).into_pyarray(py))
    }

    /// Tip compliance (3, 3) of the unloaded flexure at its rest shape (Eqs. 35–36).
    fn rest_compliance<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let c = compliance_tip_rest(&self.inner);
        strict::finite_slice("rest_compliance", c.as_slice())?;
        Ok(Array2::from_shape_fn((3, 3), |(i, j)| c[(i, j)]).into_pyarray(py))
    }

    /// Vibration modes about the equilibrium under a tip load (moment, fx, fy; Eq. 32's loaded
    /// stiffness, so a frequency falls to zero at a buckling load), with the flexure's mass
    /// (density or mass_per_length) and an optional rigid tip body: tip_mass (kg), tip_inertia
    /// (kg·m² about its centre of mass) and tip_com (x, y) (m, in the tip frame). A dict of
    /// omega (rad/s, ascending), frequency (Hz), shapes (modes, order: each row a mode's
    /// coordinates, vᵀMv = 1) and quasi_static (directions without inertia, condensed out:
    /// a massless flexure's, which have no frequency). count: the lowest modes wanted, 1 to
    /// order (default 3, or the order); fewer are returned if fewer are finite. ValueError
    /// naming `mass` without any mass; ConvergenceError past a buckling load.
    #[pyo3(signature = (count=None, *, tip_mass=None, tip_inertia=None, tip_com=None, moment=Real(0.0), fx=Real(0.0), fy=Real(0.0), accuracy=None))]
    #[allow(clippy::too_many_arguments)]
    fn modes<'py>(
        &self,
        py: Python<'py>,
        count: Option<&Bound<'py, PyAny>>,
        tip_mass: Option<Real>,
        tip_inertia: Option<Real>,
        tip_com: Option<&Bound<'py, PyAny>>,
        moment: Real,
        fx: Real,
        fy: Real,
        accuracy: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let body = modes::tip_body(tip_mass.map(|v| v.0), tip_inertia.map(|v| v.0), tip_com)?;
        let target = eigen_accuracy(accuracy)?;
        modes::flexure_modes(py, &self.inner, count, body, tip_load(moment, fx, fy)?, &target)
    }

    /// Critical compressive tip load (N) under tip constraint "free", "guided", "pinned" or
    /// "clamped", with its error estimated against a refined model (the same load at a higher
    /// order): a miss of `accuracy` (a fraction of the load; default 0.01) warns `AccuracyWarning`.
    #[pyo3(signature = (tip="free", *, accuracy=None))]
    fn buckling_load(&self, py: Python<'_>, tip: &str, accuracy: Option<&Bound<'_, PyAny>>) -> PyResult<f64> {
        let t: TipConstraint = tip.parse().map_err(to_py)?;
        let target = eigen_accuracy(accuracy)?;
        let f = &self.inner;
        let b = buckling_load(f, t).map_err(to_py)?;
        match estimate::buckling_error(f, t, &b, &target) {
            Ok(e) => {
                let (order, points) = e.reference_orders[0];
                let reference = format!("order {order} with {points} quadrature points");
                let name = |_| format!("the critical load {} N", sig(b.critical_load));
                let hint = "build the flexure with a higher order";
                warn_values(py, &format!("buckling_load ({tip} tip)"), &e, &target, name, &reference, hint, 1)?;
            }
            Err(why) => warn_unestimated(py, "buckling_load", &why, 1)?,
        }
        strict::finite_number("buckling_load", b.critical_load)
    }

    /// The tendon-driven joint (Sec. III-D, Eqs. 23–26) under a tendon of tension `force` (N, not
    /// negative) attached `root_offset` and `tip_offset` (m) from the neutral axis at the root and
    /// the tip, followed from rest: a dict as `flexure tendon --json` gives it: alpha (N,), pose
    /// [phi, x, y] (an array, as `pose` returns), tendon_length (m), stable, error_estimate (a
    /// dict as `error_estimate` returns, or None where it could not be made) and flagged, stress
    /// {max, at} (or curvature_max for a flexure given by ei), safety_factor with a yield_strength
    /// (left out while unstressed). An unstable answer warns StabilityWarning; a miss of
    /// `accuracy` (as deflect's) warns AccuracyWarning; with `order="auto"` the order is raised
    /// until it is met (order and quadrature then say which). With `limit=True`, also the factor
    /// on the tension, up to `max_factor`, at which the path stops being stable: stability_limit,
    /// or stable_up_to (with stalled, and a StabilityWarning, if the path could not be followed
    /// that far), as `tendon --limit`.
    #[pyo3(signature = (force, root_offset, tip_offset, *, accuracy=None, order=None, limit=false, max_factor=Real(analyses::MAX_FACTOR)))]
    #[allow(clippy::too_many_arguments)]
    fn tendon<'py>(
        &self,
        py: Python<'py>,
        force: Real,
        root_offset: Real,
        tip_offset: Real,
        accuracy: Option<&Bound<'py, PyAny>>,
        order: Option<&Bound<'py, PyAny>>,
        limit: bool,
        max_factor: Real,
    ) -> PyResult<Bound<'py, PyDict>> {
        let force = real("force", force)?;
        if force < 0.0 {
            return Err(PyValueError::new_err(format!(
                "invalid force = {force}: a tendon's tension must not be negative (N)"
            )));
        }
        let t = flexure::tendon::Tendon {
            root_offset: real("root_offset", root_offset)?,
            tip_offset: real("tip_offset", tip_offset)?,
        };
        let target = self::accuracy(accuracy)?;
        let auto = auto_order(order)?;
        let limit = limit.then_some(max_factor.0);
        analyses::tendon(py, &self.inner, self.yield_strength, force, t, &target, auto, limit)
    }

    /// The minimum-energy shape whose tip reaches `pose` = (phi, x, y) in the root frame (rad,
    /// m, m; Sec. II-E, Eq. 16): a dict as `flexure connect --json` gives it: alpha (N,),
    /// energy (J), load {moment, fx, fy}, the tip load that holds the shape, error_estimate
    /// (the largest distance between the answer's backbone and a refined model's) and flagged,
    /// stress (or curvature_max) and safety_factor, as `tendon`'s. A pose out of reach raises
    /// ValueError naming pose; `accuracy`, `order="auto"`, `limit` and `max_factor` as `tendon`'s
    /// (the limit is that of the holding load applied from rest as a dead load). The CLI's
    /// `eta` (the energy against the exact elastica's) is left out: see `flexure.exact`.
    #[pyo3(signature = (pose, *, accuracy=None, order=None, limit=false, max_factor=Real(analyses::MAX_FACTOR)))]
    fn connect<'py>(
        &self,
        py: Python<'py>,
        pose: &Bound<'py, PyAny>,
        accuracy: Option<&Bound<'py, PyAny>>,
        order: Option<&Bound<'py, PyAny>>,
        limit: bool,
        max_factor: Real,
    ) -> PyResult<Bound<'py, PyDict>> {
        let bad = || {
            PyValueError::new_err(format!(
                "invalid pose = {}: must be three finite numbers (phi, x, y), the tip pose in the root frame (rad, m, m)",
                pose.repr().map(|r| r.to_string()).unwrap_or_default()
            ))
        };
        strict::no_bool("pose", pose)?;
        let v: Vec<f64> = pose.extract().map_err(|_| bad())?;
        let [phi, x, y] = v[..] else { return Err(bad()) };
        if !v.iter().all(|v| v.is_finite()) {
            return Err(bad());
        }
        let target = self::accuracy(accuracy)?;
        let auto = auto_order(order)?;
        let limit = limit.then_some(max_factor.0);
        analyses::connect(py, &self.inner, self.yield_strength, Pose { phi, x, y }, &target, auto, limit)
    }

    /// The factor on the tip load (moment, fx, fy) at which the equilibrium followed from rest
    /// stops being stable (a buckling or limit load), as `flexure deflect --limit`: a dict of
    /// stability_limit, that factor (stable up to it, unstable within a relative 1e-10 above),
    /// or of stable_up_to, the bound it stays stable to: `max_factor` (default 1000), or as far
    /// as the path could be followed, with stalled (why) and a StabilityWarning. For axial
    /// compression fx = -1 the factor is the free column's buckling load, Euler's pi^2 EI/4L^2.
    #[pyo3(signature = (moment=Real(0.0), fx=Real(0.0), fy=Real(0.0), *, max_factor=Real(analyses::MAX_FACTOR)))]
    fn stability_limit<'py>(
        &self,
        py: Python<'py>,
        moment: Real,
        fx: Real,
        fy: Real,
        max_factor: Real,
    ) -> PyResult<Bound<'py, PyDict>> {
        let load = tip_load(moment, fx, fy)?;
        analyses::stability_limit(py, &self.inner, &load, max_factor.0)
    }

    fn __repr__(&self) -> String {
        format!(
            "Flexure(length={}, ei={}, order={}, quadrature={})",
            self.inner.length(),
            self.inner.ei(),
            self.inner.order(),
            self.inner.quadrature_points()
        )
    }
}

/// A mechanism read from a TOML description.
#[pyclass(frozen, module = "flexure")]
struct Mechanism {
    inner: flexure::mechanism::Mechanism,
    /// Each flexure joint's `yield_strength` and `shape`, by name.
    reports: Vec<(String, Report)>,
}

#[pymethods]
impl Mechanism {
    /// Parses mechanism TOML text.
    #[staticmethod]
    fn from_text(text: &str) -> PyResult<Self> {
        let inner = from_toml(text).map_err(to_py)?;
        Ok(Self { inner, reports: reports(text).map_err(to_py)? })
    }

    /// Equilibrium as a dict shaped like `flexure solve --json`, with `estimates`: the
    /// estimated error of each flexure joint (a dict as `Flexure.error_estimate` returns, or
    /// None where it could not be made). A joint that misses `accuracy` warns `AccuracyWarning`.
    /// Per flexure joint, by name: `stress` {max, at} (or `curvature_max` for one given by ei),
    /// `safety_factor` for one with `yield_strength` (left out while unstressed; below 1 it warns
    /// `YieldWarning`) and `shape` (a structured array, as `Flexure.shape`) for one with `shape`;
    /// each map left out when empty.
    #[pyo3(signature = (accuracy=None))]
    fn solve<'py>(&self, py: Python<'py>, accuracy: Option<&Bound<'py, PyAny>>) -> PyResult<Bound<'py, PyDict>> {
        let target = self::accuracy(accuracy)?;
        let m = &self.inner;
        let (s, estimated, open) = interruptible(py, || {
            let open = flexure::mechanism::findings::open_closures(m, &MechanismSettings::default())?;
            let s = solve(m, &MechanismSettings::default())?;
            // Each flexure joint carries only the load at its tip: its error is that of a deflect.
            let mut estimated = Vec::new();
            for j in &m.joints {
                if let JointKind::Flexure(f) = &j.kind {
                    let alpha = &s.q[j.offset..j.offset + f.order()];
                    estimated.push((j, f.as_ref(), interrupted_or(estimate::joint_error(f, alpha, &target))?));
                }
            }
            Ok((s, estimated, open))
        })?;
        let frames = body_frames(m, &s);
        let bodies = PyDict::new(py);
        for (b, f) in m.bodies.iter().zip(&frames.bodies) {
            let d = PyDict::new(py);
            d.set_item("x", f.origin[0])?;
            d.set_item("y", f.origin[1])?;
            d.set_item("phi", f.angle)?;
            bodies.set_item(&b.name, d)?;
        }
        let coordinates = PyDict::new(py);
        for j in &m.joints {
            let q = Array1::from_vec(s.q[j.offset..j.offset + j.kind.joint().dof()].to_vec());
            coordinates.set_item(&j.name, q.into_pyarray(py))?;
        }
        let estimates = PyDict::new(py);
        // Stack level 2: the line calling `flexure.Mechanism.solve`, past its Python wrapper.
        for (j, f, e) in &estimated {
            let what = format!("Mechanism.solve, flexure joint '{}'", j.name);
            match e {
                Ok(e) => {
                    if e.flagged {
                        let hint = "raise the joint's order (and quadrature) in the mechanism file";
                        warn_inaccurate(py, &what, f, e, &target, hint, 2)?;
                    }
                    estimates.set_item(&j.name, estimate_dict(py, e)?)?;
                }
                Err(why) => {
                    warn_unestimated(py, &what, why, 2)?;
                    estimates.set_item(&j.name, py.None())?;
                }
            }
        }
        let keys = ["stress", "curvature_max", "safety_factor", "shape"];
        let maps = keys.map(|_| PyDict::new(py));
        for j in &m.joints {
            let JointKind::Flexure(f) = &j.kind else { continue };
            let q = &s.q[j.offset..j.offset + f.order()];
            let report = self.reports.iter().find(|r| r.0 == j.name).map_or_else(Report::default, |r| r.1);
            let (key, peak) = peak_item(py, f, q)?;
            maps[if key == "stress" { 0 } else { 1 }].set_item(&j.name, peak)?;
            if let Some(strength) = report.yield_strength {
                let what = format!("Mechanism.solve, flexure joint '{}'", j.name);
                if let Some((_, factor)) = stress::safety_factor(py, f, q, strength, &what, 2)? {
                    maps[2].set_item(&j.name, factor)?;
                }
            }
            if let Some(k) = report.shape {
                maps[3].set_item(&j.name, stress::shape(py, f, q, k)?)?;
            }
        }
        let out = PyDict::new(py);
        out.set_item("bodies", bodies)?;
        out.set_item("coordinates", coordinates)?;
        out.set_item("energy", s.energy)?;
        out.set_item("stable", s.stable)?;
        out.set_item("estimates", estimates)?;
        let by_joint: Vec<(String, Option<&ErrorEstimate>)> =
            estimated.iter().map(|(j, _, e)| (j.name.clone(), e.as_ref().ok())).collect();
        mechanism::put_joint_estimates(py, &out, &by_joint)?;
        for (key, map) in keys.into_iter().zip(maps) {
            if !map.is_empty() {
                out.set_item(key, map)?;
            }
        }
        let crossings =
            flexure::mechanism::findings::crossings(m, &s.q).into_iter().map(|c| (None, c)).collect::<Vec<_>>();
        let listed = findings::report(py, "Mechanism.solve", &open, &crossings, 2)?;
        if !listed.is_empty() {
            out.set_item("findings", listed)?;
        }
        if let Some(limit) = s.limit {
            // A snap-through: the stable answer beyond a limit load, which the caller must know of.
            out.set_item("limit_fraction", limit)?;
            let text = format!(
                "Mechanism.solve: the loading path lost stability at {:.4} % of the load and snapped through to this stable equilibrium",
                100.0 * limit
            );
            warn(py, &py.get_type::<StabilityWarning>(), text, 2)?;
        }
        if !s.stable {
            let text = "Mechanism.solve: the equilibrium is unstable (`stable` is False): its constrained stiffness is not positive definite, so a small disturbance moves it away".to_string();
            warn(py, &py.get_type::<StabilityWarning>(), text, 2)?;
        }
        strict::finite_answer("Mechanism.solve", out.as_any())?;
        Ok(out)
    }

    /// The motion over `duration` (s) as arrays: see `flexure.Mechanism.simulate`.
    #[pyo3(signature = (duration, every=None, tolerance=Real(1e-8), start="equilibrium", max_steps=None))]
    fn simulate<'py>(
        &self,
        py: Python<'py>,
        duration: Real,
        every: Option<Real>,
        tolerance: Real,
        start: &str,
        max_steps: Option<usize>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let out = simulate::motion(py, &self.inner, (duration.0, every.map(|v| v.0)), tolerance.0, start, max_steps)?;
        strict::finite_answer("Mechanism.simulate", out.as_any())?;
        Ok(out)
    }

    /// Vibration modes about the loaded equilibrium, closures respected: a dict of omega
    /// (rad/s, ascending), frequency (Hz), shapes {joint: array (modes, joint coordinates)}
    /// and quasi_static, as `Mechanism.modes` documents.
    #[pyo3(signature = (count=None, accuracy=None))]
    fn modes<'py>(
        &self,
        py: Python<'py>,
        count: Option<&Bound<'py, PyAny>>,
        accuracy: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let target = eigen_accuracy(accuracy)?;
        modes::mechanism_modes(py, &self.inner, count, &target)
    }

    /// Linear buckling about the unloaded configuration, as `flexure buckle --json`: see
    /// `flexure.Mechanism.buckle`.
    #[pyo3(signature = (accuracy=None))]
    fn buckle<'py>(&self, py: Python<'py>, accuracy: Option<&Bound<'py, PyAny>>) -> PyResult<Bound<'py, PyDict>> {
        let target = eigen_accuracy(accuracy)?;
        mechanism::buckle(py, &self.inner, &target)
    }

    /// Compliance (3, 3), order (phi, x, y), of the frame at `at` (x, y) on `body` at the loaded
    /// equilibrium, as `flexure solve --compliance BODY --at X,Y`.
    fn compliance<'py>(&self, py: Python<'py>, body: &str, at: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        mechanism::compliance_at(py, &self.inner, body, at)
    }

    /// Equilibria along `values` of one load, as `flexure solve --sweep`: see `flexure.Mechanism.sweep`.
    #[pyo3(signature = (parameter, values, accuracy=None, compliance=None, at=None))]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        parameter: &str,
        values: &Bound<'py, PyAny>,
        accuracy: Option<&Bound<'py, PyAny>>,
        compliance: Option<&str>,
        at: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let target = self::accuracy(accuracy)?;
        let frame = match (compliance, at) {
            (Some(body), Some(at)) => Some((body, at)),
            (None, None) => None,
            _ => {
                return Err(PyValueError::new_err(
                    "compliance and at go together: the body, and the point (x, y) on it whose compliance each row reports",
                ));
            }
        };
        mechanism::sweep(py, &self.inner, parameter, values, &target, frame)
    }

    /// Number of generalized coordinates.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof()
    }
}

#[pymodule]
fn _flexure(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Flexure>()?;
    m.add_class::<Mechanism>()?;
    m.add_class::<exact::Elastica>()?;
    m.add_function(wrap_pyfunction!(exact::exact_elastica, m)?)?;
    m.add_function(wrap_pyfunction!(exact::exact_compliance, m)?)?;
    m.add_function(wrap_pyfunction!(exact::exact_buckling_load, m)?)?;
    m.add_function(wrap_pyfunction!(exact::exact_flexure, m)?)?;
    m.add_function(wrap_pyfunction!(modes::exact_frequencies, m)?)?;
    m.add("ConvergenceError", m.py().get_type::<ConvergenceError>())?;
    m.add("StabilityWarning", m.py().get_type::<StabilityWarning>())?;
    m.add("AccuracyWarning", m.py().get_type::<AccuracyWarning>())?;
    m.add("YieldWarning", m.py().get_type::<YieldWarning>())?;
    m.add("PreloadWarning", m.py().get_type::<PreloadWarning>())?;
    m.add("IntersectionWarning", m.py().get_type::<IntersectionWarning>())?;
    Ok(())
}
