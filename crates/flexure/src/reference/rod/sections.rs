//! The exact rod's cross-sections at arc lengths of one's choosing, from a
//! solution's frames.
//!
//! A [`Frame`] of [`RodSolution::shape`] holds the whole state of the rod's
//! equations at its arc length (rotation, position, internal moment), so
//! the section at any $s$ is the state of the nearest frame at or before
//! $s$ carried on to $s$ by the same equations and integrator
//! ([`super::shot`]): no shooting is repeated, and the frames between
//! which $s$ lies hold no kink of the section (the integrator stops at
//! every one), so one short integration suffices.

use super::chain::frame;
use super::shot::{MU, P, STATE, rhs};
use super::{Frame, Rod, RodSolution};
use crate::error::{Error, Result};
use crate::ode::{Tolerance, integrate};
use crate::spatial::SpatialLoad;
use nalgebra::{Rotation3, UnitQuaternion, Vector3};

/// The sections of `solution` (the rod `rod` under `load`, from
/// [`super::deflect`]) at the arc lengths `at` (m, each in $[0, L]$), each
/// carried from the nearest stored frame at or before it by the rod's
/// equations to the tolerance `tolerance`.
///
/// Errors: an `at` outside $[0, L]$ or not finite, named `at`; a load
/// component that is not finite; a solution without frames; the
/// integrator's.
///
/// # Example
/// ```
/// use flexure::reference::rod::{self, Rod, sections};
/// use flexure::section::SpatialSection;
/// use flexure::spatial::SpatialLoad;
/// // Pure twist TL/GJ: the section at s has turned by s·T/GJ about x.
/// let rod = Rod::new(2.0, SpatialSection::uniform(0.5, 1.0, 1.0).unwrap()).unwrap();
/// let load = SpatialLoad { moment: [0.1, 0.0, 0.0], force: [0.0; 3] };
/// let s = rod::deflect(&rod, &load, &Default::default()).unwrap();
/// let at = sections(&rod, &load, &s, &[0.5, 2.0], &Default::default()).unwrap();
/// assert!((at[0].rotation[(2, 1)] - 0.1f64.sin()).abs() < 1e-10 && (at[0].position.x - 0.5).abs() < 1e-10);
/// assert!((at[1].position - s.position).norm() < 1e-12);
/// ```
pub fn sections(
    rod: &Rod,
    load: &SpatialLoad,
    solution: &RodSolution,
    at: &[f64],
    tolerance: &Tolerance,
) -> Result<Vec<Frame>> {
    load.validate()?;
    tolerance.validate()?;
    let l = rod.length;
    if solution.shape.is_empty() {
        return Err(Error::invalid("solution", "no frames", "must come from rod::deflect"));
    }
    // The state's scale, as the chain's: the softest stiffness at mid-length over L.
    let k = rod.section.stiffness(0.5).into_iter().fold(f64::INFINITY, f64::min) / l;
    let f = Vector3::from(load.force) / k;
    let field = rhs(rod, k, [f.x, f.y, f.z]);
    at.iter()
        .map(|&s| {
            if !(s.is_finite() && (0.0..=l).contains(&s)) {
                return Err(Error::invalid("at", s, "must be an arc length from 0 to the rod's length"));
            }
            let i = solution.shape.partition_point(|p| p.s <= s).saturating_sub(1);
            let from = &solution.shape[i];
            if from.s == s {
                return Ok(*from);
            }
            let y = integrate(&field, from.s, s, state(from, l, k), tolerance, |_, _| {})?;
            Ok(frame(s, &y, l, k))
        })
        .collect()
}

/// The rod's state of `frame` (the inverse of the chain's `frame`): its quaternion $(w, x, y, z)$, $p/L$ and $\mu = m/k$.
fn state(frame: &Frame, l: f64, k: f64) -> [f64; STATE] {
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix(&frame.rotation));
    let mut y = [0.0; STATE];
    y[..4].copy_from_slice(&[q.w, q.i, q.j, q.k]);
    for i in 0..3 {
        y[P + i] = frame.position[i] / l;
        y[MU + i] = frame.moment[i] / k;
    }
    y
}
