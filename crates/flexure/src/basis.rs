//! The shifted-Legendre curvature basis (paper Sec. II-D) and its integrals.
//!
//! With $t = s/L$, curvature is $\hat\omega(\alpha, s) = \frac1L \sum_{i=1}^N
//! \alpha_i \tilde P_{i-1}(t)$ (Eq. 8, extended to any order), where
//! $\tilde P_n(t) = P_n(2t-1)$. The tangent angle is
//! $\phi(\alpha, s) = \sum_i \alpha_i \psi_{i-1}(t)$ (Eq. 10) with
//! $\psi_n(t) = \int_0^t \tilde P_n$.

/// Fills `out[n]` with $\tilde P_n(t)$ for `n < out.len()` (Bonnet's recurrence).
///
/// # Example
/// ```
/// let mut p = [0.0; 3];
/// flexure::basis::shifted_legendre(0.25, &mut p);
/// // P̃₂(t) = 6t² − 6t + 1 (Eq. 8)
/// assert!((p[2] - (6.0 * 0.0625 - 1.5 + 1.0)).abs() < 1e-15);
/// ```
pub fn shifted_legendre(t: f64, out: &mut [f64]) {
    let x = 2.0 * t - 1.0;
    let (mut prev, mut cur) = (1.0, x);
    for (n, slot) in out.iter_mut().enumerate() {
        *slot = match n {
            0 => 1.0,
            1 => x,
            _ => {
                let m = (n - 1) as f64;
                let next = ((2.0 * m + 1.0) * x * cur - m * prev) / (m + 1.0);
                prev = cur;
                cur = next;
                next
            }
        };
    }
}

/// Fills `out[n]` with the angle shape $\psi_n(t) = \int_0^t \tilde P_n(\tau)\thinspace d\tau$.
///
/// $\psi_0 = t$ and, for $n \ge 1$,
/// $\psi_n = \frac{\tilde P_{n+1} - \tilde P_{n-1}}{2(2n+1)}$, so
/// $\psi_n(1) = 0$ for $n \ge 1$ and the tip angle is $\alpha_1$ (Eq. 11).
///
/// # Example
/// ```
/// let mut psi = [0.0; 3];
/// flexure::basis::angle_shapes(0.3, &mut psi);
/// let t: f64 = 0.3;
/// // Eq. 10: t, t² − t, 2t³ − 3t² + t
/// assert!((psi[1] - (t * t - t)).abs() < 1e-15);
/// assert!((psi[2] - (2.0 * t.powi(3) - 3.0 * t * t + t)).abs() < 1e-15);
/// ```
pub fn angle_shapes(t: f64, out: &mut [f64]) {
    let n = out.len();
    let mut p = vec![0.0; n + 1];
    shifted_legendre(t, &mut p);
    for (k, slot) in out.iter_mut().enumerate() {
        *slot = if k == 0 { t } else { (p[k + 1] - p[k - 1]) / (2.0 * (2 * k + 1) as f64) };
    }
}

/// $\int_0^1 \tilde P_n^2\thinspace dt = \frac{1}{2n+1}$: the weight of coefficient
/// $n$ (0-based) in the bending energy, Eq. 9.
pub fn energy_weight(n: usize) -> f64 {
    1.0 / (2 * n + 1) as f64
}

/// The root mean square of the angle shape $\psi_n$ over the length,
/// relative to $\psi_0$'s: how much a unit of coefficient $n$ turns the
/// sections, next to the uniform bending. From the orthogonality of the
/// $\tilde P_k$ (Eq. 10 and [`angle_shapes`]),
/// $$\int_0^1\psi_n^2\thinspace dt = \frac{1}{4(2n+1)^2}\Bigl(\frac1{2n+3} +
/// \frac1{2n-1}\Bigr)\quad(n \ge 1),\qquad \int_0^1\psi_0^2\thinspace dt = \frac13.$$
/// It falls about as $n^{-3/2}$: the integrator weighs a coefficient's
/// error by it ([`crate::mechanism::Joint::error_weights`]).
///
/// # Example
/// ```
/// // ψ₁ = t² − t: ∫ψ₁² = 1/30, against ψ₀'s 1/3.
/// let w = flexure::basis::angle_shape_rms(1);
/// assert!((w - (0.1f64).sqrt()).abs() < 1e-15);
/// assert_eq!(flexure::basis::angle_shape_rms(0), 1.0);
/// ```
pub fn angle_shape_rms(n: usize) -> f64 {
    if n == 0 {
        return 1.0;
    }
    let k = n as f64;
    let square = (1.0 / (2.0 * k + 3.0) + 1.0 / (2.0 * k - 1.0)) / (4.0 * (2.0 * k + 1.0).powi(2));
    (3.0 * square).sqrt()
}

/// [`angle_shape_rms`] of coefficients $0, 1, \ldots$ into `out`, one per entry:
/// a flexure's error weights, one bending's or the twist's.
///
/// # Example
/// ```
/// let mut w = [0.0; 3];
/// flexure::basis::angle_shape_rms_each(&mut w);
/// assert_eq!(w, [1.0, flexure::basis::angle_shape_rms(1), flexure::basis::angle_shape_rms(2)]);
/// ```
pub fn angle_shape_rms_each(out: &mut [f64]) {
    for (n, w) in out.iter_mut().enumerate() {
        *w = angle_shape_rms(n);
    }
}

/// Curvature $\hat\omega(c, s)$ of coefficients `c` at arc length `s` (Eq. 8).
///
/// # Example
/// ```
/// // A constant curvature of 2 rad over L = 0.5 is 4 rad/m everywhere.
/// let w = flexure::basis::curvature(&[2.0, 0.0, 0.0], 0.5, 0.1);
/// assert!((w - 4.0).abs() < 1e-15);
/// ```
pub fn curvature(c: &[f64], length: f64, s: f64) -> f64 {
    // Bonnet's recurrence inline: this runs inside ODE right-hand sides.
    let x = 2.0 * s / length - 1.0;
    let (mut prev, mut cur) = (0.0, 1.0);
    let mut sum = 0.0;
    for (n, &a) in c.iter().enumerate() {
        if n > 0 {
            let m = (n - 1) as f64;
            let next = if n == 1 { x } else { ((2.0 * m + 1.0) * x * cur - m * prev) / (m + 1.0) };
            prev = cur;
            cur = next;
        }
        sum += a * cur;
    }
    sum / length
}
