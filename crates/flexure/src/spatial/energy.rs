//! The spatial flexure's elastic energy and its gradient.

use super::SpatialFlexure;
use crate::scalar::Scalar;

/// $U(\alpha) = \frac12(\alpha-\kappa)^TK(\alpha-\kappa)$ (J), the energy
/// $\frac12\int_0^L(GJ\tau^2 + EI_y\kappa_y^2 + EI_z\kappa_z^2)\thinspace ds$ about the
/// rest shape; for a uniform section
/// $\sum_c\frac{k_c}{2L}\sum_i\frac{(\alpha_{c,i}-\kappa_{c,i})^2}{2i+1}$ (Eq. 9 per component).
///
/// # Panics
/// If `alpha` does not have [`SpatialFlexure::coordinates`] entries.
///
/// # Example
/// ```
/// use flexure::{section::SpatialSection, spatial::{SpatialFlexure, energy}};
/// let f = SpatialFlexure::new(2.0, SpatialSection::uniform(0.5, 2.0, 4.0).unwrap(), [1, 1, 2]).unwrap();
/// // GJ/(2L)·1 + EI_y/(2L)·1 + EI_z/(2L)·(1 + 1/3)
/// let u = energy(&f, &[1.0, 1.0, 1.0, 1.0]);
/// assert!((u - (0.125 + 0.5 + 1.0 * (1.0 + 1.0 / 3.0))).abs() < 1e-15);
/// ```
pub fn energy<T: Scalar>(flexure: &SpatialFlexure, alpha: &[T]) -> T {
    assert_eq!(alpha.len(), flexure.coordinates(), "alpha must have one entry per coordinate");
    let mut u = T::zero();
    for (i, (&a, &k)) in alpha.iter().zip(flexure.rest()).enumerate() {
        u += (a - T::c(k)) * gradient_entry(flexure, alpha, i);
    }
    u * T::c(0.5)
}

/// $\nabla U = K(\alpha-\kappa)$ (J/rad), written into `out`.
///
/// # Panics
/// If `alpha` or `out` does not have [`SpatialFlexure::coordinates`] entries.
///
/// # Example
/// ```
/// use flexure::{section::SpatialSection, spatial::{SpatialFlexure, energy_gradient}};
/// let f = SpatialFlexure::new(2.0, SpatialSection::uniform(0.5, 2.0, 4.0).unwrap(), [1, 1, 2]).unwrap();
/// let mut g = [0.0; 4];
/// energy_gradient(&f, &[1.0, 1.0, 1.0, 1.0], &mut g);
/// assert!((g[0] - 0.25).abs() < 1e-15 && (g[3] - 2.0 / 3.0).abs() < 1e-15);
/// ```
pub fn energy_gradient<T: Scalar>(flexure: &SpatialFlexure, alpha: &[T], out: &mut [T]) {
    assert_eq!(alpha.len(), flexure.coordinates(), "alpha must have one entry per coordinate");
    assert_eq!(out.len(), flexure.coordinates(), "out must have one entry per coordinate");
    for (i, o) in out.iter_mut().enumerate() {
        *o = gradient_entry(flexure, alpha, i);
    }
}

/// Row $i$ of $K(\alpha-\kappa)$, skipping the block-diagonal zeros.
fn gradient_entry<T: Scalar>(flexure: &SpatialFlexure, alpha: &[T], i: usize) -> T {
    crate::energy::offset_row(flexure.stiffness_matrix(), flexure.rest(), alpha, i)
}
