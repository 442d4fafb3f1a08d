//! The planar twist $(\omega, v_x, v_y)$.

/// A planar twist: angular velocity $\omega$ (rad/s) and the velocity
/// $(v_x, v_y)$ (m/s) of the frame's origin, or per unit of a coordinate: a
/// column of a Jacobian (rows $(\phi, x, y)$) is a twist.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Twist<T = f64> {
    /// Angular velocity, counter-clockwise.
    pub omega: T,
    /// Velocity along x.
    pub vx: T,
    /// Velocity along y.
    pub vy: T,
}

impl Twist<f64> {
    /// Its components $[\omega, v_x, v_y]$.
    pub fn to_array(self) -> [f64; 3] {
        [self.omega, self.vx, self.vy]
    }

    /// From components $[\omega, v_x, v_y]$ (a Jacobian column).
    pub fn from_slice(c: &[f64]) -> Self {
        Twist { omega: c[0], vx: c[1], vy: c[2] }
    }
}
