//! The settings of [`super::newton`](fn@super::newton) and [`super::continuation`](fn@super::continuation): tolerance and bounds.

#[cfg(doc)]
use super::{Problem, continuation, newton};
use crate::error::{Error, Result};

/// Settings of [`newton`](fn@newton) and [`continuation`](fn@continuation), validated by [`Settings::validate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Relative tolerance: converged when $\max_i|r_i| \le$ tolerance × [`Problem::scale`].
    pub tolerance: f64,
    /// Newton iterations per solve (per continuation step).
    pub max_iterations: usize,
    /// Continuation steps before giving up.
    pub max_steps: usize,
    /// Evaluations of the problem with its Jacobian that one continuation
    /// may make, over every step it tries (accepted or rejected) and their
    /// Newton iterations: the bound on its work, whatever its steps'
    /// lengths. Past it the continuation stops where it got
    /// ([`super::Stop::WorkCap`]). One evaluation of a spatial flexure
    /// costs about $Mn^2$, $n$ its coordinates and $M$ its subintervals: at
    /// orders [64, 64, 64] ($n = 192$, $M = 1008$) some ten thousand times
    /// one at orders [3, 3, 3], so there the default bound is reached only
    /// after minutes; a solve that needs that many evaluations at such
    /// orders asks for a resolution its load does not allow (a boundary
    /// layer thinner than the orders resolve), and lower orders answer it.
    pub max_evaluations: usize,
    /// Smallest continuation step, in the scaled arc length of $(x, \lambda)$
    /// (where a step carrying the whole load without turning measures 1).
    pub min_step: f64,
    /// Largest rotation (rad) of any cross-section or body in one step.
    pub max_rotation_per_step: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            tolerance: 1e-12,
            max_iterations: 50,
            max_steps: 1000,
            max_evaluations: 20_000,
            min_step: 1e-6,
            max_rotation_per_step: 0.5,
        }
    }
}

/// The most iterations or steps a setting may ask for: enough for any
/// problem this library solves, small enough that a run always ends.
pub const MAX_COUNT: usize = 1_000_000;

impl Settings {
    /// Checks every setting: zero, negative or non-finite is an error naming it.
    ///
    /// # Example
    /// ```
    /// let bad = flexure::solver::Settings { min_step: 0.0, ..Default::default() };
    /// assert!(bad.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<()> {
        let positive = |name: &'static str, v: f64, max: f64| {
            if v.is_finite() && v > 0.0 && v <= max {
                Ok(())
            } else {
                Err(Error::invalid(name, v, "must be a finite number greater than zero (and at most 1 for min_step)"))
            }
        };
        positive("tolerance", self.tolerance, 1.0)?;
        if self.tolerance < 1e-15 {
            // Below rounding no residual can meet it: Newton would spin to its limit.
            return Err(Error::invalid(
                "tolerance",
                self.tolerance,
                "must be at least 1e-15 (double-precision rounding)",
            ));
        }
        positive("min_step", self.min_step, 1.0)?;
        positive("max_rotation_per_step", self.max_rotation_per_step, f64::MAX)?;
        crate::error::count("max_iterations", self.max_iterations, MAX_COUNT, "must be from 1 to 1000000")?;
        crate::error::count("max_steps", self.max_steps, MAX_COUNT, "must be from 1 to 1000000")?;
        crate::error::count("max_evaluations", self.max_evaluations, MAX_COUNT, "must be from 1 to 1000000")?;
        Ok(())
    }
}
