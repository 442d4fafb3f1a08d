//! The result of a run: the states and energy at the sample times.

use crate::dynamics::System;
use crate::error::{Error, Result};

/// Why a run ended, as argmin's `TerminationReason` says why an optimizer
/// did ([`Trajectory::stop`]); serialized as `{"reason": "reached"}` and so on.
///
/// [`integrate`](super::integrate) returns only runs that reached their
/// duration; [`integrate_kept`](super::integrate_kept) also returns the
/// samples of a run that ended early, with the error that ended it, which
/// this names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum TrajectoryStop {
    /// It recorded every sample up to [`MotionSettings::duration`](super::MotionSettings::duration).
    Reached,
    /// The step fell to rounding, or a rejection, step or pace limit was
    /// reached: [`Error::IntegrationStalled`].
    Stalled,
    /// The hook of [`crate::solver::with_interrupt`] asked it to stop:
    /// [`Error::InterruptedAt`].
    Interrupted,
    /// The system could not evaluate a state it reached (its dynamics at a
    /// step's start, or a sample's energy): the system's own error.
    Failed,
}

impl TrajectoryStop {
    /// The way a run ends with `error`.
    pub(super) fn of(error: &Error) -> Self {
        match error {
            Error::IntegrationStalled { .. } => Self::Stalled,
            Error::InterruptedAt { .. } => Self::Interrupted,
            _ => Self::Failed,
        }
    }
}

/// A simulated motion, sampled at [`MotionSettings::times`](super::MotionSettings::times).
///
/// It serializes with its fields' names; `coordinates` and `velocities`
/// stay flat, `dim` per sample.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Trajectory {
    /// Number of coordinates $n$.
    pub dim: usize,
    /// Sample times (s).
    pub time: Vec<f64>,
    /// Coordinates $q$ at each sample, $n$ per sample.
    pub coordinates: Vec<f64>,
    /// Velocities $\dot q$ at each sample, $n$ per sample.
    pub velocities: Vec<f64>,
    /// [`System::energy`] at each sample (J).
    pub energy: Vec<f64>,
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps (error test, rotation bound or Newton failure).
    pub rejected: usize,
    /// Largest closure violation $\max_k\lvert c_k(q)\rvert$ over the
    /// start and every accepted step (0 without closures).
    pub violation: f64,
    /// Why it ended: [`TrajectoryStop::Reached`] unless it ended before its duration.
    pub stop: TrajectoryStop,
}

impl Trajectory {
    /// The coordinates at sample `k`.
    pub fn q(&self, k: usize) -> &[f64] {
        &self.coordinates[k * self.dim..(k + 1) * self.dim]
    }

    /// The velocities at sample `k`.
    pub fn v(&self, k: usize) -> &[f64] {
        &self.velocities[k * self.dim..(k + 1) * self.dim]
    }
}

pub(super) fn record<S: System + ?Sized>(
    system: &mut S,
    run: &mut Trajectory,
    t: f64,
    q: &[f64],
    v: &[f64],
    multipliers: Option<&[f64]>,
) -> Result<()> {
    // The energy first: a sample that cannot be evaluated is not half recorded.
    let energy = system.energy(q, v, t)?;
    system.sampled(t, q, v, multipliers)?;
    run.time.push(t);
    run.coordinates.extend_from_slice(q);
    run.velocities.extend_from_slice(v);
    run.energy.push(energy);
    let columns = system.sample_columns();
    let sample = super::progress::Sample { time: t, coordinates: q, velocities: v, energy, columns: &columns };
    super::progress::sampled(&sample);
    Ok(())
}
