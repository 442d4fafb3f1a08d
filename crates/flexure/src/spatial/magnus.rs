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
//! same formula: [`Algebra`] is implemented by a twist with two derivatives
//! ([`Jet2`]). [`exponent_value`] is the value alone, written out, and
//! [`Exponent::derivative`] its first derivative along any change of the
//! nodal curvatures, written out on the value's terms.

use crate::scalar::Scalar;
use crate::space::{bracket, exp_coefficients, exp_parts};
use nalgebra::{Matrix3, SMatrix, Vector3, Vector6};

/// Nine changes at once, as columns: one per curvature at each of the three nodes, column `3 * g + c`.
pub(crate) type Nine<T> = SMatrix<T, 3, 9>;

/// The Gauss nodes on $[0, 1]$: $\frac12 \mp \frac{\sqrt{15}}{10}$ and $\frac12$.
pub(crate) const NODES: [f64; 3] = [0.5 - 0.387_298_334_620_741_7, 0.5, 0.5 + 0.387_298_334_620_741_7];

/// What the Magnus formula needs of a twist: sums, multiples and the
/// reversed bracket $[x, y]^{\prime} = [y, x]$.
pub(crate) trait Algebra: Copy {
    fn add(&self, o: &Self) -> Self;
    fn scale(&self, k: f64) -> Self;
    fn br(&self, o: &Self) -> Self;
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
/// formula's 18 do (`tests/spatial_kinematics.rs` checks the Jacobians
/// built on it and on [`Exponent::derivative`] against num-dual's dual
/// numbers through it).
#[inline(always)]
pub(crate) fn exponent_value<T: Scalar>(u: &[Vector3<T>; 3], h: f64) -> (Vector3<T>, Vector3<T>) {
    Exponent::new(u, h).value()
}

/// The terms of [`exponent_value`] at one set of nodal curvatures, kept so
/// that its derivatives along any change of them ([`Exponent::derivative`],
/// [`Exponent::along`]) reuse them: the exponent is a polynomial in the
/// curvatures, so its derivative is linear in their change. A step's
/// Jacobian takes it along each coordinate's change rather than a jet of
/// the whole formula.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Exponent<T: Scalar> {
    h: f64,
    at: Terms<T>,
}

/// The angular parts $w_i$ of $\alpha_i$, $C_1$'s linear part, $2\alpha_3 + C_1$'s
/// angular part $x$, $C_2$'s linear part, and the bracket's $L$ and $R$ (angular
/// parts; $L$'s linear part too): the terms of the module docs' formula
/// whose brackets remain once $\alpha_1$'s constant $h e_1$ is written out; or their
/// derivatives along a change of the curvatures.
#[derive(Debug, Clone, Copy)]
struct Terms<T: Scalar> {
    w1: Vector3<T>,
    w2: Vector3<T>,
    w3: Vector3<T>,
    c1v: Vector3<T>,
    xw: Vector3<T>,
    c2v: Vector3<T>,
    lw: Vector3<T>,
    lv: Vector3<T>,
    rw: Vector3<T>,
}

impl<T: Scalar> Exponent<T> {
    /// The terms at the nodal curvatures `u` on a subinterval of length `h`.
    #[inline(always)]
    pub fn new(u: &[Vector3<T>; 3], h: f64) -> Self {
        let (w1, w2, w3) = Self::alphas(u, h);
        Self::with_alphas(&[w1, w2, w3], h)
    }

    /// The terms from the angular parts $w_1, w_2, w_3$ of $\alpha_1, \alpha_2, \alpha_3$
    /// ([`Exponent::alphas`] of the nodal curvatures) on a subinterval of length `h`.
    #[inline(always)]
    pub fn with_alphas(w: &[Vector3<T>; 3], h: f64) -> Self {
        let ht = T::c(h);
        let [w1, w2, w3] = *w;
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
        Exponent { h, at: Terms { w1, w2, w3, c1v, xw, c2v, lw, lv, rw } }
    }

    /// $w_1, w_2, w_3$: linear in the curvatures, so also their change along a change of them.
    #[inline(always)]
    fn alphas(u: &[Vector3<T>; 3], h: f64) -> (Vector3<T>, Vector3<T>, Vector3<T>) {
        let w1 = u[1] * T::c(h);
        let w2 = (u[2] - u[0]) * T::c(15f64.sqrt() * h / 3.0);
        let w3 = (u[2] - u[1] * T::c(2.0) + u[0]) * T::c(10.0 * h / 3.0);
        (w1, w2, w3)
    }

