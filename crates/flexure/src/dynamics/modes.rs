//! Vibration modes of one flexure joint about its loaded equilibrium.

use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::inertia::RigidInertia;
use crate::mass::{MassData, MassModel, update};
use crate::statics::{StaticsData, TipLoad, deflect};
use nalgebra::DMatrix;

/// Directions whose mass is at most this share of the largest eigenvalue
/// of $M$ carry no inertia: rounding, not mass.
const MASSLESS: f64 = 1e-12;

/// Modes whose $1/\omega^2$ is at most this share of the lowest mode's are
/// not resolved (the eigensolver's rounding), so not reported: frequencies
/// above $10^6$ times the lowest.
const RESOLVED: f64 = 1e-12;

/// Natural frequencies and mode shapes, lowest first.
///
/// It serializes with its fields' names, `shapes` as one list of
/// amplitudes per mode.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Modes {
    /// Angular frequencies $\omega$ (rad/s), ascending.
    pub omega: Vec<f64>,
    /// Frequencies $\omega/2\pi$ (Hz).
    pub frequency: Vec<f64>,
    /// One column per mode: the coordinates' amplitudes $v$, normalized to
    /// $v^TMv = 1$, with the entry of largest magnitude positive.
    #[serde(serialize_with = "columns")]
    pub shapes: DMatrix<f64>,
    /// How many directions carry no inertia and were condensed out as
    /// quasi-static (zero for a flexure with mass).
    pub quasi_static: usize,
    /// The load fraction where the loading path to the equilibrium lost
    /// stability and snapped through to the stable state beyond, if it did
    /// (the equilibrium's `limit`); `None` from [`finite_modes`], which
    /// solves no equilibrium.
    pub limit: Option<f64>,
    /// The equilibrium's coordinates the modes are taken about (a flexure's
    /// $\alpha$, a mechanism's $q$); empty from [`finite_modes`].
    pub coordinates: Vec<f64>,
}

/// A matrix as the list of its columns (nalgebra serializes none here).
fn columns<S: serde::Serializer>(m: &DMatrix<f64>, s: S) -> std::result::Result<S::Ok, S::Error> {
    s.collect_seq(m.column_iter().map(|c| c.iter().copied().collect::<Vec<f64>>()))
}

/// The modes of `flexure` with an optional tip `body` about its equilibrium
/// under `load` ([`deflect`], from rest along the loading path): the
/// finite solutions of
///
/// $$K_t v = \omega^2 M(\alpha^\ast)v,\qquad K_t = \nabla\nabla U - F_x\nabla\nabla x - F_y\nabla\nabla y$$
///
/// (Eq. 32's loaded stiffness), so a frequency falls to zero as the load
/// reaches a buckling load. At most `count` modes are returned, fewer if
/// the model has fewer finite ones ([`finite_modes`]).
///
/// Fails with an error naming `mass` when neither the flexure (a density or
/// mass per length in its [`crate::section::Section`]) nor the body has
/// inertia, naming `count` when it is zero, and with [`Error::Unstable`]
/// when the equilibrium is not stable (its frequencies would be imaginary).
///
/// # Example
/// ```
/// use flexure::dynamics::modes;
/// use flexure::inertia::RigidInertia;
/// use flexure::{Flexure, TipLoad};
/// // A massless cantilever with a point mass: ω = √(3EI/(mL³)) exactly (the
/// // model's tip compliance is exact from order 2).
/// let f = Flexure::new(0.5, 2.0, 3).unwrap();
/// let body = RigidInertia::new(0.1, 0.0, [0.0, 0.0]).unwrap();
/// let m = modes(&f, &TipLoad::default(), Some(&body), 3).unwrap();
/// assert_eq!(m.omega.len(), 1);
/// assert!((m.omega[0] - (3.0 * 2.0 / (0.1 * 0.125f64)).sqrt()).abs() < 1e-9 * m.omega[0]);
/// ```
pub fn modes(flexure: &Flexure, load: &TipLoad, body: Option<&RigidInertia>, count: usize) -> Result<Modes> {
    if count == 0 {
        return Err(Error::invalid("count", count, "must be at least 1"));
    }
    let model = MassModel::new(flexure, body)?;
    if !model.has_inertia() {
        return Err(Error::invalid(
            "mass",
            "none",
            "the flexure has no density or mass per length and there is no tip body with mass or inertia",
        ));
    }
    let mut statics = StaticsData::new(flexure);
    let eq = deflect(flexure, load, &mut statics, &Default::default())?;
    if !eq.stable {
        return Err(Error::Unstable { what: "modes", load_fraction: eq.limit.unwrap_or(1.0) });
    }
    let mut data = MassData::new(&model);
    update(&model, statics.alpha(), None, &mut data);
    Ok(Modes {
        limit: eq.limit,
        coordinates: statics.alpha().to_vec(),
        ..finite_modes(&statics.stiffness, &data.mass_matrix, count)?
    })
}

