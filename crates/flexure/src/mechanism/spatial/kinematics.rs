//! Body frames, and Jacobians and Hessians of points and directions fixed
//! in bodies, chained through the tree in SE(3).
//!
//! Coordinate $a$ of joint $j$ moves everything beyond the joint by the
//! world twist $(\omega_a, v_a)$: $\omega_a = R_A\thinspace S_a^{\omega}$ and
//! $v_a = R_A\thinspace S_a^{p}$, the joint's motion subspace
//! ([`crate::mechanism::JointState::jacobian`]) turned by its root frame $A$,
//! $v_a$ the velocity of its output origin $o_j$. A vector $x$ fixed in a
//! body beyond the joint, a point ($\epsilon = 1$) or a direction
//! ($\epsilon = 0$), moves by
//! $$\partial_a x = \epsilon\thinspace v_a + \omega_a\times r,\qquad r = x - \epsilon\thinspace o_j .$$
//! Its second derivatives: for $b$ in a joint upstream of $a$'s,
//! $\partial_{ab}x = \omega_b\times\partial_a x$ (the whole of joint $j$'s
//! motion turns with $b$; the Jacobi identity folds the terms); within one
//! joint,
//! $$\partial_{ab}x = \epsilon R_A H_{ab}^{p} + (R_A H_{ab}^{\omega})\times r + \omega_a\times(\omega_b\times r),$$
//! with $H$ the derivative of the motion subspace
//! ([`crate::mechanism::JointState::hessian`]). A body's rotation moves by
//! $\partial_a R = \hat\omega_a R$, and $\partial_b\omega_a$ is $\omega_b\times\omega_a$
//! upstream, $R_A H_{ab}^{\omega}$ within the joint and zero downstream. As in
//! the plane, one point costs one pass along its path.
//!
//! Within a joint, a weight $u$ on $x$ meets $H$ only through
//! $$u\cdot\partial_{ab}x - u\cdot(\omega_a\times(\omega_b\times r)) = (R_A^T\tilde u)\cdot H_{ab}^{p} + (R_A^T(r\times u))\cdot H_{ab}^{\omega},$$
//! ($\tilde u = \epsilon u$), a wrench on $S$'s derivative, and a dead moment
//! $\mu$ through $(R_A^T\mu)\cdot H_{ab}^{\omega}$. So the Lagrangian
//! ([`super::lagrangian`]) sums, per joint, the root-frame wrench $W_j$ of
//! everything whose path passes through it, and the joint adds
//! $\sum_c W_{j,c}\thinspace\partial_b S_a^{c}$ once
//! ([`crate::mechanism::Joint::add_wrench_hessian`]). From frames evaluated
//! at [`Level::Hessian`] that contraction reads the joints' Hessians
//! (exact); from [`Level::Jacobian`] frames each joint makes it from its
//! Jacobian-level data, which for the spatial flexure is the virtual work's
//! quadrature (within $h^6$ of the exact one; about a tenth of the cost of
//! its Hessian). The statics' Newton matrix takes the latter; stiffness,
//! compliance, modes, buckling and dynamics evaluate frames with
//! [`frames`] or [`frames_into`], at [`Level::Hessian`], and so the former.

use super::SpatialMechanism;
use crate::kinematics::Level;
use crate::mechanism::joints::{JointState, add_contracted_hessian};
use crate::space::Spatial;
use nalgebra::{DMatrix, Isometry3, Matrix3, Matrix3xX, Point3, Vector3};

/// Every frame of the mechanism at one configuration (the Data).
#[derive(Debug, Clone)]
pub struct SpatialFrames {
    /// Body frames in the world (`pose_world_body`); index 0 is the ground.
    pub bodies: Vec<Isometry3<f64>>,
    /// Each joint's root frame in the world (`pose_world_root`).
    pub roots: Vec<Isometry3<f64>>,
    /// Each joint's pose, derivatives and energy.
    pub joints: Vec<JointState<Spatial>>,
    /// The coordinates $q$ these frames were evaluated at.
    pub coordinates: Vec<f64>,
    /// $\omega_a$ of every coordinate, in the world ($3\times n$).
    pub omega: Matrix3xX<f64>,
    /// $v_a$ of every coordinate: its joint's output origin's velocity ($3\times n$).
    pub velocity: Matrix3xX<f64>,
    /// The rotation matrix of each body frame, then of each joint's root frame.
    rotations: Vec<Matrix3<f64>>,
    /// The level the joints were evaluated to.
    level: Level,
}

