//! What the equations of motion need of a dimension ([`Dynamics`]): its
//! mass elements, the statics of a simulation's start and of the modes,
//! how a schedule sets a load, and a body's recorded motion. The plane and
//! space implement it here, side by side; [`MechanismSystem`](super::MechanismSystem),
//! [`modes`](super::modes) and [`simulate`](crate::dynamics::simulate) are
//! written once over it.

use super::{planar, spatial};
use crate::dynamics::integrate::Trajectory;
use crate::dynamics::simulation::{BodyMotion, BodyPoses};
use crate::error::Result;
use crate::mechanism::kinematics::{Frames, frames_level_into};
use crate::mechanism::statics::Statics;
use crate::mechanism::{Dimension, Loads, Mechanism, kinematics};
use crate::space::{Planar, Pose, Spatial};
use nalgebra::{DMatrix, DVector, Matrix3};
use std::fmt::Debug;

/// A dimension whose mechanisms move: [`Planar`] or [`Spatial`].
///
/// What differs between the two sits here: the mass elements
/// ([`MassElements`]: a body's rotary inertia, a scalar in the plane and a
/// matrix in space; a flexure's distributed mass, by the plane's
/// closed-form mass moments or space's stations), the statics a simulation
/// starts from and the modes are taken about, and how a body's motion is
/// written down. The rest of the equations of motion, their integration
/// and the modes are generic.
pub trait Dynamics: Statics {
    /// The mass elements and the buffers of their evaluation.
    type Masses: MassElements<Self>;
    /// One moving body's frame at each sample of a simulation.
    type BodyMotion: Debug + Clone + PartialEq + serde::Serialize;

    /// Every moving body's frame at each sample of `run`.
    fn motions(m: &Mechanism<Self>, run: &Trajectory) -> Vec<Self::BodyMotion>;
}

/// A dimension's mass elements as [`MechanismSystem`](super::MechanismSystem)
/// evaluates them: `m` is the mechanism they were made for, `loads` those
/// applied, $q$ and $\dot q$ checked (one finite value per coordinate).
pub trait MassElements<D: Dimension>: Debug + Clone + Sized {
    /// The mass elements of `m`; fails if a flexure's mass integrals cannot be made accurate.
    fn new(m: &Mechanism<D>) -> Result<Self>;
    /// Whether a body has mass or inertia, or a flexure a density or mass per length.
    fn has_inertia(&self, m: &Mechanism<D>) -> bool;
    /// Takes `loads` (validated) from now on.
    fn set_loads(&mut self, _loads: &Loads<D>) {}
    /// Writes $M(q)$ and the generalized force without damping, $f = Q - \nabla V - h$.
    fn forces(
        &mut self,
        m: &Mechanism<D>,
        loads: &Loads<D>,
        q: &[f64],
        v: &[f64],
        mass: &mut [f64],
        force: &mut [f64],
    ) -> Result<()>;
    /// $M(q)$.
    fn mass_matrix(&mut self, m: &Mechanism<D>, loads: &Loads<D>, q: &[f64]) -> DMatrix<f64>;
    /// The velocity-product terms $h(q, \dot q)$.
    fn velocity_product(&mut self, m: &Mechanism<D>, loads: &Loads<D>, q: &[f64], v: &[f64]) -> DVector<f64>;
    /// Writes the tangent stiffness $-\partial f/\partial q$ without damping.
    fn stiffness(&mut self, m: &Mechanism<D>, loads: &Loads<D>, q: &[f64], v: &[f64], out: &mut [f64]) -> Result<()>;
    /// The step in rate `c` of the tangent damping's central difference
    /// (exact at any step: $h$ is quadratic in $\dot q$).
    fn rate_step(v: &[f64], c: usize) -> f64;
    /// $T + V$ (J): kinetic, elastic and gravitational.
    fn energy(&mut self, m: &Mechanism<D>, loads: &Loads<D>, q: &[f64], v: &[f64]) -> Result<f64>;
    /// The number of closure equations the integrator holds.
    fn closures(&self, m: &Mechanism<D>) -> usize {
        m.constraints()
    }
    /// Writes $c(q)$ and $G(q)$.
    fn closure(&mut self, m: &Mechanism<D>, q: &[f64], c: &mut [f64], g: &mut [f64]);
    /// The largest rotation between two configurations.
    fn distance(&self, m: &Mechanism<D>, a: &[f64], b: &[f64]) -> f64;
}

impl Dynamics for Planar {
    type Masses = planar::ClosedFormMasses;
    type BodyMotion = BodyMotion;

    fn motions(m: &Mechanism, run: &Trajectory) -> Vec<BodyMotion> {
        let poses: Vec<_> = (0..run.time.len()).map(|k| kinematics::frames(m, run.q(k)).bodies).collect();
        let along = |b: usize, part: fn(&Pose) -> f64| poses.iter().map(|p| part(&p[b])).collect();
        (1..m.bodies.len())
            .map(|b| BodyMotion {
                name: m.bodies[b].name.clone(),
                x: along(b, |p| p.x),
                y: along(b, |p| p.y),
                phi: along(b, |p| p.phi),
            })
            .collect()
    }
}

impl Dynamics for Spatial {
    type Masses = spatial::StationMasses;
    type BodyMotion = BodyPoses;

    fn motions(m: &Mechanism<Spatial>, run: &Trajectory) -> Vec<BodyPoses> {
        let mut f = Frames::new(m);
        let poses: Vec<Vec<_>> = (0..run.time.len())
            .map(|k| {
                // The bodies' poses alone (the flexures' Hessians cost most at high orders).
                frames_level_into(m, run.q(k), crate::kinematics::Level::Pose, &mut f);
                (0..m.bodies.len()).map(|b| (f.bodies[b].translation.vector, *f.body_rotation(b))).collect()
            })
            .collect();
        let rows = |r: &Matrix3<f64>| std::array::from_fn(|i| std::array::from_fn(|j| r[(i, j)]));
        (1..m.bodies.len())
            .map(|b| BodyPoses {
                name: m.bodies[b].name.clone(),
                position: poses.iter().map(|p| p[b].0.into()).collect(),
                rotation: poses.iter().map(|p| rows(&p[b].1)).collect(),
            })
            .collect()
    }
}
