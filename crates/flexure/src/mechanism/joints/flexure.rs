//! The Smooth Curvature flexure as a joint: its tip frame is the output.

use super::{Buffers, Joint, JointState};
use crate::energy::{energy_gradient, stiffness};
use crate::error::Result;
use crate::flexure::Flexure;
use crate::kinematics::{self, Kinematics, Level};
use crate::mass::MassModel;

impl Joint for Flexure {
    fn dof(&self) -> usize {
        self.order()
    }

    fn rest_into(&self, q: &mut [f64]) {
        q.copy_from_slice(Flexure::rest(self));
    }

    fn state(&self) -> JointState {
        let n = self.order();
        let mut s = JointState::zeros(n);
        s.buffers = Buffers::Flexure(Box::new(Kinematics::new(self)));
        for i in 0..n {
            for j in 0..n {
                s.stiffness[(i, j)] = stiffness(self, i, j);
            }
        }
        s
    }

    fn evaluate_into(&self, q: &[f64], s: &mut JointState) {
        if !matches!(s.buffers, Buffers::Flexure(_)) {
            s.buffers = Buffers::Flexure(Box::new(Kinematics::new(self)));
        }
        let Buffers::Flexure(k) = &mut s.buffers else { unreachable!("made just above") };
        kinematics::update(self, q, k, Level::Hessian);
        s.pose = k.pose_root_tip;
        // The update writes every entry of these (same-shaped) buffers:
        // exchanged, not copied, the state's old ones are the next update's.
        // The tip angle is linear in α (Eq. 11): its Hessian stays zero.
        std::mem::swap(&mut s.jacobian, &mut k.jacobian_root_tip);
        std::mem::swap(&mut s.hessian[1], &mut k.hessian_root_tip_x);
        std::mem::swap(&mut s.hessian[2], &mut k.hessian_root_tip_y);
        energy_gradient(self, q, s.gradient.as_mut_slice());
        // crate::energy::energy's sum, from the gradient just computed.
        let mut u = 0.0;
        for ((a, k), g) in q.iter().zip(self.rest()).zip(s.gradient.iter()) {
            u += (a - k) * g;
        }
        s.energy = u * 0.5;
    }

    /// $\beta K$: stiffness-proportional damping.
    fn add_damping(&self, beta: f64, out: &mut nalgebra::DMatrixViewMut<'_, f64>) {
        let k = self.order();
        for r in 0..k {
            for c in 0..k {
                out[(r, c)] += beta * self.stiffness_matrix()[r * k + c];
            }
        }
    }

    fn angle_row(&self) -> Option<&[f64]> {
        Some(self.tip_angle_row())
    }

    /// Each node's section turns by $\sum_i\psi_i(t_k)(a_i - b_i)$ relative to the root.
    fn distance(&self, a: &[f64], b: &[f64], _: f64) -> f64 {
        let mut d = 0.0_f64;
        for psi in self.psi_rows() {
            let turn: f64 = psi.iter().zip(a.iter().zip(b)).map(|(p, (a, b))| p * (a - b)).sum();
            d = d.max(turn.abs());
        }
        d
    }

    fn error_weights(&self, out: &mut [f64]) {
        crate::basis::angle_shape_rms_each(out);
    }

    fn inertia(&self) -> Option<Result<MassModel>> {
        self.section().mass_per_length(0.5, self.length())?;
        Some(MassModel::new(self, None))
    }

    fn flexure(&self) -> Option<&Flexure> {
        Some(self)
    }
}
