//! Saint-Venant torsion of a solid rectangle: the torsion constant and the
//! peak shear stresses, by the series of Prandtl's stress function.
//!
//! For a rectangle of long side $b$ and short side $c$, aspect $r = b/c \ge 1$,
//! twisted at rate $\theta$ (rad/m) by the torque $T = G J\theta$
//! (S. P. Timoshenko and J. N. Goodier, *Theory of Elasticity*, 3rd ed.,
//! McGraw-Hill 1970, §109, Eqs. 163–167; the same coefficients are tabled in
//! Roark's *Formulas for Stress and Strain*, Table 10.1, case 4):
//! $$J = \beta(r)\thinspace b c^3, \qquad
//! \beta(r) = \frac13\Big(1 - \frac{192}{\pi^5 r}\sum_{n\ \mathrm{odd}}\frac{\tanh(n\pi r/2)}{n^5}\Big),$$
//! the largest shear, at the middle of each long side,
//! $$\tau_{b} = k(r)\thinspace G\theta c, \qquad k(r) = 1 - \frac{8}{\pi^2}\sum_{n\ \mathrm{odd}}\frac{1}{n^2\cosh(n\pi r/2)},$$
//! so that $\tau_b = T/(\alpha\thinspace b c^2)$ with $\alpha = \beta/k$, and the shear at the
//! middle of each short side
//! $$\tau_{c} = \frac{8}{\pi^2}\thinspace G\theta c\sum_{n\ \mathrm{odd}}(-1)^{(n-1)/2}\frac{\tanh(n\pi r/2)}{n^2}.$$
//!
//! Each sum is split into its limit for $r \to \infty$ (in closed form:
//! $\sum_{\mathrm{odd}} n^{-5} = \tfrac{31}{32}\zeta(5)$ and Catalan's constant)
//! and a remainder whose terms fall like $e^{-n\pi r}$, summed until a term
//! no longer changes the total (at most [`MAX_TERMS`] terms): each
//! coefficient is exact to rounding.

use std::f64::consts::PI;

/// The most odd terms a remainder sums; for $r \ge 1$ a term is below
/// $10^{-17}$ of the total after 13 of them.
pub const MAX_TERMS: usize = 64;

/// $\sum_{n\ \mathrm{odd}} n^{-5} = (1 - 2^{-5})\zeta(5)$.
const ODD_ZETA5: f64 = 31.0 / 32.0 * 1.036_927_755_143_37;

/// Catalan's constant $\sum_{n\ \mathrm{odd}}(-1)^{(n-1)/2}n^{-2}$.
const CATALAN: f64 = 0.915_965_594_177_219;

/// $1 - \tanh x = 2/(e^{2x} + 1)$, without cancellation.
fn one_minus_tanh(x: f64) -> f64 {
    2.0 / ((2.0 * x).exp() + 1.0)
}

/// The sum of `term(n)` over the first [`MAX_TERMS`] odd $n$, stopping when a term no
/// longer changes the sum.
fn odd_sum(term: impl Fn(f64) -> f64) -> f64 {
    let mut sum = 0.0;
    for k in 0..MAX_TERMS {
        let t = term((2 * k + 1) as f64);
        if sum + t == sum {
            break;
        }
        sum += t;
    }
    sum
}

/// Torsion constant coefficient $\beta(r)$, $J = \beta\thinspace b c^3$, for the aspect
/// $r = b/c \ge 1$ (long over short side).
///
/// # Example
/// ```
/// use flexure::section::torsion::beta;
/// // Timoshenko & Goodier's table: 0.141 for a square, 1/3 for a thin strip.
/// assert!((beta(1.0) - 0.1406).abs() < 1e-4);
/// assert!((beta(1e9) - 1.0 / 3.0).abs() < 1e-9);
/// ```
pub fn beta(r: f64) -> f64 {
    let tail = odd_sum(|n| one_minus_tanh(n * PI * r / 2.0) / n.powi(5));
    (1.0 - 192.0 / (PI.powi(5) * r) * (ODD_ZETA5 - tail)) / 3.0
}

/// $k(r)$: the peak shear at the middle of a long side is $k\thinspace G\theta c$.
///
/// # Example
/// ```
/// use flexure::section::torsion::long_side_shear;
/// // A thin strip: τ = Gθc (k → 1); a square: 0.675.
/// assert!((long_side_shear(1e9) - 1.0).abs() < 1e-12);
/// assert!((long_side_shear(1.0) - 0.675).abs() < 1e-3);
/// ```
pub fn long_side_shear(r: f64) -> f64 {
    1.0 - 8.0 / (PI * PI) * odd_sum(|n| 1.0 / (n * n * (n * PI * r / 2.0).cosh()))
}

/// The shear at the middle of a short side over $G\theta c$.
///
/// # Example
/// ```
/// use flexure::section::torsion::{long_side_shear, short_side_shear};
/// // A square's sides are alike; a thin strip's short side carries 8G/π² = 0.742 of Gθc.
/// assert!((short_side_shear(1.0) - long_side_shear(1.0)).abs() < 1e-14);
/// assert!((short_side_shear(1e9) - 0.742_454).abs() < 1e-6);
/// ```
pub fn short_side_shear(r: f64) -> f64 {
    // Σ(−1)^k tanh/n² = Catalan − Σ(−1)^k (1 − tanh)/n².
    let tail = odd_sum(|n| {
        let sign = if (n as usize / 2).is_multiple_of(2) { 1.0 } else { -1.0 };
        sign * one_minus_tanh(n * PI * r / 2.0) / (n * n)
    });
    8.0 / (PI * PI) * (CATALAN - tail)
}

/// $\alpha(r) = \beta/k$: the peak shear is $T/(\alpha\thinspace b c^2)$.
///
/// # Example
/// ```
/// use flexure::section::torsion::alpha;
/// // Timoshenko & Goodier's table: 0.208 for a square, 0.312 at r = 10.
/// assert!((alpha(1.0) - 0.208).abs() < 5e-4 && (alpha(10.0) - 0.312).abs() < 5e-4);
/// ```
pub fn alpha(r: f64) -> f64 {
    beta(r) / long_side_shear(r)
}
