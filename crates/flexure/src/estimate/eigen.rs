//! Error estimates of one flexure's eigenvalue answers, its buckling load
//! ([`buckling_error`], [`buckling_auto`]) and natural frequencies
//! ([`modes_error`], [`modes_auto`]), against [`eigen_reference`].

use super::accuracy::Accuracy;
use super::auto::raise;
use super::refinement::{eigen_reference, refined};
use super::value::ValueEstimate;
use crate::buckling::{CriticalLoad, TipConstraint, buckling_load};
use crate::dynamics::{self, Body, Modes};
use crate::error::{Error, Result};
use crate::flexure::{Flexure, MAX_ORDER};
use crate::statics::TipLoad;

/// The error of a [`crate::buckling_load`] answer `b` of `flexure` under
/// `tip`: the same load of the reference model about the rest shape.
///
/// # Example
/// ```
/// use flexure::{buckling_load, estimate, Flexure, TipConstraint};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let b = buckling_load(&f, TipConstraint::Clamped).unwrap();
/// let e = estimate::buckling_error(&f, TipConstraint::Clamped, &b, &Default::default()).unwrap();
/// // Order 3 says 42 EI/L², Euler 4π² = 39.48: 6.4 % high, and the estimate sees it.
/// let truth = b.critical_load / (4.0 * std::f64::consts::PI.powi(2)) - 1.0;
/// assert!(e.flagged && (e.relative[0].unwrap() / truth - 1.0).abs() < 0.01);
/// ```
pub fn buckling_error(
    flexure: &Flexure,
    tip: TipConstraint,
    b: &CriticalLoad,
    target: &Accuracy,
) -> Result<ValueEstimate> {
    target.validate()?;
    let reference = eigen_reference(flexure, flexure.rest())?;
    let exact = buckling_load(&reference, tip)?.critical_load;
    let orders = vec![(reference.order(), reference.quadrature_points())];
    Ok(ValueEstimate::new(&[b.critical_load], vec![exact], true, orders, target))
}

/// The lowest order (from `flexure`'s, each step the reference's order and
/// quadrature) whose buckling load under `tip` meets `target`, with that
/// flexure, the load and its estimate. At order 64 the answer is returned
/// as it is, its estimate `flagged` if it still misses.
///
/// # Example
/// ```
/// use flexure::{estimate, Flexure, TipConstraint};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let (used, b, e) = estimate::buckling_auto(&f, TipConstraint::Clamped, &Default::default()).unwrap();
/// let euler = 4.0 * std::f64::consts::PI.powi(2);
/// assert!(!e.flagged && used.order() > 3 && (b.critical_load / euler - 1.0).abs() < 0.01);
/// ```
pub fn buckling_auto(
    flexure: &Flexure,
    tip: TipConstraint,
    target: &Accuracy,
) -> Result<(Flexure, CriticalLoad, ValueEstimate)> {
    let (f, (b, e)) = raise(flexure, |f| {
        let b = buckling_load(f, tip)?;
        let e = buckling_error(f, tip, &b, target)?;
        let next = e.reference_orders[0];
        let flagged = e.flagged;
        Ok(((b, e), flagged, next))
    })?;
    Ok((f, b, e))
}

/// The error of the frequencies `modes` of `flexure` (with the tip `body`)
/// about its equilibrium under `load` ([`dynamics::modes()`]): the same
/// analysis (equilibrium, loaded stiffness, mass) in the reference model,
/// whose frequencies are paired with the model's by rank.
///
/// # Example
/// ```
/// use flexure::{dynamics, estimate, section::{Profile, Section}, Flexure, TipLoad};
/// let section = Section::uniform(1.0).unwrap().with_mass_per_length(Profile::Constant(1.0)).unwrap();
/// let f = Flexure::new(1.0, 1.0, 3).unwrap().with_section(section).unwrap();
/// let m = dynamics::modes(&f, &TipLoad::default(), None, 3).unwrap();
/// let e = estimate::modes_error(&f, &TipLoad::default(), None, &m, &Default::default()).unwrap();
/// // The third mode of order 3 is 91 % above the beam's (βL)² = 61.70: the estimate flags it.
/// assert!(e.flagged && e.relative[2].unwrap() > 0.5);
/// ```
pub fn modes_error(
    flexure: &Flexure,
    load: &TipLoad,
    body: Option<&Body>,
    modes: &Modes,
    target: &Accuracy,
) -> Result<ValueEstimate> {
    target.validate()?;
    let rest;
    let alpha = if modes.coordinates.len() == flexure.order() {
        &modes.coordinates
    } else {
        rest = flexure.rest().to_vec();
        &rest
    };
    let reference = eigen_reference(flexure, alpha)?;
    let orders = vec![(reference.order(), reference.quadrature_points())];
    let (omega, stable) = reference_values(dynamics::modes(&reference, load, body, modes.omega.len().max(1)))?;
    Ok(ValueEstimate::new(&modes.omega, omega, stable, orders, target))
}

/// The reference's frequencies, or none (unstable) when its equilibrium is
/// not stable: then no mode can be estimated.
pub(super) fn reference_values(modes: Result<Modes>) -> Result<(Vec<f64>, bool)> {
    match modes {
        Ok(m) => Ok((m.omega, true)),
        Err(Error::Unstable { .. }) => Ok((Vec::new(), false)),
        Err(e) => Err(e),
    }
}

/// The lowest order (from `flexure`'s, raised to `count` if lower, each
/// step the reference's order and quadrature) whose lowest `count`
/// frequencies all meet `target` ([`modes_error`]), with that flexure, the
/// modes and their estimate; at order 64 returned as they are, `flagged` if
/// they still miss.
///
/// # Example
/// ```
/// use flexure::{dynamics, estimate, section::{Profile, Section}, Flexure, TipLoad};
/// let section = Section::uniform(1.0).unwrap().with_mass_per_length(Profile::Constant(1.0)).unwrap();
/// let f = Flexure::new(1.0, 1.0, 3).unwrap().with_section(section).unwrap();
/// let (used, m, e) = estimate::modes_auto(&f, &TipLoad::default(), None, 3, &Default::default()).unwrap();
/// // The cantilever's third mode: (βL)² with βL = 7.8548 (ω in rad/s for EI = m = L = 1).
/// assert!(!e.flagged && used.order() > 3 && (m.omega[2] / 7.8548f64.powi(2) - 1.0).abs() < 0.01);
/// ```
pub fn modes_auto(
    flexure: &Flexure,
    load: &TipLoad,
    body: Option<&Body>,
    count: usize,
    target: &Accuracy,
) -> Result<(Flexure, Modes, ValueEstimate)> {
    let start = if count > flexure.order() && count <= MAX_ORDER {
        refined(flexure, count, flexure.quadrature_points().max(count + 2))?
    } else {
        flexure.clone()
    };
    let (f, (m, e)) = raise(&start, |f| {
        let m = dynamics::modes(f, load, body, count)?;
        let e = modes_error(f, load, body, &m, target)?;
        let next = e.reference_orders[0];
        let flagged = e.flagged;
        Ok(((m, e), flagged, next))
    })?;
    Ok((f, m, e))
}
