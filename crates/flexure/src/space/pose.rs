//! The planar pose $(\phi, x, y)$ (paper Eq. 7).

use crate::scalar::Scalar;
use nalgebra::{Matrix3, Matrix4, Point2, Vector2};

/// A planar pose $(\phi, x, y)$: a frame turned by $\phi$ and moved to
/// $(x, y)$ in its parent. The flexure's tip in its root frame
/// (`pose_root_tip`), a body in the world, a joint's root frame in its
/// parent body: one type for all.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Pose<T = f64> {
    /// Rotation of the frame, radians, counter-clockwise.
    pub phi: T,
    /// Origin along the parent's x axis, metres.
    pub x: T,
    /// Origin along the parent's y axis, metres.
    pub y: T,
}

impl<T: Scalar> Pose<T> {
    /// The homogeneous transform $G$ of Eq. 7.
    ///
    /// # Example
    /// ```
    /// use flexure::Pose;
    /// let g = Pose { phi: std::f64::consts::FRAC_PI_2, x: 1.0, y: 2.0 }.transform();
    /// assert!((g[(0, 1)] + 1.0).abs() < 1e-15 && g[(1, 3)] == 2.0 && g[(3, 3)] == 1.0);
    /// ```
    pub fn transform(&self) -> Matrix4<T> {
        let (s, c) = self.phi.sin_cos();
        let (o, i) = (T::zero(), T::one());
        Matrix4::new(c, -s, o, self.x, s, c, o, self.y, o, o, i, o, o, o, o, i)
    }
}

impl Pose<f64> {
    /// The pose with rotation `phi` at `origin`.
    pub fn new(phi: f64, origin: Point2<f64>) -> Self {
        Pose { phi, x: origin.x, y: origin.y }
    }

    /// Its origin, in the parent frame.
    pub fn origin(&self) -> Point2<f64> {
        Point2::new(self.x, self.y)
    }

    /// $(\sin\phi, \cos\phi)$, which [`Pose::act_turned`] and
    /// [`Pose::compose_turned`] take so that one evaluation turns by each
    /// frame's rotation once.
    pub fn turn(&self) -> (f64, f64) {
        self.phi.sin_cos()
    }

    /// $g\thinspace h$: `h` given in this frame, in this frame's parent. Planar
    /// rotations add: $\phi_{gh} = \phi_g + \phi_h$.
    ///
    /// # Example
    /// ```
    /// use flexure::Pose;
    /// let g = Pose { phi: std::f64::consts::FRAC_PI_2, x: 1.0, y: 0.0 };
    /// let h = g.compose(&Pose { phi: 0.5, x: 2.0, y: 0.0 });
    /// assert!((h.phi - (std::f64::consts::FRAC_PI_2 + 0.5)).abs() < 1e-15);
    /// assert!((h.x - 1.0).abs() < 1e-15 && (h.y - 2.0).abs() < 1e-15);
    /// ```
    pub fn compose(&self, h: &Pose) -> Pose {
        self.compose_turned(self.turn(), h)
    }

    /// [`Pose::compose`] with [`Pose::turn`] known.
    pub fn compose_turned(&self, turn: (f64, f64), h: &Pose) -> Pose {
        let o = self.act_turned(turn, [h.x, h.y]);
        Pose { phi: self.phi + h.phi, x: o[0], y: o[1] }
    }

    /// $g^{-1}$.
    pub fn inverse(&self) -> Pose {
        let (s, c) = self.turn();
        Pose { phi: -self.phi, x: -(c * self.x + s * self.y), y: s * self.x - c * self.y }
    }

    /// $R r + p$: the point `r` given in this frame, in the parent.
    ///
    /// # Example
    /// ```
    /// use flexure::Pose;
    /// use nalgebra::Point2;
    /// let g = Pose { phi: std::f64::consts::FRAC_PI_2, x: 1.0, y: 0.0 };
    /// let w = g.act(&Point2::new(1.0, 0.0));
    /// assert!((w.x - 1.0).abs() < 1e-15 && (w.y - 1.0).abs() < 1e-15);
    /// ```
    pub fn act(&self, r: &Point2<f64>) -> Point2<f64> {
        let w = self.act_turned(self.turn(), [r.x, r.y]);
        Point2::new(w[0], w[1])
    }

    /// [`Pose::act`] on components, with [`Pose::turn`] known.
    pub fn act_turned(&self, (s, c): (f64, f64), r: [f64; 2]) -> [f64; 2] {
        [self.x + c * r[0] - s * r[1], self.y + s * r[0] + c * r[1]]
    }

    /// $R v$: the direction `v` given in this frame, in the parent.
    pub fn rotate(&self, v: &Vector2<f64>) -> Vector2<f64> {
        let w = rotate_turned(self.turn(), [v.x, v.y]);
        Vector2::new(w[0], w[1])
    }

    /// [`Pose::act`] on components: the inner loops' form.
    pub(crate) fn act_components(&self, r: [f64; 2]) -> [f64; 2] {
        self.act_turned(self.turn(), r)
    }

    /// $\mathrm{Ad}_g$ in the order $(\omega, v_x, v_y)$:
    /// $\omega^{\prime} = \omega$, $v^{\prime} = R v + \omega\thinspace(y, -x)$.
    ///
    /// # Example
    /// ```
    /// use flexure::Pose;
    /// let ad = Pose { phi: 0.0, x: 1.0, y: 0.0 }.adjoint();
    /// // Turning about the child's origin at x = 1 moves the parent's origin down.
    /// assert_eq!((ad[(1, 0)], ad[(2, 0)]), (0.0, -1.0));
    /// ```
    pub fn adjoint(&self) -> Matrix3<f64> {
        let (s, c) = self.turn();
        Matrix3::new(1.0, 0.0, 0.0, self.y, c, -s, -self.x, s, c)
    }
}

/// `v` turned by the angle whose `(sin, cos)` is given.
pub(crate) fn rotate_turned((s, c): (f64, f64), v: [f64; 2]) -> [f64; 2] {
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

impl<T> From<Pose<T>> for [T; 3] {
    /// The pose as a row $[\phi, x, y]$, the order of the Jacobian's rows.
    fn from(p: Pose<T>) -> Self {
        [p.phi, p.x, p.y]
    }
}
