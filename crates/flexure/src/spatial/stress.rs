//! The spatial flexure's peak stress along its length: at each section the
//! peak over the section of the two bending stresses and the torsional
//! shear ([`SpatialSection::stress`](crate::section::SpatialSection::stress),
//! von Mises at the candidate points), of the curvature's change from rest
//! $u(s) - u_0(s)$; the largest along $s$ by a scan and golden section, as
//! for the planar flexure ([`crate::stress::refine`]).

use super::SpatialFlexure;
use crate::error::Result;
use crate::section::SpatialStress;
use crate::stress::{Peak, refine};

/// Samples of the coarse scan, per coordinate (at least 64 in all).
const SAMPLES_PER_COORDINATE: usize = 8;

/// Golden-section steps refining the bracketed peak.
const REFINEMENTS: usize = 80;

/// The largest stress along a spatial flexure and where it is.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SpatialPeak {
    /// The stresses of the section where the von Mises stress peaks.
    pub stress: SpatialStress,
    /// Its arc length from the root (m).
    pub at: f64,
}

/// The stresses of the section at arc length `s` (m) for coordinates `alpha`.
///
/// # Example
/// ```
/// use flexure::section::{Profile, SpatialSection};
/// use flexure::spatial::{SpatialFlexure, stress};
/// let s = SpatialSection::circle(200e9, 0.3, Profile::Constant(1e-3)).unwrap();
/// let f = SpatialFlexure::new(0.02, s, [1, 1, 1]).unwrap();
/// // A uniform bend about y of 0.02 rad over 20 mm: 1 1/m, σ = E κ d/2 = 100 MPa.
/// let sigma = stress(&f, &[0.0, 0.02, 0.0], 0.01).unwrap();
/// assert!((sigma.von_mises - 100e6).abs() < 1e-3);
/// ```
pub fn stress(flexure: &SpatialFlexure, alpha: &[f64], s: f64) -> Result<SpatialStress> {
    flexure.check_coordinates("alpha", alpha)?;
    flexure.section().stress(s / flexure.length(), flexure.curvature(&change(flexure, alpha), s))
}

/// The peak von Mises stress along the flexure (Pa) and the section's
/// stresses there. Errors for a section given by its stiffnesses alone
/// (no geometry, named `section`).
///
/// # Example
/// ```
/// use flexure::section::{Profile, Shear, SpatialSection};
/// use flexure::spatial::{SpatialFlexure, peak_stress};
/// let s = SpatialSection::rectangle(70e9, Shear::Poisson(0.33), Profile::Constant(0.01), Profile::Constant(5e-4))
///     .unwrap();
/// let f = SpatialFlexure::new(0.03, s, [2, 2, 2]).unwrap();
/// // κ_z = (0.3 + 0.3 P̃₁(s/L))/L: largest at the tip, 20 1/m.
/// let p = peak_stress(&f, &[0.0, 0.0, 0.0, 0.0, 0.3, 0.3]).unwrap();
/// assert!((p.at - 0.03).abs() < 1e-12 && (p.stress.von_mises - 70e9 * 20.0 * 2.5e-4).abs() < 1e-2);
/// ```
pub fn peak_stress(flexure: &SpatialFlexure, alpha: &[f64]) -> Result<SpatialPeak> {
    flexure.check_coordinates("alpha", alpha)?;
    let (section, l) = (flexure.section(), flexure.length());
    let change = change(flexure, alpha);
    let at = |s: f64| section.stress((s / l).clamp(0.0, 1.0), flexure.curvature(&change, s));
    let peak = peak_along(flexure, |s| at(s).map(|p| p.von_mises))?;
    Ok(SpatialPeak { stress: at(peak.at)?, at: peak.at })
}

/// The peak change of bending curvature along the flexure (1/m) and where:
/// $\max_s \lVert(\kappa_y - \kappa_{y0}, \kappa_z - \kappa_{z0})\rVert$, the
/// planar flexure's `curvature_max` in space, for a section without a
/// shape (the twist's rate is left out: it strains by shear, not bending).
///
/// # Example
/// ```
/// use flexure::section::SpatialSection;
/// use flexure::spatial::{SpatialFlexure, peak_curvature};
/// let f = SpatialFlexure::new(0.5, SpatialSection::uniform(1.0, 2.0, 2.0).unwrap(), [1, 2, 1]).unwrap();
/// // κ_y = (0.3 + 0.3 P̃₁(s/L))/L, κ_z = 0.2/L: largest at the tip, |(1.2, 0.4)|.
/// let p = peak_curvature(&f, &[5.0, 0.3, 0.3, 0.2]).unwrap();
/// assert!((p.at - 0.5).abs() < 1e-12 && (p.value - 1.2f64.hypot(0.4)).abs() < 1e-12);
/// ```
pub fn peak_curvature(flexure: &SpatialFlexure, alpha: &[f64]) -> Result<Peak> {
    flexure.check_coordinates("alpha", alpha)?;
    let change = change(flexure, alpha);
    peak_along(flexure, |s| {
        let [_, ky, kz] = flexure.curvature(&change, s);
        Ok(ky.hypot(kz))
    })
}

/// The coordinates' change from rest.
fn change(flexure: &SpatialFlexure, alpha: &[f64]) -> Vec<f64> {
    alpha.iter().zip(flexure.rest()).map(|(a, k)| a - k).collect()
}

/// The maximum of `g` on $[0, L]$: a scan of evenly spaced points and the
/// section's breakpoints, then golden section between the best point's neighbours.
fn peak_along(flexure: &SpatialFlexure, g: impl Fn(f64) -> Result<f64>) -> Result<Peak> {
    let l = flexure.length();
    let count = (SAMPLES_PER_COORDINATE * flexure.coordinates()).max(64);
    let mut points: Vec<f64> = (0..=count).map(|k| k as f64 / count as f64).collect();
    points.extend(flexure.section().breakpoints());
    points.sort_by(f64::total_cmp);
    let mut values = Vec::with_capacity(points.len());
    for t in &points {
        values.push(g(t * l)?);
    }
    let best = (0..points.len()).max_by(|&a, &b| values[a].total_cmp(&values[b])).unwrap_or(0);
    let bracket = (points[best.saturating_sub(1)] * l, points[(best + 1).min(points.len() - 1)] * l);
    let top = Peak { value: values[best], at: points[best] * l };
    refine(bracket, top, l, REFINEMENTS, g)
}
