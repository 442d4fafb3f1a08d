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
use crate::mechanism::spatial::kinematics::{SpatialFrames, frames_level_into};
use crate::mechanism::statics::{Settings, Solution};
use crate::mechanism::{Dimension, Loads, Mechanism, kinematics, spatial as space_mechanism, statics};
use crate::space::{Planar, Spatial};
use nalgebra::{DMatrix, DVector};
use std::fmt::Debug;

/// A dimension whose mechanisms move: [`Planar`] or [`Spatial`].
///
/// What differs between the two sits here: the mass elements (a body's
/// rotary inertia, a scalar in the plane and a matrix in space; a flexure's
/// distributed mass, by the plane's closed-form mass moments or space's
/// stations) with the potential they are evaluated with, the statics they
/// start from, and how a body's motion is written down. The rest of the
/// equations of motion, their integration and the modes are generic.
pub trait Dynamics: Dimension {
    /// The mass elements and the buffers of their evaluation.
    type Masses: Debug + Clone;
    /// One moving body's frame at each sample of a simulation.
    type BodyMotion: Debug + Clone + PartialEq + serde::Serialize;

    /// The mass elements of `m`; fails if a flexure's mass integrals cannot be made accurate.
    fn masses(m: &Mechanism<Self>) -> Result<Self::Masses>;
    /// Whether a body has mass or inertia, or a flexure a density or mass per length.
    fn has_inertia(masses: &Self::Masses, m: &Mechanism<Self>) -> bool;
    /// Takes `loads` (already validated) from now on.
    fn set_loads(masses: &mut Self::Masses, loads: &Loads<Self>);
    /// Writes $M(q)$ and the generalized force without damping,
    /// $f = Q - \nabla V - h$.
    fn forces(
        masses: &mut Self::Masses,
        m: &Mechanism<Self>,
        loads: &Loads<Self>,
        state: [&[f64]; 2],
        mass: &mut [f64],
        force: &mut [f64],
    ) -> Result<()>;
    /// $M(q)$.
    fn mass_matrix(masses: &mut Self::Masses, m: &Mechanism<Self>, loads: &Loads<Self>, q: &[f64]) -> DMatrix<f64>;
    /// The velocity-product terms $h(q, \dot q)$.
    fn velocity_product(
        masses: &mut Self::Masses,
        m: &Mechanism<Self>,
        loads: &Loads<Self>,
        state: [&[f64]; 2],
    ) -> DVector<f64>;
    /// Writes the tangent stiffness $-\partial f/\partial q$ without damping.
    fn stiffness(
        masses: &mut Self::Masses,
        m: &Mechanism<Self>,
        loads: &Loads<Self>,
        state: [&[f64]; 2],
        out: &mut [f64],
    ) -> Result<()>;
    /// The step in rate $c$ of the tangent damping's central difference
    /// (exact at any step: $h$ is quadratic in $\dot q$).
    fn rate_step(v: &[f64], c: usize) -> f64;
    /// $T + V$ (J).
    fn energy(masses: &mut Self::Masses, m: &Mechanism<Self>, loads: &Loads<Self>, state: [&[f64]; 2]) -> Result<f64>;
    /// The number of closure equations the integrator holds.
    fn closures(masses: &Self::Masses, m: &Mechanism<Self>) -> usize;
    /// Writes $c(q)$ and $G(q)$.
    fn closure(masses: &mut Self::Masses, m: &Mechanism<Self>, q: &[f64], c: &mut [f64], g: &mut [f64]);
    /// The largest rotation between two configurations.
    fn distance(masses: &Self::Masses, m: &Mechanism<Self>, a: &[f64], b: &[f64]) -> f64;

    /// Checks `loads` against `m`.
    fn validate(loads: &Loads<Self>, m: &Mechanism<Self>) -> Result<()>;
    /// Sets the load `parameter` names to `value`.
    fn set(parameter: &Self::Parameter, loads: &mut Loads<Self>, value: f64);

    /// The equilibrium under the mechanism's loads.
    fn solve(m: &Mechanism<Self>, settings: &Settings) -> Result<Solution<Self>>;
    /// The unloaded rest shape, closures assembled (`start`: the loads at $t = 0$).
    fn assemble_unloaded(m: &Mechanism<Self>, start: &Loads<Self>, settings: &Settings) -> Result<Solution<Self>>;
    /// The equilibrium under `to`, continued from `start`.
    fn solve_between(
        m: &Mechanism<Self>,
        start: &Solution<Self>,
        to: &Loads<Self>,
        settings: &Settings,
    ) -> Result<Solution<Self>>;
    /// The motions the closures allow, $Z$, and the loaded stiffness on them.
    fn reduced_stiffness(m: &Mechanism<Self>, s: &Solution<Self>) -> Result<(DMatrix<f64>, DMatrix<f64>)>;

