//! The rigid obstacles a flexure may touch: a half-plane and a circle.

use crate::error::{Error, Result};
use crate::scalar::Scalar;

/// The shape of a rigid obstacle in the root frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ObstacleShape {
    /// The half-plane $\lbrace p : (p - q)\cdot n < 0\rbrace$ behind the line
    /// through `point` $q$ (m) with outward normal `normal` $n$ (any length
    /// but zero; it points to the free side).
    HalfPlane {
        /// A point on the boundary line (m).
        point: [f64; 2],
        /// The outward normal (scaled to unit length when used).
        normal: [f64; 2],
    },
    /// The disc of radius `radius` (m) about `centre` (m): a circular post.
    Circle {
        /// Centre (m).
        centre: [f64; 2],
        /// Radius (m), greater than zero.
        radius: f64,
    },
}

/// A rigid obstacle: its [`ObstacleShape`] and the Coulomb friction coefficient
/// $\mu \ge 0$ between it and the flexure's tip.
///
/// The flexure's centreline $p(s)$ must keep the gap
/// $$g(p) = d(p) - h \ge 0,$$
/// where $d$ is the signed distance to the obstacle's boundary (positive
/// outside: $(p - q)\cdot\hat n$ for a half-plane, $\lvert p - c\rvert - R$
/// for a circle) and $h$ the flexure's half thickness. A contact force acts
/// at the centreline point along the outward normal $\hat n(p)$ of the
/// nearest boundary point ($\hat n$ itself, or $(p - c)/\lvert p - c\rvert$).
///
/// # Example
/// ```
/// use flexure::reference::elastica::contact::Obstacle;
/// let floor = Obstacle::half_plane([0.0, -0.1], [0.0, 2.0]);
/// assert!((floor.gap([0.5, 0.0], 0.01) - 0.09).abs() < 1e-15);
/// let post = Obstacle::circle([1.0, 0.0], 0.5).with_friction(0.3);
/// assert!((post.gap([0.0, 0.0], 0.0) - 0.5).abs() < 1e-15 && post.friction == 0.3);
/// assert!(Obstacle::circle([0.0, 0.0], -1.0).validate().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Obstacle {
    /// Where the obstacle is.
    pub shape: ObstacleShape,
    /// Coulomb's $\mu$ at a tip contact (0: frictionless).
    pub friction: f64,
}

impl Obstacle {
    /// The frictionless half-plane behind the line through `point` with outward `normal`.
    ///
    /// # Example
    /// ```
    /// use flexure::reference::elastica::contact::Obstacle;
    /// // A wall at x = 2 facing the root.
    /// let wall = Obstacle::half_plane([2.0, 0.0], [-1.0, 0.0]);
    /// assert_eq!((wall.gap([1.5, 7.0], 0.0), wall.friction), (0.5, 0.0));
    /// ```
    pub fn half_plane(point: [f64; 2], normal: [f64; 2]) -> Self {
        Self { shape: ObstacleShape::HalfPlane { point, normal }, friction: 0.0 }
    }

    /// The frictionless disc of `radius` about `centre`.
    ///
    /// # Example
    /// ```
    /// use flexure::reference::elastica::contact::Obstacle;
    /// let post = Obstacle::circle([0.0, 2.0], 1.0);
    /// assert_eq!(post.gap([0.0, 0.0], 0.25), 0.75);
    /// ```
    pub fn circle(centre: [f64; 2], radius: f64) -> Self {
        Self { shape: ObstacleShape::Circle { centre, radius }, friction: 0.0 }
    }

    /// The same obstacle with friction coefficient `mu`.
    ///
    /// # Example
    /// ```
    /// use flexure::reference::elastica::contact::Obstacle;
    /// let rough = Obstacle::circle([0.0, 2.0], 1.0).with_friction(0.4);
    /// assert!(rough.friction == 0.4 && rough.validate().is_ok());
    /// ```
    pub fn with_friction(self, mu: f64) -> Self {
        Self { friction: mu, ..self }
    }

    /// Checks the obstacle, naming the first bad field: a point or centre
    /// not finite, a normal zero or not finite, a radius not positive, a
    /// friction coefficient negative or not finite.
    ///
    /// # Example
    /// ```
    /// use flexure::reference::elastica::contact::Obstacle;
    /// let e = Obstacle::half_plane([0.0, 0.0], [0.0, 0.0]).validate().unwrap_err();
    /// assert!(e.to_string().contains("normal"));
    /// ```
    pub fn validate(&self) -> Result<()> {
        let finite = |name: &'static str, v: [f64; 2]| {
            if v.iter().all(|x| x.is_finite()) {
                Ok(())
            } else {
                Err(Error::invalid(name, format!("{v:?}"), "must be finite"))
            }
        };
        match self.shape {
            ObstacleShape::HalfPlane { point, normal } => {
                finite("point", point)?;
                finite("normal", normal)?;
                if normal[0].hypot(normal[1]) == 0.0 {
                    return Err(Error::invalid("normal", format!("{normal:?}"), "must not be zero"));
                }
            }
            ObstacleShape::Circle { centre, radius } => {
                finite("centre", centre)?;
                crate::error::positive("radius", radius)?;
            }
        }
        let mu = self.friction;
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(Error::invalid("friction", mu, "must be a finite number, zero or greater"));
        }
        Ok(())
    }

    /// The gap $g(p) = d(p) - h$ (m) of the point `p` with half thickness
    /// `h`: negative inside the obstacle.
    ///
    /// # Example
    /// ```
    /// use flexure::reference::elastica::contact::Obstacle;
    /// let floor = Obstacle::half_plane([0.0, -1.0], [0.0, 1.0]);
    /// assert_eq!(floor.gap([3.0, -1.5], 0.0), -0.5);
    /// ```
    pub fn gap(&self, p: [f64; 2], h: f64) -> f64 {
        self.gap_of(p, h)
    }

    /// [`Obstacle::gap`] for any scalar.
    pub(super) fn gap_of<T: Scalar>(&self, p: [T; 2], h: f64) -> T {
        match self.shape {
            ObstacleShape::HalfPlane { point, normal } => {
                let n = unit(normal);
                (p[0] - T::c(point[0])) * T::c(n[0]) + (p[1] - T::c(point[1])) * T::c(n[1]) - T::c(h)
            }
            ObstacleShape::Circle { centre, radius } => {
                let (dx, dy) = (p[0] - T::c(centre[0]), p[1] - T::c(centre[1]));
                (dx * dx + dy * dy).sqrt() - T::c(radius + h)
            }
        }
    }

    /// The unit outward normal $\hat n(p)$ at the boundary point nearest `p`.
    pub(super) fn normal_of<T: Scalar>(&self, p: [T; 2]) -> [T; 2] {
        match self.shape {
            ObstacleShape::HalfPlane { normal, .. } => {
                let n = unit(normal);
                [T::c(n[0]), T::c(n[1])]
            }
            ObstacleShape::Circle { centre, .. } => {
                let (dx, dy) = (p[0] - T::c(centre[0]), p[1] - T::c(centre[1]));
                let d = (dx * dx + dy * dy).sqrt();
                [dx / d, dy / d]
            }
        }
    }
}

fn unit(v: [f64; 2]) -> [f64; 2] {
    let n = v[0].hypot(v[1]);
    [v[0] / n, v[1] / n]
}
