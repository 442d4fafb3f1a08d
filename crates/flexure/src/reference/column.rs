//! The linearized buckling load of a straight, root-clamped column of
//! bending stiffness $EI(s)$, by shooting on the load.

use crate::buckling::TipConstraint;
use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::ode::{Tolerance, integrate_through};

/// Ratio of one load to the next in the scan that brackets the critical
/// load: two critical loads closer than 1 % would be missed (a uniform
/// column's first two differ by a factor 2 or more).
const SCAN_RATIO: f64 = 1.01;

/// Cross-sections sampled for the section's least and largest $EI$.
const EI_SAMPLES: usize = 1024;

/// Bisection steps on the bracket, far more than the $\approx 50$ that
/// shrink it to rounding.
const MAX_BISECTIONS: usize = 200;

/// The smallest compressive tip load $P$ (N, along the root's $-x$) at which
/// the straight column, clamped at the root and held at the tip by `tip`,
/// has a buckled neighbour: the first eigenvalue of
/// $$(EI\thinspace w^{\prime\prime})^{\prime\prime} + P w^{\prime\prime} = 0.$$
///
/// Shooting on the first-order system $y^{\prime} = \phi$,
/// $\phi^{\prime} = m/EI(s)$, with the bending moment of a column carrying
/// root moment $M_0$, lateral tip force $F_y$ and the load,
/// $m(s) = M_0 - F_y s - P y$, from $y(0) = \phi(0) = 0$. The tip conditions
/// pick the unknowns and residuals: free, $F_y = 0$ and $m(L) = 0$; guided,
/// $F_y = 0$ and $\phi(L) = 0$; pinned, $y(L) = m(L) = 0$; clamped,
/// $y(L) = \phi(L) = 0$. The system is linear in $(M_0, F_y)$, so $P$ is
/// critical where the determinant $D(P)$ of the residuals of its two
/// fundamental solutions vanishes. By comparison of Rayleigh quotients the
/// first root lies between Euler's load for the least and for the largest
/// $EI$ on the flexure; a scan from the former (steps of 1 %) brackets it,
/// bisection refines it to rounding. Integration restarts at the section's
/// breakpoints, to `tol`.
///
/// Errors: [`Error::InvalidParameter`] for a pre-curved flexure (`kappa`)
/// or a bad `tol`; [`Error::Singular`] naming the loads scanned when no
/// sign change is found up to twice Euler's load for the largest $EI$;
/// integrator failures.
///
/// # Example
/// ```
/// use flexure::{reference::{column, euler}, Flexure, TipConstraint};
/// let f = Flexure::new(0.5, 2.0, 3).unwrap();
/// let p = column::buckling_load(&f, TipConstraint::Pinned, &Default::default()).unwrap();
/// let euler = euler::buckling_load(TipConstraint::Pinned, 0.5, 2.0);
/// assert!((p / euler - 1.0).abs() < 1e-10);
/// ```
pub fn buckling_load(flexure: &Flexure, tip: TipConstraint, tol: &Tolerance) -> Result<f64> {
    tol.validate()?;
    if flexure.rest().iter().any(|&k| k != 0.0) {
        return Err(Error::invalid(
            "kappa",
            format!("{:?}", flexure.rest()),
            "the exact column buckling load is for a straight flexure",
        ));
    }
    let l = flexure.length();
    let stops = super::stops(flexure);
    let (mut lo_ei, mut hi_ei) = (f64::INFINITY, 0.0_f64);
    for s in (0..=EI_SAMPLES).map(|k| l * k as f64 / EI_SAMPLES as f64).chain(stops.iter().copied()) {
        let ei = flexure.ei_at(s);
        (lo_ei, hi_ei) = (lo_ei.min(ei), hi_ei.max(ei));
    }
    let euler = |ei: f64| super::euler::buckling_load(tip, l, ei);
    // A margin for the sampled extremes of EI.
    let (start, end) = (0.98 * euler(lo_ei), 2.0 * euler(hi_ei));
    let determinant = |p: f64| -> Result<f64> {
        // Fundamental solutions a (M₀ = 1) and b (F_y = 1/L): states y, φ of each.
        let rhs = |s: f64, y: &[f64; 4]| {
            let ei = flexure.ei_at(s);
            [y[1], (1.0 - p * y[0]) / ei, y[3], (-s / l - p * y[2]) / ei]
        };
        let y = integrate_through(rhs, 0.0, l, &stops, [0.0; 4], tol, &mut 0.0, |_, _| {})?;
        let (ma, mb) = (1.0 - p * y[0], -1.0 - p * y[2]);
        Ok(match tip {
            TipConstraint::Free => ma,
            TipConstraint::Guided => y[1],
            TipConstraint::Pinned => y[0] / l * mb - y[2] / l * ma,
            TipConstraint::Clamped => y[0] / l * y[3] - y[2] / l * y[1],
        })
    };
    let (mut a, mut da) = (start, determinant(start)?);
    let mut steps = 0;
    let mut b = a;
    loop {
        let next = (b * SCAN_RATIO).min(end);
        let dn = determinant(next)?;
        steps += 1;
        if dn == 0.0 {
            return Ok(next);
        }
        if dn.signum() != da.signum() {
            b = next;
            break;
        }
        (a, da, b) = (next, dn, next);
        if next >= end {
            return Err(Error::Singular {
                what: format!(
                    "exact column buckling: no critical load found from {start:e} to {end:e} N ({steps} loads scanned)"
                ),
            });
        }
    }
    for _ in 0..MAX_BISECTIONS {
        let mid = 0.5 * (a + b);
        if mid <= a || mid >= b {
            break;
        }
        let dm = determinant(mid)?;
        if dm == 0.0 {
            return Ok(mid);
        }
        if dm.signum() == da.signum() { (a, da) = (mid, dm) } else { b = mid }
    }
    Ok(0.5 * (a + b))
}
