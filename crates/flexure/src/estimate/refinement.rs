//! The reference model an answer is estimated against: the answer's flexure
//! refined in order and quadrature ([`reference()`]), or, for eigenvalue
//! answers at the order cap, coarsened to order 32 ([`eigen_reference`]).

use crate::error::{Error, Result};
use crate::flexure::{Basis, Flexure, MAX_ORDER};
use crate::quadrature::MAX_POINTS;

/// A bound on the total turning $\int_0^1|\partial_t\phi|\thinspace dt$
/// (rad) of the shape `alpha`: $\sum_i|\alpha_i|$, since
/// $\partial_t\psi_i = \tilde P_{i-1}$ and $|\tilde P_{i-1}| \le 1$ on
/// $[0, 1]$ (exact for an arc). It only sizes the reference's quadrature,
/// where an overestimate costs a few points and an underestimate accuracy.
pub fn turning(alpha: &[f64]) -> f64 {
    alpha.iter().map(|a| a.abs()).sum()
}

/// The reference model for an answer `alpha` of `flexure` (see the module docs).
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
/// // A circle turned by 20 rad needs many more points than the model's 5.
/// let r = flexure::estimate::reference(&f, &[20.0, 0.0, 0.0]).unwrap();
/// assert_eq!((r.order(), r.quadrature_points()), (6, 32));
/// ```
pub fn reference(flexure: &Flexure, alpha: &[f64]) -> Result<Flexure> {
    let (order, points) = reference_size(flexure, alpha)?;
    refined(flexure, order, points)
}

/// The (order, quadrature points) of [`reference()`] for `alpha`.
pub(super) fn reference_size(flexure: &Flexure, alpha: &[f64]) -> Result<(usize, usize)> {
    legendre(flexure)?;
    let n = flexure.order();
    let order = (2 * n).max(n + 3).min(MAX_ORDER);
    let v = turning(alpha);
    let points = (order as f64 + 6.0 + v.ceil()).min(MAX_POINTS as f64) as usize;
    Ok((order, points))
}

pub(super) fn legendre(flexure: &Flexure) -> Result<()> {
    if flexure.basis() != Basis::Legendre {
        return Err(Error::invalid("basis", "segments", "error estimates are made for the Legendre model"));
    }
    Ok(())
}

/// `flexure` at another order and quadrature, its rest shape padded with zeros.
pub(super) fn refined(flexure: &Flexure, order: usize, points: usize) -> Result<Flexure> {
    let mut kappa = flexure.rest().to_vec();
    kappa.resize(order, 0.0);
    Flexure::with_points(flexure.length(), flexure.ei(), order, points)?
        .with_rest(&kappa)?
        .with_section(flexure.section().clone())
}

/// The reference model for an eigenvalue answer of `flexure` about the
/// shape `alpha`: [`reference()`] (order $\min(\max(2N, N + 3), 64)$), except
/// at the cap $N = 64$, where more points alone would change a straight
/// flexure's answer by nothing and report a false 0: there it is order 32
/// (with the same rule for its points), whose change overstates the
/// order-64 answer's error.
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 64).unwrap();
/// let r = flexure::estimate::eigen_reference(&f, &[0.0; 64]).unwrap();
/// assert_eq!(r.order(), 32);
/// ```
pub fn eigen_reference(flexure: &Flexure, alpha: &[f64]) -> Result<Flexure> {
    if flexure.order() < MAX_ORDER {
        return reference(flexure, alpha);
    }
    if flexure.basis() != Basis::Legendre {
        return Err(Error::invalid("basis", "segments", "error estimates are made for the Legendre model"));
    }
    let order = MAX_ORDER / 2;
    let points = (order as f64 + 6.0 + turning(alpha).ceil()).min(MAX_POINTS as f64) as usize;
    let mut kappa = flexure.rest().to_vec();
    kappa.truncate(order);
    Flexure::with_points(flexure.length(), flexure.ei(), order, points)?
        .with_rest(&kappa)?
        .with_section(flexure.section().clone())
}
