//! The answer of a mechanism solve, built once from the library's
//! [`Solution`] for both dimensions, so that the command line (`flexure
//! solve`) and Python (`Mechanism.solve`) print the same thing in the same
//! shape without re-deriving it: the bodies' poses, the joints'
//! coordinates, the energy and stability, where the loading path snapped
//! through, and each flexure joint's carried load, error estimate and peak
//! stress (or, given by its stiffness alone, its peak change of curvature
//! $\max_s\lvert\hat\omega(\alpha, s) - \hat\omega_0(s)\rvert$, planar),
//! with the safety factor and deformed shape its file asks for.
//!
//! What differs by dimension is a leaf's coordinates (a pose, a load, a
//! shape's points, a stress's components), each an untagged enum, and the
//! few functions of [`Reported`]. It derives `serde::Serialize`: maps by
//! name (bodies, joints) keep the mechanism's order. Findings (closures
//! open at rest, crossings) and compliances are separate analyses, which
//! the caller adds.

mod dimension;

pub use dimension::Reported;

use crate::Error;
use crate::Flexure;
use crate::estimate::{Accuracy, ErrorEstimate};
use crate::kinematics::backbone;
use crate::mechanism::Mechanism;
use crate::mechanism::contact::{Contact, ContactMode};
use crate::mechanism::statics::Solution;
use crate::section::StressPoint;
use crate::space::Wrench;
use crate::spatial::{SpatialLoad, SpatialPoint};
use crate::stress::{Peak, stress};
use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};

/// Values by name, in the mechanism's order; serialized as a map.
#[derive(Debug, Clone, PartialEq)]
pub struct Named<T>(pub Vec<(String, T)>);