impl SpatialFrames {
    /// Buffers for the frames of `m`.
    pub fn new(m: &SpatialMechanism) -> Self {
        let n = m.dof();
        SpatialFrames {
            bodies: vec![Isometry3::identity(); m.bodies.len()],
            roots: vec![Isometry3::identity(); m.joints.len()],
            joints: m.joints.iter().map(|j| j.kind.joint().state()).collect(),
            coordinates: vec![0.0; n],
            omega: Matrix3xX::zeros(n),
            velocity: Matrix3xX::zeros(n),
            rotations: vec![Matrix3::identity(); m.bodies.len() + m.joints.len()],
            level: Level::Pose,
        }
    }

    /// The level the joints were last evaluated to ([`frames_level_into`]):
    /// at [`Level::Hessian`] the second derivatives of points read the
    /// joints' Hessians, below it each joint's contraction
    /// ([`crate::mechanism::Joint::add_wrench_hessian`]).
    pub fn level(&self) -> Level {
        self.level
    }

    /// The rotation matrix of body `b` in the world.
    pub fn body_rotation(&self, b: usize) -> &Matrix3<f64> {
        &self.rotations[b]
    }

    fn root_rotation(&self, j: usize) -> &Matrix3<f64> {
        &self.rotations[self.bodies.len() + j]
    }

    /// Where joint `j`'s output origin is: the origin of its child body.
    fn output_origin(&self, m: &SpatialMechanism, j: usize) -> Vector3<f64> {
        self.bodies[m.joints[j].child].translation.vector
    }
}

/// Frames at coordinates `q`, parents before children.
pub fn frames(m: &SpatialMechanism, q: &[f64]) -> SpatialFrames {
    let mut f = SpatialFrames::new(m);
    frames_into(m, q, &mut f);
    f
}

/// [`frames`] into the buffers `f` (made by [`SpatialFrames::new`] for `m`), without allocating.
pub fn frames_into(m: &SpatialMechanism, q: &[f64], f: &mut SpatialFrames) {
    frames_level_into(m, q, Level::Hessian, f);
}

/// [`frames_into`] with each joint evaluated only up to `level`
/// ([`crate::mechanism::Joint::evaluate_level_into`]): the frames alone at
/// [`Level::Pose`], with every coordinate's twist at [`Level::Jacobian`]
/// (enough for residuals and point Jacobians), and the joints' second
/// derivatives too at [`Level::Hessian`] (for point Hessians).
pub fn frames_level_into(m: &SpatialMechanism, q: &[f64], level: Level, f: &mut SpatialFrames) {
    f.coordinates.copy_from_slice(q);
    f.level = level;
    let nb = m.bodies.len();
    for (i, j) in m.joints.iter().enumerate() {
        let joint = j.kind.joint();
        let k = joint.dof();
        let state = &mut f.joints[i];
        joint.evaluate_level_into(&q[j.offset..j.offset + k], level, state);
        let root = f.bodies[j.parent] * j.origin;
        let rotation = root.rotation.to_rotation_matrix().into_inner();
        let child = root * state.pose;
        for a in (0..k).filter(|_| level >= Level::Jacobian) {
            let s = &state.jacobian;
            let w = rotation * Vector3::new(s[(0, a)], s[(1, a)], s[(2, a)]);
            let v = rotation * Vector3::new(s[(3, a)], s[(4, a)], s[(5, a)]);
            f.omega.set_column(j.offset + a, &w);
            f.velocity.set_column(j.offset + a, &v);
        }
        f.rotations[nb + i] = rotation;
        f.rotations[j.child] = child.rotation.to_rotation_matrix().into_inner();
        f.bodies[j.child] = child;
        f.roots[i] = root;
    }
}