    /// $\Omega = (\omega, v)$.
    #[inline(always)]
    pub fn value(&self) -> (Vector3<T>, Vector3<T>) {
        let (t, k) = (&self.at, T::c(1.0 / 240.0));
        let omega = t.w1 + t.w3 * T::c(1.0 / 12.0) + t.rw.cross(&t.lw) * k;
        let v = Vector3::new(T::c(self.h), T::zero(), T::zero()) + (t.rw.cross(&t.lv) - t.lw.cross(&t.c2v)) * k;
        (omega, v)
    }

    /// The terms' derivatives along the change `du`, by the product rule.
    #[inline(always)]
    fn change(&self, du: &[Vector3<T>; 3]) -> Terms<T> {
        let (w1, w2, w3) = Self::alphas(du, self.h);
        self.change_alphas(&[w1, w2, w3])
    }

    /// [`Exponent::change`] along the change `dw` of $w_1, w_2, w_3$.
    #[inline(always)]
    fn change_alphas(&self, dw: &[Vector3<T>; 3]) -> Terms<T> {
        let (t, ht) = (&self.at, T::c(self.h));
        let [w1, w2, w3] = *dw;
        let c1w = w2.cross(&t.w1) + t.w2.cross(&w1);
        let c1v = cross_e1(&w2, ht);
        let xw = w3 * T::c(2.0) + c1w;
        let k = T::c(-1.0 / 60.0);
        let c2w = (xw.cross(&t.w1) + t.xw.cross(&w1)) * k;
        let c2v = (cross_e1(&xw, ht) - w1.cross(&t.c1v) - t.w1.cross(&c1v)) * k;
        let lw = c1w - w1 * T::c(20.0) - w3;
        Terms { w1, w2, w3, c1v, xw, c2v, lw, lv: c1v, rw: w2 + c2w }
    }

    /// $D\Omega[\delta u] = (\delta\omega, \delta v)$: the derivative along
    /// the change `du` of the nodal curvatures.
    #[inline(always)]
    pub fn derivative(&self, du: &[Vector3<T>; 3]) -> (Vector3<T>, Vector3<T>) {
        self.first(&self.change(du))
    }

    /// [`Exponent::value`]'s derivative from the terms' derivatives `d`.
    #[inline(always)]
    fn first(&self, d: &Terms<T>) -> (Vector3<T>, Vector3<T>) {
        let (t, k) = (&self.at, T::c(1.0 / 240.0));
        let omega = d.w1 + d.w3 * T::c(1.0 / 12.0) + (d.rw.cross(&t.lw) + t.rw.cross(&d.lw)) * k;
        let v = (d.rw.cross(&t.lv) + t.rw.cross(&d.lv) - d.lw.cross(&t.c2v) - t.lw.cross(&d.c2v)) * k;
        (omega, v)
    }

    /// $D\Omega$ along each of the nine unit changes of the nodal
    /// curvatures (curvature $c$ at node $g$, column `3 * g + c`), as
    /// $(\delta\omega, \delta v)$: [`Exponent::derivative`]'s product rule
    /// with each change's cross products as matrices, $a\times\delta x = \hat a\thinspace\delta x$,
    /// taken first along $w_1$, $w_2$, $w_3$ and then combined as the nodes
    /// enter them. Nine derivatives in a few $3\times3$ by $3\times9$ products.
    #[inline(always)]
    pub fn jacobian(&self) -> (Nine<T>, Nine<T>) {
        let (t, h) = (&self.at, self.h);
        let i = Matrix3::<T>::identity();
        let (x1, x2) = (t.w1.cross_matrix(), t.w2.cross_matrix());
        // cross_e1(a, h) = h a × e₁ = −h ê₁ a.
        let e1 = -Vector3::new(T::c(h), T::zero(), T::zero()).cross_matrix();
        // Each term's blocks along w₁, w₂, w₃: C₁ = (x̂₂, −x̂₁, 0) and its
        // linear part (0, ê, 0), 2α₃ + C₁'s angular part (x̂₂, −x̂₁, 2I).
        let k = T::c(-1.0 / 60.0);
        let c2w = [(t.xw.cross_matrix() - x1 * x2) * k, x1 * x1 * k, x1 * (T::c(-2.0) * k)];
        let c2v = [(e1 * x2 + t.c1v.cross_matrix()) * k, -(e1 * x1 + x1 * e1) * k, e1 * (T::c(2.0) * k)];
        let lw = [x2 - i * T::c(20.0), -x1, -i];
        let rw = [c2w[0], i + c2w[1], c2w[2]];
        let (lwx, rwx, lvx, cvx) =
            (t.lw.cross_matrix(), t.rw.cross_matrix(), t.lv.cross_matrix(), t.c2v.cross_matrix());
        let k = T::c(1.0 / 240.0);
        let own = [i, Matrix3::zeros(), i * T::c(1.0 / 12.0)];
        let omega = std::array::from_fn(|b| own[b] + (rwx * lw[b] - lwx * rw[b]) * k);
        let c1v = [Matrix3::zeros(), e1, Matrix3::zeros()];
        let v = std::array::from_fn(|b| (rwx * c1v[b] - lvx * rw[b] + cvx * lw[b] - lwx * c2v[b]) * k);
        (by_nodes(&omega, h), by_nodes(&v, h))
    }

