//! Orthographic projections of the world onto a picture plane: the views
//! `draw --view iso|front|top|side` draws a spatial mechanism from.
//!
//! A view is an orthonormal, right-handed triple of world directions
//! $(r, u, t)$: the picture's right $r$, its up $u$, and $t = r\times u$
//! toward the viewer. A world point $p$ is drawn at $(p\cdot r,\ p\cdot u)$
//! (metres in the picture plane, to one scale on both axes) and lies at the
//! depth $p\cdot t$: the larger, the nearer, so parts are painted in
//! increasing depth and near parts cover far ones.
//!
//! | view | looks along | right $r$ | up $u$ | toward the viewer $t$ |
//! |---|---|---|---|---|
//! | `front` | $+y$ | $x$ | $z$ | $-y$ |
//! | `side` | $-x$ | $y$ | $z$ | $+x$ |
//! | `top` | $-z$ | $x$ | $y$ | $+z$ |
//! | `iso` | $-(1, 1, 1)/\sqrt3$ | $(-1, 1, 0)/\sqrt2$ | $(-1, -1, 2)/\sqrt6$ | $(1, 1, 1)/\sqrt3$ |
//!
//! $z$ is up in every view but `top`. The isometric view is the common
//! engineering one, the camera on the diagonal $(1, 1, 1)$ looking at the
//! origin: $x$ drawn to the lower left and $y$ to the lower right, each
//! $30°$ below the horizontal, and $z$ straight up, every axis shortened by
//! the same $\sqrt{2/3}$.

use nalgebra::Vector3;
use std::f64::consts::FRAC_1_SQRT_2;

/// Where a spatial mechanism is drawn from (the module docs give each
/// view's axes).
///
/// # Example
/// ```
/// use flexure_cli::projection::View;
/// use nalgebra::Vector3;
/// // +z is up in the front view, and its depth is nil: it lies in the picture plane.
/// let (picture, depth) = View::Front.project(&Vector3::new(0.0, 0.0, 1.0));
/// assert_eq!((picture, depth), ((0.0, 1.0), 0.0));
/// // Seen from the top, +z points at the viewer: a point, all depth.
/// assert_eq!(View::Top.project(&Vector3::new(0.0, 0.0, 1.0)), ((0.0, 0.0), 1.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum View {
    /// Isometric: x to the lower left, y to the lower right, z up.
    #[default]
    Iso,
    /// Looking along +y: x to the right, z up.
    Front,
    /// Looking down −z: x to the right, y up.
    Top,
    /// Looking along −x: y to the right, z up.
    Side,
}

impl View {
    /// Every view, in the order `--view` lists them.
    pub const ALL: [View; 4] = [View::Iso, View::Front, View::Top, View::Side];

    /// The picture's right $r$, up $u$ and toward-the-viewer $t = r\times u$,
    /// as unit world directions.
    ///
    /// # Example
    /// ```
    /// use flexure_cli::projection::View;
    /// for view in View::ALL {
    ///     let [r, u, t] = view.basis();
    ///     assert!((r.cross(&u) - t).norm() < 1e-15 && (r.norm() - 1.0).abs() < 1e-15);
    /// }
    /// ```
    pub fn basis(self) -> [Vector3<f64>; 3] {
        let (s3, s6) = (3f64.sqrt(), 6f64.sqrt());
        match self {
            View::Front => [Vector3::x(), Vector3::z(), -Vector3::y()],
            View::Side => [Vector3::y(), Vector3::z(), Vector3::x()],
            View::Top => [Vector3::x(), Vector3::y(), Vector3::z()],
            View::Iso => [
                Vector3::new(-FRAC_1_SQRT_2, FRAC_1_SQRT_2, 0.0),
                Vector3::new(-1.0 / s6, -1.0 / s6, 2.0 / s6),
                Vector3::new(1.0 / s3, 1.0 / s3, 1.0 / s3),
            ],
        }
    }

