//! The planar wrench $(M, F_x, F_y)$.

/// A planar wrench: moment $M$ (N·m, counter-clockwise positive) and force
/// $(F_x, F_y)$ (N). A flexure's tip load (in its root frame), a point load
/// (in the ground frame), a closure's reaction: one type for all, ordered
/// as the Jacobian's rows $(\phi, x, y)$ so that its generalized force is
/// $J^T w$.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Wrench<T = f64> {
    /// Moment, counter-clockwise positive.
    pub moment: T,
    /// Force along x.
    pub fx: T,
    /// Force along y.
    pub fy: T,
}

impl Wrench<f64> {
    /// Its components $[M, F_x, F_y]$.
    pub fn to_array(self) -> [f64; 3] {
        [self.moment, self.fx, self.fy]
    }

    /// From components $[M, F_x, F_y]$.
    pub fn from_array([moment, fx, fy]: [f64; 3]) -> Self {
        Wrench { moment, fx, fy }
    }
}
