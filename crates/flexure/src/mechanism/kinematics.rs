//! Body frames, and Jacobians and Hessians of points, chained through the tree.
//!
//! For a point $w$ on a body and a coordinate $a$ of joint $j$ on the path
//! from the ground (root frame $A$ in the world, output origin $o_j$):
//! $$\partial_a w = R_A\thinspace\partial_a p_j + \partial_a\phi_j\thinspace\mathrm J(w - o_j),\qquad
//! \partial_a\theta = \partial_a\phi_j,$$
//! with $\mathrm J$ the quarter turn. Second derivatives: for $a$ in a joint
//! upstream of $b$'s, $\partial_{ab} w = \partial_a\phi\thinspace\mathrm J\thinspace\partial_b w$;
//! within one joint, $\partial_{ab} w = R_A\thinspace\partial_{ab} p_j -
//! \partial_a\phi\thinspace\partial_b\phi\thinspace(w - o_j)$
//! (no joint kind here has a curved angle, $\partial_{ab}\phi = 0$). So a
//! point's Jacobian costs one pass along its path: linear in the joints.

use super::Mechanism;
use super::joints::JointState;
use crate::space::Pose;
use crate::space::rotate_turned as turn;
use nalgebra::{DMatrix, Point2, Vector2};

/// Every frame of the mechanism at one configuration (the Data).
#[derive(Debug, Clone, Default)]
pub struct Frames {
    /// Body frames in the world (`pose_world_body`); index 0 is the ground.
    pub bodies: Vec<Pose>,
    /// Each joint's root frame in the world.
    pub roots: Vec<Pose>,
    /// Each joint's pose, derivatives and energy.
    pub joints: Vec<JointState>,
    /// The coordinates $q$ these frames were evaluated at.
    pub coordinates: Vec<f64>,
    /// `sin_cos` of each body's angle, then of each joint root's: every
    /// point and Hessian of one evaluation turns by these, computed once.
    turns: Vec<(f64, f64)>,
}

impl Frames {
    /// Buffers for the frames of `m` (each joint's from [`super::Joint::state`]).
    pub fn new(m: &Mechanism) -> Self {
        Frames {
            bodies: vec![Pose::default(); m.bodies.len()],
            roots: vec![Pose::default(); m.joints.len()],
            joints: m.joints.iter().map(|j| j.kind.joint().state()).collect(),
            coordinates: vec![0.0; m.dof()],
            turns: vec![(0.0, 1.0); m.bodies.len() + m.joints.len()],
        }
    }

    /// Copies `other` (frames of the same mechanism) into these buffers,
    /// without allocating.
    pub(super) fn copy_from(&mut self, other: &Frames) {
        self.bodies.copy_from_slice(&other.bodies);
        self.roots.copy_from_slice(&other.roots);
        self.turns.copy_from_slice(&other.turns);
        self.coordinates.copy_from_slice(&other.coordinates);
        for (s, o) in self.joints.iter_mut().zip(&other.joints) {
            s.copy_from(o);
        }
    }

    fn body_turn(&self, body: usize) -> (f64, f64) {
        self.turns[body]
    }

    fn root_turn(&self, joint: usize) -> (f64, f64) {
        self.turns[self.bodies.len() + joint]
    }
}

/// Frames at coordinates `q`, parents before children.
pub fn frames(m: &Mechanism, q: &[f64]) -> Frames {
    let mut f = Frames::new(m);
    frames_into(m, q, &mut f);
    f
}

/// [`frames`] into the buffers `f` (made by [`Frames::new`] for `m`), without allocating.
pub fn frames_into(m: &Mechanism, q: &[f64], f: &mut Frames) {
    f.coordinates.copy_from_slice(q);
    f.bodies[0] = Pose::default();
    f.turns[0] = f.bodies[0].turn();
    let bodies = f.bodies.len();
    for (i, j) in m.joints.iter().enumerate() {
        let joint = j.kind.joint();
        let state = &mut f.joints[i];
        joint.evaluate_into(&q[j.offset..j.offset + joint.dof()], state);
        let root = f.bodies[j.parent].compose_turned(f.turns[j.parent], &j.origin);
        let root_turn = root.turn();
        let child = root.compose_turned(root_turn, &state.pose);
        f.turns[bodies + i] = root_turn;
        f.turns[j.child] = child.turn();
        f.bodies[j.child] = child;
        f.roots[i] = root;
    }
}

/// A point's world position and its body's rotation, with derivatives in $q$.
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

fn quarter(v: [f64; 2]) -> [f64; 2] {
    [-v[1], v[0]]
}

/// A point's position, angle and Jacobian, with the joints on its path,
/// reused from one evaluation to the next (the Data of [`point_into`]).
#[derive(Debug, Clone, Default)]
pub struct PointBuffer {
    /// Rotation of the body (rad).
    pub phi: f64,
    /// World position (m).
    pub position: Point2<f64>,
    /// $3\times n$: rows $(\phi, x, y)$; zero off the path.
    pub jacobian: DMatrix<f64>,
    /// The joints on the path, from the body down to the ground.
    path: Vec<usize>,
}

impl PointBuffer {
    /// Buffers for a point of `m`.
    pub fn new(m: &Mechanism) -> Self {
        PointBuffer {
            phi: 0.0,
            position: Point2::origin(),
            jacobian: DMatrix::zeros(3, m.dof()),
            path: Vec::with_capacity(m.joints.len()),
        }
    }
}