impl<T> Named<T> {
    /// The value named `name`, if any.
    pub fn get(&self, name: &str) -> Option<&T> {
        self.0.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    /// Whether nothing is named.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

impl<T> Default for Named<T> {
    fn default() -> Self {
        Self(Vec::new())
    }
}

impl<T: Serialize> Serialize for Named<T> {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// A body's frame in the ground frame, in its dimension's coordinates (the
/// columns a sweep prints, [`BodyPose::columns`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum BodyPose {
    /// Origin (m) and rotation $\varphi$ (rad).
    Planar { x: f64, y: f64, phi: f64 },
    /// Origin (m), rotation as URDF's roll, pitch, yaw (rad),
    /// $R = R_z(\text{yaw})R_y(\text{pitch})R_x(\text{roll})$, and as its matrix, by rows.
    Spatial { x: f64, y: f64, z: f64, roll: f64, pitch: f64, yaw: f64, rotation: [[f64; 3]; 3] },
}

impl BodyPose {
    /// A planar pose.
    pub fn planar(p: &crate::kinematics::Pose) -> Self {
        Self::Planar { x: p.x, y: p.y, phi: p.phi }
    }

    /// A spatial pose from its origin (m) and rotation matrix.
    ///
    /// # Example
    /// ```
    /// use flexure::report::BodyPose;
    /// let r = nalgebra::Rotation3::from_euler_angles(0.1, -0.2, 0.3);
    /// let p = BodyPose::spatial([1.0, 2.0, 3.0], r.matrix());
    /// let rpy = p.rpy();
    /// assert!((rpy[0] - 0.1).abs() < 1e-15 && (rpy[1] + 0.2).abs() < 1e-15 && (rpy[2] - 0.3).abs() < 1e-15);
    /// assert_eq!(p.transform()[2][3], 3.0);
    /// ```
    pub fn spatial(position: [f64; 3], rotation: &nalgebra::Matrix3<f64>) -> Self {
        let (roll, pitch, yaw) = nalgebra::Rotation3::from_matrix_unchecked(*rotation).euler_angles();
        // + 0.0 prints a zero angle as 0, not −0.
        let (roll, pitch, yaw) = (roll + 0.0, pitch + 0.0, yaw + 0.0);
        let [x, y, z] = position;
        let rotation = std::array::from_fn(|i| std::array::from_fn(|j| rotation[(i, j)]));
        Self::Spatial { x, y, z, roll, pitch, yaw, rotation }
    }

    /// The names of [`BodyPose::coordinates`].
    pub fn columns(&self) -> &'static [&'static str] {
        match self {
            Self::Planar { .. } => &["x", "y", "phi"],
            Self::Spatial { .. } => &["x", "y", "z", "roll", "pitch", "yaw"],
        }
    }

    /// The origin in space (m): the plane is $z = 0$.
    pub fn position(&self) -> [f64; 3] {
        match *self {
            Self::Planar { x, y, .. } => [x, y, 0.0],
            Self::Spatial { x, y, z, .. } => [x, y, z],
        }
    }

    /// The rotation in space, by rows: the plane's turns about $z$.
    pub fn rotation(&self) -> [[f64; 3]; 3] {
        match *self {
            Self::Planar { phi, .. } => {
                let (s, c) = phi.sin_cos();
                [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
            }
            Self::Spatial { rotation, .. } => rotation,
        }
    }

    /// Roll, pitch and yaw (rad): the plane's $\varphi$ is the yaw.
    pub fn rpy(&self) -> [f64; 3] {
        match *self {
            Self::Planar { phi, .. } => [0.0, 0.0, phi],
            Self::Spatial { roll, pitch, yaw, .. } => [roll, pitch, yaw],
        }
    }

    /// The 4 × 4 homogeneous transform, by rows.
    pub fn transform(&self) -> [[f64; 4]; 4] {
        let (r, p) = (self.rotation(), self.position());
        std::array::from_fn(|i| {
            std::array::from_fn(|j| match (i, j) {
                (3, j) => f64::from(j == 3),
                (i, 3) => p[i],
                (i, j) => r[i][j],
            })
        })
    }

    /// The angle (rad) of the rotation that takes this pose's to `other`'s.
    pub(crate) fn angle_to(&self, other: &BodyPose) -> f64 {
        match (self, other) {
            (Self::Planar { phi: a, .. }, Self::Planar { phi: b, .. }) => (a - b).abs(),
            (a, b) => {
                let m = |r: [[f64; 3]; 3]| nalgebra::Matrix3::from_fn(|i, j| r[i][j]);
                crate::space::rotation_angle(&m(a.rotation()), &m(b.rotation()))
            }
        }
    }

    /// The pose's coordinates: $(x, y, \varphi)$, or $(x, y, z)$ and roll, pitch, yaw.
    pub fn coordinates(&self) -> Vec<f64> {
        match *self {
            Self::Planar { x, y, phi } => vec![x, y, phi],
            Self::Spatial { x, y, z, roll, pitch, yaw, .. } => vec![x, y, z, roll, pitch, yaw],
        }
    }
}

/// A moving body's placement in the ground frame, in space (the plane at $z = 0$).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Placement {
    /// The body's name.
    pub name: String,
    /// Its origin (m).
    pub position: [f64; 3],
    /// Its rotation matrix, by rows.
    pub rotation: [[f64; 3]; 3],
    /// The same rotation as URDF's roll, pitch, yaw (rad).
    pub rpy: [f64; 3],
}

/// The placement of every moving body (the ground left out) at coordinates `q`.
///
/// # Example
/// ```
/// use flexure::mechanism::file::from_toml;
/// use flexure::report::placements;
/// let m = from_toml("[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\norigin = [0.1, 0.0, 0.0]\n")?;
/// let p = placements(&m, &[0.5]);
/// assert_eq!((p[0].name.as_str(), p[0].position, p[0].rpy), ("arm", [0.1, 0.0, 0.0], [0.0, 0.0, 0.5]));
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn placements<D: Reported>(m: &Mechanism<D>, q: &[f64]) -> Vec<Placement> {
    let poses = D::poses(m, q);
    (m.bodies.iter().zip(poses).skip(1))
        .map(|(b, p)| Placement { name: b.name.clone(), position: p.position(), rotation: p.rotation(), rpy: p.rpy() })
        .collect()
}

/// The largest value of a quantity along a flexure, `max`, and the arc
/// length from its root where it is reached, `at` (m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MaxAt {
    pub max: f64,
    pub at: f64,
}

