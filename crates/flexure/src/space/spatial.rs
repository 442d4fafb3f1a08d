//! SE(3): the spatial implementation of [`Space`].
//!
//! A pose is an [`Isometry3`] $g = (R, p)$; twists and wrenches are
//! [`Vector6`]s ordered (angular, linear): a twist $\xi = (\omega, v)$ with
//! hat $\hat\xi = \begin{pmatrix}\hat\omega & v\cr 0 & 0\end{pmatrix}$, a
//! wrench $(m, f)$, so that power is the dot product (Featherstone's order;
//! Murray, Li and Sastry, *A Mathematical Introduction to Robotic
//! Manipulation*, 1994, Ch. 2, list the linear part first).
//!
//! The exponential's coefficients are the entire functions
//! $$f_m(x) = \sum_{k\ge0}\frac{(-x)^k}{(2k+m)!},\qquad x = \theta^2 = \lvert\omega\rvert^2,$$
//! $f_1 = \frac{\sin\theta}{\theta}$, $f_2 = \frac{1-\cos\theta}{\theta^2}$,
//! $f_3 = \frac{\theta-\sin\theta}{\theta^3}$, with
//! $f_m^{\prime} = \frac{f_{m-1} - m f_m}{2x}$: [`exp_coefficients`] sums the
//! series below $\theta = 2$ and uses the closed forms above, so every
//! quotient keeps its precision through $\theta = 0$, and is generic over
//! [`Scalar`] so that dual numbers differentiate through it.

use super::Space;
use crate::scalar::Scalar;
use nalgebra::{Isometry3, Matrix3, Matrix6, Point3, Translation3, UnitQuaternion, Vector3, Vector6};

/// Space: poses in SE(3), twists and wrenches as (angular, linear) 6-vectors.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Spatial;

/// $f_1, f_2, f_3$ of $x = \theta^2$ and the first and second derivatives
/// of $f_2, f_3$ in $x$: everything the exponential of SE(3) and its first
/// two derivatives need.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ExpCoefficients<T> {
    /// $f_1, f_2, f_3$.
    pub f: [T; 3],
    /// $f_2^{\prime}, f_3^{\prime}$.
    pub d: [T; 2],
    /// $f_2^{\prime\prime}, f_3^{\prime\prime}$.
    pub dd: [T; 2],
}

/// Below this $x = \theta^2$ the coefficients are summed as series (15
/// terms: the second derivatives' first term left out is below $10^{-24}$ at $x = 4$);
/// above it the closed forms lose at most a digit to cancellation.
const SERIES_BELOW: f64 = 4.0;
const TERMS: usize = 15;

/// $(-1)^k/(2k+m)!$ at `[m - 1][k]`, for $m = 1, 2, 3$, computed at compile time.
const SERIES: [[f64; TERMS]; 3] = {
    let mut t = [[0.0; TERMS]; 3];
    let mut m = 0;
    while m < 3 {
        let mut k = 0;
        while k < TERMS {
            let mut f = 1.0;
            let mut j = 1;
            while j <= 2 * k + m + 1 {
                f *= j as f64;
                j += 1;
            }
            t[m][k] = if k % 2 == 0 { 1.0 / f } else { -1.0 / f };
            k += 1;
        }
        m += 1;
    }
    t
};

/// Terms of the series kept below $x = 1/4$ and $x = 1$: the first left
/// out, with its derivatives' factors $k(k-1)$, is below $10^{-18}$ there.
const TERMS_SMALL: usize = 9;
const TERMS_UNIT: usize = 12;

/// $f_1, f_2, f_3$ alone below $x = 4$: $f_2$ and $f_3$ by their series split
/// into even and odd powers (Estrin's scheme: four short chains of
/// multiply-adds instead of two long ones), with as many terms as $x$ needs
/// (the first left out below $10^{-17}$ of the value), and $f_1 = 1 - x f_3$
/// (no cancellation below $x = 4$).
#[inline(always)]
fn values<T: Scalar>(x: T) -> [T; 3] {
    let terms = if x.re() < 0.0625 {
        6
    } else if x.re() < 0.25 {
        8
    } else if x.re() < 1.0 {
        TERMS_UNIT
    } else {
        TERMS
    };
    let x2 = x * x;
    // P(x) = E(x²) + x·O(x²), with E and O by Horner's rule in x².
    let half = |c: &[f64; TERMS], parity: usize| {
        let mut k = (terms - 1 - parity) / 2 * 2 + parity;
        let mut v = T::c(c[k]);
        while k >= 2 {
            k -= 2;
            v = v * x2 + T::c(c[k]);
        }
        v
    };
    let f2 = half(&SERIES[1], 0) + x * half(&SERIES[1], 1);
    let f3 = half(&SERIES[2], 0) + x * half(&SERIES[2], 1);
    [T::one() - x * f3, f2, f3]
}