/// Position, angle and Jacobian of point `r` (in the frame of `body`) into
/// `out`, in one pass from the body down to the ground; allocates nothing
/// once `out` has held a path this long.
pub fn point_into(m: &Mechanism, f: &Frames, body: usize, r: Point2<f64>, out: &mut PointBuffer) {
    let w = f.bodies[body].act_turned(f.body_turn(body), [r.x, r.y]);
    // Column-major 3 × n: coordinate c's column is [3c, 3c + 3).
    let jacobian = out.jacobian.as_mut_slice();
    for &ji in &out.path {
        let (o, k) = (m.joints[ji].offset, f.joints[ji].gradient.len());
        jacobian[3 * o..3 * (o + k)].fill(0.0);
    }
    out.path.clear();
    let mut b = body;
    while let Some(ji) = m.parent_joint(b) {
        let j = &m.joints[ji];
        let s = &f.joints[ji];
        let root = f.root_turn(ji);
        let o = &f.bodies[j.child];
        let arm = quarter([w[0] - o.x, w[1] - o.y]);
        let k = s.gradient.len();
        let columns = jacobian[3 * j.offset..3 * (j.offset + k)].chunks_exact_mut(3);
        for (column, local) in columns.zip(s.jacobian.as_slice().chunks_exact(3)) {
            let dphi = local[0];
            let dp = turn(root, [local[1], local[2]]);
            column[0] = dphi;
            column[1] = dp[0] + dphi * arm[0];
            column[2] = dp[1] + dphi * arm[1];
        }
        out.path.push(ji);
        b = j.parent;
    }
    out.phi = f.bodies[body].phi;
    out.position = Point2::new(w[0], w[1]);
}

/// Adds $w_x\nabla^2 x + w_y\nabla^2 y$ of the point in `p` (from
/// [`point_into`]) to `h`, entries on its path only (see the module docs).
pub fn add_point_hessian(m: &Mechanism, f: &Frames, p: &PointBuffer, weight: Vector2<f64>, h: &mut DMatrix<f64>) {
    if weight == Vector2::zeros() {
        return;
    }
    let w = p.position;
    let n = h.nrows();
    let h = h.as_mut_slice();
    // Each entry is written once per point: the loops' order does not matter.
    let mut add = |r: usize, c: usize, v: f64| {
        h[c * n + r] += v;
        if r != c {
            h[r * n + c] += v;
        }
    };
    let jacobian = p.jacobian.as_slice();
    for (down, &ja) in p.path.iter().enumerate() {
        let (oa, s) = (m.joints[ja].offset, &f.joints[ja]);
        let k = s.gradient.len();
        // Within the joint: R_A ∂_ab p − ∂_a φ ∂_b φ (w − o).
        let o = &f.bodies[m.joints[ja].child];
        let arm = [w.x - o.x, w.y - o.y];
        let root = f.root_turn(ja);
        let (hx, hy, local) = (s.hessian[1].as_slice(), s.hessian[2].as_slice(), s.jacobian.as_slice());
        for a in 0..k {
            for b in a..k {
                let turned = turn(root, [hx[b * k + a], hy[b * k + a]]);
                let dphi = local[3 * a] * local[3 * b];
                let (vx, vy) = (turned[0] - dphi * arm[0], turned[1] - dphi * arm[1]);
                add(oa + a, oa + b, weight[0] * vx + weight[1] * vy);
            }
        }
        // With each joint farther from the body (upstream): ∂_up φ · J · ∂_down w.
        for &jb in &p.path[down + 1..] {
            let (ob, up) = (m.joints[jb].offset, &f.joints[jb]);
            let up_angle = up.jacobian.as_slice();
            for a in 0..k {
                let ca = oa + a;
                let t = quarter([jacobian[3 * ca + 1], jacobian[3 * ca + 2]]);
                for b in 0..up.gradient.len() {
                    let dphi = up_angle[3 * b];
                    let (vx, vy) = (dphi * t[0], dphi * t[1]);
                    add(ca, ob + b, weight[0] * vx + weight[1] * vy);
                }
            }
        }
    }
}

/// Derivatives of point `r` (in the frame of `body`), in fresh buffers.
pub fn point(m: &Mechanism, f: &Frames, body: usize, r: Point2<f64>, hessian: bool) -> PointDerivatives {
    let n = m.dof();
    let mut p = PointBuffer::new(m);
    point_into(m, f, body, r, &mut p);
    let hessian = hessian.then(|| {
        let (mut hx, mut hy) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
        add_point_hessian(m, f, &p, Vector2::x(), &mut hx);
        add_point_hessian(m, f, &p, Vector2::y(), &mut hy);
        [hx, hy]
    });
    PointDerivatives { phi: p.phi, position: p.position, jacobian: p.jacobian, hessian }
}

/// The largest rotation (rad) between configurations `a` and `b` of any
/// body or of a flexure's cross-section relative to its root, and a
/// slider's travel over `length` (the mechanism's size): what bounds a
/// continuation step ([`crate::solver::Problem::distance`]) and an
/// integration step (the dynamics' `System::distance`). `angles` holds
/// two buffers of one entry per body.
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
    let mut d = ba.iter().zip(bb.iter()).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    for j in &m.joints {
        let joint = j.kind.joint();
        let range = j.offset..j.offset + joint.dof();
        d = d.max(joint.distance(&a[range.clone()], &b[range], length));
    }
    d
}
