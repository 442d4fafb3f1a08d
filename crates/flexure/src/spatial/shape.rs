//! The deformed spatial flexure along its length: the frame of every
//! cross-section asked for, by the tip's own Magnus integration.
//!
//! The frame $g(s) = (R(s), p(s))$ of the section at $s$ solves
//! $$g^{\prime} = g\thinspace\hat\xi(s),\qquad \xi = (u(s), e_1),\qquad g(0) = I,$$
//! with $u = (\tau, \kappa_y, \kappa_z)$ the body-frame curvature (Eq. 8
//! per component). The frames at the ends of the flexure's own $M$
//! subintervals, $s_k = kL/M$, are the products
//! $g(s_k) = \exp\Omega_1\cdots\exp\Omega_k$ of the same 6th-order Magnus
//! steps as the tip pose ([`super::pose_root_tip`]), so the last is the tip
//! to rounding. A section inside subinterval $k$ is one more Magnus step
//! from $s_k$, over $d = s - s_k < L/M$, with the curvature at its own three
//! Gauss nodes: $g(s) = g(s_k)\exp\Omega(s_k, d)$. Its local error is that
//! of a step no longer than the flexure's own, so every section is as
//! accurate as the tip.

use super::SpatialFlexure;
use super::magnus::{NODES, exponential};
use crate::error::{Error, Result};
use nalgebra::{Matrix3, Vector3};

/// The most sections [`shape`] and [`shape_at`] give: as many as a
/// `--shape` prints.
pub const MAX_SHAPE_POINTS: usize = 10_000;

/// One cross-section of a deformed spatial flexure, in the root frame.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SpatialPoint {
    /// Arc length from the root (m).
    pub s: f64,
    /// The section's centre $p(s)$ (m).
    pub position: [f64; 3],
    /// $R(s)$ by rows, `rotation[i][j]` $= R_{ij}$: its columns are the
    /// section's axes in the root frame (as the tip pose's rotation).
    pub rotation: [[f64; 3]; 3],
    /// The total body-frame curvature $u(s) = (\tau, \kappa_y, \kappa_z)$ (1/m).
    pub curvature: [f64; 3],
    /// The peak von Mises stress over the section (Pa), of the curvature's
    /// change from rest ([`super::stress()`]); `None` for a section given by
    /// its stiffnesses alone, which has no geometry.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress: Option<f64>,
}

/// The deformed flexure at `points` sections evenly spaced in arc length,
/// $s_i = iL/(K-1)$ for $i = 0, \dots, K-1$, ends included (the last exactly
/// at $L$): the frames of $g^{\prime} = g\hat\xi$ as the module docs integrate
/// them, each as accurate as the tip pose and the last equal to
/// [`super::pose_root_tip`] to rounding.
///
/// Errors name `points` (from 2 to [`MAX_SHAPE_POINTS`]) or `alpha`
/// ([`SpatialFlexure::check_coordinates`]).
///
/// # Example
/// ```
/// use flexure::{section::SpatialSection, spatial::{SpatialFlexure, shape}};
/// let f = SpatialFlexure::new(2.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [1, 1, 1]).unwrap();
/// // Constant κ_z = 1.5/2: a circle's arc, x = sin(κs)/κ, y = (1 − cos κs)/κ, exact to rounding.
/// let k = 0.75;
/// let points = shape(&f, &[0.0, 0.0, 1.5], 7).unwrap();
/// assert_eq!(points.len(), 7);
/// for p in &points {
///     let [x, y, z] = p.position;
///     assert!((x - (k * p.s).sin() / k).abs() < 1e-15 && (y - (1.0 - (k * p.s).cos()) / k).abs() < 1e-15);
///     assert!(z == 0.0 && (p.rotation[1][0] - (k * p.s).sin()).abs() < 1e-15);
///     assert!((p.curvature[2] - k).abs() < 1e-15 && p.stress.is_none());
/// }
/// assert_eq!(points[6].s, 2.0);
/// assert!(shape(&f, &[0.0, 0.0, 1.5], 1).is_err());
/// ```
pub fn shape(flexure: &SpatialFlexure, alpha: &[f64], points: usize) -> Result<Vec<SpatialPoint>> {
    if !(2..=MAX_SHAPE_POINTS).contains(&points) {
        return Err(Error::invalid("points", points, "must be from 2 to 10000 sections"));
    }
    let l = flexure.length();
    let at: Vec<f64> =
        (0..points).map(|i| if i + 1 == points { l } else { l * i as f64 / (points - 1) as f64 }).collect();
    shape_at(flexure, alpha, &at)
}

