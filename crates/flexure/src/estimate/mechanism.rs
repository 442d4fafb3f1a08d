//! Error estimates of a mechanism's eigenvalue answers, its buckling load
//! factor ([`buckle_error`], [`buckle_auto`]) and natural frequencies
//! ([`mechanism_modes_error`], [`mechanism_modes_auto`]): the same analysis
//! of the reference mechanism, every flexure joint refined.

use super::accuracy::Accuracy;
use super::eigen::reference_values;
use super::refinement::{eigen_reference, refined};
use super::value::ValueEstimate;
use crate::dynamics::{self, Modes};
use crate::error::Result;
use crate::flexure::MAX_ORDER;
use crate::mechanism::{
    self, Mechanism, buckling::Buckling as MechanismBuckling, statics::Settings as MechanismSettings,
};

/// The reference mechanism: every flexure joint replaced by its
/// [`eigen_reference`] about its coordinates in `q` (the rest shape when
/// `q` is not the mechanism's), with their (order, quadrature).
fn mechanism_reference(m: &Mechanism, q: &[f64]) -> Result<(Mechanism, Vec<(usize, usize)>)> {
    let rest;
    let q = if q.len() == m.dof() {
        q
    } else {
        rest = m.rest();
        &rest
    };
    let mut orders = Vec::new();
    let reference = m.with_flexures(|j, f| {
        let o = m.joints[j].offset;
        let r = eigen_reference(f, &q[o..o + f.order()])?;
        orders.push((r.order(), r.quadrature_points()));
        Ok(Some(r))
    })?;
    Ok((reference, orders))
}

/// The next mechanism of an automatic order: each flexure joint of
/// `order = "auto"` below the cap at its reference's (order, quadrature)
/// from `orders`; `None` when no joint can be raised.
fn raised(m: &Mechanism, orders: &[(usize, usize)]) -> Result<Option<Mechanism>> {
    let (mut k, mut any) = (0, false);
    let next = m.with_flexures(|j, f| {
        let (order, points) = orders[k];
        k += 1;
        if !m.joints[j].auto_order || f.order() >= MAX_ORDER {
            return Ok(None);
        }
        any = true;
        refined(f, order.max(f.order() + 1).min(MAX_ORDER), points).map(Some)
    })?;
    Ok(any.then_some(next))
}

/// The error of a mechanism's [`mechanism::buckling::buckle`] answer `b`:
/// the load factor of the reference mechanism, every flexure refined.
///
/// # Example
/// ```
/// use flexure::{estimate, mechanism::{buckling::buckle, file::from_toml, statics::Settings}};
/// // A flexure column pushed along itself by 1 N: free-tip Euler load π²EI/(4L²) = 2.4674.
/// let m = from_toml(
///     "[[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\n\
///      [[force]]\nbody = \"tip\"\nat = [0.0, 0.0]\nforce = [-1.0, 0.0]\n",
/// )
/// .unwrap();
/// let b = buckle(&m, &Settings::default()).unwrap();
/// let e = estimate::buckle_error(&m, &b, &Settings::default(), &Default::default()).unwrap();
/// assert!((e.reference[0] / 2.4674 - 1.0).abs() < 1e-4 && e.reference_orders == vec![(6, 12)]);
/// ```
pub fn buckle_error(
    m: &Mechanism,
    b: &MechanismBuckling,
    settings: &MechanismSettings,
    target: &Accuracy,
) -> Result<ValueEstimate> {
    target.validate()?;
    let (reference, orders) = mechanism_reference(m, &[])?;
    let exact = mechanism::buckling::buckle(&reference, settings)?.load_factor;
    Ok(ValueEstimate::new(&[b.load_factor], vec![exact], true, orders, target))
}

/// [`mechanism::buckling::buckle`] with its estimate, the flexure joints of
/// `order = "auto"` raised (each to its reference's order and quadrature)
/// until the estimate meets `target`, or none can be raised further (then
/// `flagged`). Returns the mechanism used, the answer and its estimate;
/// without such joints, the mechanism as given.
pub fn buckle_auto(
    m: &Mechanism,
    settings: &MechanismSettings,
    target: &Accuracy,
) -> Result<(Mechanism, MechanismBuckling, ValueEstimate)> {
    let mut m = m.clone();
    loop {
        let b = mechanism::buckling::buckle(&m, settings)?;
        let e = buckle_error(&m, &b, settings, target)?;
        if !e.flagged {
            return Ok((m, b, e));
        }
        match raised(&m, &e.reference_orders)? {
            Some(next) => m = next,
            None => return Ok((m, b, e)),
        }
    }
}

/// The error of a mechanism's [`dynamics::mechanism::modes`] answer: the
/// same analysis of the reference mechanism (every flexure refined about
/// its coordinates at the equilibrium), frequencies paired by rank.
pub fn mechanism_modes_error(
    m: &Mechanism,
    modes: &Modes,
    settings: &MechanismSettings,
    target: &Accuracy,
) -> Result<ValueEstimate> {
    target.validate()?;
    let (reference, orders) = mechanism_reference(m, &modes.coordinates)?;
    let count = modes.omega.len().max(1).min(reference.dof().max(1));
    let (omega, stable) = reference_values(dynamics::mechanism::modes(&reference, settings, count))?;
    Ok(ValueEstimate::new(&modes.omega, omega, stable, orders, target))
}

/// [`dynamics::mechanism::modes`] with its estimate, the flexure joints of
/// `order = "auto"` raised as in [`buckle_auto`].
pub fn mechanism_modes_auto(
    m: &Mechanism,
    settings: &MechanismSettings,
    count: usize,
    target: &Accuracy,
) -> Result<(Mechanism, Modes, ValueEstimate)> {
    let mut m = m.clone();
    loop {
        let modes = dynamics::mechanism::modes(&m, settings, count)?;
        let e = mechanism_modes_error(&m, &modes, settings, target)?;
        if !e.flagged {
            return Ok((m, modes, e));
        }
        match raised(&m, &e.reference_orders)? {
            Some(next) => m = next,
            None => return Ok((m, modes, e)),
        }
    }
}
