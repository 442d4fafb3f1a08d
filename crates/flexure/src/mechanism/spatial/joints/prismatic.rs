//! The slider: a translation along a fixed axis of the root frame.

use crate::mechanism::joints::{Joint, JointState};
use crate::space::Spatial;
use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

/// A slider along `axis`, travel $q$, with an optional linear spring
/// $U = \frac12 k(q - q_0)^2$: the output frame is $(I, q a)$ and the motion
/// subspace the constant twist $(0, a)$ (URDF's `prismatic`, MuJoCo's `slide`).
/// Named as Pinocchio names a prismatic joint along any axis
/// (`JointModelPrismaticUnaligned`), apart from the planar
/// [`crate::mechanism::Prismatic`].
///
/// # Example
/// ```
/// use flexure::mechanism::Joint;
/// use flexure::mechanism::spatial::PrismaticUnaligned;
/// use flexure::space::Spatial;
/// let slide = PrismaticUnaligned { axis: nalgebra::Vector3::z_axis(), stiffness: 0.0, rest: 0.0 };
/// let s = Joint::<Spatial>::evaluate(&slide, &[0.25]);
/// assert_eq!((s.pose.translation.vector.z, s.jacobian[(5, 0)]), (0.25, 1.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrismaticUnaligned {
    /// The axis, in the root frame.
    pub axis: Unit<Vector3<f64>>,
    /// N/m (0: free).
    pub stiffness: f64,
    /// Spring's rest travel $q_0$ (m).
    pub rest: f64,
}

impl Joint<Spatial> for PrismaticUnaligned {
    fn dof(&self) -> usize {
        1
    }

    fn rest_into(&self, q: &mut [f64]) {
        q[0] = self.rest;
    }

    fn state(&self) -> JointState<Spatial> {
        let mut s = JointState::zeros(1);
        for i in 0..3 {
            s.jacobian[(i + 3, 0)] = self.axis[i];
        }
        s.stiffness[(0, 0)] = self.stiffness;
        s
    }

    fn evaluate_into(&self, q: &[f64], s: &mut JointState<Spatial>) {
        s.pose = Isometry3::from_parts(Translation3::from(self.axis.into_inner() * q[0]), UnitQuaternion::identity());
        s.energy = 0.5 * self.stiffness * (q[0] - self.rest).powi(2);
        s.gradient[0] = self.stiffness * (q[0] - self.rest);
    }

    /// Viscous: N·s/m.
    fn add_damping(&self, c: f64, out: &mut nalgebra::DMatrixViewMut<'_, f64>) {
        out[(0, 0)] += c;
    }

    fn angle_row(&self) -> Option<&[f64]> {
        None
    }

    fn is_translation(&self) -> bool {
        true
    }

    /// Its travel over the mechanism's size, to compare with rotations.
    fn distance(&self, a: &[f64], b: &[f64], length: f64) -> f64 {
        (a[0] - b[0]).abs() / length
    }
}
