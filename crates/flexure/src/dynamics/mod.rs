//! Dynamics of one flexure joint carrying an optional rigid tip body
//! ([`RigidInertia`](crate::inertia::RigidInertia)):
//! the generalized mass matrix and velocity-product terms of its
//! coordinates ([`crate::mass`]), and its vibration modes about a loaded
//! equilibrium ([`mod@modes`]); and the [`System`] interface between
//! equations of motion and a time integrator.
//!
//! The kinetic energy of the flexure (mass per length $\mu(s)$, rotary
//! inertia per length $\rho I(s)$) and of the body (mass $m$, inertia $I_c$
//! about its centre of mass $c$) is
//!
//! $$T = \tfrac12\int_0^L \mu\thinspace\lvert\dot r\rvert^2 ds +
//! \tfrac12\int_0^L \rho I\thinspace\dot\phi^2 ds +
//! \tfrac12 m\lvert v_c\rvert^2 + \tfrac12 I_c\dot\phi_{tip}^2 =
//! \tfrac12\dot\alpha^T M(\alpha)\dot\alpha,$$
//!
//! so that Lagrange's equations read
//! $M(\alpha)\ddot\alpha + h(\alpha,\dot\alpha) + \nabla U = Q$ with
//! $h = \dot M\dot\alpha - \frac12\nabla_\alpha(\dot\alpha^TM\dot\alpha)$.

pub mod contact;
pub mod integrate;
pub mod mechanism;
pub mod modes;
pub mod schedule;
pub mod simulation;
pub mod system;

// The mass models sit beside the section they integrate; their old paths stay.
/// The old name of [`RigidInertia`](crate::inertia::RigidInertia), the inertia of
/// a flexure's tip body: a mechanism's [`Body`](crate::mechanism::Body) is the
/// one body type.
pub use crate::inertia::RigidInertia as Body;
pub use crate::mass::{self, MassData, MassModel, update as update_mass};
pub use mechanism::{Dynamics, MechanismSystem};
pub use modes::{Modes, modes};
pub use simulation::{Simulation, SimulationSettings, Start, simulate};

pub use system::System;
