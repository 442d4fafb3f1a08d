//! The rest compliance of the rod by the linearized rod.

use super::Rod;
use super::shot::{P, STATE, rhs, rotation};
use crate::error::Result;
use crate::ode::{Tolerance, integrate_through};
use nalgebra::{Matrix3, Matrix6, Vector3};

/// The compliance of the unloaded rod's tip, $6\times6$ in the order
/// $(r_x, r_y, r_z, x, y, z)$ against the wrench $(M_x, M_y, M_z, F_x, F_y, F_z)$,
/// all in the root frame: the tip's small rotation (a rotation vector) and
/// displacement per unit tip wrench.
///
/// The variational equations at zero load: with the rest shape $R_0(s)$,
/// $p_0(s)$, a tip wrench $(\delta M, \delta F)$ makes the moment
/// $\delta m = \delta M + r\times\delta F$ with $r = p_0(L) - p_0(s)$, the
/// sections turn by $\delta\theta^{\prime} = R_0 K^{-1}R_0^T\delta m$ and move by
/// $\delta p^{\prime} = \delta\theta\times R_0 e_1$, and integrating by parts,
/// $$C = \int_0^L A^T R_0 K^{-1} R_0^T A\thinspace ds, \qquad A = \begin{bmatrix} I & \lbrack r\rbrack_\times\end{bmatrix},$$
/// symmetric and positive semi-definite (an inextensible rod does not
/// stretch: $C$ is singular along the tip tangent's force). Integrated by the
/// rod's own integrator to `tol` across the section's breakpoints, after a
/// first pass for $p_0(L)$.
///
/// # Example
/// ```
/// use flexure::reference::rod::{Rod, compliance_rest};
/// use flexure::section::SpatialSection;
/// // The straight cantilever: L³/3EI_z of y under F_y, L²/2EI_z coupling it to r_z.
/// let rod = Rod::new(2.0, SpatialSection::uniform(0.5, 3.0, 1.5).unwrap()).unwrap();
/// let c = compliance_rest(&rod, &Default::default()).unwrap();
/// assert!((c[(4, 4)] - 8.0 / 4.5).abs() < 1e-10 && (c[(2, 4)] - 4.0 / 3.0).abs() < 1e-10);
/// assert!((c[(0, 0)] - 4.0).abs() < 1e-10);
/// ```
pub fn compliance_rest(rod: &Rod, tol: &Tolerance) -> Result<Matrix6<f64>> {
    tol.validate()?;
    let l = rod.length;
    let stops: Vec<f64> = rod.section.breakpoints().iter().map(|t| t * l).collect();
    let mut start = [0.0; STATE];
    start[0] = 1.0;
    let field = rhs(rod, 1.0, [0.0; 3]);
    let end = integrate_through(&field, 0.0, l, &stops, start, tol, &mut 0.0, |_, _| {})?;
    let tip = Vector3::new(end[P], end[P + 1], end[P + 2]) * l;
    // The rest state and the 21 entries of the integrand's upper triangle.
    let mut y0 = [0.0; STATE + 21];
    y0[0] = 1.0;
    let integrand = |s: f64, y: &[f64; STATE + 21]| {
        let mut d = [0.0; STATE + 21];
        let mut state = [0.0; STATE];
        state.copy_from_slice(&y[..STATE]);
        d[..STATE].copy_from_slice(&field(s, &state));
        let r = rotation(&y[..4]);
        let r = Matrix3::from_fn(|i, j| r[i][j]);
        let k = rod.section.stiffness(s / l);
        let g = r * Matrix3::from_diagonal(&Vector3::new(1.0 / k[0], 1.0 / k[1], 1.0 / k[2])) * r.transpose();
        let arm = tip - Vector3::new(y[P], y[P + 1], y[P + 2]) * l;
        let mut a = nalgebra::Matrix3x6::zeros();
        a.fixed_view_mut::<3, 3>(0, 0).copy_from(&Matrix3::identity());
        a.fixed_view_mut::<3, 3>(0, 3).copy_from(&arm.cross_matrix());
        let c = a.transpose() * g * a;
        let mut idx = STATE;
        for i in 0..6 {
            for j in i..6 {
                d[idx] = c[(i, j)];
                idx += 1;
            }
        }
        d
    };
    let y = integrate_through(integrand, 0.0, l, &stops, y0, tol, &mut 0.0, |_, _| {})?;
    let mut c = Matrix6::zeros();
    let mut idx = STATE;
    for i in 0..6 {
        for j in i..6 {
            (c[(i, j)], c[(j, i)]) = (y[idx], y[idx]);
            idx += 1;
        }
    }
    Ok(c)
}
