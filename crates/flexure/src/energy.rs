//! Bending energy, its gradient and Hessian (paper Eqs. 9, 18, 28).
//!
//! The energy of Eq. 5 is the quadratic form $U = \frac12(\alpha-\kappa)^TK(\alpha-\kappa)$
//! with the flexure's stiffness matrix $K$ ([`Flexure::stiffness_matrix`]),
//! integrated once when the flexure is built. The shifted-Legendre basis is
//! $L^2$-orthogonal on $[0, L]$, so for a uniform section $K$ is diagonal.

use crate::flexure::Flexure;
use crate::flexure::assert_coordinates;
use crate::scalar::Scalar;

/// $U(\alpha) = \frac12(\alpha-\kappa)^TK(\alpha-\kappa)$, in joules; for a uniform
/// section $\frac{EI}{2L}\sum_{i} \frac{(\alpha_i - \kappa_i)^2}{2i-1}$ (Eq. 9, any order).
///
/// # Panics
/// If `alpha` does not have [`Flexure::order`] entries (never truncates;
/// validate user input with [`Flexure::check_coordinates`]).
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(2.0, 3.0, 3).unwrap();
/// // Eq. 9: EI/(2L)·(1 + 4/3 + 9/5)
/// let u = flexure::energy(&f, &[1.0, 2.0, 3.0]);
/// assert!((u - 0.75 * (1.0 + 4.0 / 3.0 + 9.0 / 5.0)).abs() < 1e-14);
/// ```
pub fn energy<T: Scalar>(flexure: &Flexure, alpha: &[T]) -> T {
    assert_coordinates(flexure, "alpha", alpha.len());
    let mut u = T::zero();
    for (i, (&a, &k)) in alpha.iter().zip(flexure.rest()).enumerate() {
        u += (a - T::c(k)) * energy_gradient_entry(flexure, alpha, i);
    }
    u * T::c(0.5)
}

/// $\nabla U = K(\alpha-\kappa)$; for a uniform section
/// $\partial U/\partial\alpha_i = \frac{EI}{L}\frac{\alpha_i - \kappa_i}{2i-1}$ (Eq. 18); written into `out`.
///
/// # Panics
/// If `alpha` or `out` does not have [`Flexure::order`] entries (never
/// truncates; validate user input with [`Flexure::check_coordinates`]).
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(2.0, 3.0, 2).unwrap();
/// let mut g = [0.0; 2];
/// flexure::energy_gradient(&f, &[1.0, 2.0], &mut g);
/// // Eq. 18: EI/L·(1, 2/3).
/// assert!((g[0] - 1.5).abs() < 1e-15 && (g[1] - 1.0).abs() < 1e-15);
/// ```
pub fn energy_gradient<T: Scalar>(flexure: &Flexure, alpha: &[T], out: &mut [T]) {
    assert_coordinates(flexure, "alpha", alpha.len());
    assert_coordinates(flexure, "out", out.len());
    for (i, o) in out.iter_mut().enumerate() {
        *o = energy_gradient_entry(flexure, alpha, i);
    }
}

/// Entry $i$ (0-based) of [`energy_gradient`], for callers that add it to
/// a gradient of their own without a scratch buffer.
#[inline]
pub fn energy_gradient_entry<T: Scalar>(flexure: &Flexure, alpha: &[T], i: usize) -> T {
    offset_row(flexure.stiffness_matrix(), flexure.rest(), alpha, i)
}

/// Row $i$ of $K(\alpha-\kappa)$ for the row-major $n\times n$ `stiffness`
/// and the rest `rest`, skipping zeros (the spatial flexure's blocks).
#[inline]
pub(crate) fn offset_row<T: Scalar>(stiffness: &[f64], rest: &[f64], alpha: &[T], i: usize) -> T {
    let n = alpha.len();
    let row = &stiffness[i * n..(i + 1) * n];
    let mut g = T::zero();
    for ((&k, &a), &r) in row.iter().zip(alpha).zip(rest) {
        if k != 0.0 {
            g += T::c(k) * (a - T::c(r));
        }
    }
    g
}

/// Entry $(i, j)$ (0-based) of the constant energy Hessian $K$; for a
/// uniform section $\frac{EI}{L}\frac{\delta_{ij}}{2i+1}$ (Eq. 28 as corrected by the
/// errata: $1, 1/3, 1/5, \dots$).
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
/// assert_eq!(flexure::energy::stiffness(&f, 1, 1), 1.0 / 3.0);
/// assert_eq!(flexure::energy::stiffness(&f, 0, 1), 0.0);
/// ```
#[inline]
pub fn stiffness(flexure: &Flexure, i: usize, j: usize) -> f64 {
    flexure.stiffness_matrix()[i * flexure.order() + j]
}
