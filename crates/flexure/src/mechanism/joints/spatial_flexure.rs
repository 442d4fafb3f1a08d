//! The spatial flexure as a joint: the second dimension behind the joint
//! interface, its tip frame the output, in SE(3).

use super::{Buffers, Joint, JointState, add_contracted_hessian};
use crate::kinematics::Level;
use crate::space::Spatial;
use crate::spatial::work::{self, Quadrature, Work};
use crate::spatial::{self, SpatialFlexure, SpatialKinematics};
use nalgebra::Vector3;
use std::cell::{OnceCell, RefCell};

/// A spatial flexure's buffers in its [`JointState`]: its kinematics, and
/// the tables and scratch of the virtual work's quadrature
/// ([`Joint::add_wrench_hessian`]), made on its first call (frames that only
/// bound a step never need them); that call reads the state, so they sit
/// behind cells.
#[derive(Debug, Clone)]
pub(super) struct Data {
    kinematics: SpatialKinematics,
    contraction: OnceCell<(Quadrature, RefCell<Work<f64>>)>,
}

impl Data {
    fn new(flexure: &SpatialFlexure) -> Self {
        Data { kinematics: SpatialKinematics::new(flexure), contraction: OnceCell::new() }
    }
}

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
        s.buffers = Buffers::SpatialFlexure(Box::new(Data::new(self)));
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
        if !matches!(&s.buffers, Buffers::SpatialFlexure(d) if d.kinematics.fits(self)) {
            s.buffers = Buffers::SpatialFlexure(Box::new(Data::new(self)));
        }
        let Buffers::SpatialFlexure(data) = &mut s.buffers else { unreachable!("made just above") };
        let k = &mut data.kinematics;
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

    /// The contraction by quadrature of the virtual work (`spatial::work`,
    /// as [`crate::spatial::deflect`] takes its Newton matrix), from the
    /// Jacobian-level data alone. $D_{ab} = \partial_b(w\cdot S_a)$ is
    /// $\partial_bQ_a$ of the dead tip wrench $w = (M, F)$; its symmetric part
    /// is taken from the quadrature (which meets the Magnus product's exact
    /// derivative to the rule's $h^6$) and its skew part exactly, from the
    /// motion subspace: for any joint,
    /// $\partial_b S_a^{\omega} - \partial_a S_b^{\omega} = S_b^{\omega}\times S_a^{\omega}$
    /// and the position's Hessian is symmetric, so
    /// $$D_{ab} = \tfrac12\big(\partial_bQ_a + \partial_aQ_b\big) + \tfrac12\thinspace M\cdot\big(S_b^{\omega}\times S_a^{\omega}\big).$$
    /// Costs about one Jacobian-level evaluation, against the Magnus
    /// product's second derivatives at [`Level::Hessian`] (about ten).
    fn add_wrench_hessian(
        &self,
        q: &[f64],
        state: &JointState<Spatial>,
        wrench: &[f64],
        out: &mut nalgebra::DMatrixViewMut<'_, f64>,
    ) {
        let n = self.coordinates();
        let Buffers::SpatialFlexure(data) = &state.buffers else {
            // Data not made by this kind holds no quadrature: the exact contraction.
            return add_contracted_hessian(state, wrench, out);
        };
        let moment = Vector3::new(wrench[0], wrench[1], wrench[2]);
        let force = Vector3::new(wrench[3], wrench[4], wrench[5]);
        let mut add = |quadrature: &Quadrature, w: &mut Work<f64>| {
            work::evaluate(self, quadrature, q, (moment, force), true, w);
            let s = &state.jacobian;
            let turn = |a: usize| Vector3::new(s[(0, a)], s[(1, a)], s[(2, a)]);
            for b in 0..n {
                let wb = turn(b);
                for a in 0..n {
                    // ∂_b Q_a is at [b n + a].
                    let symmetric = 0.5 * (w.derivative[b * n + a] + w.derivative[a * n + b]);
                    out[(a, b)] += symmetric + 0.5 * moment.dot(&wb.cross(&turn(a)));
                }
            }
        };
        let (quadrature, work) =
            data.contraction.get_or_init(|| (Quadrature::new(self), RefCell::new(Work::new(self))));
        let mut cell = work.try_borrow_mut().ok();
        match cell.as_deref_mut() {
            Some(w) if work::fits(self, quadrature, w) => add(quadrature, w),
            // Buffers of another flexure (or in use): fresh ones.
            _ => add(&Quadrature::new(self), &mut Work::new(self)),
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

    /// Each component's coefficients (twist, then the two bendings) as the
    /// planar flexure's.
    fn error_weights(&self, out: &mut [f64]) {
        let mut rest = out;
        for n in self.orders() {
            let (part, tail) = rest.split_at_mut(n);
            crate::basis::angle_shape_rms_each(part);
            rest = tail;
        }
    }

    fn distance(&self, a: &[f64], b: &[f64], _: f64) -> f64 {
        spatial::rotation_between(self, a, b)
    }
}
