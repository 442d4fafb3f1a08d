//! The integrator's settings: the duration, samples, tolerances and limits
//! of a run, checked before any work.

use crate::error::{Error, Result};

/// Settings of [`integrate`](super::integrate), checked by [`MotionSettings::validate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionSettings {
    /// Duration $T$ (s): the motion is integrated over $[0, T]$.
    pub duration: f64,
    /// Sample interval $\Delta t$ (s): states are reported at $0, \Delta t,
    /// 2\Delta t, \ldots$ and $T$.
    pub every: f64,
    /// Relative tolerance of each step's local error.
    pub tolerance: f64,
    /// Absolute tolerance of each step's local error, in the coordinates'
    /// units (rad, m) and those per second for velocities.
    pub absolute: f64,
    /// Largest step (s); `f64::INFINITY` for none.
    pub max_step: f64,
    /// Largest rotation (rad) of any section or body in one step.
    pub max_rotation_per_step: f64,
    /// Steps tried (accepted and rejected) before giving up; `None` (the
    /// default) follows the samples asked for: $10^6$ plus 10 per sample
    /// ([`MotionSettings::step_budget`]).
    pub max_steps: Option<usize>,
    /// Successive rejections of one step before giving up.
    pub max_rejections: usize,
}

impl Default for MotionSettings {
    fn default() -> Self {
        Self {
            duration: 1.0,
            every: 0.01,
            tolerance: 1e-8,
            absolute: 1e-8,
            max_step: f64::INFINITY,
            max_rotation_per_step: 0.5,
            max_steps: None,
            max_rejections: 50,
        }
    }
}

/// The most samples a run may report.
pub const MAX_SAMPLES: usize = 1_000_000;

/// The largest step budget that may be set ([`MotionSettings::max_steps`]).
pub const MAX_STEPS: usize = 1_000_000_000;

impl MotionSettings {
    /// Checks every setting: a duration, interval or tolerance that is not a
    /// finite number greater than zero is an error naming it.
    ///
    /// # Example
    /// ```
    /// use flexure::{dynamics::integrate::MotionSettings, Error};
    /// let bad = MotionSettings { every: 0.0, ..Default::default() };
    /// assert!(matches!(bad.validate(), Err(Error::InvalidParameter { name: "every", .. })));
    /// ```
    pub fn validate(&self) -> Result<()> {
        use crate::error::positive;
        positive("duration", self.duration)?;
        if self.duration < 1e-12 {
            return Err(Error::invalid("duration", self.duration, "must be at least 1e-12 s"));
        }
        positive("every", self.every)?;
        positive("tolerance", self.tolerance)?;
        positive("absolute", self.absolute)?;
        if self.tolerance > 1.0 {
            return Err(Error::invalid("tolerance", self.tolerance, "must be at most 1 (a relative error)"));
        }
        if self.tolerance < 1e-14 {
            return Err(Error::invalid(
                "tolerance",
                self.tolerance,
                "must be at least 1e-14 (double-precision rounding)",
            ));
        }
        if self.max_step.is_nan() || self.max_step <= 0.0 {
            return Err(Error::invalid("max_step", self.max_step, "must be greater than zero (or infinite for none)"));
        }
        positive("max_rotation_per_step", self.max_rotation_per_step)?;
        if let Some(k) = self.max_steps {
            crate::error::count("max_steps", k, MAX_STEPS, "must be from 1 to 1000000000")?;
        }
        crate::error::count("max_rejections", self.max_rejections, 1000, "must be from 1 to 1000")?;
        if self.duration / self.every > MAX_SAMPLES as f64 {
            return Err(Error::invalid("every", self.every, "gives more than 1000000 samples over the duration"));
        }
        Ok(())
    }

    /// The steps a run may try: [`MotionSettings::max_steps`], or $10^6$ plus 10
    /// per sample (a sample ends a step, so a run of $10^6$ samples is not
    /// cut short by a budget of $10^6$ steps).
    ///
    /// # Example
    /// ```
    /// use flexure::dynamics::integrate::MotionSettings;
    /// let s = MotionSettings { duration: 1.0, every: 1e-6, ..Default::default() };
    /// assert_eq!(s.step_budget(), 1_000_000 + 10 * 1_000_001);
    /// assert_eq!(MotionSettings { max_steps: Some(500), ..s }.step_budget(), 500);
    /// ```
    pub fn step_budget(&self) -> usize {
        let samples = (self.duration / self.every).ceil().min(MAX_SAMPLES as f64) as usize + 1;
        self.max_steps.unwrap_or(1_000_000 + 10 * samples)
    }

    /// The sample times $0, \Delta t, 2\Delta t, \ldots, T$ (a last interval
    /// shorter than $10^{-9}\Delta t$ is merged into $T$).
    pub fn times(&self) -> Vec<f64> {
        let mut times = vec![0.0];
        let mut k = 1usize;
        while (k as f64) * self.every < self.duration - 1e-9 * self.every {
            times.push(k as f64 * self.every);
            k += 1;
        }
        times.push(self.duration);
        times
    }
}
