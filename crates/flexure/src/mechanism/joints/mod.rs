//! The joint interface (Pinocchio's joint model and data): every joint kind
//! computes its placement, motion subspace and its derivative, its elastic
//! energy with gradient and stiffness, its damping, and its rest, and the
//! mechanism's algorithms only call it.
//!
//! A kind is a type implementing [`Joint`] in its own file; [`JointKind`]
//! lists them for both dimensions, each variant of the dimension's type
//! ([`Dimension`]), and its [`JointKind::joint`] is the one place that
//! matches on the kind. Adding a kind touches its file, that enum, its
//! type in each [`Dimension`], the file format's table of kinds (`file`)
//! and its docs (`docs/mechanism-format.md`).

mod fixed;
mod flexure;
mod prismatic;
mod revolute;
mod spatial_flexure;

pub use fixed::Fixed;
pub use prismatic::Prismatic;
pub use revolute::Revolute;

use super::Dimension;
use crate::error::Result;
use crate::flexure::Flexure;
use crate::kinematics::{Kinematics, Level};
use crate::mass::MassModel;
use crate::space::{Planar, Space};
use nalgebra::{DMatrix, DVector};

/// A joint's data at one configuration: placement, motion subspace and its
/// derivative, and elastic energy (Pinocchio's `JointData`), in the
/// dimension `S` ([`Planar`] by default; [`crate::space::Space`] names the
/// types).
#[derive(Debug, Clone)]
pub struct JointState<S: Space = Planar> {
    /// Placement: the output frame in the root frame.
    pub pose: S::Pose,
    /// Motion subspace $S = \partial g/\partial q$, `TWIST_DIM` $\times k$:
    /// column $a$ is the output frame's twist per unit of coordinate $a$; in
    /// the plane, $(\partial_a\phi, \partial_a x, \partial_a y)$ in the root frame.
    pub jacobian: DMatrix<f64>,
    /// Its derivative: `TWIST_DIM` matrices ($k\times k$), entry $(a, b)$ of
    /// matrix $c$ being component $c$ of $\partial_b S_a$; in the plane, the
    /// Hessians of the pose's components $(\phi, x, y)$. A kind whose
    /// rotation is linear in its coordinates ([`Joint::angle_row`]) leaves
    /// that of $\phi$ zero.
    pub hessian: Vec<DMatrix<f64>>,
    /// Elastic energy $U$ (J).
    pub energy: f64,
    /// Its gradient $\nabla U$.
    pub gradient: DVector<f64>,
    /// Its Hessian, the stiffness $\nabla^2 U$.
    pub stiffness: DMatrix<f64>,
    /// The kind's own buffers, reused by [`Joint::evaluate_into`].
    buffers: Buffers,
}

/// Buffers a kind keeps between evaluations (Pinocchio keeps each kind's
/// data in a variant the same way); only the kind that made them reads them.
#[derive(Debug, Clone, Default)]
enum Buffers {
    /// None: the rigid kinds compute in place.
    #[default]
    None,
    /// A planar flexure's kinematics.
    Flexure(Box<Kinematics>),
    /// A spatial flexure's kinematics, and its contracted Hessian's quadrature.
    SpatialFlexure(Box<spatial_flexure::Data>),
}

impl<S: Space> JointState<S> {
    /// Zeroed data for a joint of `k` coordinates.
    pub fn zeros(k: usize) -> Self {
        JointState {
            pose: S::Pose::default(),
            jacobian: DMatrix::zeros(S::TWIST_DIM, k),
            hessian: (0..S::TWIST_DIM).map(|_| DMatrix::zeros(k, k)).collect(),
            energy: 0.0,
            gradient: DVector::zeros(k),
            stiffness: DMatrix::zeros(k, k),
            buffers: Buffers::None,
        }
    }

    /// Copies `other` (data of the same joint) into these buffers, without allocating.
    pub fn copy_from(&mut self, other: &JointState<S>) {
        self.pose = other.pose;
        self.jacobian.copy_from(&other.jacobian);
        for (h, o) in self.hessian.iter_mut().zip(&other.hessian) {
            h.copy_from(o);
        }
        self.energy = other.energy;
        self.gradient.copy_from(&other.gradient);
        self.stiffness.copy_from(&other.stiffness);
    }
}

/// The data of a joint with one coordinate moving its output frame along
/// pose component `row` ($\phi$, $x$ or $y$), with a spring of `stiffness`.
fn one_coordinate(row: usize, stiffness: f64) -> JointState {
    let mut s = JointState::zeros(1);
    s.jacobian[(row, 0)] = 1.0;
    s.stiffness[(0, 0)] = stiffness;
    s
}

/// A linear spring's energy $\frac12k(q - q_0)^2$ and its gradient into `s`.
fn spring(stiffness: f64, rest: f64, q: f64, s: &mut JointState) {
    s.energy = 0.5 * stiffness * (q - rest).powi(2);
    s.gradient[0] = stiffness * (q - rest);
}

