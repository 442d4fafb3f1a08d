//! The vibration modes of a mechanism of either dimension about its loaded equilibrium.

use super::dimension::Dynamics;
use super::equations::MechanismSystem;
use crate::dynamics::modes::{Modes, finite_modes};
use crate::error::{Error, Result};
use crate::mechanism::Mechanism;
use crate::mechanism::statics::Settings;

/// The vibration modes of `m` about its equilibrium under its loads
/// ([`crate::mechanism::statics::solve`] with `settings`): the finite solutions of
///
/// $$Z^T\nabla^2L\thinspace Z\thinspace a = \omega^2Z^TM Z\thinspace a,\qquad v = Za,$$
///
/// where $\nabla^2L$ is the loaded stiffness with the closure forces' part
/// and the columns of $Z$ span the motions the closures allow
/// ([`crate::mechanism::statics::stiffness`]), so a frequency falls to zero as the loads
/// reach a buckling load. Directions without inertia are condensed out
/// as quasi-static ([`finite_modes`]); at most `count` modes are returned.
/// Shapes are in the coordinates $q$, normalized to $v^TMv = 1$.
/// [`Modes::limit`] is the load fraction where the loading path snapped
/// through a limit, if it did: the modes are then about the stable
/// equilibrium beyond it.
///
/// The equilibrium weighs the bodies; a flexure's own weight, which the
/// statics do not model, is left out of it (the dynamics include it).
///
/// Errors: `count` when zero; `mass` when nothing has mass or inertia;
/// [`Error::Unstable`] when the equilibrium is not stable; those of the
/// equilibrium solve.
///
/// # Example
/// ```
/// use flexure::dynamics::mechanism::modes;
/// use flexure::mechanism::{file::from_toml, statics::Settings};
/// // A sprung arm (k = 2 N·m/rad) carrying 0.5 kg at 0.1 m: ω = √(k / m l²) = 20 rad/s.
/// let m = from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n\
///      [[body]]\nname = \"arm\"\nmass = 0.5\ncom = [0.1, 0.0]\n",
/// )
/// .unwrap();
/// let w = modes(&m, &Settings::default(), 4).unwrap().omega;
/// assert!(w.len() == 1 && (w[0] - 20.0).abs() < 1e-12);
///
/// // The same arm in space: a sprung hinge about z.
/// use flexure::mechanism::spatial::{RevoluteUnaligned, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism};
/// use nalgebra::{Isometry3, Matrix3, Point3, Vector3};
/// let hinge = SpatialJointSpec {
///     name: "pin".into(), kind: SpatialJointKind::Revolute(RevoluteUnaligned { axis: Vector3::z_axis(), stiffness: 2.0, rest: 0.0 }),
///     parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default(),
/// };
/// let arm = SpatialBody { name: "arm".into(), mass: 0.5, com: Point3::new(0.1, 0.0, 0.0), inertia: Matrix3::zeros() };
/// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), arm], vec![hinge], vec![], vec![], vec![], Vector3::zeros()).unwrap();
/// let w = modes(&m, &Settings::default(), 4).unwrap().omega;
/// assert!(w.len() == 1 && (w[0] - 20.0).abs() < 1e-12);
/// ```
pub fn modes<D: Dynamics>(m: &Mechanism<D>, settings: &Settings, count: usize) -> Result<Modes> {
    if count == 0 {
        return Err(Error::invalid("count", count, "must be at least 1"));
    }
    let mut sys = MechanismSystem::new(m)?;
    if !sys.has_inertia() {
        return Err(Error::invalid(
            "mass",
            "none",
            "no body has mass or inertia and no flexure has a density or mass per length",
        ));
    }
    if m.dof() == 0 {
        return Err(Error::Singular { what: "the mechanism has no coordinates: nothing can vibrate".into() });
    }
    let s = crate::mechanism::statics::solve(m, settings)?;
    if !s.stable {
        return Err(Error::Unstable { what: "modes", load_fraction: s.limit.unwrap_or(1.0) });
    }
    let (z, k) = crate::mechanism::statics::stiffness(m, &s)?;
    if z.ncols() == 0 {
        return Err(Error::Singular { what: "the closures leave the mechanism no motion: nothing can vibrate".into() });
    }
    let mass = sys.mass_matrix(&s.q)?;
    let reduced = z.transpose() * &mass * &z;
    let mut modes = finite_modes(&k, &reduced, count)?;
    modes.shapes = &z * &modes.shapes;
    modes.limit = s.limit;
    modes.coordinates = s.q.clone();
    Ok(modes)
}
