//! The scalar type that kernels and solvers are generic over.
//!
//! Every evaluation and solver is written once for any [`Scalar`], so that
//! `f64` runs fast and `num-dual` numbers differentiate through the very same
//! code (including the Newton iterations and the adaptive ODE steps) for
//! derivative checks and for the exact shooting Jacobians.

use nalgebra::RealField;
use num_dual::{Dual, Dual2, DualVec, HyperDual};

/// A real scalar: `f64` or a forward-mode dual number over `f64`.
pub trait Scalar: RealField + Copy {
    /// The value part. Step-size control, line searches and convergence tests
    /// look only at values, so derivatives follow the same discrete path.
    fn re(self) -> f64;

    /// A constant.
    #[inline(always)]
    fn c(x: f64) -> Self {
        nalgebra::convert(x)
    }

    /// Whether the type is a plain value with no derivative parts. Newton
    /// on dual numbers takes at least one iteration at the solution, so the
    /// derivative parts converge with the value.
    #[inline(always)]
    fn is_value() -> bool {
        false
    }

    /// $(\cos x_k, \sin x_k)$ of every angle, one pair per angle:
    /// the quadrature nodes' trigonometry. `f64` evaluates all nodes together
    /// with [`crate::sincos::cos_sin`]; dual numbers take one angle at a time.
    #[inline(always)]
    fn cos_sin<const M: usize>(angles: &[Self; M]) -> [[Self; 2]; M] {
        angles.map(|x| {
            let (s, c) = x.sin_cos();
            [c, s]
        })
    }
}

impl Scalar for f64 {
    #[inline(always)]
    fn re(self) -> f64 {
        self
    }
    #[inline(always)]
    fn is_value() -> bool {
        true
    }
    #[inline(always)]
    fn c(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn cos_sin<const M: usize>(angles: &[Self; M]) -> [[Self; 2]; M] {
        crate::sincos::cos_sin(angles)
    }
}

impl Scalar for Dual<f64> {
    fn re(self) -> f64 {
        self.re
    }
}

impl Scalar for Dual2<f64> {
    fn re(self) -> f64 {
        self.re
    }
}

impl Scalar for HyperDual<f64> {
    fn re(self) -> f64 {
        self.re
    }
}

impl<const M: usize> Scalar for DualVec<f64, nalgebra::Const<M>> {
    fn re(self) -> f64 {
        self.re
    }
}
