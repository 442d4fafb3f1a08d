//! One Magnus step's exponential $\exp\Omega = (R, p)$ and its first and
//! second derivatives in the coordinates, as body twists.
//!
//! For $\Omega = (\omega, v)$, $R = I + f_1\hat\omega + f_2\hat\omega^2$ and
//! $p = v + f_2\thinspace\omega\times v + f_3\thinspace\omega\times(\omega\times v)$
//! (`space::Spatial::exp`). Its derivative along a coordinate, as a body twist, is
//! $$g^{-1}\partial_a g = \big(J_r(\omega)\thinspace\partial_a\omega,\ R^T\partial_a p\big),\quad
//!   J_r(\omega) = I - f_2\hat\omega + f_3\hat\omega^2,$$
//! the right-trivialized tangent $\mathrm{dexp}_{-\Omega}$ of SE(3) in closed
//! form: the SO(3) right Jacobian (Murray–Li–Sastry; Chirikjian, *Stochastic
//! Models, Information Theory, and Lie Groups* 2, 2012, Sec. 10.6) and the
//! derivative of $p$, with $\partial_a f_m = 2 f_m^{\prime}\thinspace\omega\cdot\partial_a\omega$.
//! The second derivative $\partial_b(g^{-1}\partial_a g)$ differentiates these once more:
//! its linear part is $R^T\partial_a\partial_b p - (J_r\partial_b\omega)\times(R^T\partial_a p)$.

use crate::scalar::Scalar;
use crate::space::{ExpCoefficients, exp_coefficients, exp_parts};
use nalgebra::{Matrix3, Vector3};

/// A step's exponent $(\omega, v)$, its exponential $(R, p)$ and the
/// quantities its derivatives share.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Step<T: Scalar> {
    pub omega: Vector3<T>,
    pub v: Vector3<T>,
    pub c: ExpCoefficients<T>,
    pub r: Matrix3<T>,
    pub p: Vector3<T>,
    /// $\omega\times v$.
    s: Vector3<T>,
    /// $\omega\times(\omega\times v)$.
    t: Vector3<T>,
    /// The order of the coefficients' derivatives made.
    pub order: usize,
}

/// The first derivative of a step along one coordinate.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tangent<T: Scalar> {
    /// $\partial_a\omega$, $\partial_a v$.
    pub dw: Vector3<T>,
    pub dv: Vector3<T>,
    /// $\omega\cdot\partial_a\omega$.
    pub wdw: T,
    /// $\partial_a(\omega\times v)$, $\partial_a(\omega\times(\omega\times v))$.
    pub ds: Vector3<T>,
    pub dt: Vector3<T>,
    /// The body twist's angular part $J_r\partial_a\omega$ and linear part $R^T\partial_a p$.
    pub angular: Vector3<T>,
    pub linear: Vector3<T>,
}

impl<T: Scalar> Default for Tangent<T> {
    fn default() -> Self {
        let z = Vector3::zeros();
        Tangent { dw: z, dv: z, wdw: T::zero(), ds: z, dt: z, angular: z, linear: z }
    }
}

impl<T: Scalar> Tangent<T> {
    /// `self + k * other`: a tangent is linear in $(\partial_a\omega, \partial_a v)$,
    /// so that along a combination of directions is the same combination of theirs.
    #[inline(always)]
    pub fn add_scaled(&mut self, other: &Self, k: T) {
        self.dw += other.dw * k;
        self.dv += other.dv * k;
        self.wdw += other.wdw * k;
        self.ds += other.ds * k;
        self.dt += other.dt * k;
        self.angular += other.angular * k;
        self.linear += other.linear * k;
    }
}

impl<T: Scalar> Step<T> {
    /// The step $\exp(\omega, v)$, its coefficients with derivatives to `order`.
    #[inline(always)]
    pub fn new(omega: Vector3<T>, v: Vector3<T>, order: usize) -> Self {
        let c = exp_coefficients(omega.norm_squared(), order);
        let (r, p) = exp_parts(&omega, &v, &c.f);
        let s = omega.cross(&v);
        let t = omega.cross(&s);
        Step { omega, v, c, r, p, s, t, order }
    }

    /// $J_r(\omega)\thinspace x = x - f_2\thinspace\omega\times x + f_3\thinspace\omega\times(\omega\times x)$.
    #[inline(always)]
    fn right_jacobian(&self, x: &Vector3<T>) -> Vector3<T> {
        let wx = self.omega.cross(x);
        x - wx * self.c.f[1] + self.omega.cross(&wx) * self.c.f[2]
    }

    /// The derivative along a coordinate that changes the exponent by $(\partial_a\omega, \partial_a v)$.
    #[inline(always)]
    pub fn tangent(&self, dw: Vector3<T>, dv: Vector3<T>) -> Tangent<T> {
        let (w, v) = (&self.omega, &self.v);
        let wdw = w.dot(&dw);
        let ds = dw.cross(v) + w.cross(&dv);
        let dt = dw.cross(&self.s) + w.cross(&ds);
        let [f2, f3] = [self.c.f[1], self.c.f[2]];
        let [d2, d3] = self.c.d;
        let two = T::c(2.0);
        let dp = dv + ds * f2 + dt * f3 + (self.s * d2 + self.t * d3) * (two * wdw);
        Tangent { dw, dv, wdw, ds, dt, angular: self.right_jacobian(&dw), linear: self.r.tr_mul(&dp) }
    }