/// $\sum_c w_c\thinspace\partial_bS^c_a$ from the Hessian in `state`
/// (filled at [`Level::Hessian`]) added into `out`: the exact contraction,
/// [`Joint::add_wrench_hessian`]'s default.
pub(crate) fn add_contracted_hessian<S: Space>(
    state: &JointState<S>,
    wrench: &[f64],
    out: &mut nalgebra::DMatrixViewMut<'_, f64>,
) {
    for (h, &w) in state.hessian.iter().zip(wrench) {
        if w != 0.0 {
            out.zip_apply(h, |o, h| *o += w * h);
        }
    }
}

/// The interface every joint kind implements (Pinocchio's `JointModel`).
///
/// # Example
/// ```
/// use flexure::mechanism::{Joint, Revolute};
/// let pin = Revolute { stiffness: 2.0, rest: 0.1 };
/// let s = pin.evaluate(&[0.6]);
/// assert_eq!((s.pose.phi, s.jacobian[(0, 0)]), (0.6, 1.0));
/// assert!((s.energy - 0.25).abs() < 1e-15 && (s.gradient[0] - 1.0).abs() < 1e-15);
/// // A pin carries no mass of its own; a flexure with a density does.
/// assert!(pin.inertia().is_none());
/// ```
pub trait Joint<S: Space = Planar> {
    /// Number of coordinates $k$.
    fn dof(&self) -> usize;
    /// Coordinates of the unloaded joint, into `q` ($k$ values).
    fn rest_into(&self, q: &mut [f64]);
    /// Coordinates of the unloaded joint.
    fn rest(&self) -> Vec<f64> {
        let mut q = vec![0.0; self.dof()];
        self.rest_into(&mut q);
        q
    }
    /// Buffers for [`Joint::evaluate_into`] (the Data of this joint), with
    /// what does not depend on the coordinates filled in.
    fn state(&self) -> JointState<S> {
        JointState::zeros(self.dof())
    }
    /// Placement, motion subspace and its derivative, and energy at `q`,
    /// written into `out` (made by [`Joint::state`]) without allocating.
    fn evaluate_into(&self, q: &[f64], out: &mut JointState<S>);
    /// [`Joint::evaluate_into`] only up to `level`: the pose (and energy) at
    /// [`Level::Pose`], with the motion subspace and the gradient at
    /// [`Level::Jacobian`], everything at [`Level::Hessian`]; what a lower
    /// level leaves out keeps its last values. For kinds whose derivatives
    /// cost much more than their pose (the spatial flexure), so that a
    /// residual or a step's size need not pay for them. The default
    /// evaluates everything.
    fn evaluate_level_into(&self, q: &[f64], _level: Level, out: &mut JointState<S>) {
        self.evaluate_into(q, out);
    }
    /// Adds the motion subspace's derivative contracted with a wrench,
    /// $$D_{ab} = \sum_c w_c\thinspace\partial_bS^c_a,$$
    /// into the $k\times k$ block `out`: the derivative of the generalized
    /// force $w\cdot S_a$ of a wrench $w$ fixed in the joint's root frame
    /// (`wrench`, `TWIST_DIM` components in the twist's order, the moment
    /// about the output origin; in the plane $(M, F_x, F_y)$). Every
    /// same-joint part of a mechanism's Hessian is one such contraction, so
    /// the mechanism calls this once per joint with the wrench of everything
    /// beyond it.
    ///
    /// `state` is this joint's data at `q`, evaluated at least to
    /// [`Level::Jacobian`]. The default reads [`JointState::hessian`], which
    /// [`Joint::evaluate_level_into`]'s default fills at every level; a kind
    /// that leaves its Hessian out below [`Level::Hessian`] (the spatial
    /// flexure) overrides this with what its Jacobian-level data allows.
    ///
    /// # Panics
    /// If `q`, `wrench` or `out` do not have the joint's sizes ($k$,
    /// `TWIST_DIM`, $k\times k$), as [`Joint::evaluate_into`] with a `q` of
    /// another length.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::{Joint, Revolute};
    /// use nalgebra::DMatrix;
    /// // A pin's motion subspace is constant: the contraction is zero.
    /// let pin = Revolute { stiffness: 2.0, rest: 0.0 };
    /// let s = pin.evaluate(&[0.3]);
    /// let mut d = DMatrix::zeros(1, 1);
    /// pin.add_wrench_hessian(&[0.3], &s, &[1.0, 2.0, 3.0], &mut d.view_mut((0, 0), (1, 1)));
    /// assert_eq!(d[(0, 0)], 0.0);
    /// ```
    fn add_wrench_hessian(
        &self,
        _q: &[f64],
        state: &JointState<S>,
        wrench: &[f64],
        out: &mut nalgebra::DMatrixViewMut<'_, f64>,
    ) {
        add_contracted_hessian(state, wrench, out);
    }
    /// [`Joint::evaluate_into`] in fresh buffers.
    fn evaluate(&self, q: &[f64]) -> JointState<S> {
        let mut s = self.state();
        self.evaluate_into(q, &mut s);
        s
    }
    /// The damping matrix ($k\times k$) for the joint's damping `coefficient`
    /// (`damping` in the file), added into `out`: $\beta K$ on a flexure,
    /// the viscous coefficient on a revolute or prismatic joint.
    fn add_damping(&self, coefficient: f64, out: &mut nalgebra::DMatrixViewMut<'_, f64>);
    /// The planar fast path: $d$ with the output frame's rotation
    /// $\phi = d^Tq$, when it is linear in the coordinates (every planar
    /// kind); the tree's $O(n)$ factorization needs it.
    fn angle_row(&self) -> Option<&[f64]>;
    /// Whether the coordinates are lengths (m), not angles (rad): a slider's
    /// stiffness is then N/m, compared with the others' N·m/rad through the
    /// mechanism's size squared.
    fn is_translation(&self) -> bool {
        false
    }
    /// The largest rotation (rad) inside the joint between configurations
    /// `a` and `b` (a flexure's cross-sections relative to its root), and a
    /// slider's travel over `length`: with the bodies' rotations, what bounds
    /// a continuation or integration step.
    fn distance(&self, a: &[f64], b: &[f64], length: f64) -> f64;
    /// How much an error in each coordinate counts in the integrator's error
    /// test, into `out` ($k$ values, at most 1): the section turn a unit of it
    /// makes, relative to the joint's largest. A flexure's coefficient $n$
    /// weighs [`crate::basis::angle_shape_rms`]: its high coefficients turn
    /// the sections little, and their top modes are the truncation's own
    /// (their frequencies move with the order), which the answer does not
    /// need resolved. The default: every coordinate 1.
    fn error_weights(&self, out: &mut [f64]) {
        out.fill(1.0);
    }
    /// The joint's own inertia, distributed along it: a flexure's sections'
    /// mass per length $\mu(s)$ and rotary inertia $\rho I(s)$, tabulated as
    /// a [`MassModel`]. `None` where the joint carries no mass of its own: a
    /// pin, a slider or a weld (their bodies carry it), or a flexure without
    /// a density. The call builds the tables, so an algorithm asks once and
    /// keeps them; it fails where the mass integrals cannot be made accurate.
    fn inertia(&self) -> Option<Result<MassModel>> {
        None
    }
    /// The Smooth Curvature flexure, for the analyses only a flexure has
    /// (its mode shapes, error estimate, stress and backbone).
    fn flexure(&self) -> Option<&Flexure> {
        None
    }
}

/// One of the joint kinds, in the dimension `D` ([`Planar`] by default),
/// each kind of the dimension's own type ([`Dimension`]): a pin and a
/// slider about and along the plane's fixed axes ([`Revolute`],
/// [`Prismatic`]) or along any axis in space, and no ball in the plane
/// ([`NoBall`]). `SpatialJointKind` names it in space.
///
/// # Example
/// ```
/// use flexure::mechanism::{JointKind, Revolute};
/// use flexure::mechanism::spatial::{SpatialJointKind, Spherical};
/// let pin: JointKind = JointKind::Revolute(Revolute { stiffness: 1.0, rest: 0.0 });
/// let ball = SpatialJointKind::Spherical(Spherical { stiffness: 0.0, rest: [0.0; 3] });
/// assert_eq!((pin.joint().dof(), ball.joint().dof()), (1, 3));
/// assert!(pin.flexure().is_none() && ball.flexure().is_none());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum JointKind<D: Dimension = Planar> {
    /// The Smooth Curvature flexure of the dimension (boxed: it carries
    /// its tables): in space, two bendings and a twist.
    Flexure(Box<D::Flexure>),
    /// A hinge.
    Revolute(D::Revolute),
    /// A slider.
    Prismatic(D::Prismatic),
    /// A ball joint (in space only).
    Spherical(D::Spherical),
    /// A weld of child to parent.
    Fixed(D::Fixed),
}