/// A point or a direction fixed in a body: its world value and Jacobian,
/// with the joints on its path (the Data of [`attach_into`]).
#[derive(Debug, Clone)]
pub struct Attached {
    /// The world position (a point) or direction.
    pub value: Vector3<f64>,
    /// $\partial x/\partial q$, $3\times n$; zero off the path.
    pub jacobian: Matrix3xX<f64>,
    /// A point (it translates with the body), or a direction (it only turns).
    pub point: bool,
    /// The joints on the path, from the body down to the ground.
    path: Vec<usize>,
}

impl Attached {
    /// Buffers for a point or direction of `m`.
    pub fn new(m: &SpatialMechanism) -> Self {
        Attached {
            value: Vector3::zeros(),
            jacobian: Matrix3xX::zeros(m.dof()),
            point: true,
            path: Vec::with_capacity(m.joints.len()),
        }
    }

    /// The joints on its path, from the body down to the ground.
    pub fn path(&self) -> &[usize] {
        &self.path
    }
}

/// World value and Jacobian of `local` (in the frame of `body`; a point
/// when `point`, else a direction) into `out`, in one pass from the body
/// down to the ground.
pub fn attach_into(
    m: &SpatialMechanism,
    f: &SpatialFrames,
    body: usize,
    local: Vector3<f64>,
    point: bool,
    out: &mut Attached,
) {
    let value = if point { f.bodies[body] * Point3::from(local) } else { Point3::from(f.body_rotation(body) * local) };
    for &j in &out.path {
        let (o, k) = (m.joints[j].offset, f.joints[j].gradient.len());
        out.jacobian.columns_mut(o, k).fill(0.0);
    }
    out.path.clear();
    out.value = value.coords;
    out.point = point;
    let mut b = body;
    while let Some(j) = m.parent_joint(b) {
        let spec = &m.joints[j];
        let r = if point { out.value - f.output_origin(m, j) } else { out.value };
        for c in spec.offset..spec.offset + f.joints[j].gradient.len() {
            let mut d = f.omega.column(c).cross(&r);
            if point {
                d += f.velocity.column(c);
            }
            out.jacobian.set_column(c, &d);
        }
        out.path.push(j);
        b = spec.parent;
    }
}

/// [`attach_into`] in fresh buffers.
pub fn attach(m: &SpatialMechanism, f: &SpatialFrames, body: usize, local: Vector3<f64>, point: bool) -> Attached {
    let mut out = Attached::new(m);
    attach_into(m, f, body, local, point, &mut out);
    out
}

/// The joints from the one moving `body` down to the ground.
fn chain(m: &SpatialMechanism, body: usize) -> impl Iterator<Item = usize> + '_ {
    std::iter::successors(m.parent_joint(body), |&j| m.parent_joint(m.joints[j].parent))
}

/// The same-joint parts of weighted second derivatives, gathered per joint
/// (the module docs' "within one joint"): for joint $j$, the world wrench
/// $W_j = (M_j, F_j)$, moment about its output origin $o_j$, and the matrix
/// $N_j$ of the turn of the turn, summed over every weighted vector whose
/// path passes through $j$,
/// $$M_j = \sum r\times u + \sum\mu,\qquad F_j = \sum\epsilon\thinspace u,\qquad N_j = \sum r\thinspace u^T - (u\cdot r)\thinspace I,$$
/// ($\mu$ a dead moment's weight, [`add_rotation_derivative`]). Joint $j$'s
/// block of the Hessian is then
/// $\sum_c W_{j,c}\thinspace\partial_bS^c_a$ with $W_j$ turned into its root frame
/// ([`crate::mechanism::Joint::add_wrench_hessian`], one call per joint)
/// plus $\omega_a^TN_j\thinspace\omega_b$, which is
/// $u\cdot(\omega_a\times(\omega_b\times r))$ summed.
#[derive(Debug, Clone)]
pub(crate) struct JointWrenches {
    moment: Vec<Vector3<f64>>,
    force: Vec<Vector3<f64>>,
    turn: Vec<Matrix3<f64>>,
    touched: Vec<bool>,
}

