//! Small-load tip compliance (paper Eqs. 33–36).

use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::kinematics::{self, Kinematics, Level};
use nalgebra::{DMatrix, Matrix3};

/// Tip compliance at the rest shape, $C = \mathcal J(\kappa) K^{-1} \mathcal J(\kappa)^T$
/// with $K = \nabla\nabla U$ (Eqs. 35–36).
///
/// Rows and columns are in the order $(\phi, x, y)$; $C$ maps the tip load
/// $(M, F_x, F_y)$ to the tip displacement $(\Delta\phi, \Delta x, \Delta y)$ (Eq. 33).
///
/// # Example
/// ```
/// // Straight cantilever: C_φφ = L/EI, C_φy = L²/2EI, C_yy = L³/3EI (exactly, by Eq. 36).
/// let f = flexure::Flexure::new(2.0, 4.0, 3).unwrap();
/// let c = flexure::compliance_tip_rest(&f);
/// assert!((c[(0, 0)] - 0.5).abs() < 1e-14 && (c[(0, 2)] - 0.5).abs() < 1e-14);
/// assert!((c[(2, 2)] - 8.0 / 12.0).abs() < 1e-14 && c[(1, 1)].abs() < 1e-14);
/// ```
pub fn compliance_tip_rest(flexure: &Flexure) -> Matrix3<f64> {
    let mut k = Kinematics::new(flexure);
    kinematics::update(flexure, flexure.rest(), &mut k, Level::Jacobian);
    let n = flexure.order();
    let stiffness = DMatrix::from_row_slice(n, n, flexure.stiffness_matrix());
    // K is positive definite by construction (EI > 0 everywhere, independent shapes).
    let kinv_jt = match stiffness.cholesky() {
        Some(chol) => chol.solve(&k.jacobian_root_tip.transpose()),
        None => unreachable!("a flexure's stiffness matrix is positive definite"),
    };
    Matrix3::from_iterator((&k.jacobian_root_tip * kinv_jt).iter().copied())
}

/// Tip compliance at any configuration, $C = \mathcal J K^{-1}\mathcal J^T$,
/// for the Jacobian in `kinematics` and a generalized stiffness such as
/// [`crate::StaticsData::stiffness`] or [`crate::statics::loaded_stiffness`]
/// (Eq. 32): the response to a small extra load
/// about a loaded equilibrium.
///
/// Fails when $K$ is not positive definite (the equilibrium is unstable).
///
/// # Panics
/// If `stiffness` is not $N \times N$ for the $N$ coordinates of the
/// Jacobian in `kinematics` (never truncates).
pub fn compliance_tip(kinematics: &Kinematics<f64>, stiffness: &DMatrix<f64>) -> Result<Matrix3<f64>> {
    let n = kinematics.jacobian_root_tip.ncols();
    let (rows, cols) = stiffness.shape();
    assert!(
        rows == n && cols == n,
        "stiffness must be {n} x {n} (one row and column per coordinate), got {rows} x {cols}"
    );
    let chol = stiffness.clone().cholesky().ok_or_else(|| Error::Singular {
        what:
            "the generalized stiffness is not positive definite: the equilibrium is unstable, so it has no compliance"
                .into(),
    })?;
    let j = &kinematics.jacobian_root_tip;
    let kinv_jt = chol.solve(&j.transpose());
    Ok(Matrix3::from_iterator((j * kinv_jt).iter().copied()))
}