    /// Every moving body's frame at each sample of `run`.
    fn motions(m: &Mechanism<Self>, run: &Trajectory) -> Vec<Self::BodyMotion>;
}

impl Dynamics for Planar {
    type Masses = planar::Masses;
    type BodyMotion = BodyMotion;

    fn masses(m: &Mechanism) -> Result<planar::Masses> {
        planar::Masses::new(m)
    }
    fn has_inertia(masses: &planar::Masses, _: &Mechanism) -> bool {
        masses.has_inertia()
    }
    fn set_loads(masses: &mut planar::Masses, loads: &Loads) {
        masses.set_loads(loads)
    }
    fn forces(
        masses: &mut planar::Masses,
        m: &Mechanism,
        loads: &Loads,
        [q, v]: [&[f64]; 2],
        mass: &mut [f64],
        force: &mut [f64],
    ) -> Result<()> {
        masses.forces(m, loads, q, v, mass, force)
    }
    fn mass_matrix(masses: &mut planar::Masses, m: &Mechanism, loads: &Loads, q: &[f64]) -> DMatrix<f64> {
        masses.mass_matrix(m, loads, q)
    }
    fn velocity_product(
        masses: &mut planar::Masses,
        m: &Mechanism,
        loads: &Loads,
        [q, v]: [&[f64]; 2],
    ) -> DVector<f64> {
        masses.velocity_product(m, loads, q, v)
    }
    fn stiffness(
        masses: &mut planar::Masses,
        m: &Mechanism,
        loads: &Loads,
        [q, _]: [&[f64]; 2],
        out: &mut [f64],
    ) -> Result<()> {
        masses.stiffness(m, loads, q, out)
    }
    fn rate_step(v: &[f64], c: usize) -> f64 {
        1.0 + v[c].abs()
    }
    fn energy(masses: &mut planar::Masses, m: &Mechanism, loads: &Loads, [q, v]: [&[f64]; 2]) -> Result<f64> {
        masses.energy(m, loads, q, v)
    }
    fn closures(_: &planar::Masses, m: &Mechanism) -> usize {
        m.constraints()
    }
    fn closure(masses: &mut planar::Masses, m: &Mechanism, q: &[f64], c: &mut [f64], g: &mut [f64]) {
        masses.closure(m, q, c, g)
    }
    fn distance(masses: &planar::Masses, m: &Mechanism, a: &[f64], b: &[f64]) -> f64 {
        masses.distance(m, a, b)
    }

    fn validate(loads: &Loads, m: &Mechanism) -> Result<()> {
        loads.validate(m)
    }
    fn set(parameter: &Self::Parameter, loads: &mut Loads, value: f64) {
        parameter.set(loads, value)
    }

    fn solve(m: &Mechanism, settings: &Settings) -> Result<Solution> {
        statics::solve(m, settings)
    }
    fn assemble_unloaded(m: &Mechanism, _: &Loads, settings: &Settings) -> Result<Solution> {
        statics::assemble_unloaded(m, settings)
    }
    fn solve_between(m: &Mechanism, start: &Solution, to: &Loads, settings: &Settings) -> Result<Solution> {
        statics::solve_between(m, start, to, settings)
    }
    fn reduced_stiffness(m: &Mechanism, s: &Solution) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
        statics::stiffness(m, s)
    }

    fn motions(m: &Mechanism, run: &Trajectory) -> Vec<BodyMotion> {
        let samples = run.time.len();
        let mut bodies: Vec<BodyMotion> = m.bodies[1..]
            .iter()
            .map(|b| BodyMotion {
                name: b.name.clone(),
                x: Vec::with_capacity(samples),
                y: Vec::with_capacity(samples),
                phi: Vec::with_capacity(samples),
            })
            .collect();
        for k in 0..samples {
            let f = kinematics::frames(m, run.q(k));
            for (motion, frame) in bodies.iter_mut().zip(&f.bodies[1..]) {
                motion.x.push(frame.x);
                motion.y.push(frame.y);
                motion.phi.push(frame.phi);
            }
        }
        bodies
    }
}

impl Dynamics for Spatial {
    type Masses = spatial::Masses;
    type BodyMotion = BodyPoses;