impl JointWrenches {
    /// Empty sums for the joints of `m`.
    pub(crate) fn new(m: &SpatialMechanism) -> Self {
        let n = m.joints.len();
        JointWrenches {
            moment: vec![Vector3::zeros(); n],
            force: vec![Vector3::zeros(); n],
            turn: vec![Matrix3::zeros(); n],
            touched: vec![false; n],
        }
    }

    /// Adds every joint's gathered block to `h` and empties the sums.
    pub(crate) fn flush(&mut self, m: &SpatialMechanism, f: &SpatialFrames, h: &mut DMatrix<f64>) {
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

/// Where the same-joint parts go: gathered per joint, or (`None`) added
/// to the Hessian at once, one joint at a time.
type Sink<'a> = Option<&'a mut JointWrenches>;

/// Adds the world wrench `(moment, force)` and turn matrix of joint `j` to `sink`, or straight into `h`.
fn same_joint(
    m: &SpatialMechanism,
    f: &SpatialFrames,
    j: usize,
    (moment, force, turn): (Vector3<f64>, Vector3<f64>, Matrix3<f64>),
    sink: &mut Sink<'_>,
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
    m: &SpatialMechanism,
    f: &SpatialFrames,
    j: usize,
    moment: &Vector3<f64>,
    force: &Vector3<f64>,
    turn: &Matrix3<f64>,
    h: &mut DMatrix<f64>,
) {
    let spec = &m.joints[j];
    let state = &f.joints[j];
    let (o, k) = (spec.offset, state.gradient.len());
    let rotation = f.root_rotation(j);
    let (mr, fr) = (rotation.tr_mul(moment), rotation.tr_mul(force));
    let wrench = [mr.x, mr.y, mr.z, fr.x, fr.y, fr.z];
    {
        let mut block = h.view_mut((o, o), (k, k));
        if f.level >= Level::Hessian {
            add_contracted_hessian(state, &wrench, &mut block);
        } else {
            spec.kind.joint().add_wrench_hessian(&f.coordinates[o..o + k], state, &wrench, &mut block);
        }
    }
    if *turn != Matrix3::zeros() {
        for b in 0..k {
            let nb = turn * f.omega.column(o + b);
            for a in 0..k {
                h[(o + a, o + b)] += f.omega.column(o + a).dot(&nb);
            }
        }
    }
}

/// Adds $\sum_c u_c\nabla^2 x_c$ of the vector in `x` (from [`attach_into`])
/// to `h`, entries on its path only (see the module docs).
///
/// Within a joint it reads the joints' Hessians when `f` was evaluated at
/// [`Level::Hessian`], and otherwise asks each joint for its contraction
/// ([`crate::mechanism::Joint::add_wrench_hessian`]; for the spatial
/// flexure, a quadrature that meets the exact Hessian to its $h^6$): a
/// Newton matrix assembled from Jacobian-level frames does not pay for the
/// flexures' second derivatives.
pub fn add_attached_hessian(
    m: &SpatialMechanism,
    f: &SpatialFrames,
    x: &Attached,
    u: &Vector3<f64>,
    h: &mut DMatrix<f64>,
) {
    gather_attached_hessian(m, f, x, u, h, None);
}

/// [`add_attached_hessian`] with the same-joint parts gathered into `sink`
/// (added by its [`JointWrenches::flush`]) when given.
pub(crate) fn gather_attached_hessian(
    m: &SpatialMechanism,
    f: &SpatialFrames,
    x: &Attached,
    u: &Vector3<f64>,
    h: &mut DMatrix<f64>,
    mut sink: Sink<'_>,
) {
    if *u == Vector3::zeros() {
        return;
    }
    for (down, &ja) in x.path.iter().enumerate() {
        let oa = m.joints[ja].offset;
        let k = f.joints[ja].gradient.len();
        let r = if x.point { x.value - f.output_origin(m, ja) } else { x.value };
        let force = if x.point { *u } else { Vector3::zeros() };
        let turn = r * u.transpose() - Matrix3::from_diagonal_element(u.dot(&r));
        same_joint(m, f, ja, (r.cross(u), force, turn), &mut sink, h);
        // With each joint upstream: ω_b × ∂_a x, at (a, b) and (b, a).
        for &jb in &x.path[down + 1..] {
            let ob = m.joints[jb].offset;
            for b in 0..f.joints[jb].gradient.len() {
                let uxw = f.omega.column(ob + b).cross(u);
                for a in 0..k {
                    // u·(ω_b × J_a) = J_a·(u × ω_b) = −J_a·(ω_b × u).
                    let v = -x.jacobian.column(oa + a).dot(&uxw);
                    h[(oa + a, ob + b)] += v;
                    h[(ob + b, oa + a)] += v;
                }
            }
        }
    }
}

/// Adds $\partial_b(\mu\cdot\omega_a)$ at $(a, b)$ to `k`, for body `body`'s
/// angular velocity $\sum_a\omega_a\dot q_a$ and a vector $\mu$ fixed in the
/// world (a dead moment's generalized force $Q_a = \mu\cdot\omega_a$): not
/// symmetric, since a moment fixed in space has no potential. Within a
/// joint as [`add_attached_hessian`].
pub fn add_rotation_derivative(
    m: &SpatialMechanism,
    f: &SpatialFrames,
    body: usize,
    mu: &Vector3<f64>,
    k: &mut DMatrix<f64>,
) {
    gather_rotation_derivative(m, f, body, mu, k, None);
}

/// [`add_rotation_derivative`] with the same-joint parts gathered into `sink` when given.
pub(crate) fn gather_rotation_derivative(
    m: &SpatialMechanism,
    f: &SpatialFrames,
    body: usize,
    mu: &Vector3<f64>,
    k: &mut DMatrix<f64>,
    mut sink: Sink<'_>,
) {
    if *mu == Vector3::zeros() {
        return;
    }
    for ja in chain(m, body) {
        let oa = m.joints[ja].offset;
        same_joint(m, f, ja, (*mu, Vector3::zeros(), Matrix3::zeros()), &mut sink, k);
        // ∂_b ω_a = ω_b × ω_a for b in a joint upstream.
        for jb in chain(m, m.joints[ja].parent) {
            let ob = m.joints[jb].offset;
            for b in 0..f.joints[jb].gradient.len() {
                let mxw = mu.cross(&f.omega.column(ob + b));
                for a in 0..f.joints[ja].gradient.len() {
                    // μ·(ω_b × ω_a) = ω_a·(μ × ω_b).
                    k[(oa + a, ob + b)] += f.omega.column(oa + a).dot(&mxw);
                }
            }
        }
    }
}

/// The largest rotation (rad) between configurations `a` and `b` of any
/// body, or inside a joint (a flexure's sections relative to its root),
/// and a slider's travel over the mechanism's size: what bounds a
/// continuation or integration step. `buffers` holds the frames at `a` and `b`.
pub fn distance(m: &SpatialMechanism, a: &[f64], b: &[f64], buffers: &mut [SpatialFrames; 2]) -> f64 {
    let [fa, fb] = buffers;
    frames_level_into(m, a, Level::Pose, fa);
    frames_level_into(m, b, Level::Pose, fb);
    distance_of(m, fa, fb)
}

/// [`distance`] between the frames `fa` and `fb`, evaluated (to any
/// level) at the configurations it compares.
pub(crate) fn distance_of(m: &SpatialMechanism, fa: &SpatialFrames, fb: &SpatialFrames) -> f64 {
    let (a, b) = (&fa.coordinates, &fb.coordinates);
    let mut d: f64 = 0.0;
    for i in 1..m.bodies.len() {
        d = d.max(crate::space::rotation_angle(fa.body_rotation(i), fb.body_rotation(i)));
    }
    let length = m.size();
    for j in &m.joints {
        let joint = j.kind.joint();
        let range = j.offset..j.offset + joint.dof();
        d = d.max(joint.distance(&a[range.clone()], &b[range], length));
    }
    d
}