impl From<Peak> for MaxAt {
    fn from(p: Peak) -> Self {
        Self { max: p.value, at: p.at }
    }
}

/// A flexure's peak stress: the largest von Mises stress `max` (Pa; in the
/// plane, where it is the bending stress, $\sigma = M c / I$) at arc length
/// `at` (m); in space also the section's point where it sits and its parts
/// there, each a peak over the section.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PeakStress {
    pub max: f64,
    pub at: f64,
    /// Where over the section (space).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub point: Option<StressPoint>,
    /// The normal stress of bending about $y$ (Pa; space).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bending_y: Option<f64>,
    /// The normal stress of bending about $z$ (Pa; space).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bending_z: Option<f64>,
    /// The torsional shear stress (Pa; space).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shear: Option<f64>,
}

impl From<Peak> for PeakStress {
    /// A planar flexure's peak bending stress.
    fn from(p: Peak) -> Self {
        Self { max: p.value, at: p.at, point: None, bending_y: None, bending_z: None, shear: None }
    }
}

/// The tip load a flexure joint carries, in its root frame: the wrench
/// with which the flexure alone is in equilibrium at its coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum CarriedLoad {
    /// Moment (N·m) and force $(F_x, F_y)$ (N).
    Planar(Wrench),
    /// Moment and force (N·m, N), each about or along $x$, $y$, $z$.
    Spatial(SpatialLoad),
}

/// One point of a deformed flexure in its root frame: arc length `s` (m),
/// pose, total curvature $\hat\omega(\alpha, s)$ (1/m) and, with a
/// thickness, the bending stress (Pa).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ShapePoint {
    pub s: f64,
    pub x: f64,
    pub y: f64,
    pub phi: f64,
    pub curvature: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress: Option<f64>,
}

/// One section of a deformed spatial flexure in its root frame, as answers
/// print it: arc length `s` (m), the section's pose as a body's
/// ([`BodyPose`], flattened as the plane's [`ShapePoint`] is), its total
/// body-frame curvature by component (1/m) and, with a section's shape,
/// the peak von Mises stress over it (Pa).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ShapeSection {
    pub s: f64,
    #[serde(flatten)]
    pub pose: BodyPose,
    pub curvature: Curvature,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress: Option<f64>,
}

/// A spatial curvature by component (1/m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Curvature {
    pub twist: f64,
    pub kappa_y: f64,
    pub kappa_z: f64,
}

impl From<&SpatialPoint> for ShapeSection {
    fn from(p: &SpatialPoint) -> Self {
        let [twist, kappa_y, kappa_z] = p.curvature;
        let rotation = nalgebra::Matrix3::from_fn(|i, j| p.rotation[i][j]);
        let pose = BodyPose::spatial(p.position, &rotation);
        ShapeSection { s: p.s, pose, curvature: Curvature { twist, kappa_y, kappa_z }, stress: p.stress }
    }
}

/// A deformed flexure's points, evenly spaced in arc length, ends included.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Shape {
    /// In the plane ([`shape`]): `{s, x, y, phi, curvature, stress}`.
    Planar(Vec<ShapePoint>),
    /// In space ([`crate::spatial::shape`]): `{s, x, y, z, roll, pitch,
    /// yaw, rotation, curvature: {twist, kappa_y, kappa_z}, stress}`.
    Spatial(Vec<ShapeSection>),
}

