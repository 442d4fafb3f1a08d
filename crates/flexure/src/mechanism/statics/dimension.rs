//! What the statics needs of a dimension beyond [`Potential`] (its frames,
//! [`crate::mechanism::kinematics`], and its Lagrangian,
//! [`crate::mechanism::lagrangian`]): the level its frames are evaluated
//! to for Newton, its loads' arithmetic, the
//! size of its closure rows and loads, and the few tests whose fast paths
//! only one dimension has. [`Kkt`], the paths, the assembly, stiffness,
//! compliance, sweeps and buckling are written once over it; the plane and
//! space implement it here, side by side.

use super::Kkt;
use crate::error::{Error, Result};
use crate::kinematics::Level;
use crate::linalg;
use crate::mechanism::indeterminate::{full_row_rank, settle};
use crate::mechanism::kinematics::{Frames, frames, frames_into, frames_level_into};
use crate::mechanism::lagrangian::{Assembly, Potential, check_sizes};
use crate::mechanism::tree::Tree;
use crate::mechanism::{Loads, Mechanism};
use crate::space::Wrench;
use crate::space::{Planar, Spatial};
use nalgebra::{DMatrix, DVector, Matrix3, Matrix6, Point2, Point3, Vector2, Vector3, Vector6};
use std::cell::RefCell;
use std::fmt::Debug;

/// The Lagrangian as the KKT conditions read it: $\nabla V$, its Hessian
/// (with the closures' $\sum_i\mu_i\nabla^2c_i$), $c$ and $G$.
#[doc(hidden)]
pub struct Parts<'a> {
    pub gradient: &'a DVector<f64>,
    pub hessian: &'a DMatrix<f64>,
    pub closure: &'a DVector<f64>,
    pub closure_jacobian: &'a DMatrix<f64>,
}

/// The parts of an assembly the KKT conditions read.
pub(crate) fn parts<D: Potential>(a: &Assembly<D>) -> Parts<'_> {
    Parts { gradient: &a.gradient, hessian: &a.hessian, closure: &a.closure, closure_jacobian: &a.closure_jacobian }
}

/// A dimension the statics of a [`Mechanism`] is solved in: [`Planar`] or [`Spatial`].
///
/// # Example
/// ```
/// use flexure::mechanism::spatial::{RevoluteUnaligned, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism, SpatialPointLoad};
/// use flexure::mechanism::statics::{Statics, solve};
/// use flexure::space::{Planar, Spatial};
/// use nalgebra::{Isometry3, Point3, Vector3, Vector6};
/// // A closure's position rows: x, y in the plane; x, y, z in space.
/// assert_eq!((Planar::POSITION_ROWS, Spatial::POSITION_ROWS), (2, 3));
/// // The one `solve`, in space: a sprung hinge (k = 2 N·m/rad) under 0.5 N·m about its axis.
/// let hinge = SpatialJointSpec {
///     name: "hinge".into(), kind: SpatialJointKind::Revolute(RevoluteUnaligned { axis: Vector3::x_axis(), stiffness: 2.0, rest: 0.0 }),
///     parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0, auto_order: false, report: Default::default(),
/// };
/// let push = SpatialPointLoad { name: "m".into(), body: 1, at: Point3::origin(), wrench: Vector6::new(0.5, 0.0, 0.0, 0.0, 0.0, 0.0) };
/// let bodies = vec![SpatialBody::massless("ground"), SpatialBody::massless("arm")];
/// let m = SpatialMechanism::new(bodies, vec![hinge], vec![], vec![push], vec![], Vector3::zeros()).unwrap();
/// let s = solve(&m, &Default::default()).unwrap();
/// assert!(s.stable && (s.q[0] - 0.25).abs() < 1e-12); // M/k
/// ```
pub trait Statics: Potential + crate::mechanism::contact::Touch + PartialEq + Sized {
    /// The buffers only this dimension's problem uses.
    type Own: Clone + Debug;
    /// A point's compliance: $3\times3$ in the plane, $6\times6$ in space.
    type Compliance;
    /// The position rows that open each closure's equations (the rest are angles).
    const POSITION_ROWS: usize;
    /// Whether a dead moment makes the load stiffness unsymmetric (a
    /// rotation that does not commute), so that stiffness and compliance
    /// are not symmetrized.
    const DEAD_MOMENTS: bool;
    /// Whether the assembly converges to the tolerance of its own loads
    /// (those at $\lambda = 0$), not of the whole path's; and whether a
    /// path's iterations leave out the assembly's.
    const OWN_ASSEMBLY: bool;
    /// Whether a path that cannot start names the joints of the start's
    /// free motion (else it says the solver's words: the rest state has a
    /// zero-stiffness mode along the load).
    const NAMES_FREE_MOTION: bool;
    /// What loads that do not soften this dimension's mechanism are, for
    /// [`crate::mechanism::buckling::buckle`]'s error.
    const NO_SOFTENING: &'static str;

