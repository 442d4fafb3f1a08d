//! SE(2): the planar implementation of [`Space`].

use super::{Pose, Space, Twist, Wrench};
use nalgebra::{Matrix3, Point2, Vector2};

/// The plane: poses in SE(2), rotations that add.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Planar;

/// $\sin\omega/\omega$ and $(1 - \cos\omega)/\omega = 2\sin^2(\omega/2)/\omega$: the
/// columns of $V(\omega)$, the translation part of $\exp$. The half-angle
/// form keeps full relative precision at small angles, where $1 - \cos\omega$
/// would cancel; both quotients are exact limits at 0.
fn v_columns(w: f64) -> (f64, f64) {
    if w == 0.0 {
        return (1.0, 0.0);
    }
    let h = (0.5 * w).sin();
    (w.sin() / w, 2.0 * h * h / w)
}

impl Space for Planar {
    const TWIST_DIM: usize = 3;
    const POINT_DIM: usize = 2;
    type Pose = Pose;
    type Point = Point2<f64>;
    type Vector = Vector2<f64>;
    type Twist = Twist;
    type Wrench = Wrench;
    type Adjoint = Matrix3<f64>;

    fn identity() -> Pose {
        Pose::default()
    }

    fn compose(a: &Pose, b: &Pose) -> Pose {
        a.compose(b)
    }

    fn inverse(a: &Pose) -> Pose {
        a.inverse()
    }

    fn act(a: &Pose, r: &Point2<f64>) -> Point2<f64> {
        a.act(r)
    }

    fn at(p: &Point2<f64>) -> Pose {
        Pose { phi: 0.0, x: p.x, y: p.y }
    }

    fn origin(a: &Pose) -> Point2<f64> {
        a.origin()
    }

    fn reach(a: &Pose) -> f64 {
        a.x.hypot(a.y)
    }

    fn rotate(a: &Pose, v: &Vector2<f64>) -> Vector2<f64> {
        a.rotate(v)
    }

    fn adjoint(a: &Pose) -> Matrix3<f64> {
        a.adjoint()
    }

    /// $\exp(\omega, v) = (\omega,\ V(\omega)v)$ with
    /// $V = \frac1\omega\begin{pmatrix}\sin\omega & \cos\omega - 1\cr 1 - \cos\omega & \sin\omega\end{pmatrix}$.
    fn exp(t: &Twist) -> Pose {
        let (a, b) = v_columns(t.omega);
        Pose { phi: t.omega, x: a * t.vx - b * t.vy, y: b * t.vx + a * t.vy }
    }

    /// $\log(\phi, p) = (\phi,\ V(\phi)^{-1}p)$ with the angle wrapped to
    /// $(-\pi, \pi]$, where
    /// $V^{-1} = \frac\phi2\begin{pmatrix}\cot\frac\phi2 & 1\cr -1 & \cot\frac\phi2\end{pmatrix}$.
    fn log(g: &Pose) -> Twist {
        let mut w = g.phi % std::f64::consts::TAU;
        if w > std::f64::consts::PI {
            w -= std::f64::consts::TAU;
        } else if w <= -std::f64::consts::PI {
            w += std::f64::consts::TAU;
        }
        let (a, b) = v_columns(w);
        // V⁻¹ = [[a, b], [−b, a]] / (a² + b²).
        let d = a * a + b * b;
        Twist { omega: w, vx: (a * g.x + b * g.y) / d, vy: (a * g.y - b * g.x) / d }
    }

    fn power(w: &Wrench, t: &Twist) -> f64 {
        w.moment * t.omega + w.fx * t.vx + w.fy * t.vy
    }

    /// $v + \omega\times r = (v_x - \omega r_y,\ v_y + \omega r_x)$.
    fn velocity_at(t: &Twist, r: &Vector2<f64>) -> Vector2<f64> {
        Vector2::new(t.vx - t.omega * r.y, t.vy + t.omega * r.x)
    }
}
