//! The result of a run: the states and energy at the sample times.

use crate::dynamics::System;
use crate::error::Result;

/// A simulated motion, sampled at [`Settings::times`](super::Settings::times).
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
) -> Result<()> {
    // The energy first: a sample that cannot be evaluated is not half recorded.
    let energy = system.energy(q, v, t)?;
    run.time.push(t);
    run.coordinates.extend_from_slice(q);
    run.velocities.extend_from_slice(v);
    run.energy.push(energy);
    Ok(())
}
