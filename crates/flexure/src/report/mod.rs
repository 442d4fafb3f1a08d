//! The answer of a mechanism solve, built once from the library's
//! [`Solution`] so that the command line (`flexure solve`) and Python
//! (`Mechanism.solve`) print the same thing without re-deriving it: the
//! bodies' poses, the joints' coordinates, the energy and stability, where
//! the loading path snapped through, each flexure joint's error estimate
//! and its peak stress (or, given by $EI$ alone, its peak change of
//! curvature $\max_s\lvert\hat\omega(\alpha, s) - \hat\omega_0(s)\rvert$),
//! with the safety factor and deformed shape its file asks for.
//!
//! It derives `serde::Serialize`: maps by name (bodies, joints) keep the
//! mechanism's order. Findings (closures open at rest, crossings) and
//! compliances are separate analyses, which the caller adds.

pub mod spatial;

use crate::Error;
use crate::Flexure;
use crate::estimate::{Accuracy, ErrorEstimate, joint_error};
use crate::kinematics::backbone;
use crate::mechanism::Mechanism;
use crate::mechanism::file::ReportOptions;
use crate::mechanism::statics::{Solution, body_frames};
use crate::stress::{Peak, peak_curvature, peak_stress, stress};
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

/// A body's frame in the ground frame: origin (m) and rotation $\varphi$ (rad).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BodyPose {
    pub x: f64,
    pub y: f64,
    pub phi: f64,
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

/// The answer of a mechanism solve; see the module docs. Maps left empty
/// (no flexure with a thickness, no `yield_strength`, no `shape`) are not
/// serialized, nor `limit_fraction` without a snap-through.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SolveReport {
    /// Each body's frame, by name.
    pub bodies: Named<BodyPose>,
    /// Each joint's coordinates, by name.
    pub coordinates: Named<Vec<f64>>,
    /// The potential energy (J).
    pub energy: f64,
    /// Whether the equilibrium is stable.
    pub stable: bool,
    /// Each flexure joint's error estimate ([`joint_error`]), by name.
    pub error_estimate: Named<ErrorEstimate>,
    /// Whether any of them misses the accuracy target.
    pub flagged: bool,
    /// The peak bending stress (Pa) of each flexure joint with a thickness.
    #[serde(skip_serializing_if = "Named::is_empty")]
    pub stress: Named<MaxAt>,
    /// The peak change of curvature (1/m) of each flexure joint given by $EI$ alone.
    #[serde(skip_serializing_if = "Named::is_empty")]
    pub curvature_max: Named<MaxAt>,
    /// Yield strength over peak stress, of each flexure joint whose file
    /// gives a `yield_strength` and that is stressed.
    #[serde(skip_serializing_if = "Named::is_empty")]
    pub safety_factor: Named<f64>,
    /// The deformed shape of each flexure joint whose file asks for one (`shape`).
    #[serde(skip_serializing_if = "Named::is_empty")]
    pub shape: Named<Vec<ShapePoint>>,
    /// Where the loading path lost stability and snapped through, as a
    /// fraction of the load ([`Solution::limit`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit_fraction: Option<f64>,
}

/// A flexure joint whose error estimate (the joint alone under the tip
/// load it carries, against the refined model) failed, and why.
#[derive(Debug)]
pub struct EstimateFailed {
    pub joint: String,
    pub error: Error,
}

/// The report of `s`, a solution of `m`; `reports` are the file's report
/// keys of its flexure joints ([`crate::mechanism::file::reports`]), by name.
///
/// # Example
///
/// ```
/// use flexure::estimate::Accuracy;
/// use flexure::mechanism::file::{from_toml, reports};
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
/// let r = solve_report(&m, &s, &reports(&text)?, &Accuracy::default()).map_err(|f| f.error)?;
/// assert_eq!(r.coordinates.get("hinge").map(Vec::len), Some(3));
/// assert!(r.stable && r.bodies.get("link").is_some_and(|b| b.phi > 0.0));
/// assert!(r.curvature_max.get("hinge").is_some() && r.stress.is_empty());
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn solve_report(
    m: &Mechanism,
    s: &Solution,
    reports: &[(String, ReportOptions)],
    target: &Accuracy,
) -> std::result::Result<SolveReport, EstimateFailed> {
    let frames = body_frames(m, s);
    let bodies = m
        .bodies
        .iter()
        .zip(&frames.bodies)
        .map(|(b, f)| (b.name.clone(), BodyPose { x: f.x, y: f.y, phi: f.phi }))
        .collect();
    let coordinates =
        m.joints.iter().map(|j| (j.name.clone(), s.q[j.offset..j.offset + j.kind.joint().dof()].to_vec())).collect();
    let mut r = SolveReport {
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
    };
    for j in &m.joints {
        let Some(f) = j.kind.flexure() else { continue };
        let q = &s.q[j.offset..j.offset + f.order()];
        let name = j.name.clone();
        let e = joint_error(f, q, target).map_err(|error| EstimateFailed { joint: name.clone(), error })?;
        r.flagged |= e.flagged;
        r.error_estimate.0.push((name.clone(), e));
        let keys = reports.iter().find(|k| k.0 == j.name).map_or_else(ReportOptions::default, |k| k.1);
        match peak_stress(f, q) {
            Some(p) => {
                r.stress.0.push((name.clone(), p.into()));
                if let Some(strength) = keys.yield_strength.filter(|_| p.value > 0.0) {
                    r.safety_factor.0.push((name.clone(), strength / p.value));
                }
            }
            None => r.curvature_max.0.push((name.clone(), peak_curvature(f, q).into())),
        }
        if let Some(count) = keys.shape {
            r.shape.0.push((name, shape(f, q, count)));
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
