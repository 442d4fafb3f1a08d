//! What the tree's kinematics needs of a dimension beyond [`Dimension`]:
//! how a frame's rotation is kept for one evaluation, an angular velocity
//! and its cross product, and the same-joint block of a point's Hessian
//! (parry's math aliases: one set of names, a scalar angle in the plane).
//! The plane and space implement it here, side by side.
//!
//! In the plane $\omega$ is a rate about $z$ and $\omega\times r$ is the
//! quarter turn $\omega\thinspace\mathrm J r$; rotations add, so a frame keeps
//! its $(\sin\phi, \cos\phi)$, computed once per evaluation (the planar fast
//! path), and no joint kind has a curved angle ($\partial_{ab}\phi = 0$). In
//! space a frame keeps its rotation matrix.

use super::wrenches::{JointWrenches, same_joint};
use super::{Attached, Frames};
use crate::mechanism::{Dimension, Mechanism};
use crate::space::{Planar, Pose, Spatial, rotate_turned};
use nalgebra::{DMatrix, Isometry3, Matrix3, Point3, Vector2, Vector3};
use std::fmt::Debug;

/// A dimension whose tree of frames, points and their derivatives
/// [`super::frames_into`] and [`super::attach_into`] compute.
///
/// # Example
/// ```
/// use flexure::mechanism::kinematics::FrameChain;
/// use flexure::space::{Planar, Spatial};
/// use nalgebra::{Vector2, Vector3};
/// // ω × r: the quarter turn in the plane, the cross product in space.
/// assert_eq!(Planar::spin(&2.0, &Vector2::new(1.0, 0.0)), Vector2::new(0.0, 2.0));
/// assert_eq!(Spatial::spin(&Vector3::z(), &Vector3::x()), Vector3::y());
/// ```
pub trait FrameChain: Dimension {
    /// An angular velocity: a rate about $z$ in the plane, a vector in space.
    type Angular: Copy + Debug + Default + PartialEq;
    /// A frame's rotation as one evaluation keeps it: $(\sin\phi, \cos\phi)$, or the matrix.
    type Turn: Copy + Debug;
    /// The same-joint parts of Hessians gathered per joint (none in the plane).
    type Sums: Clone + Debug;
    /// Components of [`FrameChain::Angular`]: the rows that open a point's Jacobian.
    const ANGULAR: usize;

    /// The rotation of `pose`, kept for one evaluation.
    fn turn(pose: &Self::Pose) -> Self::Turn;
    /// $a\thinspace b$, with `a`'s [`FrameChain::turn`] known.
    fn compose_turned(a: &Self::Pose, turn: &Self::Turn, b: &Self::Pose) -> Self::Pose;
    /// $R r + p$ (a point) or $R r$ (a direction), with `a`'s [`FrameChain::turn`] known.
    fn act_turned(a: &Self::Pose, turn: &Self::Turn, r: &Self::Vector, point: bool) -> Self::Vector;
    /// $p$: the frame's origin.
    fn translation(a: &Self::Pose) -> Self::Vector;
    /// The world twist $(\omega_a, v_a)$ of a joint's motion subspace column
    /// `s` (`TWIST_DIM` components), turned by its root frame's `turn`.
    fn twist(turn: &Self::Turn, s: &[f64]) -> (Self::Angular, Self::Vector);
    /// $\omega\times r$.
    fn spin(w: &Self::Angular, r: &Self::Vector) -> Self::Vector;
    /// $u\cdot(\omega\times x)$, each dimension in its cheapest form.
    fn triple(u: &Self::Vector, w: &Self::Angular, x: &Self::Vector) -> f64;
    /// Writes $(\omega, x)$ into a Jacobian column of `TWIST_DIM` rows.
    fn write(column: &mut [f64], w: &Self::Angular, x: &Self::Vector);
    /// The position rows of a Jacobian column.
    fn linear(column: &[f64]) -> Self::Vector;
    /// Empty sums for the joints of `m`.
    fn sums(m: &Mechanism<Self>) -> Self::Sums;
    /// Adds every joint's gathered block to `h` and empties the sums.
    fn flush(m: &Mechanism<Self>, f: &Frames<Self>, sums: &mut Self::Sums, h: &mut DMatrix<f64>);
    /// The part of $\sum_c u_c\nabla^2 x_c$ within joint `j` on the path of
    /// `x`, added to `h` or gathered into `sums`.
    fn within_joint(
        m: &Mechanism<Self>,
        f: &Frames<Self>,
        j: usize,
        x: &Attached<Self>,
        u: &Self::Vector,
        sums: Option<&mut Self::Sums>,
        h: &mut DMatrix<f64>,
    );
}

impl FrameChain for Planar {
    type Angular = f64;
    type Turn = (f64, f64);
    type Sums = ();
    const ANGULAR: usize = 1;