/// The coefficients at $x = \theta^2$, with derivatives to `order` (0, 1 or
/// 2; the others are left zero).
#[inline(always)]
pub(crate) fn exp_coefficients<T: Scalar>(x: T, order: usize) -> ExpCoefficients<T> {
    let zero = T::zero();
    let mut out = ExpCoefficients { f: [zero; 3], d: [zero; 2], dd: [zero; 2] };
    if x.re() < SERIES_BELOW {
        let terms = if x.re() < 0.25 {
            TERMS_SMALL
        } else if x.re() < 1.0 {
            TERMS_UNIT
        } else {
            TERMS
        };
        if order == 0 {
            return ExpCoefficients { f: values(x), ..out };
        }
        // Horner's rule on value, first and second derivative together.
        for m in 0..3 {
            let c = &SERIES[m];
            let (mut v, mut d1, mut d2) = (T::c(c[terms - 1]), zero, zero);
            for k in (0..terms - 1).rev() {
                if order >= 2 {
                    d2 = d2 * x + d1 * T::c(2.0);
                }
                d1 = d1 * x + v;
                v = v * x + T::c(c[k]);
            }
            out.f[m] = v;
            if m > 0 {
                out.d[m - 1] = d1;
                out.dd[m - 1] = d2;
            }
        }
        return out;
    }
    let theta = x.sqrt();
    let (s, c) = theta.sin_cos();
    let f1 = s / theta;
    let f2 = (T::one() - c) / x;
    let f3 = (T::one() - f1) / x;
    out.f = [f1, f2, f3];
    if order >= 1 {
        let two_x = x * T::c(2.0);
        let d1 = (c - f1) / two_x;
        let d2 = (f1 - f2 * T::c(2.0)) / two_x;
        let d3 = (f2 - f3 * T::c(3.0)) / two_x;
        out.d = [d2, d3];
        if order >= 2 {
            out.dd = [(d1 - d2 * T::c(4.0)) / two_x, (d2 - d3 * T::c(5.0)) / two_x];
        }
    }
    out
}

/// $\exp$ of the twist $(\omega, v)$ as $(R, p)$, generic over [`Scalar`]:
/// $R = I + f_1\hat\omega + f_2\hat\omega^2$, $p = v + f_2\thinspace\omega\times v + f_3\thinspace\omega\times(\omega\times v)$
/// (Murray–Li–Sastry Eq. 2.36, with $V = I + f_2\hat\omega + f_3\hat\omega^2$).
#[inline(always)]
pub(crate) fn exp_parts<T: Scalar>(omega: &Vector3<T>, v: &Vector3<T>, f: &[T; 3]) -> (Matrix3<T>, Vector3<T>) {
    // ω̂² = ωωᵀ − θ²I.
    let x = omega.norm_squared();
    let d = T::one() - x * f[1];
    let (a, b) = (omega * f[0], omega * f[1]);
    let r = Matrix3::new(
        d + b[0] * omega[0],
        b[0] * omega[1] - a[2],
        b[0] * omega[2] + a[1],
        b[1] * omega[0] + a[2],
        d + b[1] * omega[1],
        b[1] * omega[2] - a[0],
        b[2] * omega[0] - a[1],
        b[2] * omega[1] + a[0],
        d + b[2] * omega[2],
    );
    let wv = omega.cross(v);
    let p = v + wv * f[1] + omega.cross(&wv) * f[2];
    (r, p)
}

/// The rotation's quaternion from an orthonormal matrix (nalgebra's
/// Shepperd-style conversion).
fn quaternion(r: &Matrix3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(*r))
}