impl<D: Dimension> JointKind<D> {
    /// The kind as its interface: the one match on the kind.
    pub fn joint(&self) -> &dyn Joint<D> {
        match self {
            JointKind::Flexure(f) => f.as_ref(),
            JointKind::Revolute(r) => r,
            JointKind::Prismatic(p) => p,
            JointKind::Spherical(s) => s,
            JointKind::Fixed(f) => f,
        }
    }

    /// The flexure, where the kind is one: for what only a flexure has
    /// (its error estimate, stress and backbone).
    pub fn flexure(&self) -> Option<&D::Flexure> {
        match self {
            JointKind::Flexure(f) => Some(f),
            _ => None,
        }
    }
}

/// The plane's ball joint: there is none. A type without values, so that a
/// planar [`JointKind::Spherical`] cannot be made and one kind type serves
/// both dimensions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NoBall {}

impl Joint for NoBall {
    fn dof(&self) -> usize {
        match *self {}
    }

    fn rest_into(&self, _: &mut [f64]) {
        match *self {}
    }

    fn evaluate_into(&self, _: &[f64], _: &mut JointState) {
        match *self {}
    }

    fn add_damping(&self, _: f64, _: &mut nalgebra::DMatrixViewMut<'_, f64>) {
        match *self {}
    }

    fn angle_row(&self) -> Option<&[f64]> {
        match *self {}
    }

    fn distance(&self, _: &[f64], _: &[f64], _: f64) -> f64 {
        match *self {}
    }
}
