//! Stiffness and compliance of a mechanism at an equilibrium.

use super::Solution;
use super::kkt::constrained;
use crate::error::{Error, Result};
use crate::linalg;
use crate::mechanism::Mechanism;
use crate::mechanism::kinematics::{Frames, frames, point};
use crate::mechanism::lagrangian::lagrangian;
use nalgebra::{DMatrix, Matrix3};

/// Frames of the solution.
pub fn body_frames(m: &Mechanism, s: &Solution) -> Frames {
    frames(m, &s.q)
}

/// $Z$ and the generalized stiffness on the admissible motions,
/// $Z^T\nabla^2 L\thinspace Z$ (Eq. 27, projected), at a solution.
pub fn stiffness(m: &Mechanism, s: &Solution) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    let a = lagrangian(m, &s.q, &s.multipliers, &s.loads)?;
    let z = linalg::null_space(&a.closure_jacobian);
    let k = constrained(&a.hessian, &z);
    Ok((z, k))
}

/// Compliance of the frame at `at` on `body` to a small extra load
/// $(M, F_x, F_y)$ there: $C = J Z (Z^T\nabla^2 L Z)^{-1} Z^T J^T$, order $(\phi, x, y)$.
///
/// # Example
/// ```
/// use flexure::mechanism::{file::from_toml, statics::{assemble_unloaded, compliance, Settings}};
/// // A sprung arm (k = 2 N·m/rad): its tip, 0.1 m out, yields l²/k sideways.
/// let m = from_toml("[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n").unwrap();
/// let s = assemble_unloaded(&m, &Settings::default()).unwrap();
/// let c = compliance(&m, &s, m.body("arm").unwrap(), [0.1, 0.0].into()).unwrap();
/// assert!((c[(0, 0)] - 0.5).abs() < 1e-15 && (c[(2, 2)] - 0.005).abs() < 1e-15);
/// ```
pub fn compliance(m: &Mechanism, s: &Solution, body: usize, at: nalgebra::Point2<f64>) -> Result<Matrix3<f64>> {
    if body >= m.bodies.len() {
        return Err(Error::invalid("body", body, "names no body of the mechanism"));
    }
    if !at.iter().all(|v| v.is_finite()) {
        return Err(Error::invalid("at", format!("{at:?}"), "must be finite"));
    }
    let (z, k) = stiffness(m, s)?;
    let not_definite = || Error::Singular {
        what: "the constrained stiffness is not positive definite: the equilibrium is unstable or a joint is free"
            .into(),
    };
    if !linalg::is_positive_definite(&k) {
        return Err(not_definite());
    }
    let chol = k.cholesky().ok_or_else(not_definite)?;
    let jz = point(m, &frames(m, &s.q), body, at, false).jacobian * &z;
    let c = &jz * chol.solve(&jz.transpose());
    let c = Matrix3::from_fn(|i, j| c[(i, j)]);
    if c.iter().all(|v| v.is_finite()) {
        Ok(c)
    } else {
        Err(Error::Singular { what: "the compliance is not finite".into() })
    }
}