    fn turn(pose: &Pose) -> (f64, f64) {
        pose.turn()
    }
    fn compose_turned(a: &Pose, turn: &(f64, f64), b: &Pose) -> Pose {
        a.compose_turned(*turn, b)
    }
    fn act_turned(a: &Pose, turn: &(f64, f64), r: &Vector2<f64>, point: bool) -> Vector2<f64> {
        let w = if point { a.act_turned(*turn, [r.x, r.y]) } else { rotate_turned(*turn, [r.x, r.y]) };
        Vector2::new(w[0], w[1])
    }
    fn translation(a: &Pose) -> Vector2<f64> {
        Vector2::new(a.x, a.y)
    }
    fn twist(turn: &(f64, f64), s: &[f64]) -> (f64, Vector2<f64>) {
        let v = rotate_turned(*turn, [s[1], s[2]]);
        (s[0], Vector2::new(v[0], v[1]))
    }
    fn spin(w: &f64, r: &Vector2<f64>) -> Vector2<f64> {
        Vector2::new(w * -r.y, w * r.x)
    }
    fn triple(u: &Vector2<f64>, w: &f64, x: &Vector2<f64>) -> f64 {
        let t = [-x.y, x.x];
        u.x * (w * t[0]) + u.y * (w * t[1])
    }
    fn write(column: &mut [f64], w: &f64, x: &Vector2<f64>) {
        column[0] = *w;
        column[1] = x.x;
        column[2] = x.y;
    }
    fn linear(column: &[f64]) -> Vector2<f64> {
        Vector2::new(column[1], column[2])
    }
    fn sums(_: &Mechanism) {}
    fn flush(_: &Mechanism, _: &Frames, _: &mut (), _: &mut DMatrix<f64>) {}
    /// $u\cdot(R_A\thinspace\partial_{ab}p_j - \partial_a\phi\thinspace\partial_b\phi\thinspace(w - o_j))$,
    /// read straight from the joint's Hessians.
    fn within_joint(
        m: &Mechanism,
        f: &Frames,
        j: usize,
        x: &Attached,
        u: &Vector2<f64>,
        _: Option<&mut ()>,
        h: &mut DMatrix<f64>,
    ) {
        let (o, s) = (m.joints[j].offset, &f.joints[j]);
        let k = s.gradient.len();
        let origin = &f.bodies[m.joints[j].child];
        let arm = [x.value.x - origin.x, x.value.y - origin.y];
        let root = *f.root_turn(j);
        let (hx, hy, local) = (s.hessian[1].as_slice(), s.hessian[2].as_slice(), s.jacobian.as_slice());
        let n = h.nrows();
        let h = h.as_mut_slice();
        for a in 0..k {
            for b in a..k {
                let turned = rotate_turned(root, [hx[b * k + a], hy[b * k + a]]);
                let dphi = local[3 * a] * local[3 * b];
                let (vx, vy) = (turned[0] - dphi * arm[0], turned[1] - dphi * arm[1]);
                let v = u[0] * vx + u[1] * vy;
                let (r, c) = (o + a, o + b);
                h[c * n + r] += v;
                if r != c {
                    h[r * n + c] += v;
                }
            }
        }
    }
}

impl FrameChain for Spatial {
    type Angular = Vector3<f64>;
    type Turn = Matrix3<f64>;
    type Sums = JointWrenches;
    const ANGULAR: usize = 3;

    fn turn(pose: &Isometry3<f64>) -> Matrix3<f64> {
        pose.rotation.to_rotation_matrix().into_inner()
    }
    fn compose_turned(a: &Isometry3<f64>, _: &Matrix3<f64>, b: &Isometry3<f64>) -> Isometry3<f64> {
        a * b
    }
    fn act_turned(a: &Isometry3<f64>, turn: &Matrix3<f64>, r: &Vector3<f64>, point: bool) -> Vector3<f64> {
        if point { (a * Point3::from(*r)).coords } else { turn * r }
    }
    fn translation(a: &Isometry3<f64>) -> Vector3<f64> {
        a.translation.vector
    }
    fn twist(turn: &Matrix3<f64>, s: &[f64]) -> (Vector3<f64>, Vector3<f64>) {
        (turn * Vector3::new(s[0], s[1], s[2]), turn * Vector3::new(s[3], s[4], s[5]))
    }
    fn spin(w: &Vector3<f64>, r: &Vector3<f64>) -> Vector3<f64> {
        w.cross(r)
    }
    /// $-x\cdot(\omega\times u)$.
    fn triple(u: &Vector3<f64>, w: &Vector3<f64>, x: &Vector3<f64>) -> f64 {
        -x.dot(&w.cross(u))
    }
    fn write(column: &mut [f64], w: &Vector3<f64>, x: &Vector3<f64>) {
        column[..3].copy_from_slice(w.as_slice());
        column[3..].copy_from_slice(x.as_slice());
    }
    fn linear(column: &[f64]) -> Vector3<f64> {
        Vector3::new(column[3], column[4], column[5])
    }
    fn sums(m: &Mechanism<Spatial>) -> JointWrenches {
        JointWrenches::new(m)
    }
    fn flush(m: &Mechanism<Spatial>, f: &Frames<Spatial>, sums: &mut JointWrenches, h: &mut DMatrix<f64>) {
        sums.flush(m, f, h);
    }
    /// The world wrench of $u$ on joint $j$ and its turn matrix
    /// ([`JointWrenches`]), contracted with the joint's $\partial S$.
    fn within_joint(
        m: &Mechanism<Spatial>,
        f: &Frames<Spatial>,
        j: usize,
        x: &Attached<Spatial>,
        u: &Vector3<f64>,
        sums: Option<&mut JointWrenches>,
        h: &mut DMatrix<f64>,
    ) {
        let r = if x.point { x.value - f.output_origin(m, j) } else { x.value };
        let force = if x.point { *u } else { Vector3::zeros() };
        let turn = r * u.transpose() - Matrix3::from_diagonal_element(u.dot(&r));
        same_joint(m, f, j, (r.cross(u), force, turn), sums, h);
    }
}
