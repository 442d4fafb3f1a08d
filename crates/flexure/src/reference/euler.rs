//! Euler's closed-form buckling loads of a root-clamped column (Table I, errata).

use crate::buckling::TipConstraint;

/// The first positive root of $\tan x = x$, $x \approx 4.4934$ (clamped–pinned column).
///
/// # Example
/// ```
/// let x = flexure::reference::euler::tan_root();
/// assert!((x.tan() - x).abs() < 1e-9 && (x - 4.4934).abs() < 1e-4);
/// ```
pub fn tan_root() -> f64 {
    // Newton on g(x) = sin x − x cos x, g' = x sin x, from inside (π, 3π/2).
    let mut x = 4.5_f64;
    for _ in 0..50 {
        let step = (x.sin() - x * x.cos()) / (x * x.sin());
        x -= step;
        if step.abs() < 1e-15 * x {
            break;
        }
    }
    x
}

/// Critical load $P = c\thinspace EI/L^2$ with $c$ = $\pi^2/4$ (free), $\pi^2$ (guided),
/// $4.4934^2$ (pinned, errata: not $2\pi^2$), $4\pi^2$ (clamped).
///
/// # Example
/// ```
/// use flexure::{reference::euler::buckling_load, TipConstraint};
/// // Errata: the clamped–pinned load is 20.1907 EI/L².
/// assert!((buckling_load(TipConstraint::Pinned, 1.0, 1.0) - 20.1907).abs() < 1e-4);
/// ```
pub fn buckling_load(tip: TipConstraint, length: f64, ei: f64) -> f64 {
    let pi2 = std::f64::consts::PI.powi(2);
    let c = match tip {
        TipConstraint::Free => pi2 / 4.0,
        TipConstraint::Guided => pi2,
        TipConstraint::Pinned => tan_root().powi(2),
        TipConstraint::Clamped => 4.0 * pi2,
    };
    c * ei / (length * length)
}