impl Spatial {
    /// A pose of the plane as one of space: the rotation $\phi$ about $z$,
    /// the origin at $(x, y, 0)$.
    ///
    /// # Example
    /// ```
    /// use flexure::space::{Pose, Spatial};
    /// let g = Spatial::from_planar_pose(&Pose { phi: 0.5, x: 1.0, y: 2.0 });
    /// assert!((g.rotation.angle() - 0.5).abs() < 1e-15 && g.translation.vector.z == 0.0);
    /// ```
    pub fn from_planar_pose(g: &super::Pose) -> Isometry3<f64> {
        Isometry3::new(Vector3::new(g.x, g.y, 0.0), Vector3::new(0.0, 0.0, g.phi))
    }

    /// A planar twist $(\omega, v_x, v_y)$ as $(0, 0, \omega, v_x, v_y, 0)$.
    pub fn from_planar_twist(t: &super::Twist) -> Vector6<f64> {
        Vector6::new(0.0, 0.0, t.omega, t.vx, t.vy, 0.0)
    }

    /// The Lie bracket $[\xi_1, \xi_2] = (\omega_1\times\omega_2,\ \omega_1\times v_2 - \omega_2\times v_1)$,
    /// the twist of $\hat\xi_1\hat\xi_2 - \hat\xi_2\hat\xi_1$.
    ///
    /// # Example
    /// ```
    /// use flexure::space::Spatial;
    /// use nalgebra::Vector6;
    /// let b = Spatial::bracket(&Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0), &Vector6::new(0.0, 0.0, 0.0, 1.0, 0.0, 0.0));
    /// assert_eq!(b, Vector6::new(0.0, 0.0, 0.0, 0.0, 1.0, 0.0));
    /// ```
    pub fn bracket(a: &Vector6<f64>, b: &Vector6<f64>) -> Vector6<f64> {
        bracket(a, b)
    }
}

/// [`Spatial::bracket`] over any [`Scalar`].
#[inline(always)]
pub(crate) fn bracket<T: Scalar>(a: &Vector6<T>, b: &Vector6<T>) -> Vector6<T> {
    let (wa, va) = (a.fixed_rows::<3>(0), a.fixed_rows::<3>(3));
    let (wb, vb) = (b.fixed_rows::<3>(0), b.fixed_rows::<3>(3));
    let w = wa.cross(&wb);
    let v = wa.cross(&vb) - wb.cross(&va);
    Vector6::new(w[0], w[1], w[2], v[0], v[1], v[2])
}

impl Space for Spatial {
    const TWIST_DIM: usize = 6;
    const POINT_DIM: usize = 3;
    type Pose = Isometry3<f64>;
    type Point = Point3<f64>;
    type Vector = Vector3<f64>;
    type Twist = Vector6<f64>;
    type Wrench = Vector6<f64>;
    type Adjoint = Matrix6<f64>;

    fn identity() -> Isometry3<f64> {
        Isometry3::identity()
    }

    fn compose(a: &Isometry3<f64>, b: &Isometry3<f64>) -> Isometry3<f64> {
        a * b
    }

    fn inverse(a: &Isometry3<f64>) -> Isometry3<f64> {
        a.inverse()
    }

    fn act(a: &Isometry3<f64>, r: &Point3<f64>) -> Point3<f64> {
        a * r
    }

    fn at(p: &Point3<f64>) -> Isometry3<f64> {
        Isometry3::translation(p.x, p.y, p.z)
    }

    fn origin(a: &Isometry3<f64>) -> Point3<f64> {
        Point3::from(a.translation.vector)
    }

    fn reach(a: &Isometry3<f64>) -> f64 {
        a.translation.vector.norm()
    }

    fn rotate(a: &Isometry3<f64>, v: &Vector3<f64>) -> Vector3<f64> {
        a.rotation * v
    }

    /// $\mathrm{Ad}_g = \begin{pmatrix}R & 0\cr \hat pR & R\end{pmatrix}$ in the
    /// (angular, linear) order: $\mathrm{Ad}_g(\omega, v) = (R\omega,\ Rv + p\times R\omega)$
    /// (Murray–Li–Sastry Eq. 2.58, rows swapped).
    fn adjoint(a: &Isometry3<f64>) -> Matrix6<f64> {
        let r = a.rotation.to_rotation_matrix().into_inner();
        let pr = a.translation.vector.cross_matrix() * r;
        let mut m = Matrix6::zeros();
        m.fixed_view_mut::<3, 3>(0, 0).copy_from(&r);
        m.fixed_view_mut::<3, 3>(3, 3).copy_from(&r);
        m.fixed_view_mut::<3, 3>(3, 0).copy_from(&pr);
        m
    }

