//! The pin joint.

use super::{Joint, JointState, one_coordinate, spring};
use crate::kinematics::Pose;

/// A pin joint about the root frame's origin, rotation $\phi$, with an
/// optional torsional spring: $U = \frac12 k(\phi - \phi_0)^2$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Revolute {
    /// N·m/rad (0: free).
    pub stiffness: f64,
    /// Spring's rest rotation $\phi_0$ (rad).
    pub rest: f64,
}

impl Joint for Revolute {
    fn dof(&self) -> usize {
        1
    }

    fn rest_into(&self, q: &mut [f64]) {
        q[0] = self.rest;
    }

    fn state(&self) -> JointState {
        one_coordinate(0, self.stiffness)
    }

    fn evaluate_into(&self, q: &[f64], s: &mut JointState) {
        s.pose = Pose { phi: q[0], x: 0.0, y: 0.0 };
        spring(self.stiffness, self.rest, q[0], s);
    }

    /// Viscous: N·m·s/rad.
    fn add_damping(&self, c: f64, out: &mut nalgebra::DMatrixViewMut<'_, f64>) {
        out[(0, 0)] += c;
    }

    fn angle_row(&self) -> Option<&[f64]> {
        Some(&[1.0])
    }

    /// The body beyond turns with the joint: counted among the bodies'
    /// rotations, nothing inside.
    fn distance(&self, _: &[f64], _: &[f64], _: f64) -> f64 {
        0.0
    }
}
