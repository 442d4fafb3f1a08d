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
//! Physics Reports 470, 2009, Sec. 4; Iserles et al., Acta Numerica 9,
//! 2000, Sec. 4). Those papers integrate $Y^{\prime} = A Y$; the flexure's
//! $g^{\prime} = g\hat\xi$ multiplies on the right, which is the same equation in
//! the opposite Lie algebra, so each bracket is taken reversed,
//! $[x, y]^{\prime} = [y, x]$. The error of the tip pose falls as $h^6$
//! (`tests/spatial_kinematics.rs` measures the slope).
//!
//! The exponent is a polynomial in the nodal twists, each affine in the
//! coordinates, so its derivatives follow by the product rule through the
//! same formula: [`Algebra`] is implemented by a twist with one derivative
//! ([`Jet1`]) and a twist with two ([`Jet2`]); [`exponent_value`] is the
//! value alone, written out.

use crate::scalar::Scalar;
use crate::space::{bracket, exp_coefficients, exp_parts};
use nalgebra::{Matrix3, Vector3, Vector6};

/// The Gauss nodes on $[0, 1]$: $\frac12 \mp \frac{\sqrt{15}}{10}$ and $\frac12$.
pub(crate) const NODES: [f64; 3] = [0.5 - 0.387_298_334_620_741_7, 0.5, 0.5 + 0.387_298_334_620_741_7];

/// What the Magnus formula needs of a twist: sums, multiples and the
/// reversed bracket $[x, y]^{\prime} = [y, x]$.
pub(crate) trait Algebra: Copy {
    fn add(&self, o: &Self) -> Self;
    fn scale(&self, k: f64) -> Self;
    fn br(&self, o: &Self) -> Self;
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

/// $\times e_1$: $a\times e_1 = (0, a_z, -a_y)$.
#[inline(always)]
fn cross_e1<T: Scalar>(a: &Vector3<T>, h: T) -> Vector3<T> {
    Vector3::new(T::zero(), a[2] * h, -a[1] * h)
}

/// [`exponent`] of plain twists written out, as $(\omega, v)$ from the nodal
/// curvatures `u`: $\alpha_2$ and $\alpha_3$ have no linear part and
/// $\alpha_1$'s is $h e_1$, so 8 cross products do what the general
/// formula's 18 do (the tests check one against the other: dual numbers
/// through this one against [`Jet1`] through that one).
#[inline(always)]
pub(crate) fn exponent_value<T: Scalar>(u: &[Vector3<T>; 3], h: f64) -> (Vector3<T>, Vector3<T>) {
    let ht = T::c(h);
    let w1 = u[1] * ht;
    let w2 = (u[2] - u[0]) * T::c(15f64.sqrt() * h / 3.0);
    let w3 = (u[2] - u[1] * T::c(2.0) + u[0]) * T::c(10.0 * h / 3.0);
    // C₁ = [α₁, α₂]′ = [α₂, α₁] = (w₂ × w₁, w₂ × h e₁).
    let c1w = w2.cross(&w1);
    let c1v = cross_e1(&w2, ht);
    // C₂ = −[α₁, 2α₃ + C₁]′/60 = −[2α₃ + C₁, α₁]/60.
    let xw = w3 * T::c(2.0) + c1w;
    let k = T::c(-1.0 / 60.0);
    let c2w = xw.cross(&w1) * k;
    let c2v = (cross_e1(&xw, ht) - w1.cross(&c1v)) * k;
    // [L, R]′ = [R, L] with L = −20α₁ − α₃ + C₁, R = α₂ + C₂.
    let lw = c1w - w1 * T::c(20.0) - w3;
    let lv = c1v - Vector3::new(ht * T::c(20.0), T::zero(), T::zero());
    let rw = w2 + c2w;
    let k = T::c(1.0 / 240.0);
    let omega = w1 + w3 * T::c(1.0 / 12.0) + rw.cross(&lw) * k;
    let v = Vector3::new(ht, T::zero(), T::zero()) + (rw.cross(&lv) - lw.cross(&c2v)) * k;
    (omega, v)
}

/// One Magnus step of length `h` from the nodal curvatures `u`: $\exp\Omega$ as $(R, p)$.
#[inline(always)]
pub(crate) fn exponential<T: Scalar>(u: &[Vector3<T>; 3], h: f64) -> (Matrix3<T>, Vector3<T>) {
    let (w, v) = exponent_value(u, h);
    let c = exp_coefficients(w.norm_squared(), 0);
    exp_parts(&w, &v, &c.f)
}
