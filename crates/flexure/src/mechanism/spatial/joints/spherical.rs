//! The ball joint, in exponential coordinates.

use crate::mechanism::joints::{Joint, JointState};
use crate::space::{Spatial, exp_coefficients};
use nalgebra::{Isometry3, Matrix3, Translation3, UnitQuaternion, Vector3};

/// A ball joint about the root frame's origin. Its coordinates are the
/// rotation vector $\theta$ (axis times angle) of the output frame,
/// $R = \exp\hat\theta$, with an optional isotropic spring
/// $U = \frac12 k\lvert\theta - \theta_0\rvert^2$. Its motion subspace is the
/// left Jacobian of SO(3),
/// $$\omega = J(\theta)\thinspace\dot\theta,\qquad J = I + f_2\hat\theta + f_3\hat\theta^2,$$
/// with $f_2 = \frac{1-\cos t}{t^2}$, $f_3 = \frac{t - \sin t}{t^3}$ and $t = \lvert\theta\rvert$
/// (Murray–Li–Sastry Eq. 2.36), and its derivative
/// $\partial_b J = 2\theta_b(f_2^{\prime}\hat\theta + f_3^{\prime}\hat\theta^2) + f_2\hat e_b + f_3(\hat e_b\hat\theta + \hat\theta\hat e_b)$.
/// The chart is regular for $t < 2\pi$: a pendulum that swings through a
/// half turn is still well inside it.
///
/// # Example
/// ```
/// use flexure::mechanism::Joint;
/// use flexure::mechanism::spatial::Spherical;
/// use flexure::space::Spatial;
/// let ball = Spherical { stiffness: 0.0, rest: [0.0; 3] };
/// let s = Joint::<Spatial>::evaluate(&ball, &[0.0, 0.0, 0.5]);
/// assert!((s.pose.rotation.angle() - 0.5).abs() < 1e-15);
/// // About its own axis the rate is the coordinate's.
/// assert!((s.jacobian[(2, 2)] - 1.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spherical {
    /// N·m/rad (0: free).
    pub stiffness: f64,
    /// Spring's rest rotation vector $\theta_0$ (rad).
    pub rest: [f64; 3],
}

impl Joint<Spatial> for Spherical {
    fn dof(&self) -> usize {
        3
    }

    fn rest_into(&self, q: &mut [f64]) {
        q.copy_from_slice(&self.rest);
    }

    fn state(&self) -> JointState<Spatial> {
        let mut s = JointState::zeros(3);
        for i in 0..3 {
            s.stiffness[(i, i)] = self.stiffness;
        }
        s
    }

    fn evaluate_into(&self, q: &[f64], s: &mut JointState<Spatial>) {
        let theta = Vector3::new(q[0], q[1], q[2]);
        s.pose = Isometry3::from_parts(Translation3::identity(), UnitQuaternion::from_scaled_axis(theta));
        let c = exp_coefficients(theta.norm_squared(), 1);
        let (f2, f3, d2, d3) = (c.f[1], c.f[2], c.d[0], c.d[1]);
        let hat = theta.cross_matrix();
        let hat2 = hat * hat;
        let j = Matrix3::identity() + hat * f2 + hat2 * f3;
        s.jacobian.view_mut((0, 0), (3, 3)).copy_from(&j);
        for b in 0..3 {
            let e = Vector3::ith(b, 1.0).cross_matrix();
            let dj = (hat * d2 + hat2 * d3) * (2.0 * theta[b]) + e * f2 + (e * hat + hat * e) * f3;
            // Component i of ∂_b S_a = (∂_b J)_{ia}.
            for a in 0..3 {
                for i in 0..3 {
                    s.hessian[i][(a, b)] = dj[(i, a)];
                }
            }
        }
        let mut energy = 0.0;
        for i in 0..3 {
            let d = q[i] - self.rest[i];
            s.gradient[i] = self.stiffness * d;
            energy += 0.5 * self.stiffness * d * d;
        }
        s.energy = energy;
    }

    /// Viscous on each coordinate: N·m·s/rad.
    fn add_damping(&self, c: f64, out: &mut nalgebra::DMatrixViewMut<'_, f64>) {
        for i in 0..3 {
            out[(i, i)] += c;
        }
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