/// The answer of a mechanism solve; see the module docs. Maps left empty
/// (no flexure with a section, no `yield_strength`, no `shape`) are not
/// serialized, nor `limit_fraction` without a snap-through.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SolveReport {
    /// 2 or 3.
    pub dimension: u8,
    /// Each body's frame, by name, the ground first.
    pub bodies: Named<BodyPose>,
    /// Each joint's coordinates, by name.
    pub coordinates: Named<Vec<f64>>,
    /// The potential energy (J).
    pub energy: f64,
    /// Whether the equilibrium is stable.
    pub stable: bool,
    /// Each flexure joint's error estimate, by name: the joint alone under
    /// the tip load it carries, against its refined reference.
    pub error_estimate: Named<ErrorEstimate>,
    /// Whether any of them misses the accuracy target.
    pub flagged: bool,
    /// The peak stress of each flexure joint with a section.
    #[serde(skip_serializing_if = "Named::is_empty")]
    pub stress: Named<PeakStress>,
    /// The peak change of (bending) curvature (1/m) of each flexure joint given by its stiffnesses alone.
    #[serde(skip_serializing_if = "Named::is_empty")]
    pub curvature_max: Named<MaxAt>,
    /// Yield strength over peak stress, of each flexure joint whose file
    /// gives a `yield_strength` and that is stressed.
    #[serde(skip_serializing_if = "Named::is_empty")]
    pub safety_factor: Named<f64>,
    /// The deformed shape of each flexure joint whose file asks for one (`shape`).
    #[serde(skip_serializing_if = "Named::is_empty")]
    pub shape: Named<Shape>,
    /// Where the loading path lost stability and snapped through, as a
    /// fraction of the load ([`Solution::limit`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit_fraction: Option<f64>,
    /// The tip load each flexure joint carries, by name.
    pub load: Named<CarriedLoad>,
    /// The closures' multipliers ([`Solution::multipliers`]).
    pub multipliers: Vec<f64>,
    /// The final KKT residual, relative.
    pub residual: f64,
    /// Load-continuation steps.
    pub load_steps: usize,
    /// Newton iterations over all steps.
    pub iterations: usize,
    /// The contacts with the mechanism's geoms ([`Solution::contacts`]): an
    /// empty list where none touches or just opened, `None` (left out of the
    /// JSON) where no pair may touch, so a script reads the key whenever the
    /// file has a geom a part may reach.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contacts: Option<Vec<Contact>>,
}

/// A flexure joint whose error estimate (the joint alone under the tip
/// load it carries, against the refined model) failed, and why.
#[derive(Debug)]
pub struct EstimateFailed {
    pub joint: String,
    pub error: Error,
}

