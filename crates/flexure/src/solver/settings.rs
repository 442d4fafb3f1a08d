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
    /// Smallest continuation step, in the scaled arc length of $(x, \lambda)$
    /// (where a step carrying the whole load without turning measures 1).
    pub min_step: f64,
    /// Largest rotation (rad) of any cross-section or body in one step.
    pub max_rotation_per_step: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self { tolerance: 1e-12, max_iterations: 50, max_steps: 1000, min_step: 1e-6, max_rotation_per_step: 0.5 }
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
        Ok(())
    }
}
