//! Motion of a mechanism of either dimension over time: its start, its
//! loads in time and its integration, end to end.
//!
//! The equations of motion are those of [`super::mechanism`], with the loads
//! of [`super::schedule`] at each time, integrated by [`super::integrate`].
//! The start is, by default, the static equilibrium under the loads at
//! $t = 0$, at rest ([`Start::Equilibrium`]), or the unloaded shape
//! ([`Start::Rest`]); the file's `[initial]` and `[initial_velocity]`
//! override the coordinates of the joints they name. Directions with
//! neither inertia nor damping (massless flexures) are then moved onto
//! their quasi-static equilibrium under the loads at $t = 0$ (the
//! integrator's consistent start), which the run records at $t = 0$.
//!
//! The statics weigh every mass the dynamics do (bodies and flexure
//! sections, [`crate::mechanism::lagrangian`]), so under gravity the default
//! start is an equilibrium of the equations of motion, and a mechanism
//! started there stays at rest.

use super::contact::{ContactChange, ContactSystem};
use super::integrate::{self, Trajectory, integrate_kept};
use super::mechanism::Dynamics;
use super::schedule::{ScheduledSystem, loads_at};
use crate::error::{Error, Result};
use crate::mechanism::Mechanism;
use crate::mechanism::contact::{Contact, pairs};
use crate::mechanism::statics;
use crate::space::Planar;

/// Where a simulation starts, before `[initial]` and `[initial_velocity]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Start {
    /// The static equilibrium under the loads at $t = 0$, at rest.
    #[default]
    Equilibrium,
    /// The unloaded rest shape (closures assembled), at rest; directions
    /// with neither inertia nor damping start on their equilibrium under the
    /// loads at $t = 0$.
    Rest,
}

/// Settings of [`simulate`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SimulationSettings {
    /// The integration: duration, sample interval, tolerances, bounds.
    pub motion: integrate::MotionSettings,
    /// The static solves of the start.
    pub equilibrium: statics::Settings,
}

/// One body's motion in the plane: its frame in the ground frame at each sample.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BodyMotion {
    /// The body's name.
    pub name: String,
    /// Its origin's x (m), ground frame.
    pub x: Vec<f64>,
    /// Its origin's y (m), ground frame.
    pub y: Vec<f64>,
    /// Its angle (rad) from the ground frame.
    pub phi: Vec<f64>,
}

/// One body's motion in space: its frame in the ground frame at each sample.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BodyPoses {
    /// The body's name.
    pub name: String,
    /// Its origin (m), ground frame, at each sample.
    pub position: Vec<[f64; 3]>,
    /// Its rotation matrix (rows), ground frame, at each sample.
    pub rotation: Vec<[[f64; 3]; 3]>,
}

/// A simulated motion, sampled at [`integrate::MotionSettings::times`]: the
/// integrator's [`Trajectory`] (times, coordinates, rates, energy, steps,
/// closure violation; read through it directly, `simulation.time`), and
/// every moving body's frame at each sample.
///
/// It serializes as the trajectory's fields beside `bodies`, and `stopped`
/// as the error's message when the run stopped early.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Simulation<D: Dynamics = Planar> {
    /// Every moving body (not the ground), in the mechanism's order
    /// ([`BodyMotion`] in the plane, [`BodyPoses`] in space).
    pub bodies: Vec<D::BodyMotion>,
    /// The integrator's samples and counts. Its energy is the kinetic,
    /// elastic and gravitational energy (J); the work of the other loads and
    /// of damping is not in it.
    #[serde(flatten)]
    pub trajectory: Trajectory,
    /// The contacts at each sample, where the mechanism has geoms a part may
    /// touch ([`super::contact::ContactSystem::samples`]; empty otherwise).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub contacts: Vec<Vec<Contact>>,
    /// Where contacts touched and opened, in time.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub changes: Vec<ContactChange>,
    /// Why the run ended before its duration, if it did (stalled,
    /// interrupted, a state that cannot be evaluated): the samples above
    /// are those reached ([`integrate::integrate_kept`]).
    #[serde(serialize_with = "message", skip_serializing_if = "Option::is_none")]
    pub stopped: Option<Error>,
}

/// An error as its message: the library's [`Error`] is not data.
fn message<S: serde::Serializer>(error: &Option<Error>, s: S) -> std::result::Result<S::Ok, S::Error> {
    match error {
        Some(e) => s.collect_str(e),
        None => s.serialize_none(),
    }
}

impl<D: Dynamics> std::ops::Deref for Simulation<D> {
    type Target = Trajectory;

    fn deref(&self) -> &Trajectory {
        &self.trajectory
    }
}

/// The state $(q, \dot q)$ a simulation of `m` starts from (module docs).
/// When `[initial]` names every joint, no static solve is made.
///
/// Errors: those of the static solve of the start.
pub fn initial_state<D: Dynamics>(
    m: &Mechanism<D>,
    settings: &statics::Settings,
    start: Start,
) -> Result<(Vec<f64>, Vec<f64>)> {
    // `[initial]` for every joint leaves nothing to solve for (and a free
    // joint, a pendulum's, has no static start to solve).
    let mut q = if every_joint_given(m) {
        m.rest()
    } else {
        let loads = loads_at(m, 0.0);
        let unloaded = crate::mechanism::statics::assemble_unloaded(m, settings)?;
        match start {
            Start::Rest => unloaded.q,
            Start::Equilibrium => {
                crate::mechanism::statics::solve_between(m, &unloaded, &loads, settings).map_err(or_from_rest)?.q
            }
        }
    };
    let mut v = vec![0.0; m.dof()];
    set_given(m, &mut q, &mut v);
    Ok((q, v))
}