/// The finite modes of $Kv = \omega^2Mv$ for a symmetric stiffness $K$ and a
/// symmetric positive semi-definite mass matrix $M$, lowest `count` first.
///
/// $M$ may be singular (a massless flexure carrying a body: rank at most
/// 3). Its eigenvectors split the coordinates into directions with
/// inertia, $Z$, and without, $Z_0$ (eigenvalues at most $10^{-12}$ of the
/// largest). Those without inertia follow quasi-statically and are
/// condensed out (static condensation):
///
/// $$\tilde K = Z^TKZ - Z^TKZ_0(Z_0^TKZ_0)^{-1}Z_0^TKZ,\qquad
/// \tilde K a = \omega^2 Z^TMZ\thinspace a,\qquad v = Za - Z_0(Z_0^TKZ_0)^{-1}Z_0^TKZa,$$
///
/// so they are neither reported nor turned into infinite frequencies.
///
/// The reduced problem is solved as $\tilde M a = \mu\tilde K a$, $\mu = 1/\omega^2$,
/// so the lowest frequencies keep their relative accuracy; frequencies above
/// $10^6$ times the lowest are not resolved and not reported.
///
/// Errors: `count` when zero, `stiffness` or `mass` when not square, of
/// different sizes or not finite, `mass` when $M$ is zero, [`Error::Unstable`] when $K$ (or
/// $Z_0^TKZ_0$, or $\tilde K$) is not positive definite.
///
/// # Example
/// ```
/// use nalgebra::DMatrix;
/// // Two springs in series, mass only at the end: one finite mode, ω² = k/2m.
/// let k = DMatrix::from_row_slice(2, 2, &[2.0, -1.0, -1.0, 1.0]);
/// let m = DMatrix::from_row_slice(2, 2, &[0.0, 0.0, 0.0, 3.0]);
/// let modes = flexure::dynamics::modes::finite_modes(&k, &m, 2).unwrap();
/// assert_eq!((modes.omega.len(), modes.quasi_static), (1, 1));
/// assert!((modes.omega[0] - (1.0f64 / 6.0).sqrt()).abs() < 1e-14);
/// ```
pub fn finite_modes(stiffness: &DMatrix<f64>, mass: &DMatrix<f64>, count: usize) -> Result<Modes> {
    let n = mass.nrows();
    if count == 0 {
        return Err(Error::invalid("count", count, "must be at least 1"));
    }
    for (name, a) in [("stiffness", stiffness), ("mass", mass)] {
        if a.nrows() != n || a.ncols() != n || n == 0 {
            return Err(Error::invalid(
                name,
                format!("{}x{}", a.nrows(), a.ncols()),
                "must be square, non-empty and of the same size as the other matrix",
            ));
        }
        if !a.iter().all(|x| x.is_finite()) {
            return Err(Error::invalid(name, "a matrix with non-finite entries", "must be finite"));
        }
    }
    let k = (stiffness + stiffness.transpose()) * 0.5;
    let m = (mass + mass.transpose()) * 0.5;
    let eig = nalgebra::SymmetricEigen::new(m.clone());
    let top = eig.eigenvalues.amax();
    if !(top > 0.0 && top.is_finite()) {
        return Err(Error::invalid("mass", top, "the mass matrix must not be zero (and must be finite)"));
    }
    let (with, without): (Vec<usize>, Vec<usize>) = (0..n).partition(|&i| eig.eigenvalues[i] > MASSLESS * top);
    let columns = |idx: &[usize]| DMatrix::from_fn(n, idx.len(), |r, c| eig.eigenvectors[(r, idx[c])]);
    let (z, z0) = (columns(&with), columns(&without));
    // Stiffness on the massive directions, with the massless ones condensed,
    // and the map from a massive amplitude a to the whole shape.
    let (k_reduced, to_shape) = if without.is_empty() {
        (k.clone(), DMatrix::identity(n, n))
    } else {
        let k00 = z0.transpose() * &k * &z0;
        let k0z = z0.transpose() * &k * &z;
        let chol = nalgebra::Cholesky::new(k00).ok_or(Error::Unstable { what: "modes", load_fraction: 1.0 })?;
        let follow = chol.solve(&k0z);
        (z.transpose() * &k * &z - k0z.transpose() * &follow, &z - &z0 * follow)
    };
    let m_reduced = if without.is_empty() { m.clone() } else { z.transpose() * &m * &z };
    // Reduced with K's Cholesky factor, M v = μ K v with μ = 1/ω²: the
    // eigensolver's error is a share of the largest μ, so the lowest
    // frequencies, those that matter, keep their relative accuracy (reducing
    // with M's would lose it to the stiffest coordinate's frequency).
    let (inverse_omega2, vectors) = crate::linalg::generalized_symmetric(&k_reduced, &m_reduced)
        .ok_or(Error::Unstable { what: "modes", load_fraction: 1.0 })?;
    let largest = inverse_omega2.amax();
    let mut order: Vec<usize> = (0..inverse_omega2.len()).filter(|&i| inverse_omega2[i] > RESOLVED * largest).collect();
    order.sort_by(|&a, &b| inverse_omega2[b].total_cmp(&inverse_omega2[a]));
    let take = count.min(order.len());
    let mut omega = Vec::with_capacity(take);
    let mut shapes = DMatrix::zeros(n, take);
    for (c, &i) in order.iter().take(take).enumerate() {
        omega.push(inverse_omega2[i].recip().sqrt());
        let mut v = &to_shape * vectors.column(i);
        let norm = (v.transpose() * &m * &v)[(0, 0)].sqrt();
        let big = v.iter().fold(0.0_f64, |b, x| if x.abs() > b.abs() { *x } else { b });
        v *= big.signum() / norm;
        shapes.set_column(c, &v);
    }
    let frequency = omega.iter().map(|w| w / std::f64::consts::TAU).collect();
    Ok(Modes { omega, frequency, shapes, quasi_static: without.len(), limit: None, coordinates: Vec::new() })
}
