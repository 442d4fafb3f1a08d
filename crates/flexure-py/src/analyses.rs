//! The paper's analyses on one flexure, as the CLI answers them: the
//! tendon-driven joint (`Flexure.tendon`, as `flexure tendon`), the
//! minimum-energy shape reaching a tip pose (`Flexure.connect`, as
//! `flexure connect`) and the factor on a tip load at which stability is
//! lost (`Flexure.stability_limit`, as `deflect --limit`). Each answer
//! carries its error estimate, warned about as `deflect`'s is.

use crate::error_estimate::{estimate_dict, interrupted_or};
use crate::errors::StabilityWarning;
use crate::interrupt::interruptible;
use crate::serialize::to_dict;
use crate::stress::{self, peak_item};
use crate::strict::finite_answer;
use crate::warnings::{sig, warn, warn_inaccurate, warn_unestimated};
use flexure::connect::connect as connect_pose;
use flexure::estimate::{self, Accuracy};
use flexure::tendon::{TendonData, TendonOffsets, equilibrium};
use flexure::{Error, Pose, StabilityLimit, TipLoad};
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

pub use flexure::limit::MAX_FACTOR;

/// `max_factor`, finite and greater than zero.
pub fn max_factor(v: f64) -> PyResult<f64> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(PyValueError::new_err(format!("invalid max_factor = {v}: must be a finite number greater than zero")))
    }
}

/// The pose [phi, x, y] as an array.
fn pose_array<'py>(py: Python<'py>, p: &Pose) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, &[p.phi, p.x, p.y])
}

/// A stability limit as one object, the library's serialization, the same
/// wherever it is answered: `{"factor", "status": "lost"}`, the factor where
/// stability is lost, or `{"factor", "status": "stable_up_to", "stalled"}`, the
/// factor it holds to, with `stalled` None when that is `max_factor` and
/// otherwise why the path could not be followed further (and a StabilityWarning).
pub fn limit_dict<'py>(
    py: Python<'py>,
    l: &StabilityLimit,
    what: &str,
    stacklevel: i32,
) -> PyResult<Bound<'py, PyDict>> {
    if let StabilityLimit::StableUpTo { factor, stalled: Some(why) } = l {
        let text = format!(
            "{what}: the loading path stays stable up to {} times the load, as far as it could be followed; beyond it stability is unknown: {why}",
            sig(*factor)
        );
        warn(py, &py.get_type::<StabilityWarning>(), text, stacklevel)?;
    }
    to_dict(py, l)
}

/// The stability limit of a tip load on `f`: see `Flexure.stability_limit`.
pub fn stability_limit<'py>(
    py: Python<'py>,
    f: &flexure::Flexure,
    load: &TipLoad,
    max: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let max = max_factor(max)?;
    let l = interruptible(py, || flexure::statics::stability_limit(f, load, max))?;
    let out = limit_dict(py, &l, "stability_limit", 1)?;
    finite_answer("stability_limit", out.as_any())?;
    Ok(out)
}

/// Bending and estimate of an answer `alpha` into `out`, with their warnings
/// (`what` names the answer): `stress` or `curvature_max`, `safety_factor`
/// with a yield strength, `error_estimate` and `flagged`.
fn insert_checks(
    py: Python<'_>,
    out: &Bound<'_, PyDict>,
    (f, yield_strength): (&flexure::Flexure, Option<f64>),
    alpha: &[f64],
    estimated: &Result<estimate::ErrorEstimate, Error>,
    (target, what, hint): (&Accuracy, &str, &str),
) -> PyResult<()> {
    match estimated {
        Ok(e) => {
            if e.flagged {
                warn_inaccurate(py, what, f.length(), e, target, hint, 1)?;
            }
            out.set_item("error_estimate", estimate_dict(py, e)?)?;
            out.set_item("flagged", e.flagged)?;
        }
        Err(why) => {
            warn_unestimated(py, what, why, 1)?;
            out.set_item("error_estimate", py.None())?;
            out.set_item("flagged", true)?;
        }
    }
    let (key, peak) = peak_item(py, f, alpha)?;
    out.set_item(key, peak)?;
    if let Some(s) = yield_strength
        && let Some((_, factor)) = stress::safety_factor(py, f, alpha, s, what, 1)?
    {
        out.set_item("safety_factor", factor)?;
    }
    Ok(())
}