/// The equilibrium start's refusal of a mechanism with no single
/// equilibrium (a part free at no load, a singular balance), with the
/// start that needs none.
fn or_from_rest(e: Error) -> Error {
    match e {
        Error::Singular { what } => Error::Singular {
            what: format!("{what}; or start the motion from rest (start \"rest\"), where it needs no equilibrium"),
        },
        e => e,
    }
}

/// Whether `[initial]` names every joint: nothing is left to solve for.
fn every_joint_given<D: Dynamics>(m: &Mechanism<D>) -> bool {
    (0..m.joints.len()).all(|j| m.initial.iter().any(|(k, _)| *k == j))
}

/// The file's `[initial]` and `[initial_velocity]` written over `q` and `v`.
fn set_given<D: Dynamics>(m: &Mechanism<D>, q: &mut [f64], v: &mut [f64]) {
    for (state, given) in [(q, &m.initial), (v, &m.initial_velocity)] {
        for (j, values) in given {
            let o = m.joints[*j].offset;
            state[o..o + values.len()].copy_from_slice(values);
        }
    }
}

/// Simulates `m` from `start` (with the file's `[initial]` and
/// `[initial_velocity]`) under its loads and schedules over
/// `settings.motion.duration`.
///
/// Errors: `mass` when nothing has mass or inertia (no motion to
/// simulate); a bad setting by name ([`integrate::MotionSettings::validate`]);
/// those of the start's static solve. A run that stops after its first
/// sample ([`Error::IntegrationStalled`], [`Error::InterruptedAt`]) keeps the
/// samples it reached, with the error in [`Simulation::stopped`].
///
/// # Example
/// ```
/// use flexure::dynamics::simulation::{simulate, SimulationSettings, Start};
/// use flexure::dynamics::integrate::MotionSettings;
/// use flexure::mechanism::file::from_toml;
/// // A sprung arm (k = 2 N·m/rad, I = 0.5 kg·m²), started at 0.1 rad: φ = 0.1 cos 2t.
/// let m = from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n\
///      [[body]]\nname = \"arm\"\ninertia = 0.5\n[initial]\npin = 0.1\n",
/// )
/// .unwrap();
/// let motion = MotionSettings { duration: 1.0, every: 0.5, tolerance: 1e-10, absolute: 1e-10, ..Default::default() };
/// let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Equilibrium).unwrap();
/// assert_eq!(run.time, [0.0, 0.5, 1.0]);
/// assert!((run.bodies[0].phi[2] - 0.1 * 2f64.cos()).abs() < 1e-8);
/// ```
pub fn simulate<D: Dynamics>(m: &Mechanism<D>, settings: &SimulationSettings, start: Start) -> Result<Simulation<D>> {
    settings.motion.validate()?;
    settings.equilibrium.validate()?;
    let mut system = ScheduledSystem::new(m)?;
    if !system.system().has_inertia() {
        return Err(Error::invalid(
            "mass",
            "mass everywhere zero",
            "no body has mass or inertia and no flexure has a density or mass per length: nothing moves",
        ));
    }
    let (run, stopped, contacts, changes) = if pairs(m).is_empty() {
        let (q0, v0) = initial_state(m, &settings.equilibrium, start)?;
        let (run, stopped) = integrate_kept(&mut system, &q0, &v0, &settings.motion)?;
        (run, stopped, Vec::new(), Vec::new())
    } else {
        let (q0, v0, touching) = initial_touching(m, &settings.equilibrium, start)?;
        let mut system = ContactSystem::new(m, (&q0, &v0), &touching, settings.motion.tolerance)?;
        let (run, stopped) = integrate_kept(&mut system, &q0, &v0, &settings.motion)?;
        (run, stopped, system.samples().to_vec(), system.changes().to_vec())
    };
    Ok(Simulation { bodies: D::motions(m, &run), trajectory: run, contacts, changes, stopped })
}

/// [`initial_state`] of a mechanism with geoms, and the contacts that touch
/// there: an equilibrium's, with their pushes ([`statics::follow_touching`]),
/// sliding where `[initial_velocity]` moves them along their geom; none
/// from the rest shape or where `[initial]` sets coordinates (a part
/// there that overlaps a geom is refused by [`ContactSystem::new`], and one
/// that touches is held once it presses in).
fn initial_touching<D: Dynamics>(
    m: &Mechanism<D>,
    settings: &statics::Settings,
    start: Start,
) -> Result<(Vec<f64>, Vec<f64>, Vec<Contact>)> {
    if start == Start::Rest || every_joint_given(m) {
        let (q, v) = initial_state(m, settings, start)?;
        return Ok((q, v, Vec::new()));
    }
    let work = &mut statics::Workspace::new(m);
    let (solution, _) = statics::follow_touching(m, None, &loads_at(m, 0.0), settings, work).map_err(or_from_rest)?;
    let (mut q, mut v) = (solution.q, vec![0.0; m.dof()]);
    set_given(m, &mut q, &mut v);
    // Coordinates set by hand leave the equilibrium's contacts behind (the
    // parts are elsewhere); velocities keep them, sliding where launched.
    let touching = if m.initial.is_empty() { solution.contacts } else { Vec::new() };
    Ok((q, v, touching))
}
