//! The answers of the door to one flexure: each one type for both
//! dimensions, serialized in the shape the command line prints. What is a
//! dimension's own (coordinates by component, a pose, a section of the
//! shape, the orders) is an untagged enum, as [`crate::report::BodyPose`].

use crate::estimate::ErrorEstimate;
use crate::kinematics::TipKinematics;
use crate::limit::StabilityLimit;
use crate::report::{BodyPose, MaxAt, PeakStress, Shape};
use crate::spatial::StabilityTest;
use nalgebra::{Dim, Matrix, RawStorage};
use serde::Serialize;

/// Any matrix by rows.
pub(super) fn rows<R: Dim, C: Dim, S: RawStorage<f64, R, C>>(m: &Matrix<f64, R, C, S>) -> Vec<Vec<f64>> {
    m.row_iter().map(|r| r.iter().copied().collect()).collect()
}

/// The coordinates: the plane's list, or space's by component.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Alpha {
    /// $\alpha_1, \ldots, \alpha_N$.
    Planar(Vec<f64>),
    /// The twist's, then the bendings' about $y$ and $z$.
    Spatial { twist: Vec<f64>, kappa_y: Vec<f64>, kappa_z: Vec<f64> },
}

impl Alpha {
    /// All the coordinates in one list, space's by component.
    pub fn flat(&self) -> Vec<f64> {
        match self {
            Alpha::Planar(a) => a.clone(),
            Alpha::Spatial { twist, kappa_y, kappa_z } => [twist.as_slice(), kappa_y, kappa_z].concat(),
        }
    }
}

/// The orders an answer was found at, with `--order auto`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Refinement {
    /// The order and its Gauss points.
    Planar { order: usize, quadrature: usize },
    /// The three orders and the Magnus subintervals.
    Spatial { orders: [usize; 3], subintervals: usize },
}

/// What is left to try when an estimate misses its target.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Headroom {
    /// A higher order (`--order auto`).
    #[default]
    Higher,
    /// None: the orders are the highest, `order` the largest, and the
    /// estimate is against the exact reference if `against_exact`.
    Exhausted { order: usize, against_exact: bool },
}

/// What an answer gives of the flexure's bending: the peak stress (in
/// space with its parts), or the peak change of (bending) curvature for a
/// section without a shape; the safety factor; the deformed shape.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Bending {
    #[serde(skip_serializing_if = "Option::is_none", serialize_with = "point_last")]
    pub stress: Option<PeakStress>,
    /// The peak change of (bending) curvature, for a section without a shape.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curvature_max: Option<MaxAt>,
    /// The yield strength over the peak stress, when both are known and it is stressed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub safety_factor: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shape: Option<Shape>,
}

/// The model's equilibrium under a tip load, with its estimate.
#[derive(Debug, Clone, Serialize)]
pub struct Deflected {
    pub alpha: Alpha,
    pub pose: BodyPose,
    pub stiffness: Vec<Vec<f64>>,
    pub stable: bool,
    /// What `stable` answers: `energy`, or `static` under a dead moment in space.
    pub stability_test: StabilityTest,
    pub residual: f64,
    /// Where the path from rest lost stability, if it did (left out with a stability limit).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit_fraction: Option<f64>,
    #[serde(flatten)]
    pub bending: Bending,
    /// With `--order auto`, the orders reached.
    #[serde(flatten)]
    pub refinement: Option<Refinement>,
    pub error_estimate: ErrorEstimate,
    pub flagged: bool,
    /// Asked for: written by the front end, which says why a path stalled.
    #[serde(skip)]
    pub stability_limit: Option<StabilityLimit>,
    /// What is left to try if `flagged`.
    #[serde(skip)]
    pub headroom: Headroom,
    /// The flexure's length (m), for what an estimate's miss is relative to.
    #[serde(skip)]
    pub length: f64,
}

