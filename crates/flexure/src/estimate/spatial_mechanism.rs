//! Error estimates and stresses of every flexure of a spatial mechanism.

use super::{Accuracy, ErrorEstimate, spatial::deflect_error};
use crate::error::Result;
use crate::mechanism::spatial::SpatialMechanism;
use crate::mechanism::spatial::statics::{SpatialSolution, flexure_loads};

/// Each spatial flexure joint's error estimate at a solution: the flexure
/// under the tip wrench it carries ([`flexure_loads`]) against its own
/// refined reference ([`deflect_error`]), flagged against `target`, as the
/// planar mechanism's per-flexure estimates are. One entry per joint,
/// `None` for the other kinds.
///
/// # Example
/// ```
/// use flexure::estimate::spatial_mechanism::flexure_errors;
/// use flexure::mechanism::spatial::statics::solve;
/// use flexure::mechanism::spatial::{SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism, SpatialPointLoad};
/// use flexure::section::SpatialSection;
/// use flexure::spatial::SpatialFlexure;
/// use nalgebra::{Isometry3, Point3, Vector3, Vector6};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(0.8, 1.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
/// let joint = SpatialJointSpec { name: "f".into(), kind: SpatialJointKind::Flexure(Box::new(f)), parent: 0, child: 1, origin: Isometry3::identity(), offset: 0, damping: 0.0 };
/// let push = SpatialPointLoad { name: "p".into(), body: 1, at: Point3::origin(), wrench: Vector6::new(0.0, 0.0, 0.0, 0.0, 0.5, 0.5) };
/// let m = SpatialMechanism::new(vec![SpatialBody::massless("ground"), SpatialBody::massless("tip")], vec![joint], vec![], vec![push], vec![], Vector3::zeros()).unwrap();
/// let s = solve(&m, &Default::default()).unwrap();
/// let e = flexure_errors(&m, &s, &Default::default()).unwrap();
/// assert!(e[0].as_ref().unwrap().position < 1e-3);
/// ```
pub fn flexure_errors(
    m: &SpatialMechanism,
    s: &SpatialSolution,
    target: &Accuracy,
) -> Result<Vec<Option<ErrorEstimate>>> {
    let loads = flexure_loads(m, s);
    m.joints
        .iter()
        .zip(loads)
        .map(|(j, load)| match (j.kind.flexure(), load) {
            (Some(f), Some(load)) => {
                let alpha = &s.q[j.offset..j.offset + f.coordinates()];
                deflect_error(f, &load, alpha, target).map(Some)
            }
            _ => Ok(None),
        })
        .collect()
}
