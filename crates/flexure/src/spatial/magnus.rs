//! The 6th-order Magnus exponent of one subinterval, and its first and
//! second derivatives in the coordinates.
//!
//! On a subinterval of length $h$, with the twists $\xi_j = (u(s_j), e_1)$
//! at the three Gauss nodes $s_j$ (at $\frac12 - \frac{\sqrt{15}}{10}$,
//! $\frac12$, $\frac12 + \frac{\sqrt{15}}{10}$ of it),
//! $$\alpha_1 = h\xi_2,\quad \alpha_2 = \frac{\sqrt{15}h}{3}(\xi_3 - \xi_1),\quad \alpha_3 = \frac{10h}{3}(\xi_3 - 2\xi_2 + \xi_1),$$
//! $$C_1 = [\alpha_1, \alpha_2]^{\prime},\quad C_2 = -\tfrac1{60}[\alpha_1, 2\alpha_3 + C_1]^{\prime},\quad
//!   \Omega = \alpha_1 + \tfrac1{12}\alpha_3 + \tfrac1{240}[-20\alpha_1 - \alpha_3 + C_1,\ \alpha_2 + C_2]^{\prime}$$
//! (Blanes, Casas and Ros, BIT 40, 2000; Blanes, Casas, Oteo and Ros,
//! Physics Reports 470, 2009, Eq. 4.?; Iserles et al., Acta Numerica 9,
//! 2000, Sec. 4). Those papers integrate $Y^{\prime} = A Y$; the flexure's
//! $g^{\prime} = g\hat\xi$ multiplies on the right, which is the same equation in
//! the opposite Lie algebra, so each bracket is taken reversed,
//! $[x, y]^{\prime} = [y, x]$. The error of the tip pose falls as $h^6$
//! (`tests/spatial_kinematics.rs` measures the slope).
//!
//! The exponent is a polynomial in the nodal twists, each affine in the
//! coordinates, so its derivatives follow by the product rule through the
//! same formula: [`Algebra`] is implemented by a plain twist, a twist with
//! one derivative ([`Jet1`]) and a twist with two ([`Jet2`]).

use crate::scalar::Scalar;
use crate::space::bracket;
use nalgebra::Vector6;

/// The Gauss nodes on $[0, 1]$: $\frac12 \mp \frac{\sqrt{15}}{10}$ and $\frac12$.
pub(crate) const NODES: [f64; 3] = [0.5 - 0.387_298_334_620_741_7, 0.5, 0.5 + 0.387_298_334_620_741_7];

/// What the Magnus formula needs of a twist: sums, multiples and the
/// reversed bracket $[x, y]^{\prime} = [y, x]$.
pub(crate) trait Algebra: Copy {
    fn add(&self, o: &Self) -> Self;
    fn scale(&self, k: f64) -> Self;
    fn br(&self, o: &Self) -> Self;
}

impl<T: Scalar> Algebra for Vector6<T> {
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    #[inline(always)]
    fn scale(&self, k: f64) -> Self {
        self * T::c(k)
    }
    #[inline(always)]
    fn br(&self, o: &Self) -> Self {
        bracket(o, self)
    }
}

/// A twist and its derivative along one coordinate.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Jet1<T: Scalar> {
    pub v: Vector6<T>,
    pub d: Vector6<T>,
}

impl<T: Scalar> Algebra for Jet1<T> {
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        Jet1 { v: self.v + o.v, d: self.d + o.d }
    }
    #[inline(always)]
    fn scale(&self, k: f64) -> Self {
        Jet1 { v: self.v * T::c(k), d: self.d * T::c(k) }
    }
    #[inline(always)]
    fn br(&self, o: &Self) -> Self {
        Jet1 { v: bracket(&o.v, &self.v), d: bracket(&o.d, &self.v) + bracket(&o.v, &self.d) }
    }
}

/// A twist, its derivatives along coordinates $a$ and $b$, and $\partial_a\partial_b$.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Jet2<T: Scalar> {
    pub v: Vector6<T>,
    pub a: Vector6<T>,
    pub b: Vector6<T>,
    pub ab: Vector6<T>,
}

impl<T: Scalar> Algebra for Jet2<T> {
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        Jet2 { v: self.v + o.v, a: self.a + o.a, b: self.b + o.b, ab: self.ab + o.ab }
    }
    #[inline(always)]
    fn scale(&self, k: f64) -> Self {
        let k = T::c(k);
        Jet2 { v: self.v * k, a: self.a * k, b: self.b * k, ab: self.ab * k }
    }
    #[inline(always)]
    fn br(&self, o: &Self) -> Self {
        Jet2 {
            v: bracket(&o.v, &self.v),
            a: bracket(&o.a, &self.v) + bracket(&o.v, &self.a),
            b: bracket(&o.b, &self.v) + bracket(&o.v, &self.b),
            ab: bracket(&o.ab, &self.v) + bracket(&o.a, &self.b) + bracket(&o.b, &self.a) + bracket(&o.v, &self.ab),
        }
    }
}

/// $\Omega$ of the module docs from the nodal twists `xi` on a subinterval of length `h`.
#[inline(always)]
pub(crate) fn exponent<A: Algebra>(xi: &[A; 3], h: f64) -> A {
    let s = 15f64.sqrt() * h / 3.0;
    let a1 = xi[1].scale(h);
    let a2 = xi[2].add(&xi[0].scale(-1.0)).scale(s);
    let a3 = xi[2].add(&xi[1].scale(-2.0)).add(&xi[0]).scale(10.0 * h / 3.0);
    let c1 = a1.br(&a2);
    let c2 = a1.br(&a3.scale(2.0).add(&c1)).scale(-1.0 / 60.0);
    let left = a1.scale(-20.0).add(&a3.scale(-1.0)).add(&c1);
    a1.add(&a3.scale(1.0 / 12.0)).add(&left.br(&a2.add(&c2)).scale(1.0 / 240.0))
}