    /// $\exp(\omega, v) = \big(I + f_1\hat\omega + f_2\hat\omega^2,\ (I + f_2\hat\omega + f_3\hat\omega^2)v\big)$
    /// (Rodrigues; Murray–Li–Sastry Eq. 2.36), with the $f_m$ of the module docs.
    fn exp(t: &Vector6<f64>) -> Isometry3<f64> {
        let omega = Vector3::new(t[0], t[1], t[2]);
        let v = Vector3::new(t[3], t[4], t[5]);
        let c = exp_coefficients(omega.norm_squared(), 0);
        let (_, p) = exp_parts(&omega, &v, &c.f);
        // The rotation from its axis and angle directly: exactly a unit quaternion.
        Isometry3::from_parts(Translation3::from(p), UnitQuaternion::from_scaled_axis(omega))
    }

    /// $\log(R, p) = (\omega,\ V^{-1}p)$ with $\omega$ the rotation's axis
    /// times its angle $\theta \in [0, \pi]$ (from the quaternion by
    /// $\theta = 2\operatorname{atan2}(\lvert q_v\rvert, q_w)$, accurate at
    /// small angles where $\arccos$ is not) and
    /// $V^{-1} = I - \frac12\hat\omega + \frac{1 - \frac\theta2\cot\frac\theta2}{\theta^2}\hat\omega^2$,
    /// whose last coefficient is $\frac1{12} + \frac{\theta^2}{720} + \frac{\theta^4}{30240} + \dots$
    /// below $\theta = 0.1$.
    fn log(a: &Isometry3<f64>) -> Vector6<f64> {
        let q = a.rotation.quaternion();
        let (qw, qv) = if q.w < 0.0 { (-q.w, -q.imag()) } else { (q.w, q.imag()) };
        let n = qv.norm();
        let omega = if n == 0.0 { Vector3::zeros() } else { qv * (2.0 * n.atan2(qw) / n) };
        let theta = omega.norm();
        let c = if theta < 0.1 {
            let x = theta * theta;
            1.0 / 12.0 + x * (1.0 / 720.0 + x * (1.0 / 30240.0 + x * (1.0 / 1_209_600.0)))
        } else {
            let h = 0.5 * theta;
            (1.0 - h / h.tan()) / (theta * theta)
        };
        let p = a.translation.vector;
        let wp = omega.cross(&p);
        let v = p - wp * 0.5 + omega.cross(&wp) * c;
        Vector6::new(omega[0], omega[1], omega[2], v[0], v[1], v[2])
    }

    /// $w\cdot\xi = m\cdot\omega + f\cdot v$.
    fn power(w: &Vector6<f64>, t: &Vector6<f64>) -> f64 {
        w.dot(t)
    }

    /// $v + \omega\times r$.
    fn velocity_at(t: &Vector6<f64>, r: &Vector3<f64>) -> Vector3<f64> {
        Vector3::new(t[3], t[4], t[5]) + Vector3::new(t[0], t[1], t[2]).cross(r)
    }
}

/// The angle (rad) between two rotations, $\lvert\log(R_a^TR_b)\rvert$ in $[0, \pi]$.
///
/// # Example
/// ```
/// use nalgebra::{Rotation3, Vector3};
/// let a = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.3).into_inner();
/// let b = Rotation3::from_axis_angle(&Vector3::z_axis(), -2.9).into_inner();
/// assert!((flexure::space::rotation_angle(&a, &b) - 3.2f64.min(2.0 * std::f64::consts::PI - 3.2)).abs() < 1e-14);
/// ```
pub fn rotation_angle(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    let r = a.tr_mul(b);
    // Robust for angles near 0 and π: atan2 of |axis part| and the cosine.
    let axis = Vector3::new(r[(2, 1)] - r[(1, 2)], r[(0, 2)] - r[(2, 0)], r[(1, 0)] - r[(0, 1)]);
    (0.5 * axis.norm()).atan2(0.5 * (r.trace() - 1.0))
}

/// The rotation matrix and translation of an isometry, and back.
pub(crate) fn isometry(r: &Matrix3<f64>, p: &Vector3<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(*p), quaternion(r))
}
