//! Body frames, and Jacobians and Hessians of points and directions fixed
//! in bodies, chained through the tree: once for both dimensions, what
//! differs in [`FrameChain`].
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
//! upstream, $R_A H_{ab}^{\omega}$ within the joint and zero downstream. So a
//! point's Jacobian costs one pass along its path: linear in the joints.
//!
//! In the plane $\omega$ is a rate about $z$ and $\omega\times r$ the quarter
//! turn $\mathrm J r$, so these are
//! $\partial_a w = R_A\thinspace\partial_a p_j + \partial_a\phi_j\thinspace\mathrm J(w - o_j)$
//! and, within a joint whose angle is linear in its coordinates,
//! $\partial_{ab} w = R_A\thinspace\partial_{ab} p_j - \partial_a\phi\thinspace\partial_b\phi\thinspace(w - o_j)$.

mod dimension;
mod wrenches;

pub use dimension::FrameChain;
pub use wrenches::{JointWrenches, add_rotation_derivative};

use super::Mechanism;
use super::joints::JointState;
use crate::kinematics::Level;
use crate::space::{Planar, Spatial};
use nalgebra::{DMatrix, Point2, Vector2};

/// Every frame of the mechanism at one configuration (the Data).
#[derive(Debug, Clone)]
pub struct Frames<D: FrameChain = Planar> {
    /// Body frames in the world (`pose_world_body`); index 0 is the ground.
    pub bodies: Vec<D::Pose>,
    /// Each joint's root frame in the world (`pose_world_root`).
    pub roots: Vec<D::Pose>,
    /// Each joint's pose, derivatives and energy.
    pub joints: Vec<JointState<D>>,
    /// The coordinates $q$ these frames were evaluated at.
    pub coordinates: Vec<f64>,
    /// $\omega_a$ of every coordinate, in the world.
    pub omega: Vec<D::Angular>,
    /// $v_a$ of every coordinate: its joint's output origin's velocity.
    pub velocity: Vec<D::Vector>,
    /// The rotation of each body frame, then of each joint's root frame:
    /// every point and Hessian of one evaluation turns by these, computed once.
    turns: Vec<D::Turn>,
    /// The level the joints were evaluated to.
    level: Level,
}

impl<D: FrameChain> Frames<D> {
    /// Buffers for the frames of `m` (each joint's from [`super::Joint::state`]).
    pub fn new(m: &Mechanism<D>) -> Self {
        let n = m.dof();
        let identity = D::identity();
        Frames {
            bodies: vec![identity; m.bodies.len()],
            roots: vec![identity; m.joints.len()],
            joints: m.joints.iter().map(|j| j.kind.joint().state()).collect(),
            coordinates: vec![0.0; n],
            omega: vec![D::Angular::default(); n],
            velocity: vec![D::Vector::default(); n],
            turns: vec![D::turn(&identity); m.bodies.len() + m.joints.len()],
            level: Level::Pose,
        }
    }

    /// Copies `other` (frames of the same mechanism) into these buffers,
    /// without allocating (the joints' own buffers stay).
    pub(crate) fn copy_from(&mut self, other: &Frames<D>) {
        self.bodies.copy_from_slice(&other.bodies);
        self.roots.copy_from_slice(&other.roots);
        self.turns.copy_from_slice(&other.turns);
        self.coordinates.copy_from_slice(&other.coordinates);
        self.omega.copy_from_slice(&other.omega);
        self.velocity.copy_from_slice(&other.velocity);
        self.level = other.level;
        for (s, o) in self.joints.iter_mut().zip(&other.joints) {
            s.copy_from(o);
        }
    }

    /// The level the joints were last evaluated to ([`frames_level_into`]):
    /// at [`Level::Hessian`] the second derivatives of points read the
    /// joints' Hessians, below it each joint's contraction
    /// ([`crate::mechanism::Joint::add_wrench_hessian`]).
    pub fn level(&self) -> Level {
        self.level
    }

    /// The rotation of body `b` in the world.
    pub fn body_rotation(&self, b: usize) -> &D::Turn {
        &self.turns[b]
    }

    pub(crate) fn root_turn(&self, j: usize) -> &D::Turn {
        &self.turns[self.bodies.len() + j]
    }