/// The deformed flexure's sections at the arc lengths `at` (m, from 0 to
/// $L$, non-decreasing, 1 to [`MAX_SHAPE_POINTS`] of them), integrated as
/// the module docs say: $g(s) = g(s_k)\exp\Omega(s_k, s - s_k)$ from the
/// last end of a subinterval $s_k = kL/M$ before $s$.
///
/// Errors name `at` or `alpha`.
///
/// # Example
/// ```
/// use flexure::{section::SpatialSection, spatial::{SpatialFlexure, shape_at}};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [1, 1, 1]).unwrap();
/// // Pure twist: the sections turn about x by τs and stay on the x axis.
/// let points = shape_at(&f, &[0.6, 0.0, 0.0], &[0.0, 0.25, 0.9]).unwrap();
/// let p = &points[2];
/// assert!((p.position[0] - 0.9).abs() < 1e-15 && p.position[1] == 0.0 && p.position[2] == 0.0);
/// assert!((p.rotation[2][1] - (0.6f64 * 0.9).sin()).abs() < 1e-15);
/// assert!(shape_at(&f, &[0.6, 0.0, 0.0], &[0.5, 0.25]).is_err());
/// ```
pub fn shape_at(flexure: &SpatialFlexure, alpha: &[f64], at: &[f64]) -> Result<Vec<SpatialPoint>> {
    flexure.check_coordinates("alpha", alpha)?;
    check_arc_lengths(flexure.length(), at)?;
    let (l, m) = (flexure.length(), flexure.subintervals());
    let h = l / m as f64;
    // Whether the section has a geometry, so a stress: decided once, at rest.
    let shaped = flexure.section().stress(0.0, [0.0; 3]).is_ok();
    let change: Vec<f64> = alpha.iter().zip(flexure.rest()).map(|(a, k)| a - k).collect();
    // The frame at the start of subinterval `k`.
    let (mut k, mut r, mut p) = (0, Matrix3::identity(), Vector3::zeros());
    let mut out = Vec::with_capacity(at.len());
    for &s in at {
        // The subinterval holding s (the last one's end for s = L).
        let target = ((s / h).floor() as usize).min(m);
        while k < target {
            let (rk, pk) = step(flexure, alpha, k as f64 * h, h);
            p += r * pk;
            r *= rk;
            k += 1;
        }
        let d = s - k as f64 * h;
        let (rs, ps) = if d > 0.0 {
            let (rd, pd) = step(flexure, alpha, k as f64 * h, d);
            (r * rd, p + r * pd)
        } else {
            (r, p)
        };
        let stress =
            if shaped { Some(flexure.section().stress(s / l, flexure.curvature(&change, s))?.von_mises) } else { None };
        out.push(SpatialPoint {
            s,
            position: [ps.x, ps.y, ps.z],
            rotation: std::array::from_fn(|i| std::array::from_fn(|j| rs[(i, j)])),
            curvature: flexure.curvature(alpha, s),
            stress,
        });
    }
    Ok(out)
}

/// One Magnus step from `start` over `length` (m): $\exp\Omega$ as $(R, p)$,
/// with the curvature at the step's three Gauss nodes.
fn step(flexure: &SpatialFlexure, alpha: &[f64], start: f64, length: f64) -> (Matrix3<f64>, Vector3<f64>) {
    exponential(&NODES.map(|t| Vector3::from(flexure.curvature(alpha, start + t * length))), length)
}

/// Checks that `at` holds 1 to [`MAX_SHAPE_POINTS`] finite arc lengths in
/// $[0, L]$, non-decreasing; errors name `at`.
fn check_arc_lengths(l: f64, at: &[f64]) -> Result<()> {
    if !(1..=MAX_SHAPE_POINTS).contains(&at.len()) {
        return Err(Error::invalid("at", format!("{} arc lengths", at.len()), "must hold from 1 to 10000"));
    }
    let mut last = 0.0;
    for &s in at {
        if !(s.is_finite() && (0.0..=l).contains(&s)) {
            return Err(Error::invalid("at", s, "must be a finite arc length from 0 to the flexure's length"));
        }
        if s < last {
            return Err(Error::invalid("at", s, "must not be below the arc length before it (increasing order)"));
        }
        last = s;
    }
    Ok(())
}
