//! What a mechanism needs of its dimension beyond the group operations of
//! [`Space`]: its joint kinds, its flexure, a body's rotary inertia and its
//! loads' names. The plane and space implement it here, side by side, so
//! that [`Mechanism<D>`](super::Mechanism) and its parts (bodies, joints,
//! tendons, point loads, closures, loads, solutions) are one model for both
//! dimensions (Pinocchio's one model; parry's one set of dimension aliases).

use super::joints::{Joint, JointKind};
use super::spatial::SpatialJointKind;
use super::sweep::LoadNames;
use crate::flexure::Flexure;
use crate::space::{Planar, Space, Spatial};
use crate::spatial::SpatialFlexure;
use nalgebra::Matrix3;
use std::fmt::Debug;

/// A dimension a mechanism lives in: [`Planar`] or [`Spatial`].
///
/// # Example
/// ```
/// use flexure::mechanism::{Dimension, JointKind, Revolute};
/// use flexure::space::Planar;
/// let pin = JointKind::Revolute(Revolute { stiffness: 1.0, rest: 0.0 });
/// assert_eq!(Planar::joint(&pin).dof(), 1);
/// assert!(Planar::flexure(&pin).is_none());
/// ```
pub trait Dimension: Space {
    /// A body's rotary inertia about its centre of mass: kg·m² in the plane,
    /// a 3 × 3 matrix (kg·m²) in the body frame's axes in space.
    type AngularInertia: Copy + Debug + PartialEq + Default;
    /// The joint kinds of this dimension.
    type JointKind: Clone + Debug + PartialEq;
    /// The Smooth Curvature flexure of this dimension.
    type Flexure: Clone + Debug + PartialEq;
    /// How its loads are named in a sweep or a schedule.
    const LOADS: LoadNames;

    /// The kind as its interface: the one match on the kind.
    fn joint(kind: &Self::JointKind) -> &dyn Joint<Self>;
    /// The flexure, where the kind is one.
    fn flexure(kind: &Self::JointKind) -> Option<&Self::Flexure>;
    /// A flexure's length (m).
    fn flexure_length(f: &Self::Flexure) -> f64;
}

impl Dimension for Planar {
    type AngularInertia = f64;
    type JointKind = JointKind;
    type Flexure = Flexure;
    const LOADS: LoadNames = LoadNames {
        components: &["moment", "fx", "fy"],
        axes: &["x", "y"],
        must_be: "must be tendon.NAME.tension, force.NAME.fx|fy|moment or gravity.x|y",
        component: "a force's component is fx, fy or moment",
        axis: None,
        dotted: true,
        quoted: true,
    };

    fn joint(kind: &JointKind) -> &dyn Joint<Planar> {
        kind.joint()
    }

    fn flexure(kind: &JointKind) -> Option<&Flexure> {
        kind.flexure()
    }

    fn flexure_length(f: &Flexure) -> f64 {
        f.length()
    }
}

impl Dimension for Spatial {
    type AngularInertia = Matrix3<f64>;
    type JointKind = SpatialJointKind;
    type Flexure = SpatialFlexure;
    const LOADS: LoadNames = LoadNames {
        components: &["mx", "my", "mz", "fx", "fy", "fz"],
        axes: &["x", "y", "z"],
        must_be: "must be force.NAME.mx|my|mz|fx|fy|fz, tendon.NAME.tension or gravity.x|y|z",
        component: "a force's component must be mx, my, mz, fx, fy or fz",
        axis: Some("gravity's component must be x, y or z"),
        dotted: false,
        quoted: false,
    };

    fn joint(kind: &SpatialJointKind) -> &dyn Joint<Spatial> {
        kind.joint()
    }

    fn flexure(kind: &SpatialJointKind) -> Option<&SpatialFlexure> {
        kind.flexure()
    }

    fn flexure_length(f: &SpatialFlexure) -> f64 {
        f.length()
    }
}
