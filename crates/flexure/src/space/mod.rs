//! The dimension seam: the one vocabulary of poses, points, twists and
//! wrenches that joints, mechanisms, dynamics, the CLI and Python share.
//!
//! A [`Space`] names the types of one dimension and the Lie-group
//! operations the algorithms need: [`Space::compose`], [`Space::inverse`],
//! [`Space::act`] on points, [`Space::rotate`] of directions,
//! [`Space::adjoint`], [`Space::exp`] and [`Space::log`], and the pairing of
//! a wrench with a twist. [`Planar`] implements it for the plane, SE(2),
//! with [`Pose`] $(\phi, x, y)$, [`Twist`] $(\omega, v_x, v_y)$ and [`Wrench`]
//! $(M, F_x, F_y)$; [`Spatial`] is the second `impl Space`, SE(3), with
//! `Isometry3` poses and (angular, linear) 6-vector twists and wrenches, as
//! parry's `math` aliases are one set of names for 2-D and 3-D.
//!
//! **Ordering** (the crate's *Conventions*): rotation first. A pose, a
//! Jacobian row, a twist and a wrench list their angular part, then their
//! linear part, so that a wrench's power on a twist is the dot product of
//! the two (Featherstone's convention of spatial vectors).
//!
//! The planar fast paths stay behind the seam: planar rotations add
//! ([`Pose::compose`] adds angles instead of multiplying rotations), which
//! the flexure's closed-form kernel and the tree's $O(n)$ factorization use.

mod planar;
mod pose;
mod spatial;
mod twist;
mod wrench;

pub use planar::Planar;
pub use pose::Pose;
pub(crate) use pose::rotate_turned;
pub(crate) use spatial::{ExpCoefficients, bracket, exp_coefficients, exp_parts, isometry};
pub use spatial::{Spatial, rotation_angle};
pub use twist::Twist;
pub use wrench::{MAX_LOAD, Wrench};

use std::fmt::Debug;

/// The types and group operations of one dimension (SE(2) or SE(3)).
///
/// A pose $g$ acts on points by $g\cdot r = R r + p$. Twists and wrenches
/// are in the frame a pose maps *from*; [`Space::adjoint`] carries a twist
/// to the frame it maps *to*, $\xi^{\prime} = \mathrm{Ad}_g\thinspace\xi$, and a wrench goes
/// the other way, $w = \mathrm{Ad}_g^T w^{\prime}$, so power is frame-free:
/// $w^{\prime}\cdot\xi^{\prime} = w^{\prime}\cdot\mathrm{Ad}_g\xi = (\mathrm{Ad}_g^Tw^{\prime})\cdot\xi$.
///
/// # Example
/// ```
/// use flexure::space::{Planar, Pose, Space, Twist};
/// let g = Pose { phi: 0.3, x: 1.0, y: -2.0 };
/// let back = Planar::compose(&g, &Planar::inverse(&g));
/// assert!(back.phi.abs() < 1e-15 && back.x.abs() < 1e-15 && back.y.abs() < 1e-15);
/// let t = Planar::log(&g);
/// let h = Planar::exp(&t);
/// assert!((h.x - g.x).abs() < 1e-14 && (h.y - g.y).abs() < 1e-14);
/// # let _: Twist = t;
/// ```
pub trait Space: Copy + Debug + Default + 'static {
    /// Components of a twist or a wrench: 3 in the plane, 6 in space.
    const TWIST_DIM: usize;
    /// Components of a point: 2 or 3.
    const POINT_DIM: usize;
    /// A rigid placement: the pose of one frame in another.
    type Pose: Copy + Debug + PartialEq + Default;
    /// A position.
    type Point: Copy + Debug + PartialEq;
    /// A direction or displacement.
    type Vector: Copy
        + Debug
        + PartialEq
        + Default
        + std::ops::Add<Output = Self::Vector>
        + std::ops::Sub<Output = Self::Vector>
        + std::ops::IndexMut<usize, Output = f64>;
    /// A velocity of a frame (angular, then linear).
    type Twist: Copy + Debug + PartialEq + Default;
    /// A force and moment on a frame (moment, then force), by component.
    type Wrench: Copy + Debug + PartialEq + Default + std::ops::IndexMut<usize, Output = f64>;
    /// The matrix of [`Space::adjoint`], `TWIST_DIM` square.
    type Adjoint: Copy + Debug + PartialEq;

    /// The identity pose.
    fn identity() -> Self::Pose;
    /// $a\thinspace b$: frame `b` given in frame `a`, in `a`'s parent.
    fn compose(a: &Self::Pose, b: &Self::Pose) -> Self::Pose;
    /// $a^{-1}$.
    fn inverse(a: &Self::Pose) -> Self::Pose;
    /// $a\cdot r = R r + p$: a point given in the frame, in its parent.
    fn act(a: &Self::Pose, r: &Self::Point) -> Self::Point;
    /// The frame at point `p` with its parent's axes.
    fn at(p: &Self::Point) -> Self::Pose;
    /// $p$: the frame's origin, in its parent.
    fn origin(a: &Self::Pose) -> Self::Point;
    /// $\lvert p\rvert$: how far the frame's origin is from its parent's.
    fn reach(a: &Self::Pose) -> f64;
    /// $R v$: a direction given in the frame, in its parent.
    fn rotate(a: &Self::Pose, v: &Self::Vector) -> Self::Vector;
    /// $\mathrm{Ad}_a$: a twist in the frame, in its parent.
    fn adjoint(a: &Self::Pose) -> Self::Adjoint;
    /// The pose reached by following a constant body twist for unit time.
    fn exp(t: &Self::Twist) -> Self::Pose;
    /// The inverse of [`Space::exp`] (angles in $(-\pi, \pi]$).
    fn log(a: &Self::Pose) -> Self::Twist;
    /// The power $w\cdot\xi$ of a wrench on a twist (W, per unit speed).
    fn power(w: &Self::Wrench, t: &Self::Twist) -> f64;
    /// The velocity of a point at `arm` from the twist's origin: $v + \omega\times r$.
    fn velocity_at(t: &Self::Twist, arm: &Self::Vector) -> Self::Vector;
}