/// The report of `s`, a solution of `m`, with each flexure joint's
/// report keys ([`crate::mechanism::ReportOptions`]).
///
/// # Example
///
/// ```
/// use flexure::estimate::Accuracy;
/// use flexure::mechanism::file::from_toml;
/// use flexure::report::solve_report;
/// use flexure::mechanism::statics::{Settings, solve};
///
/// let text = r#"
///     [[joint]]
///     name = "hinge"
///     kind = "flexure"
///     parent = "ground"
///     child = "link"
///     length = 0.05
///     ei = 0.01
///     [[force]]
///     name = "tip"
///     body = "link"
///     at = [0.05, 0.0]
///     force = [0.0, 0.1]
/// "#;
/// let m = from_toml(&text)?;
/// let s = solve(&m, &Settings::default())?;
/// let r = solve_report(&m, &s, &Accuracy::default()).map_err(|f| f.error)?;
/// assert_eq!(r.coordinates.get("hinge").map(Vec::len), Some(3));
/// assert!(r.stable && r.bodies.get("link").is_some_and(|b| b.coordinates()[2] > 0.0));
/// assert!(r.curvature_max.get("hinge").is_some() && r.stress.is_empty());
/// // The joint carries the tip force: 0.1 N along y, and no moment at the tip.
/// let json = serde_json::to_value(&r.load.get("hinge").unwrap()).unwrap();
/// assert!((json["fy"].as_f64().unwrap() - 0.1).abs() < 1e-9);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn solve_report<D: Reported>(
    m: &Mechanism<D>,
    s: &Solution<D>,
    target: &Accuracy,
) -> std::result::Result<SolveReport, EstimateFailed> {
    let bodies = m.bodies.iter().map(|b| b.name.clone()).zip(D::poses(m, &s.q)).collect();
    let coordinates =
        m.joints.iter().map(|j| (j.name.clone(), s.q[j.offset..j.offset + j.kind.joint().dof()].to_vec())).collect();
    let mut r = SolveReport {
        dimension: D::POINT_DIM as u8,
        bodies: Named(bodies),
        coordinates: Named(coordinates),
        energy: s.energy,
        stable: s.stable,
        error_estimate: Named::default(),
        flagged: false,
        stress: Named::default(),
        curvature_max: Named::default(),
        safety_factor: Named::default(),
        shape: Named::default(),
        limit_fraction: s.limit,
        load: Named::default(),
        multipliers: s.multipliers.clone(),
        residual: s.residual,
        load_steps: s.load_steps,
        iterations: s.iterations,
        contacts: None,
    };
    let flexures = m.joints.iter().filter_map(|j| Some((j, j.kind.flexure()?)));
    let mut estimates = D::estimates(m, s, target);
    if s.contacts.iter().any(|c| c.state != ContactMode::Open) {
        // Contact forces along a span: the refined mechanism's estimate, the loads as carried.
        match crate::estimate::contact_estimates(m, s, target) {
            Ok(found) => {
                for (e, c) in estimates.iter_mut().zip(found) {
                    if let Ok((old, _)) = e {
                        *old = c;
                    }
                }
            }
            Err(error) => {
                let joint =
                    m.joints.iter().find(|j| j.kind.flexure().is_some()).map_or(String::new(), |j| j.name.clone());
                return Err(EstimateFailed { joint, error });
            }
        }
    }
    if !crate::mechanism::contact::pairs(m).is_empty() {
        r.contacts = Some(s.contacts.clone());
    }
    for ((j, f), estimate) in flexures.zip(estimates) {
        let q = &s.q[j.offset..j.offset + j.kind.joint().dof()];
        let name = j.name.clone();
        let failed = |error| EstimateFailed { joint: name.clone(), error };
        let (e, load) = estimate.map_err(failed)?;
        r.flagged |= e.flagged;
        r.error_estimate.0.push((name.clone(), e));
        r.load.0.push((name.clone(), load));
        match D::bending(f, q).map_err(failed)? {
            (Some(p), _) => {
                r.stress.0.push((name.clone(), p));
                if let Some(strength) = j.report.yield_strength.filter(|_| p.max > 0.0) {
                    r.safety_factor.0.push((name.clone(), strength / p.max));
                }
            }
            (None, c) => r.curvature_max.0.extend(c.map(|c| (name.clone(), c))),
        }
        if let Some(count) = j.report.shape {
            r.shape.0.push((name.clone(), D::shape(f, q, count).map_err(failed)?));
        }
    }
    Ok(r)
}

/// The deformed flexure at `count` points evenly spaced in arc length, ends included.
///
/// # Example
///
/// ```
/// use flexure::Flexure;
/// use flexure::report::shape;
///
/// let f = Flexure::new(2.0, 1.0, 3)?;
/// let points = shape(&f, &[0.5, 0.0, 0.0], 5);
/// assert_eq!(points.len(), 5);
/// assert!((points[4].s - 2.0).abs() < 1e-15 && (points[4].phi - 0.5).abs() < 1e-12);
/// assert!(points.iter().all(|p| (p.curvature - 0.25).abs() < 1e-12 && p.stress.is_none()));
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn shape(f: &Flexure, alpha: &[f64], count: usize) -> Vec<ShapePoint> {
    let poses = backbone(f, alpha, count);
    let step = f.length() / (poses.len() - 1) as f64;
    poses
        .iter()
        .enumerate()
        .map(|(i, p)| {
            // The last point exactly at the tip, not at a rounded multiple.
            let s = if i + 1 == poses.len() { f.length() } else { i as f64 * step };
            ShapePoint { s, x: p.x, y: p.y, phi: p.phi, curvature: f.curvature(alpha, s), stress: stress(f, alpha, s) }
        })
        .collect()
}
