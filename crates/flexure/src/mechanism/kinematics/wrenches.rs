//! The same-joint parts of SE(3) Hessians as wrenches on each joint, and
//! the derivative of a dead moment's generalized force: what space has and
//! the plane does not (planar rotations commute and no planar joint has a
//! curved angle).
//!
//! Within a joint, a weight $u$ on $x$ meets $H$ only through
//! $$u\cdot\partial_{ab}x - u\cdot(\omega_a\times(\omega_b\times r)) = (R_A^T\tilde u)\cdot H_{ab}^{p} + (R_A^T(r\times u))\cdot H_{ab}^{\omega},$$
//! ($\tilde u = \epsilon u$), a wrench on $S$'s derivative, and a dead moment
//! $\mu$ through $(R_A^T\mu)\cdot H_{ab}^{\omega}$. So the Lagrangian sums,
//! per joint, the root-frame wrench $W_j$ of everything whose path passes
//! through it, and the joint adds $\sum_c W_{j,c}\thinspace\partial_b S_a^{c}$
//! once ([`crate::mechanism::Joint::add_wrench_hessian`]). From frames
//! evaluated at [`Level::Hessian`] that contraction reads the joints'
//! Hessians (exact); from [`Level::Jacobian`] frames each joint makes it
//! from its Jacobian-level data, which for the spatial flexure is the
//! virtual work's quadrature (within $h^6$ of the exact one; about a tenth
//! of the cost of its Hessian). The statics' Newton matrix takes the
//! latter; stiffness, compliance, modes, buckling and dynamics evaluate
//! frames at [`Level::Hessian`], and so the former.

use super::Frames;
use crate::kinematics::Level;
use crate::mechanism::Mechanism;
use crate::mechanism::joints::add_contracted_hessian;
use crate::space::Spatial;
use nalgebra::{DMatrix, Matrix3, Vector3};

/// The same-joint parts of weighted second derivatives, gathered per joint
/// (the module docs): for joint $j$, the world wrench $W_j = (M_j, F_j)$,
/// moment about its output origin $o_j$, and the matrix $N_j$ of the turn
/// of the turn, summed over every weighted vector whose path passes through $j$,
/// $$M_j = \sum r\times u + \sum\mu,\qquad F_j = \sum\epsilon\thinspace u,\qquad N_j = \sum r\thinspace u^T - (u\cdot r)\thinspace I,$$
/// ($\mu$ a dead moment's weight, [`add_rotation_derivative`]). Joint $j$'s
/// block of the Hessian is then
/// $\sum_c W_{j,c}\thinspace\partial_bS^c_a$ with $W_j$ turned into its root frame
/// ([`crate::mechanism::Joint::add_wrench_hessian`], one call per joint)
/// plus $\omega_a^TN_j\thinspace\omega_b$, which is
/// $u\cdot(\omega_a\times(\omega_b\times r))$ summed.
#[derive(Debug, Clone)]
pub struct JointWrenches {
    moment: Vec<Vector3<f64>>,
    force: Vec<Vector3<f64>>,
    turn: Vec<Matrix3<f64>>,
    touched: Vec<bool>,
}

impl JointWrenches {
    /// Empty sums for the joints of `m`.
    pub(crate) fn new(m: &Mechanism<Spatial>) -> Self {
        let n = m.joints.len();
        JointWrenches {
            moment: vec![Vector3::zeros(); n],
            force: vec![Vector3::zeros(); n],
            turn: vec![Matrix3::zeros(); n],
            touched: vec![false; n],
        }
    }

    /// Adds every joint's gathered block to `h` and empties the sums.
    pub(crate) fn flush(&mut self, m: &Mechanism<Spatial>, f: &Frames<Spatial>, h: &mut DMatrix<f64>) {
        for j in 0..self.touched.len() {
            if std::mem::take(&mut self.touched[j]) {
                add_same_joint(m, f, j, &self.moment[j], &self.force[j], &self.turn[j], h);
                self.moment[j] = Vector3::zeros();
                self.force[j] = Vector3::zeros();
                self.turn[j] = Matrix3::zeros();
            }
        }
    }
}