    /// Where joint `j`'s output origin is: the origin of its child body.
    fn output_origin(&self, m: &Mechanism<D>, j: usize) -> D::Vector {
        D::translation(&self.bodies[m.joints[j].child])
    }
}

/// Frames at coordinates `q`, parents before children.
pub fn frames<D: FrameChain>(m: &Mechanism<D>, q: &[f64]) -> Frames<D> {
    let mut f = Frames::new(m);
    frames_into(m, q, &mut f);
    f
}

/// [`frames`] into the buffers `f` (made by [`Frames::new`] for `m`), without allocating.
pub fn frames_into<D: FrameChain>(m: &Mechanism<D>, q: &[f64], f: &mut Frames<D>) {
    frames_level_into(m, q, Level::Hessian, f);
}

/// [`frames_into`] with each joint evaluated only up to `level`
/// ([`crate::mechanism::Joint::evaluate_level_into`]): the frames alone at
/// [`Level::Pose`], with every coordinate's twist at [`Level::Jacobian`]
/// (enough for residuals and point Jacobians), and the joints' second
/// derivatives too at [`Level::Hessian`] (for point Hessians).
pub fn frames_level_into<D: FrameChain>(m: &Mechanism<D>, q: &[f64], level: Level, f: &mut Frames<D>) {
    chain_into(m, q, level, f, &[], |_, _| {});
}

/// [`frames_level_into`] at [`Level::Jacobian`] where the caller already
/// holds some joints' motion subspaces: a joint `i` with `given[i]` is
/// evaluated only at [`Level::Pose`] (its pose, energy and gradient), and
/// `fill(i, state)` then writes its motion subspace into `state.jacobian`.
/// The dynamics take a massive spatial flexure's from its stations' pass,
/// which carries the tip's columns anyway, rather than from a second pass
/// of the joint's own.
pub(crate) fn frames_given_into<D: FrameChain>(
    m: &Mechanism<D>,
    q: &[f64],
    f: &mut Frames<D>,
    given: &[bool],
    fill: impl FnMut(usize, &mut JointState<D>),
) {
    chain_into(m, q, Level::Jacobian, f, given, fill);
}

/// The frames down the tree, each joint to `level` unless `given` (then `fill` writes its motion subspace).
fn chain_into<D: FrameChain>(
    m: &Mechanism<D>,
    q: &[f64],
    level: Level,
    f: &mut Frames<D>,
    given: &[bool],
    mut fill: impl FnMut(usize, &mut JointState<D>),
) {
    f.coordinates.copy_from_slice(q);
    f.level = level;
    let nb = m.bodies.len();
    for (i, j) in m.joints.iter().enumerate() {
        let joint = j.kind.joint();
        let k = joint.dof();
        let state = &mut f.joints[i];
        let coordinates = &q[j.offset..j.offset + k];
        if level >= Level::Jacobian && given.get(i) == Some(&true) {
            joint.evaluate_level_into(coordinates, Level::Pose, state);
            fill(i, state);
        } else {
            joint.evaluate_level_into(coordinates, level, state);
        }
        let root = D::compose_turned(&f.bodies[j.parent], &f.turns[j.parent], &j.origin);
        let turn = D::turn(&root);
        let child = D::compose_turned(&root, &turn, &state.pose);
        if level >= Level::Jacobian {
            let rows = D::TWIST_DIM;
            for (a, s) in state.jacobian.as_slice().chunks_exact(rows).enumerate() {
                (f.omega[j.offset + a], f.velocity[j.offset + a]) = D::twist(&turn, s);
            }
        }
        f.turns[nb + i] = turn;
        f.turns[j.child] = D::turn(&child);
        f.bodies[j.child] = child;
        f.roots[i] = root;
    }
}

/// A point or a direction fixed in a body: its world value and Jacobian,
/// with the joints on its path (the Data of [`attach_into`]).
#[derive(Debug, Clone)]
pub struct Attached<D: FrameChain = Planar> {
    /// The world position (a point) or direction.
    pub value: D::Vector,
    /// `TWIST_DIM` $\times n$: rows the body's rotation $\omega$ (in the
    /// plane $\phi$), then $\partial x/\partial q$; zero off the path.
    pub jacobian: DMatrix<f64>,
    /// A point (it translates with the body), or a direction (it only turns).
    pub point: bool,
    /// The joints on the path, from the body down to the ground.
    path: Vec<usize>,
}

