//! The statics of one flexure: equilibrium under a tip load with its error
//! estimate (`Flexure.deflect`), the loaded stiffness of Eq. 32, and the
//! buckling load with its estimate.

use crate::accuracy::{auto_order, eigen_accuracy};
use crate::convert::tip_load;
use crate::error_estimate::{ESTIMATOR, interrupted_or};
use crate::errors::to_py;
use crate::interrupt::interruptible;
use crate::stress;
use crate::strict::{self, Real};
use crate::warnings::{sig, warn_inaccurate, warn_unestimated, warn_unstable, warn_values};
use flexure::estimate;
use flexure::{
    Error, Kinematics, Level, StaticsData, TipConstraint, TipLoad, buckling_load as buckling, deflect as solve,
    update_kinematics,
};
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The stiffness $K = \nabla\nabla U - F_x\nabla\nabla x - F_y\nabla\nabla y$
/// (Eq. 32) at `alpha`, the library's ([`flexure::statics::loaded_stiffness`]),
/// with the kinematics there (Hessian level), which callers also read.
pub fn loaded_stiffness(
    f: &flexure::Flexure,
    alpha: &[f64],
    load: &TipLoad,
) -> (Kinematics<f64>, nalgebra::DMatrix<f64>) {
    let mut k = Kinematics::new(f);
    update_kinematics(f, alpha, &mut k, Level::Hessian);
    let stiffness = flexure::statics::loaded_stiffness(f, &k, load);
    (k, stiffness)
}

/// `Flexure.deflect`: the equilibrium under the tip load (moment, fx, fy), warned about
/// as its docstring says; with `order="auto"`, also the flexure used (which
/// `Flexure.deflect` returns beside alpha).
pub fn deflect<'py>(
    py: Python<'py>,
    (f, yield_strength): (&flexure::Flexure, Option<f64>),
    (moment, fx, fy): (Real, Real, Real),
    accuracy: Option<&Bound<'py, PyAny>>,
    order: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Option<flexure::Flexure>, Bound<'py, PyArray1<f64>>)> {
    let load = tip_load(moment, fx, fy)?;
    let target = crate::accuracy::accuracy(accuracy)?;
    let auto = auto_order(order)?;
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
                    flexure::flexure::MAX_ORDER,
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
        if let Some(s) = yield_strength {
            stress::safety_factor(py, &used, &alpha, s, "deflect", 1)?;
        }
        strict::finite_slice("deflect", &alpha)?;
        return Ok((Some(used), PyArray1::from_vec(py, alpha)));
    }
    let (alpha, stable, estimated) = interruptible(py, || {
        let mut data = StaticsData::new(f);
        let eq = solve(f, &load, &mut data, &Default::default())?;
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
            warn_inaccurate(py, "deflect", f.length(), &e, &target, hint, 1)?
        }
        Ok(_) => {}
        Err(why) => warn_unestimated(py, "deflect", &why, 1)?,
    }
    if let Some(s) = yield_strength {
        stress::safety_factor(py, f, &alpha, s, "deflect", 1)?;
    }
    strict::finite_slice("deflect", &alpha)?;
    Ok((None, PyArray1::from_vec(py, alpha)))
}

/// `Flexure.buckling_load`: the critical load under tip constraint `tip`, warned about
/// when its estimate misses `accuracy`.
pub fn buckling_load(
    py: Python<'_>,
    f: &flexure::Flexure,
    tip: &str,
    accuracy: Option<&Bound<'_, PyAny>>,
) -> PyResult<f64> {
    let t: TipConstraint = tip.parse().map_err(to_py)?;
    let target = eigen_accuracy(accuracy)?;
    let b = buckling(f, t).map_err(to_py)?;
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
