//! The linear buckling pencil of a mechanism, whatever its dimension: the
//! pre-buckling closure forces and the smallest load factor of
//! $Z^T(K_0 + \lambda K_g)Z$, for [`super::buckling::buckle`] in either dimension.

use crate::buckling::normalized;
use crate::error::{Error, Result};
use crate::linalg;
use nalgebra::{DMatrix, DVector};

/// The closure forces $\delta\mu$ of the linear pre-buckling state: the
/// admissible motion $\delta q = Zy$ with $(Z^TK_0Z)y = -Z^Tf$, $f$ the
/// loads' gradient `load_gradient`, then $G^T\delta\mu = -(f + K_0\delta q)$
/// in least norm. `k0` is $Z^TK_0Z$, positive definite (else `free`).
pub(in crate::mechanism) fn pre_buckling_forces(
    k0: &DMatrix<f64>,
    z: &DMatrix<f64>,
    hessian: &DMatrix<f64>,
    load_gradient: &DVector<f64>,
    g: &DMatrix<f64>,
    free: impl Fn() -> Error,
) -> Result<DVector<f64>> {
    let y = k0.clone().cholesky().ok_or_else(&free)?.solve(&-(z.transpose() * load_gradient));
    let dq = z * y;
    let rhs = -(load_gradient + hessian * &dq);
    Ok(if g.nrows() == 0 { DVector::zeros(0) } else { linalg::least_squares(&g.transpose(), &rhs) })
}

/// The smallest $\lambda > 0$ with $\det(K + \lambda B) = 0$, `k` = $Z^TK_0Z$
/// (symmetric positive definite) and `b` = $Z^TK_gZ$, with its mode $Zv$
/// ([`normalized`]). A symmetric `b` (to 1e-12 of its size) is the
/// symmetric pencil: $\lambda = -1/\mu$ for the most negative eigenvalue
/// $\mu$ of $Bv = \mu Kv$. An unsymmetric one (a dead moment's follower
/// part) takes the smallest positive real $\lambda$ of the pencil, and may
/// have none: flutter, not buckling (Ziegler), which is an error that says
/// so. Loads that do not soften are an error with `no_softening`'s words.
pub(in crate::mechanism) fn smallest_load_factor(
    k: &DMatrix<f64>,
    b: &DMatrix<f64>,
    z: &DMatrix<f64>,
    free: impl Fn() -> Error,
    no_softening: &str,
) -> Result<(f64, Vec<f64>)> {
    let no_buckling = || Error::Singular {
        what: format!("these loads do not soften the mechanism ({no_softening}): no buckling load"),
    };
    let symmetric = (b - b.transpose()).amax() <= 1e-12 * b.amax().max(f64::MIN_POSITIVE);
    let (load_factor, reduced) = if symmetric {
        let b = (b + b.transpose()) * 0.5;
        let (mus, modes) = linalg::generalized_symmetric(k, &b).ok_or_else(&free)?;
        // det(A + λB) = 0 ⇔ λ = −1/μ for eigenvalues μ of B v = μ A v; the
        // smallest positive λ comes from the most negative μ.
        let (best, &mu) = mus
            .iter()
            .enumerate()
            .min_by(|x, y| x.1.total_cmp(y.1))
            .ok_or_else(|| Error::Singular { what: "no admissible motion to buckle".into() })?;
        if mu.is_nan() || mu >= -1e-14 * mus.amax() {
            return Err(no_buckling());
        }
        (-1.0 / mu, modes.column(best).into_owned())
    } else {
        // det(K + λB) = 0 ⇔ −1/λ is an eigenvalue of K⁻¹B.
        let a = k.clone().lu().solve(b).ok_or_else(&free)?;
        let eig = a.complex_eigenvalues();
        let top = eig.iter().map(|e| e.norm()).fold(0.0, f64::max);
        let lambda = eig
            .iter()
            .filter(|e| e.im.abs() <= 1e-9 * top && e.re < -1e-14 * top)
            .map(|e| -1.0 / e.re)
            .fold(f64::INFINITY, f64::min);
        if !lambda.is_finite() {
            return Err(Error::Singular {
                what: "no load factor makes the stiffness singular: a dead moment, whose stiffness is not symmetric, may destabilize the mechanism by flutter rather than by buckling (Ziegler), which a static analysis cannot find".into(),
            });
        }
        let pencil = k + b * lambda;
        let svd = pencil.svd(false, true);
        let v_t = svd.v_t.ok_or_else(&free)?;
        let smallest = svd.singular_values.imin();
        (lambda, v_t.row(smallest).transpose())
    };
    let mode = normalized(z * reduced);
    if !(load_factor.is_finite() && mode.iter().all(|v| v.is_finite())) {
        return Err(Error::Singular { what: "the buckling load is not finite".into() });
    }
    Ok((load_factor, mode.iter().copied().collect()))
}
