//! The answer to a spatial mechanism's solve, as the CLI and Python print
//! it: the solution, every body's placement, each joint's coordinates, and
//! each flexure's carried wrench, error estimate and peak stress.

use crate::Level;
use crate::error::Result;
use crate::estimate::spatial_mechanism::flexure_errors;
use crate::estimate::{Accuracy, ErrorEstimate};
use crate::mechanism::spatial::SpatialMechanism;
use crate::mechanism::spatial::kinematics::{SpatialFrames, frames_level_into};
use crate::mechanism::spatial::statics::{SpatialSolution, flexure_loads};
use crate::spatial::{SpatialLoad, SpatialPeak, peak_stress};

/// A body's placement in the ground frame.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Placement {
    /// The body's name.
    pub name: String,
    /// Its origin (m).
    pub position: [f64; 3],
    /// Its rotation matrix, by rows.
    pub rotation: [[f64; 3]; 3],
    /// The same rotation as URDF's roll, pitch, yaw (rad):
    /// $R = R_z(\text{yaw})R_y(\text{pitch})R_x(\text{roll})$.
    pub rpy: [f64; 3],
}

/// A joint's coordinates.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct JointCoordinates {
    /// The joint's name.
    pub name: String,
    /// Its coordinates: a flexure's $\alpha$ (twist, then the bendings about
    /// $y$ and $z$), a hinge's angle, a slider's travel, a ball's rotation vector.
    pub coordinates: Vec<f64>,
}

/// What one flexure joint carries and how well it is modelled.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FlexureAnswer {
    /// The joint's name.
    pub name: String,
    /// The tip wrench it carries, in its root frame.
    pub load: SpatialLoad,
    /// Its error estimate against its own refined reference.
    pub error_estimate: ErrorEstimate,
    /// Its peak stress, for a section with a shape and material.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress: Option<SpatialPeak>,
}

/// The whole answer of [`report`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SpatialReport {
    /// Always 3.
    pub dimension: u8,
    /// The equilibrium.
    #[serde(flatten)]
    pub solution: SpatialSolution,
    /// Every moving body's placement.
    pub bodies: Vec<Placement>,
    /// Every joint's coordinates.
    pub joints: Vec<JointCoordinates>,
    /// Every flexure joint, in joint order.
    pub flexures: Vec<FlexureAnswer>,
    /// Whether any flexure's error estimate misses the target.
    pub flagged: bool,
}

/// The placement of every moving body at coordinates `q`.
pub fn placements(m: &SpatialMechanism, q: &[f64]) -> Vec<Placement> {
    // Poses alone: the Hessians of flexures at high orders cost most.
    let mut f = SpatialFrames::new(m);
    frames_level_into(m, q, Level::Pose, &mut f);
    (1..m.bodies.len())
        .map(|b| {
            let p = f.bodies[b].translation.vector;
            let r = f.body_rotation(b);
            let (roll, pitch, yaw) = f.bodies[b].rotation.euler_angles();
            Placement {
                name: m.bodies[b].name.clone(),
                position: [p.x, p.y, p.z],
                rotation: std::array::from_fn(|i| std::array::from_fn(|j| r[(i, j)])),
                rpy: [roll, pitch, yaw],
            }
        })
        .collect()
}

/// The answer for solution `s` of `m`, with error estimates against `target`.
pub fn report(m: &SpatialMechanism, s: &SpatialSolution, target: &Accuracy) -> Result<SpatialReport> {
    let errors = flexure_errors(m, s, target)?;
    let loads = flexure_loads(m, s);
    let mut flexures = Vec::new();
    for ((j, error), load) in m.joints.iter().zip(errors).zip(loads) {
        let (Some(f), Some(error_estimate), Some(load)) = (j.kind.flexure(), error, load) else { continue };
        let alpha = &s.q[j.offset..j.offset + f.coordinates()];
        let stress = if f.section().has_geometry() { Some(peak_stress(f, alpha)?) } else { None };
        flexures.push(FlexureAnswer { name: j.name.clone(), load, error_estimate, stress });
    }
    let joints = m
        .joints
        .iter()
        .map(|j| JointCoordinates {
            name: j.name.clone(),
            coordinates: s.q[j.offset..j.offset + j.kind.joint().dof()].to_vec(),
        })
        .collect();
    Ok(SpatialReport {
        dimension: 3,
        solution: s.clone(),
        bodies: placements(m, &s.q),
        joints,
        flagged: flexures.iter().any(|f| f.error_estimate.flagged),
        flexures,
    })
}
