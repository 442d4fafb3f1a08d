//! The compliance ODE of a curved beam (paper Eq. 34).

use crate::error::Result;
use crate::flexure::Flexure;
use crate::ode::{Tolerance, integrate_through};
use nalgebra::Matrix3;

/// Exact tip compliance of the continuous beam with rest curvature
/// $\omega_0(s) = \hat\omega(\kappa, s)$: integrates
/// $\frac{dC}{ds} = AC + CA^T + B$, $C(0) = 0$ (Eq. 34) with
/// $A = \begin{bmatrix}0&0&0\cr -\sin\phi&0&0\cr \cos\phi&0&0\end{bmatrix}$,
/// $B = \mathrm{diag}(1/EI(s), 0, 0)$, $\phi^{\prime} = \omega_0$, to `tol`,
/// restarting at the section's breakpoints (where $EI(s)$ has a kink).
/// Order $(\phi, x, y)$ as in Eq. 33.
///
/// # Example
/// ```
/// // Straight cantilever: C_yy = L³/3EI.
/// let f = flexure::Flexure::new(2.0, 4.0, 3).unwrap();
/// let c = flexure::reference::compliance::compliance_tip(&f, &Default::default()).unwrap();
/// assert!((c[(2, 2)] - 8.0 / 12.0).abs() < 1e-12);
/// ```
pub fn compliance_tip(flexure: &Flexure, tol: &Tolerance) -> Result<Matrix3<f64>> {
    let (l, kappa) = (flexure.length(), flexure.rest());
    let stops: Vec<f64> = flexure.section().breakpoints(l).iter().map(|t| t * l).collect();
    // State: φ, C00, C01, C02, C11, C12, C22.
    let rhs = |s: f64, y: &[f64; 7]| {
        let (sn, cs) = y[0].sin_cos();
        [
            flexure.curvature(kappa, s),
            1.0 / flexure.ei_at(s),
            -sn * y[1],
            cs * y[1],
            -2.0 * sn * y[2],
            -sn * y[3] + cs * y[2],
            2.0 * cs * y[3],
        ]
    };
    let y = integrate_through(rhs, 0.0, l, &stops, [0.0; 7], tol, &mut 0.0, |_, _| {})?;
    Ok(Matrix3::new(y[1], y[2], y[3], y[2], y[4], y[5], y[3], y[5], y[6]))
}
