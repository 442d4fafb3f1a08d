//! The error estimate of a simulated motion: the run against a reference
//! run of the same mechanism at a tenth of its tolerances.
//!
//! The integrator controls each step's local error to its tolerance, and
//! the error it leaves in the motion is near proportional to it. A run at a
//! tenth of the tolerance then has about a tenth of the error, and their
//! difference at each sample estimates the error of the coarser run (to
//! within about 10 %): the tolerance-proportionality estimate of global
//! error that integrator suites (SUNDIALS' guide, Hairer and Wanner's
//! tests) use. The model's own error, its order, is the statics' estimate.

use super::Motion;
use crate::estimate::Accuracy;
use crate::report::BodyPose;

/// The estimated error of a [`Motion`]: the largest difference of a body's
/// position and angle from the reference run over the samples both reached,
/// with where it was and whether it misses the [`Accuracy`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MotionEstimate {
    /// The largest position difference of any body at any sample (m).
    pub position: f64,
    /// The largest rotation between a body's two frames at any sample (rad).
    pub angle: f64,
    /// The time (s) of the largest position difference, or of the largest
    /// angle when no body moved apart.
    pub at: f64,
    /// The reference run's relative tolerance.
    pub reference_tolerance: f64,
    /// The samples compared: those both runs reached.
    pub samples: usize,
    /// Whether the reference reached every sample the run did; the
    /// estimate covers only the samples compared when it did not.
    pub complete: bool,
    /// The position tolerance it is held to (m): the accuracy's fraction of
    /// the mechanism's size ([`crate::mechanism::Mechanism::size`]).
    pub position_tolerance: f64,
    /// Whether it misses the accuracy, or the reference is incomplete.
    #[serde(skip)]
    pub flagged: bool,
}

/// `run` against `reference` (the same mechanism at `reference_tolerance`),
/// held to `target` with positions scaled by `size` (m).
pub(super) fn motion_error(
    run: &Motion,
    reference: &Motion,
    (reference_tolerance, size): (f64, f64),
    target: &Accuracy,
) -> MotionEstimate {
    let samples = run.trajectory.time.len().min(reference.trajectory.time.len());
    let (mut position, mut angle, mut at, mut angle_at) = (0.0_f64, 0.0_f64, 0.0, 0.0);
    for ((_, poses), (_, reference_poses)) in run.bodies.iter().zip(&reference.bodies) {
        for k in 0..samples {
            let (p, a) = apart(&poses[k], &reference_poses[k]);
            if p > position {
                (position, at) = (p, run.trajectory.time[k]);
            }
            if a > angle {
                (angle, angle_at) = (a, run.trajectory.time[k]);
            }
        }
    }
    let complete = samples == run.trajectory.time.len();
    let position_tolerance = target.position * size;
    MotionEstimate {
        position,
        angle,
        at: if position > 0.0 { at } else { angle_at },
        reference_tolerance,
        samples,
        complete,
        position_tolerance,
        // Written so that a NaN is flagged.
        flagged: !(complete && position <= position_tolerance && angle <= target.angle),
    }
}

/// How far apart two poses of one body are: the distance of their origins
/// (m) and the angle of the rotation between their frames (rad).
fn apart(a: &BodyPose, b: &BodyPose) -> (f64, f64) {
    let (pa, pb) = (a.position(), b.position());
    let distance = (0..3).map(|i| (pa[i] - pb[i]).powi(2)).sum::<f64>().sqrt();
    let (ra, rb) = (a.rotation(), b.rotation());
    // R = Raᵀ Rb: its angle from the skew part's norm and the trace, by atan2 (exact near 0).
    let r = |i: usize, j: usize| (0..3).map(|k| ra[k][i] * rb[k][j]).sum::<f64>();
    let skew = ((r(2, 1) - r(1, 2)).powi(2) + (r(0, 2) - r(2, 0)).powi(2) + (r(1, 0) - r(0, 1)).powi(2)).sqrt();
    let trace = r(0, 0) + r(1, 1) + r(2, 2);
    (distance, skew.atan2(trace - 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The angle between two planar frames is the difference of their
    /// angles (closed form), to rounding, from 1e-9 rad to near a half turn.
    #[test]
    fn the_angle_apart_is_the_turn_between_the_frames() {
        for (phi, turn) in [(0.3, 1e-9), (-2.0, 0.5), (1.0, 3.1)] {
            let a = BodyPose::Planar { x: 1.0, y: 2.0, phi };
            let b = BodyPose::Planar { x: 4.0, y: 6.0, phi: phi + turn };
            let (distance, angle) = apart(&a, &b);
            assert!((distance - 5.0).abs() < 1e-15 && (angle - turn).abs() < 1e-15 * (1.0 + turn), "{angle} {turn}");
        }
    }
}
