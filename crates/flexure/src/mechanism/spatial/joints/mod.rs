//! The joint kinds of a spatial mechanism, each in its own file, behind the
//! one joint interface ([`Joint<Spatial>`]): the spatial flexure, a hinge
//! and a slider along an axis, a ball joint and a weld.
//!
//! [`SpatialJointKind::joint`] is the one match on the kind; the
//! mechanism's algorithms ([`crate::mechanism::kinematics`], [`crate::mechanism::lagrangian`])
//! only call the interface.

mod prismatic;
mod revolute;
mod spherical;

pub use prismatic::PrismaticUnaligned;
pub use revolute::RevoluteUnaligned;
pub use spherical::Spherical;

use crate::mechanism::joints::{Fixed, Joint};
use crate::space::Spatial;
use crate::spatial::SpatialFlexure;
use nalgebra::{Unit, Vector3};

/// One of the spatial joint kinds.
#[derive(Debug, Clone, PartialEq)]
pub enum SpatialJointKind {
    /// The spatial Smooth Curvature flexure: two bendings and a twist
    /// (boxed: it carries its tables).
    Flexure(Box<SpatialFlexure>),
    /// A hinge about an axis.
    Revolute(RevoluteUnaligned),
    /// A slider along an axis.
    Prismatic(PrismaticUnaligned),
    /// A ball joint.
    Spherical(Spherical),
    /// A weld of child to parent.
    Fixed(Fixed),
}

impl SpatialJointKind {
    /// The kind as its interface: the one match on the kind.
    pub fn joint(&self) -> &dyn Joint<Spatial> {
        match self {
            SpatialJointKind::Flexure(f) => f.as_ref(),
            SpatialJointKind::Revolute(r) => r,
            SpatialJointKind::Prismatic(p) => p,
            SpatialJointKind::Spherical(s) => s,
            SpatialJointKind::Fixed(f) => f,
        }
    }

    /// The spatial flexure, for what only a flexure has (its error
    /// estimate, stress and backbone).
    pub fn flexure(&self) -> Option<&SpatialFlexure> {
        match self {
            SpatialJointKind::Flexure(f) => Some(f),
            _ => None,
        }
    }
}

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
