//! The exact large-deflection elastica (paper Eq. 3), solved by shooting on
//! the shared solver core ([`crate::solver`]).
//!
//! One concept a file:
//!
//! - `shot.rs`: one shot of Eq. 3 from the clamped root ([`shoot`]);
//! - `chain.rs`: the tip-load elastica by multiple shooting, the solver
//!   core's problem ([`MAX_FORCE_GROWTH`] bounds the force it follows);
//! - `deflection.rs`: the load followed from rest ([`deflect`],
//!   [`deflect_traced`], [`ElasticaSolution`]);
//! - `jacobi.rs`: its stability, the Jacobi (conjugate-point) test ([`is_stable`]);
//! - `connection.rs`: the exact minimum-energy shape through a pose (Eq. 16,
//!   [`connect`](fn@connect), [`ElasticaConnection`]);
//! - `contact/`: the elastica touching rigid obstacles, frictionless or with
//!   friction at the tip, along a load path ([`contact`](fn@contact), [`contact::Obstacle`]);
//! - `trace.rs`: cross-sections, bending moment and stress along a solved
//!   shape ([`Trace`], [`Point`]).
//!
//! [`ShootingSettings`] here serve them all.

mod chain;
mod connection;
pub mod contact;
mod deflection;
mod jacobi;
mod shot;
mod trace;

pub use chain::MAX_FORCE_GROWTH;
pub use connection::{ElasticaConnection, connect};
pub use contact::contact;
pub use deflection::{ElasticaSolution, deflect, deflect_traced};
pub use jacobi::is_stable;
pub use shot::shoot;
pub use trace::{Point, Trace};

use crate::error::{Error, Result};
use crate::ode::Tolerance;
use crate::solver;

/// Settings of [`deflect`] and [`connect`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShootingSettings {
    /// Integrator tolerance.
    pub ode: Tolerance,
    /// Newton and load-continuation settings. The residual is the tip-moment
    /// mismatch, relative to $EI/L + |M| + L(|F_x| + |F_y|)$ ([`deflect`]),
    /// or the tip-pose mismatch relative to $L$ ([`connect`]).
    pub solver: solver::Settings,
    /// The integrator's tolerance (relative and absolute) while [`deflect`]
    /// follows the loading path; the end state is then refined to `ode`.
    /// The path only has to keep to its branch and tell where it loses
    /// stability, and a looser integration takes far fewer steps, the more
    /// so the more the beam bends. Zero (or anything below `ode`'s
    /// tolerances) follows the path at `ode` itself.
    pub path_tolerance: f64,
}

impl Default for ShootingSettings {
    fn default() -> Self {
        Self { ode: Tolerance::default(), solver: solver::Settings::default(), path_tolerance: PATH_TOLERANCE }
    }
}

/// The default [`ShootingSettings::path_tolerance`]: where the loading path still
/// costs a few times less than the refinement of its end (a tip angle of
/// 45° to 270°), while its states and stability stay those of the exact
/// elastica to about that tolerance.
pub const PATH_TOLERANCE: f64 = 1e-6;

impl ShootingSettings {
    /// Checks the integrator and solver settings, naming the first bad one.
    ///
    /// # Example
    /// ```
    /// use flexure::reference::elastica::ShootingSettings;
    /// let mut s = ShootingSettings::default();
    /// s.ode.relative = f64::NAN;
    /// assert!(s.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<()> {
        self.ode.validate()?;
        self.solver.validate()?;
        let p = self.path_tolerance;
        if !(p.is_finite() && (0.0..=1e-4).contains(&p)) {
            return Err(Error::invalid("path_tolerance", p, "must be a finite number from 0 to 1e-4"));
        }
        Ok(())
    }

    /// Settings of one tolerance: the integrator's relative and absolute
    /// tolerance `tolerance` for the answer and the path alike (a speed
    /// knob: for the rod, $10^{-6}$ puts the tip within about $10^{-6}L$),
    /// and the solver's defaults.
    ///
    /// # Example
    /// ```
    /// let s = flexure::reference::elastica::ShootingSettings::with_tolerance(1e-6);
    /// assert_eq!(s.ode.relative, 1e-6);
    /// assert!(flexure::reference::rod::ShootingSettings::with_tolerance(0.0).validate().is_err());
    /// ```
    pub fn with_tolerance(tolerance: f64) -> Self {
        let ode = Tolerance { relative: tolerance, absolute: tolerance, ..Tolerance::default() };
        Self { ode, solver: solver::Settings::default(), path_tolerance: 0.0 }
    }

    /// The integrator's tolerance along the loading path.
    pub(crate) fn path_ode(&self) -> Tolerance {
        let p = self.path_tolerance;
        Tolerance { relative: self.ode.relative.max(p), absolute: self.ode.absolute.max(p), ..self.ode }
    }
}