impl<D: FrameChain> Attached<D> {
    /// Buffers for a point or direction of `m`.
    pub fn new(m: &Mechanism<D>) -> Self {
        Attached {
            value: D::Vector::default(),
            jacobian: DMatrix::zeros(D::TWIST_DIM, m.dof()),
            point: true,
            path: Vec::with_capacity(m.joints.len()),
        }
    }

    /// The joints on its path, from the body down to the ground.
    pub fn path(&self) -> &[usize] {
        &self.path
    }

    /// $\partial x/\partial q_c$.
    pub fn linear(&self, c: usize) -> D::Vector {
        let rows = D::TWIST_DIM;
        D::linear(&self.jacobian.as_slice()[rows * c..rows * (c + 1)])
    }
}

/// World value and Jacobian of `local` (in the frame of `body`; a point
/// when `point`, else a direction) into `out`, in one pass from the body
/// down to the ground; allocates nothing once `out` has held a path this long.
pub fn attach_into<D: FrameChain>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    body: usize,
    local: D::Vector,
    point: bool,
    out: &mut Attached<D>,
) {
    let rows = D::TWIST_DIM;
    let value = D::act_turned(&f.bodies[body], f.body_rotation(body), &local, point);
    let jacobian = out.jacobian.as_mut_slice();
    for &j in &out.path {
        let (o, k) = (m.joints[j].offset, f.joints[j].gradient.len());
        jacobian[rows * o..rows * (o + k)].fill(0.0);
    }
    out.path.clear();
    out.value = value;
    out.point = point;
    let mut b = body;
    while let Some(j) = m.parent_joint(b) {
        let spec = &m.joints[j];
        let r = if point { value - f.output_origin(m, j) } else { value };
        let k = f.joints[j].gradient.len();
        let columns = jacobian[rows * spec.offset..rows * (spec.offset + k)].chunks_exact_mut(rows);
        for (c, column) in (spec.offset..).zip(columns) {
            let w = &f.omega[c];
            let mut d = D::spin(w, &r);
            if point {
                d = d + f.velocity[c];
            }
            D::write(column, w, &d);
        }
        out.path.push(j);
        b = spec.parent;
    }
}

/// [`attach_into`] in fresh buffers.
pub fn attach<D: FrameChain>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    body: usize,
    local: D::Vector,
    point: bool,
) -> Attached<D> {
    let mut out = Attached::new(m);
    attach_into(m, f, body, local, point, &mut out);
    out
}

/// Adds $\sum_c u_c\nabla^2 x_c$ of the vector in `x` (from [`attach_into`])
/// to `h`, entries on its path only (see the module docs).
///
/// In space, within a joint it reads the joints' Hessians when `f` was
/// evaluated at [`Level::Hessian`], and otherwise asks each joint for its
/// contraction ([`crate::mechanism::Joint::add_wrench_hessian`]; for the
/// spatial flexure, a quadrature that meets the exact Hessian to its
/// $h^6$): a Newton matrix assembled from Jacobian-level frames does not pay
/// for the flexures' second derivatives.
pub fn add_attached_hessian<D: FrameChain>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    x: &Attached<D>,
    u: &D::Vector,
    h: &mut DMatrix<f64>,
) {
    gather_attached_hessian(m, f, x, u, h, None);
}

/// [`add_attached_hessian`] with the same-joint parts gathered into `sums`
/// (added by [`FrameChain::flush`]) when given.
pub(crate) fn gather_attached_hessian<D: FrameChain>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    x: &Attached<D>,
    u: &D::Vector,
    h: &mut DMatrix<f64>,
    mut sums: Option<&mut D::Sums>,
) {
    if *u == D::Vector::default() {
        return;
    }
    let n = h.nrows();
    for (down, &ja) in x.path.iter().enumerate() {
        D::within_joint(m, f, ja, x, u, sums.as_deref_mut(), h);
        let (oa, k) = (m.joints[ja].offset, f.joints[ja].gradient.len());
        // With each joint upstream: u·(ω_b × ∂_a x), at (a, b) and (b, a).
        let h = h.as_mut_slice();
        for &jb in &x.path[down + 1..] {
            let ob = m.joints[jb].offset;
            for a in oa..oa + k {
                let da = x.linear(a);
                for b in ob..ob + f.joints[jb].gradient.len() {
                    let v = D::triple(u, &f.omega[b], &da);
                    h[b * n + a] += v;
                    h[a * n + b] += v;
                }
            }
        }
    }
}

