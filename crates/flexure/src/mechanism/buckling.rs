//! Linear buckling of a mechanism about its unloaded, assembled configuration.

use super::kinematics::{Frames, frames};
use super::lagrangian::{Assembly, assemble_into};
use super::pencil::{pre_buckling_forces, smallest_load_factor};
use super::statics::parts;
use super::statics::{Settings, Statics, assemble_unloaded, constrained, free_motion};
use super::{Loads, Mechanism};
use crate::error::{Error, Result};
use crate::linalg;

/// Result of [`buckle`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Buckling {
    /// Factor on all forces, tensions and gravity at which the constrained stiffness becomes singular.
    pub load_factor: f64,
    /// Buckling mode in generalized coordinates, unit length, largest entry positive.
    pub mode: Vec<f64>,
}

/// Linear buckling: the smallest $\lambda > 0$ with
/// $\det Z^T(K_0 + \lambda K_g)Z = 0$ at the unloaded configuration, where
/// $K_0$ is the elastic stiffness, $K_g$ the loads' geometric stiffness
/// with the closure forces of the linear pre-buckling solve, and $Z$ =
/// [`linalg::null_space`]$(G)$. With redundant closures the indeterminate
/// part of the pre-buckling closure forces is the one with the least force
/// through the flexures (see [`super::statics::Solution::multipliers`]),
/// in the plane ([`Statics::settle_pre_buckling`]). A dead moment in space
/// makes $K_g$ unsymmetric (its follower part, as in lateral-torsional
/// buckling); the eigenvalues are then those of the unsymmetric pencil, and
/// the smallest positive real one is taken. Such loads may have none (a
/// cantilever under a dead end torque has no adjacent equilibrium, only
/// flutter: Ziegler's example), which is an error that says so.
///
/// # Example
/// ```
/// use flexure::mechanism::{buckling::buckle, file::from_toml, statics::Settings};
/// // A sprung arm (k = 1 N·m/rad, l = 0.1 m) pushed along itself by 2 N
/// // buckles at P = k/l = 10 N: a factor of 5.
/// let m = from_toml(
///     "[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 1.0\n\
///      [[force]]\nbody = \"arm\"\nat = [0.1, 0.0]\nforce = [-2.0, 0.0]\n",
/// )
/// .unwrap();
/// assert!((buckle(&m, &Settings::default()).unwrap().load_factor - 5.0).abs() < 1e-12);
/// ```
pub fn buckle<D: Statics>(m: &Mechanism<D>, settings: &Settings) -> Result<Buckling> {
    if m.dof() == 0 {
        return Err(Error::Singular { what: "the mechanism has no coordinates: nothing can buckle".into() });
    }
    let s0 = assemble_unloaded(m, settings)?;
    let (zero, base) = (&s0.loads, m.loads());
    let (f0, a0) = hessian(m, &s0.q, &s0.multipliers, zero)?;
    let (_, a1) = hessian(m, &s0.q, &s0.multipliers, &base)?;
    let p0 = parts(&a0);
    let g = p0.closure_jacobian;
    let z = linalg::null_space(g);
    if z.ncols() == 0 {
        return Err(Error::Singular { what: "the closures leave the mechanism no motion: nothing can buckle".into() });
    }
    let moving = free_motion(m, &s0).map_or(String::new(), |j| format!(" ({j})"));
    let free = || Error::Singular {
        what: format!(
            "the unloaded mechanism has a zero-stiffness motion{moving}: linear buckling is undefined; give a joint on it a stiffness, or hold it with a closure"
        ),
    };
    let k0 = constrained(p0.hessian, &z);
    if !linalg::is_positive_definite(&k0) {
        return Err(free());
    }
    // Linear pre-buckling state and its closure forces (least norm).
    let p1 = parts(&a1);
    let load_gradient = p1.gradient - p0.gradient;
    let dmu = pre_buckling_forces(&k0, &z, p0.hessian, &load_gradient, g, free)?;
    // The indeterminate part of δμ: least transmitted force under the base loads.
    let dmu = D::settle_pre_buckling(m, &f0, &a0, dmu.as_slice(), &base);
    let mu1: Vec<f64> = s0.multipliers.iter().zip(&dmu).map(|(a, b)| a + b).collect();
    let closure_part = parts(&hessian(m, &s0.q, &mu1, zero)?.1).hessian - p0.hessian;
    let geometric = p1.hessian - p0.hessian + closure_part;
    let b = z.transpose() * &geometric * &z;
    let (load_factor, mode) = smallest_load_factor(&k0, &b, &z, free, D::NO_SOFTENING)?;
    Ok(Buckling { load_factor, mode })
}

/// The frames and the Lagrangian with its exact Hessian at `q`.
fn hessian<D: Statics>(m: &Mechanism<D>, q: &[f64], mu: &[f64], loads: &Loads<D>) -> Result<(Frames<D>, Assembly<D>)> {
    D::check_start(m, q, mu, loads)?;
    let f = frames(m, q);
    let mut a = Assembly::new(m);
    assemble_into(m, &f, mu, loads, true, &mut a)?;
    Ok((f, a))
}
