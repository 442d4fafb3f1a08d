//! One shot of Eq. 3 from the clamped root.

use crate::error::Result;
use crate::flexure::Flexure;
use crate::ode::{Tolerance, integrate_through};
use crate::scalar::Scalar;

/// Integrates Eq. 3 from the clamped root, $\phi(0) = x(0) = y(0) = 0$, with
/// $\phi^{\prime} = \omega_0(s) + (M_0 - F_y x + F_x y)/EI(s)$: the internal moment of a
/// beam carrying tip force $(F_x, F_y)$ and root moment $M_0$.
/// Returns $(\phi, x, y)$ at $s = L$; `observe` sees every accepted step
/// (the integration restarts at the section's breakpoints).
pub fn shoot<T: Scalar>(
    flexure: &Flexure,
    root_moment: T,
    fx: T,
    fy: T,
    tol: &Tolerance,
    observe: impl FnMut(f64, &[T; 3]),
) -> Result<[T; 3]> {
    let (l, stops) = (flexure.length(), crate::reference::stops(flexure));
    integrate_through(rhs(flexure, root_moment, fx, fy), 0.0, l, &stops, [T::zero(); 3], tol, &mut 0.0, observe)
}

/// The right-hand side of Eq. 3 for [`shoot`].
fn rhs<T: Scalar>(flexure: &Flexure, root_moment: T, fx: T, fy: T) -> impl FnMut(f64, &[T; 3]) -> [T; 3] {
    let kappa = flexure.rest();
    move |s: f64, y: &[T; 3]| {
        let (sn, cs) = y[0].sin_cos();
        let ei = T::c(flexure.ei_at(s));
        [T::c(flexure.curvature(kappa, s)) + (root_moment - fy * y[1] + fx * y[2]) / ei, cs, sn]
    }
}
