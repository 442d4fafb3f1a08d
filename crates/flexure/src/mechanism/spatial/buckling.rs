//! Linear buckling of a spatial mechanism about its unloaded, assembled
//! configuration, as the planar [`crate::mechanism::buckling`].

use super::kinematics::frames;
use super::lagrangian::{SpatialAssembly, assemble_into};
use super::statics::assemble_unloaded;
use super::{SpatialLoads, SpatialMechanism};
use crate::error::{Error, Result};
use crate::linalg;
use crate::mechanism::buckling::Buckling;
use crate::mechanism::pencil::{pre_buckling_forces, smallest_load_factor};
use crate::solver::Settings;
use nalgebra::DMatrix;

fn hessian(m: &SpatialMechanism, q: &[f64], mu: &[f64], loads: &SpatialLoads) -> SpatialAssembly {
    let mut a = SpatialAssembly::new(m);
    assemble_into(m, &frames(m, q), mu, loads, true, &mut a);
    a
}

/// Linear buckling: the smallest $\lambda > 0$ with
/// $\det Z^T(K_0 + \lambda K_g)Z = 0$ at the unloaded configuration, $K_0$
/// the elastic stiffness, $K_g$ the loads' geometric stiffness with the
/// closure forces of the linear pre-buckling solve, $Z$ the closures' null
/// space. A dead moment makes $K_g$ unsymmetric (its follower part, as in
/// lateral-torsional buckling); the eigenvalues are then those of the
/// unsymmetric pencil, and the smallest positive real one is taken. Such
/// loads may have none (a cantilever under a dead end torque has no
/// adjacent equilibrium, only flutter: Ziegler's example), which is an error that says so.
///
/// # Example
/// ```
/// use flexure::mechanism::spatial::buckling::buckle;
/// use flexure::mechanism::spatial::{Revolute, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism, SpatialPointLoad};
/// use nalgebra::{Isometry3, Point3, Vector3, Vector6};
/// // A sprung hinge about z (k = 1 N·m/rad) with an arm of 0.1 m pushed along itself by 2 N: P = k/l = 10 N.
/// let hinge = SpatialJointSpec {
///     name: "pivot".into(), kind: SpatialJointKind::Revolute(Revolute { axis: Vector3::z_axis(), stiffness: 1.0, rest: 0.0 }),
///     parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default(),
/// };
/// let push = SpatialPointLoad { name: "p".into(), body: 1, at: Point3::new(0.1, 0.0, 0.0), wrench: Vector6::new(0.0, 0.0, 0.0, -2.0, 0.0, 0.0) };
/// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), SpatialBody::massless("arm")], vec![hinge], vec![], vec![push], vec![], Vector3::zeros()).unwrap();
/// assert!((buckle(&m, &Default::default()).unwrap().load_factor - 5.0).abs() < 1e-12);
/// ```
pub fn buckle(m: &SpatialMechanism, settings: &Settings) -> Result<Buckling> {
    if m.dof() == 0 {
        return Err(Error::Singular { what: "the mechanism has no coordinates: nothing can buckle".into() });
    }
    let base = m.loads();
    let zero = base.zero_like();
    let s0 = assemble_unloaded(m, &zero, settings)?;
    let a0 = hessian(m, &s0.q, &s0.multipliers, &zero);
    let a1 = hessian(m, &s0.q, &s0.multipliers, &base);
    let g = &a0.closure_jacobian;
    let z = if g.nrows() == 0 { DMatrix::identity(m.dof(), m.dof()) } else { linalg::null_space(g) };
    let free =
        || Error::Singular { what: "the unloaded mechanism has a free motion: its stiffness is singular".into() };
    if z.ncols() == 0 {
        return Err(Error::Singular { what: "the closures leave the mechanism no motion: nothing can buckle".into() });
    }
    let k0 = z.transpose() * &a0.hessian * &z;
    let k0 = (&k0 + k0.transpose()) * 0.5;
    if !linalg::is_positive_definite(&k0) {
        // As the planar buckle: the joints that move in it are named.
        let moving = moving(m, &z, &k0).map_or(String::new(), |j| format!(" ({j})"));
        return Err(Error::Singular {
            what: format!(
                "the unloaded mechanism has a zero-stiffness motion{moving}: linear buckling is undefined; give a joint on it a stiffness, or hold it with a closure"
            ),
        });
    }
    // Linear pre-buckling state and its closure forces (least norm).
    let load_gradient = &a1.gradient - &a0.gradient;
    let dmu = pre_buckling_forces(&k0, &z, &a0.hessian, &load_gradient, g, free)?;
    let mu1: Vec<f64> = s0.multipliers.iter().zip(dmu.iter()).map(|(a, b)| a + b).collect();
    let closure_part = hessian(m, &s0.q, &mu1, &zero).hessian - &a0.hessian;
    let geometric = &a1.hessian - &a0.hessian + closure_part;
    let b = z.transpose() * &geometric * &z;
    let (load_factor, mode) = smallest_load_factor(&k0, &b, &z, free, "only tension, or loads that stiffen it")?;
    Ok(Buckling { load_factor, mode })
}

/// The joints that move in the softest mode of the constrained stiffness
/// `k` (on the closures' null space `z`).
fn moving(m: &SpatialMechanism, z: &DMatrix<f64>, k: &DMatrix<f64>) -> Option<String> {
    let (_, soft) = linalg::softest_mode(k)?;
    let joints = m.joints.iter().map(|j| (j.name.as_str(), j.offset, j.kind.joint().dof()));
    crate::mechanism::statics::moving_joints(joints, &(z * soft))
}
