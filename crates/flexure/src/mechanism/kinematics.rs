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
use nalgebra::DMatrix;

/// A planar frame in the world: angle and origin.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Frame {
    /// Rotation (rad).
    pub angle: f64,
    /// Origin (m).
    pub origin: [f64; 2],
}

impl Frame {
    /// A point given in this frame, in the world.
    pub fn point(&self, r: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.angle.sin_cos();
        [self.origin[0] + c * r[0] - s * r[1], self.origin[1] + s * r[0] + c * r[1]]
    }

    /// A direction given in this frame, in the world.
    pub fn rotate(&self, v: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.angle.sin_cos();
        [c * v[0] - s * v[1], s * v[0] + c * v[1]]
    }

    /// The frame `(x, y, phi)` relative to this one.
    pub fn then(&self, x: f64, y: f64, phi: f64) -> Frame {
        Frame { angle: self.angle + phi, origin: self.point([x, y]) }
    }
}

/// Every frame of the mechanism at one configuration (the Data).
#[derive(Debug, Clone)]
pub struct Frames {
    /// Body frames in the world; index 0 is the ground.
    pub bodies: Vec<Frame>,
    /// Each joint's root frame in the world.
    pub roots: Vec<Frame>,
    /// Each joint's pose, derivatives and energy.
    pub joints: Vec<JointState>,
}

/// Frames at coordinates `q`, parents before children.
pub fn frames(m: &Mechanism, q: &[f64]) -> Frames {
    let mut bodies = vec![Frame::default(); m.bodies.len()];
    let mut roots = Vec::with_capacity(m.joints.len());
    let mut joints = Vec::with_capacity(m.joints.len());
    for j in &m.joints {
        let dof = j.kind.joint().dof();
        let state = j.kind.joint().evaluate(&q[j.offset..j.offset + dof]);
        let root = bodies[j.parent].then(j.origin.x, j.origin.y, j.origin.phi);
        bodies[j.child] = root.then(state.pose.x, state.pose.y, state.pose.phi);
        roots.push(root);
        joints.push(state);
    }
    Frames { bodies, roots, joints }
}

/// A point's world position and angle with derivatives in $q$.
#[derive(Debug, Clone)]
pub struct PointDerivatives {
    /// Angle of the body (rad).
    pub angle: f64,
    /// World position (m).
    pub position: [f64; 2],
    /// $3\times n$: rows $(\theta, x, y)$.
    pub jacobian: DMatrix<f64>,
    /// Hessians of $x$ and $y$ ($n\times n$), if asked for.
    pub hessian: Option<[DMatrix<f64>; 2]>,
}

fn quarter(v: [f64; 2]) -> [f64; 2] {
    [-v[1], v[0]]
}

/// Derivatives of point `r` (in the frame of `body`).
pub fn point(m: &Mechanism, f: &Frames, body: usize, r: [f64; 2], hessian: bool) -> PointDerivatives {
    let n = m.dof();
    let w = f.bodies[body].point(r);
    let mut jac = DMatrix::zeros(3, n);
    let path = m.path(body);
    // Coordinates on the path, with their joint's position along it.
    let mut coords: Vec<(usize, usize, usize)> = Vec::new();
    for (step, &ji) in path.iter().enumerate() {
        let j = &m.joints[ji];
        let s = &f.joints[ji];
        let root = f.roots[ji];
        let o = f.bodies[j.child].origin;
        let arm = [w[0] - o[0], w[1] - o[1]];
        for i in 0..j.kind.joint().dof() {
            let col = j.offset + i;
            let dphi = s.jacobian[(0, i)];
            let dp = root.rotate([s.jacobian[(1, i)], s.jacobian[(2, i)]]);
            let turn = quarter(arm);
            jac[(0, col)] = dphi;
            jac[(1, col)] = dp[0] + dphi * turn[0];
            jac[(2, col)] = dp[1] + dphi * turn[1];
            coords.push((step, ji, i));
        }
    }
    let hessian = hessian.then(|| {
        let (mut hx, mut hy) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
        for (ia, &(sa, ja, a)) in coords.iter().enumerate() {
            let ca = m.joints[ja].offset + a;
            for &(sb, jb, b) in &coords[ia..] {
                let cb = m.joints[jb].offset + b;
                let (vx, vy) = if sa == sb {
                    let s = &f.joints[ja];
                    let root = f.roots[ja];
                    let o = f.bodies[m.joints[ja].child].origin;
                    let local = root.rotate([s.hessian_x[(a, b)], s.hessian_y[(a, b)]]);
                    let k = s.jacobian[(0, a)] * s.jacobian[(0, b)];
                    (local[0] - k * (w[0] - o[0]), local[1] - k * (w[1] - o[1]))
                } else {
                    // a is upstream of b: ∂_a φ · J · ∂_b w.
                    let dphi = f.joints[ja].jacobian[(0, a)];
                    let t = quarter([jac[(1, cb)], jac[(2, cb)]]);
                    (dphi * t[0], dphi * t[1])
                };
                hx[(ca, cb)] = vx;
                hx[(cb, ca)] = vx;
                hy[(ca, cb)] = vy;
                hy[(cb, ca)] = vy;
            }
        }
        [hx, hy]
    });
    PointDerivatives { angle: f.bodies[body].angle, position: w, jacobian: jac, hessian }
}
