//! The joint kinds only a spatial mechanism has, each in its own file,
//! behind the one joint interface ([`Joint<Spatial>`](crate::mechanism::Joint)): a hinge and a slider
//! along an axis, and a ball joint; with the spatial flexure and the weld,
//! they are [`JointKind`]'s in space ([`SpatialJointKind`]).
//!
//! [`JointKind::joint`] is the one match on the kind; the
//! mechanism's algorithms ([`crate::mechanism::kinematics`], [`crate::mechanism::lagrangian`])
//! only call the interface.

mod prismatic;
mod revolute;
mod spherical;

pub use prismatic::PrismaticUnaligned;
pub use revolute::RevoluteUnaligned;
pub use spherical::Spherical;

use crate::mechanism::joints::JointKind;
use crate::space::Spatial;
use nalgebra::{Unit, Vector3};

/// The spatial joint kinds: [`JointKind`] in space.
pub type SpatialJointKind = JointKind<Spatial>;

/// A unit axis from a vector, or an error naming `name`.
pub fn unit_axis(name: &'static str, axis: Vector3<f64>) -> crate::Result<Unit<Vector3<f64>>> {
    let norm = axis.norm();
    if !(norm.is_finite() && norm > 1e-12) {
        return Err(crate::Error::invalid(
            name,
            format!("[{}, {}, {}]", axis.x, axis.y, axis.z),
            "must be a finite, non-zero direction",
        ));
    }
    Ok(Unit::new_unchecked(axis / norm))
}
