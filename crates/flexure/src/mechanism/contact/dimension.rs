//! What contact needs of a dimension: a point's coordinates as a vector
//! (for the shapes' closed forms) and a flexure's surface, its centreline
//! with the half thickness it touches with. The plane and space side by side.

use crate::error::Result;
use crate::kinematics::backbone;
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
    /// `samples` (at least 2) points of the flexure with coordinates
    /// `alpha`, evenly spaced in arc length from root to tip, each with the
    /// half thickness of its section: half the `thickness` of a strip (in
    /// space too, where a strip's edges reach a further half of its width
    /// off the bending plane), half the diameter of a rod, 0 for a flexure
    /// given by its stiffness alone (the centreline touches).
    fn surface(f: &Self::Flexure, alpha: &[f64], samples: usize) -> Result<Vec<SurfacePoint<Self>>>;
}

impl Touch for Planar {
    fn position(p: &Point2<f64>) -> Vector2<f64> {
        p.coords
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
}

impl Touch for Spatial {
    fn position(p: &Point3<f64>) -> Vector3<f64> {
        p.coords
    }

    fn surface(
        f: &crate::spatial::SpatialFlexure,
        alpha: &[f64],
        samples: usize,
    ) -> Result<Vec<SurfacePoint<Spatial>>> {
        let l = f.length();
        Ok(crate::spatial::shape(f, alpha, samples.max(2))?
            .into_iter()
            .map(|sec| {
                let half = match f.section().outline(sec.s / l) {
                    Some(Outline::Rectangle { thickness, .. }) => 0.5 * thickness,
                    Some(Outline::Circle { diameter }) => 0.5 * diameter,
                    None => 0.0,
                };
                (sec.s, Point3::from(sec.position), half)
            })
            .collect())
    }
}
