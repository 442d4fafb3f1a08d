//! What the solve report needs of a dimension: its bodies' poses, its
//! flexures' carried loads, error estimates, stresses and shapes. The plane
//! and space implement it here, side by side; [`super::solve_report`] is
//! written once over it.

use super::{BodyPose, CarriedLoad, MaxAt, PeakStress, Shape};
use crate::error::Result;
use crate::estimate::{Accuracy, ErrorEstimate, joint_error_and_load, spatial::deflect_error};
use crate::flexure::Flexure;
use crate::mechanism::Mechanism;
use crate::mechanism::statics::Solution;
use crate::space::{Planar, Spatial};
use crate::spatial::SpatialFlexure;

/// A dimension whose solutions [`super::solve_report`] reports.
pub trait Reported: crate::estimate::Refined {
    /// Every body's pose at coordinates `q`, in body order (the ground first).
    fn poses(m: &Mechanism<Self>, q: &[f64]) -> Vec<BodyPose>;
    /// Each flexure joint's error estimate at `s`, the joint alone under
    /// the tip load it carries against its refined reference, and that load;
    /// one per flexure joint, in joint order.
    fn estimates(
        m: &Mechanism<Self>,
        s: &Solution<Self>,
        target: &Accuracy,
    ) -> Vec<Result<(ErrorEstimate, CarriedLoad)>>;
    /// A flexure's peak stress, if its section gives one.
    fn peak_stress(f: &Self::Flexure, alpha: &[f64]) -> Result<Option<PeakStress>>;
    /// A flexure's peak change of (bending) curvature, for a section without a shape.
    fn peak_curvature(f: &Self::Flexure, alpha: &[f64]) -> Result<MaxAt>;
    /// A flexure's peak stress where its section gives one, else its peak
    /// change of (bending) curvature: what an answer reports of its bending.
    fn bending(f: &Self::Flexure, alpha: &[f64]) -> Result<(Option<PeakStress>, Option<MaxAt>)> {
        match Self::peak_stress(f, alpha)? {
            Some(p) => Ok((Some(p), None)),
            None => Ok((None, Some(Self::peak_curvature(f, alpha)?))),
        }
    }
    /// A flexure's deformed shape at `count` points.
    fn shape(f: &Self::Flexure, alpha: &[f64], count: usize) -> Result<Shape>;
}

impl Reported for Planar {
    fn poses(m: &Mechanism, q: &[f64]) -> Vec<BodyPose> {
        let f = crate::mechanism::kinematics::frames(m, q);
        f.bodies.iter().map(|p| BodyPose::Planar { x: p.x, y: p.y, phi: p.phi }).collect()
    }

    fn estimates(m: &Mechanism, s: &Solution, target: &Accuracy) -> Vec<Result<(ErrorEstimate, CarriedLoad)>> {
        let flexures =
            m.joints.iter().filter_map(|j| Some((j.kind.flexure()?, &s.q[j.offset..j.offset + j.kind.joint().dof()])));
        flexures
            .map(|(f, alpha)| joint_error_and_load(f, alpha, target).map(|(e, load)| (e, CarriedLoad::Planar(load))))
            .collect()
    }

    fn peak_stress(f: &Flexure, alpha: &[f64]) -> Result<Option<PeakStress>> {
        Ok(crate::stress::peak_stress(f, alpha).map(PeakStress::from))
    }

    fn peak_curvature(f: &Flexure, alpha: &[f64]) -> Result<MaxAt> {
        Ok(crate::stress::peak_curvature(f, alpha).into())
    }

    fn shape(f: &Flexure, alpha: &[f64], count: usize) -> Result<Shape> {
        Ok(Shape::Planar(super::shape(f, alpha, count)))
    }
}

impl Reported for Spatial {
    fn poses(m: &Mechanism<Spatial>, q: &[f64]) -> Vec<BodyPose> {
        // Poses alone: the Hessians of flexures at high orders cost most.
        let mut f = crate::mechanism::kinematics::Frames::new(m);
        crate::mechanism::kinematics::frames_level_into(m, q, crate::kinematics::Level::Pose, &mut f);
        (0..m.bodies.len())
            .map(|b| {
                let p = f.bodies[b].translation.vector;
                let r = f.body_rotation(b);
                let (roll, pitch, yaw) = f.bodies[b].rotation.euler_angles();
                let rotation = std::array::from_fn(|i| std::array::from_fn(|j| r[(i, j)]));
                BodyPose::Spatial { x: p.x, y: p.y, z: p.z, roll, pitch, yaw, rotation }
            })
            .collect()
    }

    fn estimates(
        m: &Mechanism<Spatial>,
        s: &Solution<Spatial>,
        target: &Accuracy,
    ) -> Vec<Result<(ErrorEstimate, CarriedLoad)>> {
        let loads = crate::mechanism::spatial::statics::flexure_loads(m, s);
        let flexures = m.joints.iter().zip(loads).filter_map(|(j, load)| Some((j.kind.flexure()?, j, load?)));
        flexures
            .map(|(f, j, load)| {
                let alpha = &s.q[j.offset..j.offset + f.coordinates()];
                Ok((deflect_error(f, &load, alpha, target)?, CarriedLoad::Spatial(load)))
            })
            .collect()
    }

    fn peak_stress(f: &SpatialFlexure, alpha: &[f64]) -> Result<Option<PeakStress>> {
        if !f.section().has_geometry() {
            return Ok(None);
        }
        let p = crate::spatial::peak_stress(f, alpha)?;
        Ok(Some(PeakStress {
            max: p.stress.von_mises,
            at: p.at,
            point: Some(p.stress.at),
            bending_y: Some(p.stress.bending_y),
            bending_z: Some(p.stress.bending_z),
            shear: Some(p.stress.shear),
        }))
    }

    fn peak_curvature(f: &SpatialFlexure, alpha: &[f64]) -> Result<MaxAt> {
        crate::spatial::peak_curvature(f, alpha).map(MaxAt::from)
    }

    fn shape(f: &SpatialFlexure, alpha: &[f64], count: usize) -> Result<Shape> {
        let points = crate::spatial::shape(f, alpha, count)?;
        Ok(Shape::Spatial(points.iter().map(super::ShapeSection::from).collect()))
    }
}