    /// The world point (or direction) `p` in the picture, $(p\cdot r, p\cdot u)$,
    /// and its depth toward the viewer, $p\cdot t$.
    ///
    /// # Example
    /// ```
    /// use flexure_cli::projection::View;
    /// use nalgebra::Vector3;
    /// // Isometric: x to the lower left, 30° below the horizontal, shortened by √(2/3).
    /// let ((a, b), _) = View::Iso.project(&Vector3::new(1.0, 0.0, 0.0));
    /// assert!((b.atan2(a).to_degrees() + 150.0).abs() < 1e-12 && (a.hypot(b) - (2.0f64 / 3.0).sqrt()).abs() < 1e-15);
    /// ```
    pub fn project(self, p: &Vector3<f64>) -> ((f64, f64), f64) {
        let [r, u, t] = self.basis();
        ((p.dot(&r), p.dot(&u)), p.dot(&t))
    }

    /// Its name, as `--view` spells it.
    pub fn name(self) -> &'static str {
        match self {
            View::Iso => "iso",
            View::Front => "front",
            View::Top => "top",
            View::Side => "side",
        }
    }

    /// The picture's axis labels, (horizontal, vertical).
    pub fn axis_labels(self) -> (&'static str, &'static str) {
        match self {
            View::Front => ("x (m)", "z (m)"),
            View::Side => ("y (m)", "z (m)"),
            View::Top => ("x (m)", "y (m)"),
            View::Iso => ("(y − x)/√2 (m)", "(2z − x − y)/√6 (m)"),
        }
    }

    /// How the world's axes lie in the picture, for the legend.
    pub fn description(self) -> &'static str {
        match self {
            View::Iso => "isometric view: x to the lower left, y to the lower right, z up",
            View::Front => "front view, looking along +y: x to the right, z up",
            View::Top => "top view, looking down −z: x to the right, y up",
            View::Side => "side view, looking along −x: y to the right, z up",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::View;
    use nalgebra::Vector3;
    use std::f64::consts::SQRT_2 as ROOT_TWO;

    /// Reference: the table of the module docs, exactly (each entry is a
    /// unit vector or its negative in three of the views; 1e-15 for the
    /// isometric's square roots).
    #[test]
    fn each_view_maps_the_world_axes_as_its_table_says() {
        let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
        assert_eq!(View::Front.project(&x), ((1.0, 0.0), 0.0));
        assert_eq!(View::Front.project(&z), ((0.0, 1.0), 0.0));
        assert_eq!(View::Front.project(&y), ((0.0, 0.0), -1.0), "front looks along +y: y goes away");
        assert_eq!(View::Side.project(&y), ((1.0, 0.0), 0.0));
        assert_eq!(View::Side.project(&z), ((0.0, 1.0), 0.0));
        assert_eq!(View::Side.project(&x), ((0.0, 0.0), 1.0), "side looks along −x: x comes near");
        assert_eq!(View::Top.project(&x), ((1.0, 0.0), 0.0));
        assert_eq!(View::Top.project(&y), ((0.0, 1.0), 0.0));
        assert_eq!(View::Top.project(&z), ((0.0, 0.0), 1.0));
        let s6 = 6f64.sqrt();
        let close = |a: ((f64, f64), f64), b: ((f64, f64), f64)| {
            (a.0.0 - b.0.0).abs() < 1e-15 && (a.0.1 - b.0.1).abs() < 1e-15 && (a.1 - b.1).abs() < 1e-15
        };
        let d = 1.0 / 3f64.sqrt();
        assert!(close(View::Iso.project(&x), ((-1.0 / ROOT_TWO, -1.0 / s6), d)));
        assert!(close(View::Iso.project(&y), ((1.0 / ROOT_TWO, -1.0 / s6), d)));
        assert!(close(View::Iso.project(&z), ((0.0, 2.0 / s6), d)));
        // The diagonal (1, 1, 1) points at the viewer: drawn at the origin.
        assert!(close(View::Iso.project(&Vector3::new(1.0, 1.0, 1.0)), ((0.0, 0.0), 3f64.sqrt())));
    }

    /// Reference: an orthographic projection keeps lengths in the picture
    /// plane: $|p|^2 = a^2 + b^2 + d^2$ (Pythagoras in the view's
    /// orthonormal basis), to 1e-14 relative.
    #[test]
    fn a_projection_and_its_depth_keep_the_length() {
        let p = Vector3::new(0.3, -1.7, 2.2);
        for view in View::ALL {
            let ((a, b), d) = view.project(&p);
            assert!((a * a + b * b + d * d - p.norm_squared()).abs() < 1e-14 * p.norm_squared(), "{view:?}");
        }
    }
}