    fn new_own(m: &Mechanism<Self>) -> Self::Own;
    fn copy_frames(from: &Frames<Self>, to: &mut Frames<Self>);
    /// The frames of the bodies (poses alone, where that is cheaper).
    fn pose_frames(m: &Mechanism<Self>, q: &[f64]) -> Frames<Self>;
    fn point_finite(at: &Self::Point) -> bool;
    fn compliance_matrix(c: &DMatrix<f64>) -> Self::Compliance;
    /// The frames Newton's residual and matrix are assembled from.
    fn newton_frames(m: &Mechanism<Self>, q: &[f64], f: &mut Frames<Self>);
    /// The largest moment `l` applies (N·m), with the mechanism's length `length`.
    fn load_size(m: &Mechanism<Self>, l: &Loads<Self>, length: f64) -> f64;
    /// No load, shaped like `l`, into `out`.
    fn zero_into(l: &Loads<Self>, out: &mut Loads<Self>);
    /// No load, shaped like `l`.
    fn zero(l: &Loads<Self>) -> Loads<Self> {
        let mut out = Loads::default();
        Self::zero_into(l, &mut out);
        out
    }
    /// `from` into `to`, in `to`'s buffers.
    fn copy_loads(from: &Loads<Self>, to: &mut Loads<Self>) {
        to.tension.clone_from(&from.tension);
        to.force.clone_from(&from.force);
        to.gravity = from.gravity;
    }
    /// `b − a` into `out` (shaped like them).
    fn difference_into(a: &Loads<Self>, b: &Loads<Self>, out: &mut Loads<Self>);
    /// $(1 - s)a + sb$ into `out`.
    fn lerp_into(a: &Loads<Self>, b: &Loads<Self>, s: f64, out: &mut Loads<Self>);
    /// Checks that a start solution's sizes fit `m`.
    fn check_start(m: &Mechanism<Self>, q: &[f64], mu: &[f64], loads: &Loads<Self>) -> Result<()>;
    /// Whether Newton steps and stability tests may factor the tree in $O(n)$.
    fn tree(m: &Mechanism<Self>) -> bool;
    /// [`crate::solver::Problem::stable`].
    fn stable(k: &mut Kkt<'_, Self>, x: &[f64], lambda: f64, jacobian: &[f64]) -> bool;
    /// [`crate::solver::Problem::far_from_instability`].
    fn far_from_instability(k: &mut Kkt<'_, Self>, jacobian: &[f64]) -> bool;
    /// [`crate::solver::Problem::factor`].
    fn factor(k: &mut Kkt<'_, Self>, jacobian: &[f64]) -> bool;
    /// [`crate::solver::Problem::solve_factored`].
    fn solve_factored(k: &mut Kkt<'_, Self>, b: &mut [f64]);
    /// [`crate::solver::Problem::distance`].
    fn distance(k: &Kkt<'_, Self>, a: &[f64], b: &[f64]) -> f64;
    /// The multipliers `mu` of a solution at `q` under `loads`, their
    /// statically indeterminate part settled (see [`super::Solution::multipliers`]);
    /// leaves the frames at `q` in the workspace.
    fn settled(k: &mut Kkt<'_, Self>, q: &[f64], mu: Vec<f64>, loads: &Loads<Self>) -> Vec<f64>;
    /// The pre-buckling closure forces `mu` (at the frames `f`, assembly
    /// `a`) with their indeterminate part settled under `loads`.
    fn settle_pre_buckling(
        m: &Mechanism<Self>,
        f: &Frames<Self>,
        a: &Assembly<Self>,
        mu: &[f64],
        loads: &Loads<Self>,
    ) -> Vec<f64>;
    /// Whether the rows of `g` are independent, so that no closure force is indeterminate.
    fn full_row_rank(g: &DMatrix<f64>) -> bool;
    /// A point load's force, padded with zeros.
    fn force(w: &Self::Wrench) -> [f64; 3];
    /// A vector's components, padded with zeros.
    fn vector(v: &Self::Vector) -> [f64; 3];
    /// The pulls of a tendon along `path` (at the frames `f`) on the bodies
    /// of its via points, each toward its neighbours, into `out`.
    fn tendon_pulls(f: &Frames<Self>, path: &[(usize, Self::Point)], tension: f64, out: &mut Vec<(usize, [f64; 3])>);
    /// The error for closures Newton could not close from rest.
    fn unassembled(m: &Mechanism<Self>, length: f64, e: Error) -> Error;
}

/// The planar problem's own buffers: the tree's factorization and two states' body angles.
#[derive(Debug, Clone)]
#[doc(hidden)]
pub struct PlanarOwn {
    pub(super) tree: Tree,
    pub(super) angles: RefCell<[Vec<f64>; 2]>,
}

/// The spatial problem's own buffers: pose-level frames of two states for
/// [`crate::solver::Problem::distance`], each with whether it holds its
/// coordinates' frames yet.
#[derive(Debug, Clone)]
#[doc(hidden)]
pub struct SpatialOwn {
    pub(crate) pair: RefCell<([Frames<Spatial>; 2], [bool; 2])>,
}

impl Statics for Planar {
    type Own = PlanarOwn;
    type Compliance = Matrix3<f64>;
    const POSITION_ROWS: usize = 2;
    const DEAD_MOMENTS: bool = false;
    const OWN_ASSEMBLY: bool = false;
    const NAMES_FREE_MOTION: bool = true;
    const NO_SOFTENING: &'static str = "a pure moment, or only tension";

    fn new_own(m: &Mechanism) -> PlanarOwn {
        PlanarOwn { tree: Tree::new(m), angles: RefCell::new([vec![0.0; m.bodies.len()], vec![0.0; m.bodies.len()]]) }
    }
    fn copy_frames(from: &Frames, to: &mut Frames) {
        if (to.bodies.len(), to.joints.len()) != (from.bodies.len(), from.joints.len()) {
            *to = from.clone();
        } else {
            to.copy_from(from);
        }
    }
    fn pose_frames(m: &Mechanism, q: &[f64]) -> Frames {
        frames(m, q)
    }
    fn point_finite(at: &Point2<f64>) -> bool {
        at.iter().all(|v| v.is_finite())
    }
    fn compliance_matrix(c: &DMatrix<f64>) -> Matrix3<f64> {
        Matrix3::from_fn(|i, j| c[(i, j)])
    }
    fn newton_frames(m: &Mechanism, q: &[f64], f: &mut Frames) {
        frames_into(m, q, f);
    }
    fn load_size(m: &Mechanism, l: &Loads, length: f64) -> f64 {
        let forces: f64 = l.force.iter().map(|f| f.fx.hypot(f.fy) * length + f.moment.abs()).sum();
        let tendons: f64 = l.tension.iter().map(|t| t * length).sum();
        let mass: f64 = m.bodies.iter().map(|b| b.mass).sum();
        forces + tendons + mass * l.gravity[0].hypot(l.gravity[1]) * length
    }
    /// [`Loads::zero_like`]: every load times zero.
    fn zero_into(l: &Loads, out: &mut Loads) {
        Self::copy_loads(l, out);
        out.scale(0.0);
    }
    fn difference_into(a: &Loads, b: &Loads, out: &mut Loads) {
        Self::copy_loads(b, out);
        out.tension.iter_mut().zip(&a.tension).for_each(|(b, a)| *b -= a);
        out.force.iter_mut().zip(&a.force).for_each(|(b, a)| (0..3).for_each(|i| b[i] -= a[i]));
        out.gravity = b.gravity - a.gravity;
    }
    fn lerp_into(a: &Loads, b: &Loads, s: f64, out: &mut Loads) {
        a.lerp_into(b, s, out);
    }
    fn check_start(m: &Mechanism, q: &[f64], mu: &[f64], loads: &Loads) -> Result<()> {
        check_sizes(m, q, mu, loads)
    }
    fn tree(m: &Mechanism) -> bool {
        m.closures.is_empty() && m.tendons.is_empty() && Tree::applies(m)
    }
    fn stable(k: &mut Kkt<'_, Planar>, x: &[f64], lambda: f64, jacobian: &[f64]) -> bool {
        k.stable_planar(x, lambda, jacobian)
    }
    fn far_from_instability(k: &mut Kkt<'_, Planar>, jacobian: &[f64]) -> bool {
        k.far_planar(jacobian)
    }
    fn factor(k: &mut Kkt<'_, Planar>, jacobian: &[f64]) -> bool {
        let n = k.mechanism.dof();
        if !k.tree || n == 0 {
            return false;
        }
        let rows = &k.row_scale;
        k.work.own.tree.factor(|r, c| jacobian[c * n + r] / rows[r], &[], false).is_some()
    }
    fn solve_factored(k: &mut Kkt<'_, Planar>, b: &mut [f64]) {
        // ∂r/∂q = diag(row_scale) ∇²V.
        for (b, r) in b.iter_mut().zip(&k.row_scale) {
            *b /= r;
        }
        k.work.own.tree.solve(b);
    }
    /// The largest rotation of a body, or of a flexure's cross-section
    /// relative to its root, and a slider's travel over the mechanism's length.
    fn distance(k: &Kkt<'_, Planar>, a: &[f64], b: &[f64]) -> f64 {
        let n = k.mechanism.dof();
        let mut buffers = k.work.own.angles.borrow_mut();
        crate::mechanism::kinematics::distance(k.mechanism, &a[..n], &b[..n], k.length, &mut buffers)
    }
    fn settled(k: &mut Kkt<'_, Planar>, q: &[f64], mu: Vec<f64>, loads: &Loads) -> Vec<f64> {
        k.settled_planar(q, mu, loads)
    }
    fn settle_pre_buckling(m: &Mechanism, f: &Frames, a: &Assembly, mu: &[f64], loads: &Loads) -> Vec<f64> {
        settle(m, f, &a.closure_jacobian, mu, loads)
    }
    /// Independent by a wide margin ([`crate::linalg::columns_independent`] of $G^T$).
    fn full_row_rank(g: &DMatrix<f64>) -> bool {
        full_row_rank(g)
    }
    fn force(w: &Wrench) -> [f64; 3] {
        [w.fx, w.fy, 0.0]
    }
    fn vector(v: &Vector2<f64>) -> [f64; 3] {
        [v[0], v[1], 0.0]
    }
    fn tendon_pulls(f: &Frames, path: &[(usize, Point2<f64>)], tension: f64, out: &mut Vec<(usize, [f64; 3])>) {
        let w: Vec<[f64; 2]> = path.iter().map(|(b, r)| f.bodies[*b].act_components([r.x, r.y])).collect();
        for (i, pair) in w.windows(2).enumerate() {
            let d = [pair[1][0] - pair[0][0], pair[1][1] - pair[0][1]];
            let len = d[0].hypot(d[1]);
            if len > 0.0 {
                let pull = [tension * d[0] / len, tension * d[1] / len];
                out.push((path[i].0, [pull[0], pull[1], 0.0]));
                out.push((path[i + 1].0, [-pull[0], -pull[1], 0.0]));
            }
        }
    }
    fn unassembled(m: &Mechanism, length: f64, e: Error) -> Error {
        super::assembly::unassembled(m, length, e)
    }
}

impl Statics for Spatial {
    type Own = SpatialOwn;
    type Compliance = Matrix6<f64>;
    const POSITION_ROWS: usize = 3;
    const DEAD_MOMENTS: bool = true;
    const OWN_ASSEMBLY: bool = true;
    const NAMES_FREE_MOTION: bool = false;
    const NO_SOFTENING: &'static str = "only tension, or loads that stiffen it";

    fn new_own(m: &Mechanism<Spatial>) -> SpatialOwn {
        SpatialOwn { pair: RefCell::new(([Frames::new(m), Frames::new(m)], [false; 2])) }
    }
    fn copy_frames(from: &Frames<Spatial>, to: &mut Frames<Spatial>) {
        to.clone_from(from);
    }
    /// Jacobian-level frames even for the Newton matrix: each joint's
    /// second derivatives enter contracted with the wrench it carries
    /// ([`crate::mechanism::Joint::add_wrench_hessian`]; for a spatial
    /// flexure by quadrature of the virtual work, within the Magnus rule's
    /// $h^6$ of the exact Hessian). The residual is exact, so only Newton's
    /// rate and the stability tests see the difference; [`super::stiffness()`]
    /// takes the exact Hessian.
    fn newton_frames(m: &Mechanism<Spatial>, q: &[f64], f: &mut Frames<Spatial>) {
        frames_level_into(m, q, Level::Jacobian, f);
    }
    fn pose_frames(m: &Mechanism<Spatial>, q: &[f64]) -> Frames<Spatial> {
        spatial_frames_at(m, q, Level::Pose)
    }
    fn point_finite(at: &Point3<f64>) -> bool {
        at.iter().all(|v| v.is_finite())
    }
    fn compliance_matrix(c: &DMatrix<f64>) -> Matrix6<f64> {
        Matrix6::from_fn(|r, col| c[(r, col)])
    }
    fn load_size(m: &Mechanism<Spatial>, l: &Loads<Spatial>, length: f64) -> f64 {
        let forces: f64 =
            l.force.iter().map(|w| w.fixed_rows::<3>(3).norm() * length + w.fixed_rows::<3>(0).norm()).sum();
        let tendons: f64 = l.tension.iter().map(|t| t * length).sum();
        let mass: f64 = m.bodies.iter().map(|b| b.mass).sum();
        forces + tendons + mass * l.gravity.norm() * length
    }
    fn zero_into(l: &Loads<Spatial>, out: &mut Loads<Spatial>) {
        Self::copy_loads(l, out);
        out.tension.fill(0.0);
        out.force.fill(nalgebra::Vector6::zeros());
        out.gravity = nalgebra::Vector3::zeros();
    }
    fn difference_into(a: &Loads<Spatial>, b: &Loads<Spatial>, out: &mut Loads<Spatial>) {
        *out = a.difference(b);
    }
    fn lerp_into(a: &Loads<Spatial>, b: &Loads<Spatial>, s: f64, out: &mut Loads<Spatial>) {
        a.lerp_into(b, s, out);
    }
    fn check_start(m: &Mechanism<Spatial>, q: &[f64], mu: &[f64], _: &Loads<Spatial>) -> Result<()> {
        if q.len() != m.dof() || mu.len() != m.constraints() {
            return Err(Error::invalid("start", q.len(), "was solved for another mechanism"));
        }
        Ok(())
    }
    fn tree(_: &Mechanism<Spatial>) -> bool {
        false
    }
    fn stable(k: &mut Kkt<'_, Spatial>, _: &[f64], _: f64, jacobian: &[f64]) -> bool {
        k.stable_spatial(jacobian)
    }
    fn far_from_instability(k: &mut Kkt<'_, Spatial>, jacobian: &[f64]) -> bool {
        k.far_spatial(jacobian)
    }
    fn factor(_: &mut Kkt<'_, Spatial>, _: &[f64]) -> bool {
        false
    }
    fn solve_factored(_: &mut Kkt<'_, Spatial>, _: &mut [f64]) {}
    fn distance(k: &Kkt<'_, Spatial>, a: &[f64], b: &[f64]) -> f64 {
        k.distance_spatial(a, b)
    }
    fn settled(k: &mut Kkt<'_, Spatial>, q: &[f64], mu: Vec<f64>, loads: &Loads<Spatial>) -> Vec<f64> {
        k.settled_spatial(q, mu, loads)
    }
    /// The least-norm forces as they are (the spatial buckling has never settled them).
    fn settle_pre_buckling(
        _: &Mechanism<Spatial>,
        _: &Frames<Spatial>,
        _: &Assembly<Spatial>,
        mu: &[f64],
        _: &Loads<Spatial>,
    ) -> Vec<f64> {
        mu.to_vec()
    }
    /// Independent by a wide margin (a Cholesky of $GG^T$), or else to the singular values.
    fn full_row_rank(g: &DMatrix<f64>) -> bool {
        let rows = g.nrows();
        let mut gram = vec![0.0; rows * rows];
        linalg::columns_independent(g.transpose().as_slice(), g.ncols(), rows, &mut gram)
            || g.clone().svd(false, false).rank(1e-10 * g.amax().max(f64::MIN_POSITIVE)) == rows
    }
    fn force(w: &Vector6<f64>) -> [f64; 3] {
        [w[3], w[4], w[5]]
    }
    fn vector(v: &Vector3<f64>) -> [f64; 3] {
        [v[0], v[1], v[2]]
    }
    fn tendon_pulls(
        f: &Frames<Spatial>,
        path: &[(usize, Point3<f64>)],
        tension: f64,
        out: &mut Vec<(usize, [f64; 3])>,
    ) {
        let w: Vec<Vector3<f64>> = path.iter().map(|(b, r)| (f.bodies[*b] * r).coords).collect();
        for (i, pair) in w.windows(2).enumerate() {
            let d = pair[1] - pair[0];
            if d.norm() > 0.0 {
                let pull = d * (tension / d.norm());
                out.push((path[i].0, [pull[0], pull[1], pull[2]]));
                out.push((path[i + 1].0, [-pull[0], -pull[1], -pull[2]]));
            }
        }
    }
    fn unassembled(_: &Mechanism<Spatial>, _: f64, e: Error) -> Error {
        Error::Singular {
            what: format!("mechanism assembly: the closures could not be closed from the joints' rest ({e})"),
        }
    }
}

/// The frames of `m` at `q`, with the joints evaluated to `level`.
fn spatial_frames_at(m: &Mechanism<Spatial>, q: &[f64], level: Level) -> Frames<Spatial> {
    let mut f = Frames::new(m);
    frames_level_into(m, q, level, &mut f);
    f
}
