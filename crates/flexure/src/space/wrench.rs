//! The planar wrench $(M, F_x, F_y)$.

use crate::error::{Error, Result, finite};

/// A planar wrench: moment $M$ (N·m, counter-clockwise positive) and force
/// $(F_x, F_y)$ (N). A flexure's tip load (in its root frame), a point load
/// (in the ground frame), a closure's reaction: one type for all, ordered
/// as the Jacobian's rows $(\phi, x, y)$ so that its generalized force is
/// $J^T w$.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Wrench<T = f64> {
    /// Moment, counter-clockwise positive.
    pub moment: T,
    /// Force along x.
    pub fx: T,
    /// Force along y.
    pub fy: T,
}

/// The largest magnitude of a wrench's component (N·m, N), as a mechanism
/// file bounds every number: beyond, the products the model forms leave the
/// range of floating point.
pub const MAX_LOAD: f64 = 1e30;

impl Wrench<f64> {
    /// The paper's load (Sec. III-C): force of magnitude $P$ at angle $\theta$,
    /// $F_x = -P\sin\theta$, $F_y = P\cos\theta$, with moment $M$.
    ///
    /// # Example
    /// ```
    /// let l = flexure::TipLoad::polar(0.0, 2.0, std::f64::consts::FRAC_PI_2);
    /// assert!((l.fx + 2.0).abs() < 1e-15 && l.fy.abs() < 1e-15);
    /// ```
    pub fn polar(moment: f64, force: f64, angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        // + 0.0 turns the −0 of a zero angle into 0.
        Self { moment, fx: -force * s + 0.0, fy: force * c }
    }

    /// Checks that every component is finite and at most [`MAX_LOAD`] in
    /// magnitude, naming the component otherwise.
    pub fn validate(&self) -> Result<()> {
        for (name, v) in [("moment", self.moment), ("fx", self.fx), ("fy", self.fy)] {
            finite(name, v)?;
            if v.abs() > MAX_LOAD {
                return Err(Error::invalid(name, v, "must be at most 1e30 in magnitude (SI units)"));
            }
        }
        Ok(())
    }

    /// Its components $[M, F_x, F_y]$.
    pub fn to_array(self) -> [f64; 3] {
        [self.moment, self.fx, self.fy]
    }

    /// From components $[M, F_x, F_y]$.
    pub fn from_array([moment, fx, fy]: [f64; 3]) -> Self {
        Wrench { moment, fx, fy }
    }
}

impl std::ops::Index<usize> for Wrench<f64> {
    type Output = f64;
    /// Component `i` in the order $(M, F_x, F_y)$.
    fn index(&self, i: usize) -> &f64 {
        match i {
            0 => &self.moment,
            1 => &self.fx,
            2 => &self.fy,
            _ => panic!("a planar wrench has components 0 to 2, not {i}"),
        }
    }
}

impl std::ops::IndexMut<usize> for Wrench<f64> {
    fn index_mut(&mut self, i: usize) -> &mut f64 {
        match i {
            0 => &mut self.moment,
            1 => &mut self.fx,
            2 => &mut self.fy,
            _ => panic!("a planar wrench has components 0 to 2, not {i}"),
        }
    }
}