    fn masses(m: &Mechanism<Spatial>) -> Result<spatial::Masses> {
        Ok(spatial::Masses::new(m))
    }
    fn has_inertia(masses: &spatial::Masses, m: &Mechanism<Spatial>) -> bool {
        masses.has_inertia(m)
    }
    fn set_loads(_: &mut spatial::Masses, _: &Loads<Spatial>) {}
    fn forces(
        masses: &mut spatial::Masses,
        m: &Mechanism<Spatial>,
        loads: &Loads<Spatial>,
        [q, v]: [&[f64]; 2],
        mass: &mut [f64],
        force: &mut [f64],
    ) -> Result<()> {
        masses.forces(m, loads, q, v, mass, force);
        Ok(())
    }
    fn mass_matrix(
        masses: &mut spatial::Masses,
        m: &Mechanism<Spatial>,
        _: &Loads<Spatial>,
        q: &[f64],
    ) -> DMatrix<f64> {
        masses.mass_matrix(m, q)
    }
    fn velocity_product(
        masses: &mut spatial::Masses,
        m: &Mechanism<Spatial>,
        _: &Loads<Spatial>,
        [q, v]: [&[f64]; 2],
    ) -> DVector<f64> {
        masses.velocity_product(m, q, v)
    }
    fn stiffness(
        masses: &mut spatial::Masses,
        m: &Mechanism<Spatial>,
        loads: &Loads<Spatial>,
        [q, v]: [&[f64]; 2],
        out: &mut [f64],
    ) -> Result<()> {
        masses.stiffness(m, loads, q, v, out);
        Ok(())
    }
    fn rate_step(v: &[f64], _: usize) -> f64 {
        1e-3 * v.iter().fold(0.0_f64, |a, x| a.max(x.abs())).max(1.0)
    }
    fn energy(
        masses: &mut spatial::Masses,
        m: &Mechanism<Spatial>,
        loads: &Loads<Spatial>,
        [q, v]: [&[f64]; 2],
    ) -> Result<f64> {
        Ok(masses.energy(m, loads, q, v))
    }
    fn closures(masses: &spatial::Masses, m: &Mechanism<Spatial>) -> usize {
        masses.closures(m)
    }
    fn closure(masses: &mut spatial::Masses, m: &Mechanism<Spatial>, q: &[f64], c: &mut [f64], g: &mut [f64]) {
        masses.closure(m, q, c, g)
    }
    fn distance(masses: &spatial::Masses, m: &Mechanism<Spatial>, a: &[f64], b: &[f64]) -> f64 {
        masses.distance(m, a, b)
    }

    fn validate(loads: &Loads<Spatial>, m: &Mechanism<Spatial>) -> Result<()> {
        loads.validate(m)
    }
    fn set(parameter: &Self::Parameter, loads: &mut Loads<Spatial>, value: f64) {
        parameter.set(loads, value)
    }

    fn solve(m: &Mechanism<Spatial>, settings: &Settings) -> Result<Solution<Spatial>> {
        space_mechanism::statics::solve(m, settings)
    }
    fn assemble_unloaded(
        m: &Mechanism<Spatial>,
        start: &Loads<Spatial>,
        settings: &Settings,
    ) -> Result<Solution<Spatial>> {
        space_mechanism::statics::assemble_unloaded(m, &start.zero_like(), settings)
    }
    fn solve_between(
        m: &Mechanism<Spatial>,
        start: &Solution<Spatial>,
        to: &Loads<Spatial>,
        settings: &Settings,
    ) -> Result<Solution<Spatial>> {
        space_mechanism::statics::solve_between(m, start, to, settings)
    }
    fn reduced_stiffness(m: &Mechanism<Spatial>, s: &Solution<Spatial>) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
        Ok(space_mechanism::statics::stiffness(m, s))
    }

    fn motions(m: &Mechanism<Spatial>, run: &Trajectory) -> Vec<BodyPoses> {
        let mut bodies: Vec<BodyPoses> = m.bodies[1..]
            .iter()
            .map(|b| BodyPoses { name: b.name.clone(), position: Vec::new(), rotation: Vec::new() })
            .collect();
        let mut f = SpatialFrames::new(m);
        for k in 0..run.time.len() {
            // The bodies' poses alone (the flexures' Hessians cost most at high orders).
            frames_level_into(m, run.q(k), crate::kinematics::Level::Pose, &mut f);
            for (i, motion) in bodies.iter_mut().enumerate() {
                let (p, r) = (f.bodies[i + 1].translation.vector, f.body_rotation(i + 1));
                motion.position.push([p.x, p.y, p.z]);
                motion.rotation.push(std::array::from_fn(|row| std::array::from_fn(|col| r[(row, col)])));
            }
        }
        bodies
    }
}