/// Adds the world wrench `(moment, force)` and turn matrix of joint `j` to
/// `sink`, or (`None`) straight into `h`.
pub(super) fn same_joint(
    m: &Mechanism<Spatial>,
    f: &Frames<Spatial>,
    j: usize,
    (moment, force, turn): (Vector3<f64>, Vector3<f64>, Matrix3<f64>),
    sink: Option<&mut JointWrenches>,
    h: &mut DMatrix<f64>,
) {
    match sink {
        Some(w) => {
            w.moment[j] += moment;
            w.force[j] += force;
            w.turn[j] += turn;
            w.touched[j] = true;
        }
        None => add_same_joint(m, f, j, &moment, &force, &turn, h),
    }
}

/// Adds joint `j`'s block for the world wrench `(moment, force)` and turn
/// matrix `turn` ([`JointWrenches`]) to `h`: from the joint's Hessian when
/// the frames carry it ([`Level::Hessian`]), else by the joint's own
/// contraction.
fn add_same_joint(
    m: &Mechanism<Spatial>,
    f: &Frames<Spatial>,
    j: usize,
    moment: &Vector3<f64>,
    force: &Vector3<f64>,
    turn: &Matrix3<f64>,
    h: &mut DMatrix<f64>,
) {
    let spec = &m.joints[j];
    let state = &f.joints[j];
    let (o, k) = (spec.offset, state.gradient.len());
    let rotation = f.root_turn(j);
    let (mr, fr) = (rotation.tr_mul(moment), rotation.tr_mul(force));
    let wrench = [mr.x, mr.y, mr.z, fr.x, fr.y, fr.z];
    {
        let mut block = h.view_mut((o, o), (k, k));
        if f.level() >= Level::Hessian {
            add_contracted_hessian(state, &wrench, &mut block);
        } else {
            spec.kind.joint().add_wrench_hessian(&f.coordinates[o..o + k], state, &wrench, &mut block);
        }
    }
    if *turn != Matrix3::zeros() {
        for b in 0..k {
            let nb = turn * f.omega[o + b];
            for a in 0..k {
                h[(o + a, o + b)] += f.omega[o + a].dot(&nb);
            }
        }
    }
}

/// Adds $\partial_b(\mu\cdot\omega_a)$ at $(a, b)$ to `k`, for body `body`'s
/// angular velocity $\sum_a\omega_a\dot q_a$ and a vector $\mu$ fixed in the
/// world (a dead moment's generalized force $Q_a = \mu\cdot\omega_a$): not
/// symmetric, since a moment fixed in space has no potential. Within a
/// joint as [`super::add_attached_hessian`]; the same-joint parts go to
/// `sink` when given.
pub fn add_rotation_derivative(
    m: &Mechanism<Spatial>,
    f: &Frames<Spatial>,
    body: usize,
    mu: &Vector3<f64>,
    k: &mut DMatrix<f64>,
    mut sink: Option<&mut JointWrenches>,
) {
    if *mu == Vector3::zeros() {
        return;
    }
    for ja in chain(m, body) {
        let oa = m.joints[ja].offset;
        same_joint(m, f, ja, (*mu, Vector3::zeros(), Matrix3::zeros()), sink.as_deref_mut(), k);
        // ∂_b ω_a = ω_b × ω_a for b in a joint upstream.
        for jb in chain(m, m.joints[ja].parent) {
            let ob = m.joints[jb].offset;
            for b in 0..f.joints[jb].gradient.len() {
                let mxw = mu.cross(&f.omega[ob + b]);
                for a in 0..f.joints[ja].gradient.len() {
                    // μ·(ω_b × ω_a) = ω_a·(μ × ω_b).
                    k[(oa + a, ob + b)] += f.omega[oa + a].dot(&mxw);
                }
            }
        }
    }
}

/// The joints from the one moving `body` down to the ground.
fn chain(m: &Mechanism<Spatial>, body: usize) -> impl Iterator<Item = usize> + '_ {
    std::iter::successors(m.parent_joint(body), |&j| m.parent_joint(m.joints[j].parent))
}