    /// [`Exponent::jacobian`]'s blocks before they are combined as the nodes
    /// enter $w_1, w_2, w_3$, `each(b, δω, δv)` along unit changes of $w_b$
    /// (a block given as made, not kept), with each product by a cross matrix written out,
    /// $\hat a\hat b = ba^T - (a\cdot b)\thinspace 1$ and $\hat aM$ as $a$ crossed with each column:
    /// the same blocks for about a third of the multiplications, equal to
    /// rounding (the unit test below compares them). The dynamics' stations
    /// take it, their tables giving each coordinate's change of the $w_b$
    /// (`MassQuadrature`); the weight's statics keep [`Exponent::jacobian`],
    /// whose answers stay bit for bit.
    #[inline(always)]
    pub fn jacobian_alphas(&self, mut each: impl FnMut(usize, &Matrix3<T>, &Matrix3<T>)) {
        let t = &self.at;
        let i = Matrix3::<T>::identity();
        // ê₁ of the code above is the cross matrix of e = −h e₁.
        let e = Vector3::new(-T::c(self.h), T::zero(), T::zero());
        let k = T::c(-1.0 / 60.0);
        let c2w = [
            (t.xw.cross_matrix() - crosses(&t.w1, &t.w2)) * k,
            crosses(&t.w1, &t.w1) * k,
            t.w1.cross_matrix() * (T::c(-2.0) * k),
        ];
        let c2v = [
            (crosses(&e, &t.w2) + t.c1v.cross_matrix()) * k,
            -(crosses(&e, &t.w1) + crosses(&t.w1, &e)) * k,
            e.cross_matrix() * (T::c(2.0) * k),
        ];
        let rw = [c2w[0], i + c2w[1], c2w[2]];
        // â times lw = (ŵ₂ − 20, −ŵ₁, −1), for â = r̂w and ĉ₂v.
        let by_lw = |a: &Vector3<T>| {
            let x = a.cross_matrix();
            [crosses(a, &t.w2) - x * T::c(20.0), -crosses(a, &t.w1), -x]
        };
        let (rlw, clw) = (by_lw(&t.rw), by_lw(&t.c2v));
        let k = T::c(1.0 / 240.0);
        let own = [i, Matrix3::zeros(), i * T::c(1.0 / 12.0)];
        let rc1v = [Matrix3::zeros(), crosses(&t.rw, &e), Matrix3::zeros()];
        for b in 0..3 {
            let omega = own[b] + (rlw[b] - cross_columns(&t.lw, &rw[b])) * k;
            let v = (rc1v[b] - cross_columns(&t.lv, &rw[b]) + clw[b] - cross_columns(&t.lw, &c2v[b])) * k;
            each(b, &omega, &v);
        }
    }

    /// The first and second derivatives $D\Omega[\delta u]$ and
    /// $D^2\Omega[\delta u, \delta u]$ along one change `du` of the nodal
    /// curvatures: what a rate's bias needs, for the cost of about two
    /// first derivatives rather than a [`Jet2`] of the whole formula.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    pub fn along(&self, du: &[Vector3<T>; 3]) -> ((Vector3<T>, Vector3<T>), (Vector3<T>, Vector3<T>)) {
        self.along_terms(&self.change(du))
    }

    /// [`Exponent::along`] along the change `dw` of $w_1, w_2, w_3$ rather than of the nodal curvatures.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    pub fn along_alphas(&self, dw: &[Vector3<T>; 3]) -> ((Vector3<T>, Vector3<T>), (Vector3<T>, Vector3<T>)) {
        self.along_terms(&self.change_alphas(dw))
    }

    /// [`Exponent::along`] from the terms' derivatives `d` along the change.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    fn along_terms(&self, d: &Terms<T>) -> ((Vector3<T>, Vector3<T>), (Vector3<T>, Vector3<T>)) {
        let (t, d) = (&self.at, *d);
        let (two, ht) = (T::c(2.0), T::c(self.h));
        // The w's and C₁'s linear part are linear in the curvatures: only
        // the products' cross terms have second derivatives.
        let k = T::c(-1.0 / 60.0);
        let c1w = d.w2.cross(&d.w1) * two;
        let c2w = (c1w.cross(&t.w1) + d.xw.cross(&d.w1) * two) * k;
        let c2v = (cross_e1(&c1w, ht) - d.w1.cross(&d.c1v) * two) * k;
        let (lw, rw) = (c1w, c2w);
        let k = T::c(1.0 / 240.0);
        let omega = (rw.cross(&t.lw) + d.rw.cross(&d.lw) * two + t.rw.cross(&lw)) * k;
        let v = (rw.cross(&t.lv) + d.rw.cross(&d.lv) * two
            - lw.cross(&t.c2v)
            - d.lw.cross(&d.c2v) * two
            - t.lw.cross(&c2v))
            * k;
        (self.first(&d), (omega, v))
    }
}