/// A planar point's position, angle and Jacobian, with derivatives in $q$.
#[derive(Debug, Clone)]
pub struct PointDerivatives {
    /// Rotation of the body (rad).
    pub phi: f64,
    /// World position (m).
    pub position: Point2<f64>,
    /// $3\times n$: rows $(\phi, x, y)$.
    pub jacobian: DMatrix<f64>,
    /// Hessians of $x$ and $y$ ($n\times n$), if asked for.
    pub hessian: Option<[DMatrix<f64>; 2]>,
}

/// Derivatives of point `r` (in the frame of `body`), in fresh buffers.
pub fn point(m: &Mechanism, f: &Frames, body: usize, r: Point2<f64>, hessian: bool) -> PointDerivatives {
    let n = m.dof();
    let p = attach(m, f, body, r.coords, true);
    let hessian = hessian.then(|| {
        let (mut hx, mut hy) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
        add_attached_hessian(m, f, &p, &Vector2::x(), &mut hx);
        add_attached_hessian(m, f, &p, &Vector2::y(), &mut hy);
        [hx, hy]
    });
    PointDerivatives { phi: f.bodies[body].phi, position: Point2::from(p.value), jacobian: p.jacobian, hessian }
}

/// The largest rotation (rad) between configurations `a` and `b` of any
/// body or of a flexure's cross-section relative to its root, and a
/// slider's travel over `length` (the mechanism's size): what bounds a
/// continuation step ([`crate::solver::Problem::distance`]) and an
/// integration step (the dynamics' `System::distance`). The planar fast
/// path: body angles add down the tree, no frame is evaluated. `angles`
/// holds two buffers of one entry per body.
pub fn distance(m: &Mechanism, a: &[f64], b: &[f64], length: f64, angles: &mut [Vec<f64>; 2]) -> f64 {
    let [ba, bb] = angles;
    // Body angles down the tree: the parent's, the origin's, the joint's.
    let fill = |q: &[f64], body: &mut Vec<f64>| {
        body.resize(m.bodies.len(), 0.0);
        body.fill(0.0);
        for j in &m.joints {
            let row = j.kind.joint().angle_row().unwrap_or(&[]);
            let phi: f64 = row.iter().zip(&q[j.offset..]).map(|(r, v)| r * v).sum();
            body[j.child] = body[j.parent] + j.origin.phi + phi;
        }
    };
    fill(a, ba);
    fill(b, bb);
    let d = ba.iter().zip(bb.iter()).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    joint_distance(m, a, b, length, d)
}

/// [`distance`] in space, between the frames `fa` and `fb` evaluated (to
/// any level) at the configurations it compares.
pub(crate) fn distance_of(m: &Mechanism<Spatial>, fa: &Frames<Spatial>, fb: &Frames<Spatial>) -> f64 {
    let mut d: f64 = 0.0;
    for i in 1..m.bodies.len() {
        d = d.max(crate::space::rotation_angle(fa.body_rotation(i), fb.body_rotation(i)));
    }
    joint_distance(m, &fa.coordinates, &fb.coordinates, m.size(), d)
}

/// `d`, or the largest distance inside a joint if more.
fn joint_distance<D: FrameChain>(m: &Mechanism<D>, a: &[f64], b: &[f64], length: f64, mut d: f64) -> f64 {
    for j in &m.joints {
        let joint = j.kind.joint();
        let range = j.offset..j.offset + joint.dof();
        d = d.max(joint.distance(&a[range.clone()], &b[range], length));
    }
    d
}

/// [`distance`] in space, evaluating the frames at `a` and `b` (poses
/// alone) into `buffers`.
pub fn frame_distance(m: &Mechanism<Spatial>, a: &[f64], b: &[f64], buffers: &mut [Frames<Spatial>; 2]) -> f64 {
    let [fa, fb] = buffers;
    frames_level_into(m, a, Level::Pose, fa);
    frames_level_into(m, b, Level::Pose, fb);
    distance_of(m, fa, fb)
}
