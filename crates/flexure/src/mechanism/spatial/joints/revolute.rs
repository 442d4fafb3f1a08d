//! The hinge: a rotation about a fixed axis of the root frame.

use crate::mechanism::joints::{Joint, JointState};
use crate::space::Spatial;
use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

/// A hinge about `axis` through the root frame's origin, rotation $q$,
/// with an optional torsional spring $U = \frac12 k(q - q_0)^2$: the output
/// frame is $(\exp(q\hat a), 0)$ and the motion subspace the constant twist
/// $(a, 0)$ (URDF's `revolute`, MuJoCo's `hinge`). Named as Pinocchio names
/// a revolute joint about any axis (`JointModelRevoluteUnaligned`), apart
/// from the planar [`crate::mechanism::Revolute`] about z.
///
/// # Example
/// ```
/// use flexure::mechanism::Joint;
/// use flexure::mechanism::spatial::RevoluteUnaligned;
/// use flexure::space::Spatial;
/// let hinge = RevoluteUnaligned { axis: nalgebra::Vector3::x_axis(), stiffness: 2.0, rest: 0.0 };
/// let s = Joint::<Spatial>::evaluate(&hinge, &[0.5]);
/// assert!((s.pose.rotation.angle() - 0.5).abs() < 1e-15 && s.jacobian[(0, 0)] == 1.0);
/// assert!((s.energy - 0.25).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RevoluteUnaligned {
    /// The axis, in the root frame.
    pub axis: Unit<Vector3<f64>>,
    /// N·m/rad (0: free).
    pub stiffness: f64,
    /// Spring's rest rotation $q_0$ (rad).
    pub rest: f64,
}

impl Joint<Spatial> for RevoluteUnaligned {
    fn dof(&self) -> usize {
        1
    }

    fn rest_into(&self, q: &mut [f64]) {
        q[0] = self.rest;
    }

    fn state(&self) -> JointState<Spatial> {
        let mut s = JointState::zeros(1);
        for i in 0..3 {
            s.jacobian[(i, 0)] = self.axis[i];
        }
        s.stiffness[(0, 0)] = self.stiffness;
        s
    }

    fn evaluate_into(&self, q: &[f64], s: &mut JointState<Spatial>) {
        s.pose = Isometry3::from_parts(Translation3::identity(), UnitQuaternion::from_axis_angle(&self.axis, q[0]));
        s.energy = 0.5 * self.stiffness * (q[0] - self.rest).powi(2);
        s.gradient[0] = self.stiffness * (q[0] - self.rest);
    }

    /// Viscous: N·m·s/rad.
    fn add_damping(&self, c: f64, out: &mut nalgebra::DMatrixViewMut<'_, f64>) {
        out[(0, 0)] += c;
    }

    fn angle_row(&self) -> Option<&[f64]> {
        None
    }

    /// The body beyond turns with the joint: counted among the bodies'
    /// rotations, nothing inside.
    fn distance(&self, _: &[f64], _: &[f64], _: f64) -> f64 {
        0.0
    }
}
