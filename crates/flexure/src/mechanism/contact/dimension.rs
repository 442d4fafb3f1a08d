//! What contact needs of a dimension: a point's coordinates as a vector
//! (for the shapes' closed forms) and a flexure's surface, its centreline
//! with the half thickness it touches with. The plane and space side by side.

use crate::error::Result;
use crate::kinematics::{backbone, pose_at};
use crate::mechanism::Dimension;
use crate::section::Outline;
use crate::space::{Planar, Spatial};
use nalgebra::{Point2, Point3, Vector2, Vector3};

/// A point of a flexure's surface: its arc length $s$ (m), its centreline
/// point in the flexure's root frame, and the half thickness $h$ (m) it
/// touches with there.
pub type SurfacePoint<D> = (f64, <D as crate::space::Space>::Point, f64);

/// A dimension whose shapes and flexures may touch: [`Planar`] or [`Spatial`].
///
/// # Example
/// ```
/// use flexure::mechanism::contact::Touch;
/// use flexure::space::Planar;
/// use nalgebra::{Point2, Vector2};
/// assert_eq!(Planar::position(&Point2::new(1.0, 2.0)), Vector2::new(1.0, 2.0));
/// ```
pub trait Touch: Dimension {
    /// A point's coordinates, as a vector from the origin.
    fn position(p: &Self::Point) -> Self::Vector;
    /// $p + k v$.
    fn moved(p: &Self::Point, v: &Self::Vector, k: f64) -> Self::Point;
    /// `samples` (at least 2) points of the flexure with coordinates
    /// `alpha`, evenly spaced in arc length from root to tip, each with the
    /// half thickness of its section: half the `thickness` of a strip (in
    /// space too, where a strip's edges reach a further half of its width
    /// off the bending plane), half the diameter of a rod, 0 for a flexure
    /// given by its stiffness alone (the centreline touches).
    fn surface(f: &Self::Flexure, alpha: &[f64], samples: usize) -> Result<Vec<SurfacePoint<Self>>>;
    /// The surface point at arc length `s` (m, in $[0, L]$), as [`Touch::surface`] gives them.
    fn surface_at(f: &Self::Flexure, alpha: &[f64], s: f64) -> Result<SurfacePoint<Self>>;
}

impl Touch for Planar {
    fn position(p: &Point2<f64>) -> Vector2<f64> {
        p.coords
    }

    fn moved(p: &Point2<f64>, v: &Vector2<f64>, k: f64) -> Point2<f64> {
        p + v * k
    }

    fn surface(f: &crate::Flexure, alpha: &[f64], samples: usize) -> Result<Vec<SurfacePoint<Planar>>> {
        let count = samples.max(2);
        let l = f.length();
        let points = backbone(f, alpha, count);
        Ok(points
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let t = i as f64 / (count - 1) as f64;
                (t * l, p.origin(), 0.5 * f.section().thickness(t, l).unwrap_or(0.0))
            })
            .collect())
    }

    /// The centreline point by [`crate::kinematics::pose_at`], on 64 pieces of $[0, s]$.
    fn surface_at(f: &crate::Flexure, alpha: &[f64], s: f64) -> Result<SurfacePoint<Planar>> {
        f.check_coordinates("alpha", alpha)?;
        let l = f.length();
        if !(0.0..=l).contains(&s) {
            return Err(crate::Error::invalid("s", s, "must be an arc length on the flexure, from 0 to its length"));
        }
        let p = pose_at(f, alpha, s, 64);
        Ok((s, p.origin(), 0.5 * f.section().thickness(s / l, l).unwrap_or(0.0)))
    }
}

impl Touch for Spatial {
    fn position(p: &Point3<f64>) -> Vector3<f64> {
        p.coords
    }

    fn moved(p: &Point3<f64>, v: &Vector3<f64>, k: f64) -> Point3<f64> {
        p + v * k
    }

    fn surface(
        f: &crate::spatial::SpatialFlexure,
        alpha: &[f64],
        samples: usize,
    ) -> Result<Vec<SurfacePoint<Spatial>>> {
        let l = f.length();
        Ok(crate::spatial::shape(f, alpha, samples.max(2))?
            .into_iter()
            .map(|sec| (sec.s, Point3::from(sec.position), half_thickness(f, sec.s / l)))
            .collect())
    }

    fn surface_at(f: &crate::spatial::SpatialFlexure, alpha: &[f64], s: f64) -> Result<SurfacePoint<Spatial>> {
        let sec = crate::spatial::shape_at(f, alpha, &[s])?.remove(0);
        Ok((s, Point3::from(sec.position), half_thickness(f, s / f.length())))
    }
}

/// Half a spatial flexure's thickness (a strip's) or diameter (a rod's) at
/// $t = s/L$; 0 for one given by its stiffnesses alone.
fn half_thickness(f: &crate::spatial::SpatialFlexure, t: f64) -> f64 {
    match f.section().outline(t) {
        Some(Outline::Rectangle { thickness, .. }) => 0.5 * thickness,
        Some(Outline::Circle { diameter }) => 0.5 * diameter,
        None => 0.0,
    }
}
