//! The slider.

use super::{Joint, JointState, one_coordinate, spring};
use crate::kinematics::Pose;

/// A slider along the root frame's x axis, travel $d$, with an optional
/// spring: $U = \frac12 k(d - d_0)^2$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prismatic {
    /// N/m (0: free).
    pub stiffness: f64,
    /// Spring's rest travel $d_0$ (m).
    pub rest: f64,
}

impl Joint for Prismatic {
    fn dof(&self) -> usize {
        1
    }

    fn rest_into(&self, q: &mut [f64]) {
        q[0] = self.rest;
    }

    fn state(&self) -> JointState {
        one_coordinate(1, self.stiffness)
    }

    fn evaluate_into(&self, q: &[f64], s: &mut JointState) {
        s.pose = Pose { phi: 0.0, x: q[0], y: 0.0 };
        spring(self.stiffness, self.rest, q[0], s);
    }

    /// Viscous: N·s/m.
    fn add_damping(&self, c: f64, out: &mut nalgebra::DMatrixViewMut<'_, f64>) {
        out[(0, 0)] += c;
    }

    fn angle_row(&self) -> Option<&[f64]> {
        Some(&[0.0])
    }

    fn is_translation(&self) -> bool {
        true
    }

    /// The travel over the mechanism's size.
    fn distance(&self, a: &[f64], b: &[f64], length: f64) -> f64 {
        (a[0] - b[0]).abs() / length
    }
}