/// The tendon-driven joint under `tension`: see `Flexure.tendon`.
#[allow(clippy::too_many_arguments)]
pub fn tendon<'py>(
    py: Python<'py>,
    f: &flexure::Flexure,
    yield_strength: Option<f64>,
    tension: f64,
    t: TendonOffsets,
    target: &Accuracy,
    auto: bool,
    limit: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    t.validate().map_err(crate::errors::to_py)?;
    let limit = limit.map(max_factor).transpose()?;
    let (used, eq, estimated, l) = interruptible(py, || {
        let used = if auto { estimate::tendon_auto(f, &t, tension, target)?.0 } else { f.clone() };
        let eq = equilibrium(&used, &t, tension, &mut TendonData::new(&used))?;
        let estimated = interrupted_or(estimate::tendon_error(&used, &t, tension, &eq.alpha, target))?;
        let l = limit.map(|max| flexure::tendon::stability_limit(&used, &t, tension, max)).transpose()?;
        Ok((used, eq, estimated, l))
    })?;
    // The library's answer, less the tension the caller gave; coordinates and pose as arrays.
    let out = to_dict(py, &eq)?;
    out.del_item("tension")?;
    out.set_item("alpha", PyArray1::from_slice(py, &eq.alpha))?;
    out.set_item("pose", pose_array(py, &eq.pose))?;
    let (alpha, stable) = (eq.alpha, eq.stable);
    if !stable {
        let text = format!(
            "tendon: the equilibrium under a tension of {tension} N is unstable: its stiffness is not positive definite, so a small disturbance moves it away"
        );
        warn(py, &py.get_type::<StabilityWarning>(), text, 1)?;
    }
    if auto {
        out.set_item("order", used.order())?;
        out.set_item("quadrature", used.quadrature_points())?;
    }
    let hint = if auto {
        "even order 64 misses it: loosen accuracy or reduce the tension"
    } else {
        "use tendon(..., order=\"auto\") to raise the order until the target is met"
    };
    insert_checks(py, &out, (&used, yield_strength), &alpha, &estimated, (target, "tendon", hint))?;
    if let Some(l) = &l {
        out.set_item("stability_limit", limit_dict(py, l, "tendon(limit=...)", 1)?)?;
    }
    finite_answer("tendon", out.as_any())?;
    Ok(out)
}

/// The minimum-energy shape reaching `pose`: see `Flexure.connect`.
pub fn connect<'py>(
    py: Python<'py>,
    f: &flexure::Flexure,
    yield_strength: Option<f64>,
    pose: Pose,
    target: &Accuracy,
    auto: bool,
    limit: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let limit = limit.map(max_factor).transpose()?;
    let (used, c, estimated, l) = interruptible(py, || {
        let used = if auto { estimate::connect_auto(f, &pose, target)?.0 } else { f.clone() };
        let c = connect_pose(&used, &pose)?;
        let estimated = interrupted_or(estimate::connect_error(&used, &pose, &c.alpha, target))?;
        let l = limit.map(|max| flexure::statics::stability_limit(&used, &c.load, max)).transpose()?;
        Ok((used, c, estimated, l))
    })?;
    // The library's answer {alpha, energy, load}, the coordinates as an array.
    let out = to_dict(py, &c)?;
    out.set_item("alpha", PyArray1::from_slice(py, &c.alpha))?;
    if auto {
        out.set_item("order", used.order())?;
        out.set_item("quadrature", used.quadrature_points())?;
    }
    let hint = if auto {
        "even order 64 misses it: loosen accuracy"
    } else {
        "use connect(..., order=\"auto\") to raise the order until the target is met"
    };
    insert_checks(py, &out, (&used, yield_strength), &c.alpha, &estimated, (target, "connect", hint))?;
    if let Some(l) = &l {
        out.set_item("stability_limit", limit_dict(py, l, "connect(limit=...)", 1)?)?;
    }
    finite_answer("connect", out.as_any())?;
    Ok(out)
}