/// $\hat a\hat b = ba^T - (a\cdot b)\thinspace 1$: the product of two cross matrices.
#[inline(always)]
fn crosses<T: Scalar>(a: &Vector3<T>, b: &Vector3<T>) -> Matrix3<T> {
    b * a.transpose() - Matrix3::from_diagonal_element(a.dot(b))
}

/// $\hat aM$: $a$ crossed with each column of `m`.
#[inline(always)]
fn cross_columns<T: Scalar>(a: &Vector3<T>, m: &Matrix3<T>) -> Matrix3<T> {
    Matrix3::from_columns(&[
        a.cross(&m.column(0).into_owned()),
        a.cross(&m.column(1).into_owned()),
        a.cross(&m.column(2).into_owned()),
    ])
}

/// Three $3\times3$ blocks side by side.
#[inline(always)]
fn blocks<T: Scalar>(a: &Matrix3<T>, b: &Matrix3<T>, c: &Matrix3<T>) -> Nine<T> {
    let mut m = Nine::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(a);
    m.fixed_view_mut::<3, 3>(0, 3).copy_from(b);
    m.fixed_view_mut::<3, 3>(0, 6).copy_from(c);
    m
}

/// Derivatives along $w_1$, $w_2$, $w_3$ (the blocks `d`) as derivatives along
/// the nodal curvatures of a subinterval of length `h`, by [`Exponent::alphas`]:
/// node 0 is $-sA_2 + qA_3$, node 1 $hA_1 - 2qA_3$, node 2 $sA_2 + qA_3$ with
/// $s = \sqrt{15}h/3$ and $q = 10h/3$.
#[inline(always)]
fn by_nodes<T: Scalar>(d: &[Matrix3<T>; 3], h: f64) -> Nine<T> {
    let (s, q) = (T::c(15f64.sqrt() * h / 3.0), T::c(10.0 * h / 3.0));
    let [a1, a2, a3] = d;
    blocks(&(a3 * q - a2 * s), &(a1 * T::c(h) - a3 * (q * T::c(2.0))), &(a2 * s + a3 * q))
}

/// One Magnus step of length `h` from the nodal curvatures `u`: $\exp\Omega$ as $(R, p)$.
#[inline(always)]
pub(crate) fn exponential<T: Scalar>(u: &[Vector3<T>; 3], h: f64) -> (Matrix3<T>, Vector3<T>) {
    let (w, v) = exponent_value(u, h);
    let c = exp_coefficients(w.norm_squared(), 0);
    exp_parts(&w, &v, &c.f)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The expanded Jacobian, combined by nodes, meets the matrix form to rounding, at curvatures
    /// large and small and at rest (where both are exact).
    #[test]
    fn jacobian_alphas_meets_jacobian() {
        for (scale, h) in [(0.0, 0.5), (1e-3, 0.1), (0.3, 1.25), (2.0, 0.7)] {
            let u: [Vector3<f64>; 3] =
                std::array::from_fn(|g| Vector3::from_fn(|c, _| scale * ((3 * g + c) as f64 * 1.7 + 0.3).sin()));
            let e = Exponent::new(&u, h);
            let (w, v) = e.jacobian();
            let (mut wa, mut va) = ([Matrix3::zeros(); 3], [Matrix3::zeros(); 3]);
            e.jacobian_alphas(|b, w, v| (wa[b], va[b]) = (*w, *v));
            let (we, ve) = (by_nodes(&wa, h), by_nodes(&va, h));
            let size = w.amax().max(v.amax());
            assert!((w - we).amax() <= 1e-15 * size && (v - ve).amax() <= 1e-15 * size, "{w} {we} {v} {ve}");
            if scale != 0.0 {
                assert!(w != we || v != ve, "the same bits: not the expanded form?");
            }
        }
    }
}
