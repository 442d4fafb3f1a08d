//! The Kirchhoff rod's equations along one stretch: the right-hand side
//! that [`super::chain`] integrates, on a unit quaternion.

use super::Rod;
use crate::scalar::Scalar;

/// The state integrated along the rod: the quaternion $q$ of the cross-section
/// (4), its position $p/L$ (3) and the internal moment $\mu = m/k$ (3), all in
/// the root frame.
pub(super) const STATE: usize = 10;

/// Index of $p/L$ in the state.
pub(super) const P: usize = 4;

/// Index of $\mu$ in the state.
pub(super) const MU: usize = 7;

/// The rotation matrix (rows) of the quaternion $q = (w, x, y, z)$ divided by
/// its norm: exactly orthogonal whatever $|q|$, so the shape never drifts
/// off $SO(3)$ while the integrator's rounding moves $|q|$ (which
/// $q^{\prime} = \tfrac12 q\otimes(0, u)$ keeps in exact arithmetic).
pub(super) fn rotation<T: Scalar>(q: &[T]) -> [[T; 3]; 3] {
    let (w, x, y, z) = (q[0], q[1], q[2], q[3]);
    let n = T::one() / (w * w + x * x + y * y + z * z);
    let two = T::c(2.0) * n;
    [
        [(w * w + x * x - y * y - z * z) * n, two * (x * y - w * z), two * (x * z + w * y)],
        [two * (x * y + w * z), (w * w - x * x + y * y - z * z) * n, two * (y * z - w * x)],
        [two * (x * z - w * y), two * (y * z + w * x), (w * w - x * x - y * y + z * z) * n],
    ]
}

/// $a \times b$.
pub(super) fn cross<T: Scalar>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// The right-hand side of the rod under the dead tip force `f` $= \lambda F/k$:
/// with $R = R(q)$ and the body-frame curvature $u = K^{-1}R^T(k\mu) + u^0(s)$,
/// $$q^{\prime} = \tfrac12\thinspace q\otimes(0, u), \qquad (p/L)^{\prime} = R e_1/L, \qquad
/// \mu^{\prime} = -R e_1 \times f.$$
pub(super) fn rhs<'r, T: Scalar>(rod: &'r Rod, k: f64, f: [T; 3]) -> impl Fn(f64, &[T; STATE]) -> [T; STATE] + 'r {
    move |s: f64, y: &[T; STATE]| {
        let l = rod.length;
        let stiffness = rod.section.stiffness(s / l);
        let rest = rod.rest_at(s);
        let r = rotation(&y[..4]);
        let m = [y[MU] * T::c(k), y[MU + 1] * T::c(k), y[MU + 2] * T::c(k)];
        let mut u = [T::zero(); 3];
        for i in 0..3 {
            let body = r[0][i] * m[0] + r[1][i] * m[1] + r[2][i] * m[2];
            u[i] = body / T::c(stiffness[i]) + T::c(rest[i]);
        }
        let (w, v) = (y[0], [y[1], y[2], y[3]]);
        let vu = cross(v, u);
        let half = T::c(0.5);
        let tangent = [r[0][0], r[1][0], r[2][0]];
        let dmu = cross(tangent, f);
        let mut d = [T::zero(); STATE];
        d[0] = -(v[0] * u[0] + v[1] * u[1] + v[2] * u[2]) * half;
        for i in 0..3 {
            d[1 + i] = (w * u[i] + vu[i]) * half;
            d[P + i] = tangent[i] / T::c(l);
            d[MU + i] = -dmu[i];
        }
        d
    }
}