    /// [`Step::tangent`] as maps of the exponent's change $(\delta\omega, \delta v)$, seen
    /// from the frame $(R, p)$ the step is taken from: the frame reached turns by
    /// $RJ_l(\omega)\thinspace\delta\omega$ and moves by $R\thinspace\delta p = RJ_l\delta v + RQ\delta\omega$,
    /// the tangent's body twist turned by $RR_k$ ($J_l = R_kJ_r = I + f_2\hat\omega + f_3\hat\omega^2$), with
    /// $Q = -f_2\hat v - f_3(\hat\omega\hat v + \hat s) + 2(f_2^{\prime}s + f_3^{\prime}t)\thinspace\omega^T$
    /// ($s = \omega\times v$, $t = \omega\times s$): $(RJ_l, RQ)$. Composed first, so that
    /// many changes (the columns of a $3\times9$) see three products.
    #[inline(always)]
    pub fn maps(&self, frame: &Matrix3<T>) -> (Matrix3<T>, Matrix3<T>) {
        let (w, v) = (self.omega.cross_matrix(), self.v.cross_matrix());
        let [f2, f3] = [self.c.f[1], self.c.f[2]];
        let [d2, d3] = self.c.d;
        let left = frame * (Matrix3::identity() + w * f2 + w * w * f3);
        let q = (self.s * d2 + self.t * d3) * (self.omega.transpose() * T::c(2.0))
            - v * f2
            - (w * v + self.s.cross_matrix()) * f3;
        (left, frame * q)
    }

    /// The parts of the second derivatives along one change $(\delta\omega, \delta v)$
    /// of the exponent, twice, that are quadratic in it: with $\delta^2\omega$ and $\delta^2v$
    /// the exponent's second derivative along the change, the frame reached
    /// turns at $\dot\omega = J_l\delta^2\omega + a$ and moves at $\ddot p = J_l\delta^2v + Q\delta^2\omega + b$ ([`Step::maps`]'s $J_l$
    /// and $Q$), and this is $(a, b)$ in the step's own frame: by the product rule on $J_l(\omega)\dot\omega$
    /// and on $p = v + f_2\thinspace\omega\times v + f_3\thinspace\omega\times(\omega\times v)$, the terms of
    /// [`Step::second`] along one direction without those of $\delta^2$.
    #[inline(always)]
    pub fn quadratic(&self, dw: &Vector3<T>, dv: &Vector3<T>) -> (Vector3<T>, Vector3<T>) {
        let two = T::c(2.0);
        let (w, v) = (&self.omega, &self.v);
        let [f2, f3] = [self.c.f[1], self.c.f[2]];
        let [d2, d3] = self.c.d;
        let [e2, e3] = self.c.dd;
        let wdw = w.dot(dw);
        // The coefficients' first derivative ∂f_m = 2 f_m' ω·δω.
        let (g2, g3) = (d2 * (two * wdw), d3 * (two * wdw));
        let a = w.cross(dw);
        let turn = dw.cross(&a) * f3 + a * g2 + w.cross(&a) * g3;
        let ds = dw.cross(v) + w.cross(dv);
        let dt = dw.cross(&self.s) + w.cross(&ds);
        let sab = dw.cross(dv) * two;
        let tab = dw.cross(&ds) * two + w.cross(&sab);
        let move_ = sab * f2
            + tab * f3
            + (ds * g2 + dt * g3) * two
            + (self.s * d2 + self.t * d3) * (two * dw.dot(dw))
            + (self.s * e2 + self.t * e3) * (T::c(4.0) * wdw * wdw);
        (turn, move_)
    }

    /// $\partial_b$ of the body twist $g^{-1}\partial_a g$ of the step, as
    /// (angular, linear), where the exponent's second derivative is $(\partial_{ab}\omega, \partial_{ab}v)$.
    #[inline(always)]
    pub fn second(
        &self,
        a: &Tangent<T>,
        b: &Tangent<T>,
        dwab: Vector3<T>,
        dvab: Vector3<T>,
    ) -> (Vector3<T>, Vector3<T>) {
        let two = T::c(2.0);
        let (w, v) = (&self.omega, &self.v);
        let [f2, f3] = [self.c.f[1], self.c.f[2]];
        let [d2, d3] = self.c.d;
        let [e2, e3] = self.c.dd;
        // ∂_b(J_r ∂_a ω).
        let wa = w.cross(&a.dw);
        let ba = b.dw.cross(&a.dw);
        let angular = self.right_jacobian(&dwab) - ba * f2
            + (b.dw.cross(&wa) + w.cross(&ba)) * f3
            + (w.cross(&wa) * d3 - wa * d2) * (two * b.wdw);
        // ∂_a∂_b p.
        let wdwab = w.dot(&dwab) + a.dw.dot(&b.dw);
        let sab = dwab.cross(v) + a.dw.cross(&b.dv) + b.dw.cross(&a.dv) + w.cross(&dvab);
        let tab = dwab.cross(&self.s) + a.dw.cross(&b.ds) + b.dw.cross(&a.ds) + w.cross(&sab);
        let dpab = dvab
            + sab * f2
            + tab * f3
            + (a.ds * d2 + a.dt * d3) * (two * b.wdw)
            + (b.ds * d2 + b.dt * d3) * (two * a.wdw)
            + (self.s * d2 + self.t * d3) * (two * wdwab)
            + (self.s * e2 + self.t * e3) * (T::c(4.0) * a.wdw * b.wdw);
        let linear = self.r.tr_mul(&dpab) - b.angular.cross(&a.linear);
        (angular, linear)
    }
}
