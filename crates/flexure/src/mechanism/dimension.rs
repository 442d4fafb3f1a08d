//! What a mechanism needs of its dimension beyond the group operations of
//! [`Space`]: the types of its joint kinds, a body's rotary inertia and its
//! loads' names. The plane and space implement it here, side by side, so
//! that [`Mechanism<D>`](super::Mechanism) and its parts (bodies, joints,
//! tendons, point loads, closures, loads, solutions) are one model for both
//! dimensions (Pinocchio's one model; parry's one set of dimension aliases).

use super::joints::{Fixed, Joint, NoBall, Prismatic, Revolute};
use super::spatial::{PrismaticUnaligned, RevoluteUnaligned, Spherical};
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
/// use flexure::space::{Planar, Spatial};
/// let pin: JointKind<Planar> = JointKind::Revolute(Revolute { stiffness: 1.0, rest: 0.0 });
/// assert_eq!(pin.joint().dof(), 1);
/// assert_eq!((Planar::LOADS.axes.len(), Spatial::LOADS.axes.len()), (2, 3));
/// ```
pub trait Dimension: Space {
    /// A body's rotary inertia about its centre of mass: kg·m² in the plane,
    /// a 3 × 3 matrix (kg·m²) in the body frame's axes in space.
    type AngularInertia: Copy + Debug + PartialEq + Default;
    /// The Smooth Curvature flexure of this dimension.
    type Flexure: Joint<Self> + Clone + Debug + PartialEq;
    /// A hinge: about the plane's normal, or about an axis in space.
    type Revolute: Joint<Self> + Clone + Debug + PartialEq;
    /// A slider: along the root frame's x in the plane, along an axis in space.
    type Prismatic: Joint<Self> + Clone + Debug + PartialEq;
    /// A ball joint: none in the plane ([`NoBall`]).
    type Spherical: Joint<Self> + Clone + Debug + PartialEq;
    /// A weld: [`Fixed`] in both.
    type Fixed: Joint<Self> + Clone + Debug + PartialEq;
    /// How its loads are named in a sweep or a schedule.
    const LOADS: LoadNames;

    /// A flexure's length (m).
    fn flexure_length(f: &Self::Flexure) -> f64;
}

impl Dimension for Planar {
    type AngularInertia = f64;
    type Flexure = Flexure;
    type Revolute = Revolute;
    type Prismatic = Prismatic;
    type Spherical = NoBall;
    type Fixed = Fixed;
    const LOADS: LoadNames = LoadNames {
        components: &["moment", "fx", "fy"],
        axes: &["x", "y"],
        must_be: "must be tendon.NAME.tension, force.NAME.fx|fy|moment or gravity.x|y",
        component: "a force's component is fx, fy or moment",
        axis: None,
        dotted: true,
        quoted: true,
    };

    fn flexure_length(f: &Flexure) -> f64 {
        f.length()
    }
}

impl Dimension for Spatial {
    type AngularInertia = Matrix3<f64>;
    type Flexure = SpatialFlexure;
    type Revolute = RevoluteUnaligned;
    type Prismatic = PrismaticUnaligned;
    type Spherical = Spherical;
    type Fixed = Fixed;
    const LOADS: LoadNames = LoadNames {
        components: &["mx", "my", "mz", "fx", "fy", "fz"],
        axes: &["x", "y", "z"],
        must_be: "must be force.NAME.mx|my|mz|fx|fy|fz, tendon.NAME.tension or gravity.x|y|z",
        component: "a force's component must be mx, my, mz, fx, fy or fz",
        axis: Some("gravity's component must be x, y or z"),
        dotted: false,
        quoted: false,
    };

    fn flexure_length(f: &SpatialFlexure) -> f64 {
        f.length()
    }
}