/// A peak stress with its parts first and the section's point last, as
/// the single flexure's answer has always given it.
fn point_last<S: serde::Serializer>(p: &Option<PeakStress>, s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeMap;
    let Some(p) = p else { return s.serialize_none() };
    let mut map = s.serialize_map(None)?;
    map.serialize_entry("max", &p.max)?;
    map.serialize_entry("at", &p.at)?;
    let parts = [("bending_y", p.bending_y), ("bending_z", p.bending_z), ("shear", p.shear)];
    for (name, value) in parts.iter().filter_map(|(n, v)| Some((n, (*v)?))) {
        map.serialize_entry(name, &value)?;
    }
    if let Some(point) = &p.point {
        map.serialize_entry("point", point)?;
    }
    map.end()
}

/// How far the model's tip is from the exact reference's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Compared {
    pub position: f64,
    pub position_over_length: f64,
    pub angle: f64,
    pub angle_degrees: f64,
}

impl Compared {
    /// The model's pose against the exact one, for a flexure of `length`.
    pub(super) fn of(model: &BodyPose, exact: &BodyPose, length: f64) -> Self {
        let position = match (model, exact) {
            (BodyPose::Planar { x, y, .. }, BodyPose::Planar { x: ex, y: ey, .. }) => (x - ex).hypot(y - ey),
            _ => (nalgebra::Vector3::from(model.position()) - nalgebra::Vector3::from(exact.position())).norm(),
        };
        let angle = model.angle_to(exact);
        Self { position, position_over_length: position / length, angle, angle_degrees: angle.to_degrees() }
    }
}

/// The exact reference's equilibrium, without the model's.
#[derive(Debug, Clone)]
pub struct ExactReference {
    pub pose: BodyPose,
    /// The root's reaction moment: one number in the plane, three in space.
    pub root_moment: Vec<f64>,
    pub stable: bool,
    pub compared: Compared,
    pub bending: Bending,
}

/// The exact reference's equilibrium, with the model's under `model`.
#[derive(Debug, Clone, Serialize)]
pub struct ExactDeflected {
    pub pose: BodyPose,
    #[serde(serialize_with = "one_or_three")]
    pub root_moment: Vec<f64>,
    pub stable: bool,
    pub stability_test: StabilityTest,
    pub model: Deflected,
    pub error: Compared,
    #[serde(flatten)]
    pub bending: Bending,
}

/// One number as a number, three as a list.
fn one_or_three<S: serde::Serializer>(v: &[f64], s: S) -> Result<S::Ok, S::Error> {
    match v {
        [x] => x.serialize(s),
        _ => v.serialize(s),
    }
}

/// What [`super::OneFlexure::deflect`] answers: the model's equilibrium,
/// or with the exact reference the exact one with the model's inside.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum Deflection {
    /// The model's.
    Model(Box<Deflected>),
    /// The exact reference's, with the model's.
    Exact(Box<ExactDeflected>),
}

impl Deflection {
    /// The model's equilibrium.
    pub fn model(&self) -> &Deflected {
        match self {
            Deflection::Model(m) => m,
            Deflection::Exact(e) => &e.model,
        }
    }
}

/// The tip's kinematics at given coordinates, the plane's with the
/// transform and Hessians.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum TipMotion {
    /// Pose, transform, Jacobian rows and Hessians (Eqs. 7, 19–21, 30–31).
    Planar(TipKinematics),
    /// Pose and the body Jacobian (6 × n, rows rx, ry, rz, x, y, z in the tip frame).
    Spatial { pose: BodyPose, jacobian: Vec<Vec<f64>> },
}

/// What [`super::OneFlexure::kinematics`] answers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Posed {
    #[serde(flatten)]
    pub tip: TipMotion,
    /// The elastic energy (J).
    pub energy: f64,
    /// Its gradient.
    pub gradient: Vec<f64>,
}

/// What [`super::OneFlexure::compliance`] answers: the tip's compliance at
/// rest, by rows (φ, x, y in the plane; rx, ry, rz, x, y, z in space, named in `order`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RestCompliance {
    pub compliance: Vec<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub order: Option<&'static [&'static str]>,
}
