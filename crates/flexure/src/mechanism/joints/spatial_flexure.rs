//! The spatial flexure as a joint: the second dimension behind the joint
//! interface, its tip frame the output, in SE(3).

use super::{Buffers, Joint, JointState};
use crate::kinematics::Level;
use crate::space::Spatial;
use crate::spatial::{self, SpatialFlexure, SpatialKinematics};
use nalgebra::Vector3;

impl Joint<Spatial> for SpatialFlexure {
    fn dof(&self) -> usize {
        self.coordinates()
    }

    fn rest_into(&self, q: &mut [f64]) {
        q.copy_from_slice(SpatialFlexure::rest(self));
    }

    fn state(&self) -> JointState<Spatial> {
        let n = self.coordinates();
        let mut s = JointState::zeros(n);
        s.buffers = Buffers::SpatialFlexure(Box::new(SpatialKinematics::new(self)));
        s.stiffness.copy_from_slice(self.stiffness_matrix());
        s
    }

    /// The motion subspace in the root frame, as the planar flexure's:
    /// column $a$ is $(R\omega_a, \partial_ap)$, the tip's angular velocity
    /// and its origin's velocity per unit $\alpha_a$ ($(\omega_a, v_a)$ the
    /// body Jacobian's column, $\partial_ap = Rv_a$); its derivative is
    /// $\partial_b(R\omega_a) = R(\omega_b\times\omega_a + H^{\omega}_{ab})$
    /// and $\partial_a\partial_bp$.
    fn evaluate_into(&self, q: &[f64], s: &mut JointState<Spatial>) {
        self.evaluate_level_into(q, Level::Hessian, s);
    }

    /// At [`Level::Pose`] the tip pose and energy alone (the Magnus product,
    /// 7 × a planar pose), at [`Level::Jacobian`] with the motion subspace
    /// and gradient (the Hessians of every Magnus step are what cost most).
    fn evaluate_level_into(&self, q: &[f64], level: Level, s: &mut JointState<Spatial>) {
        if !matches!(s.buffers, Buffers::SpatialFlexure(_)) {
            s.buffers = Buffers::SpatialFlexure(Box::new(SpatialKinematics::new(self)));
        }
        let Buffers::SpatialFlexure(k) = &mut s.buffers else { unreachable!("made just above") };
        spatial::update(self, q, level, k);
        s.pose = k.pose();
        let n = self.coordinates();
        spatial::energy_gradient(self, q, s.gradient.as_mut_slice());
        let mut u = 0.0;
        for ((a, k), g) in q.iter().zip(self.rest()).zip(s.gradient.iter()) {
            u += (a - k) * g;
        }
        s.energy = 0.5 * u;
        if level == Level::Pose {
            return;
        }
        let r = k.rotation;
        let omega = |a: usize| Vector3::new(k.jacobian[(0, a)], k.jacobian[(1, a)], k.jacobian[(2, a)]);
        for a in 0..n {
            let w = r * omega(a);
            let v = r * Vector3::new(k.jacobian[(3, a)], k.jacobian[(4, a)], k.jacobian[(5, a)]);
            for i in 0..3 {
                s.jacobian[(i, a)] = w[i];
                s.jacobian[(i + 3, a)] = v[i];
            }
            if level < Level::Hessian {
                continue;
            }
            for b in 0..n {
                let h = k.hessian(a, b);
                let turn = r * (omega(b).cross(&omega(a)) + Vector3::new(h[0], h[1], h[2]));
                let p = k.hessian_position(a, b);
                for i in 0..3 {
                    s.hessian[i][(a, b)] = turn[i];
                    s.hessian[i + 3][(a, b)] = p[i];
                }
            }
        }
    }

    /// $\beta K$: stiffness-proportional damping, as the planar flexure's.
    fn add_damping(&self, beta: f64, out: &mut nalgebra::DMatrixViewMut<'_, f64>) {
        let n = self.coordinates();
        for r in 0..n {
            for c in 0..n {
                out[(r, c)] += beta * self.stiffness_matrix()[r * n + c];
            }
        }
    }

    /// None: in space the tip's rotation is not linear in the coordinates,
    /// so a tree of spatial flexures takes the dense factorization.
    fn angle_row(&self) -> Option<&[f64]> {
        None
    }

    fn distance(&self, a: &[f64], b: &[f64], _: f64) -> f64 {
        spatial::rotation_between(self, a, b)
    }
}
