//! An adaptive Dormand–Prince 5(4) integrator.
//!
//! Our own rather than ode_solvers, which still depends on nalgebra 0.34, a
//! second, incompatible nalgebra. Generic over [`Scalar`]: step sizes are
//! chosen from value parts only, so `num-dual` numbers carried through it
//! give the exact derivative of the discrete solution (for shooting Jacobians).

use crate::error::{Error, Result};
use crate::scalar::Scalar;

/// Error control.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Relative tolerance per step.
    pub relative: f64,
    /// Absolute tolerance per step.
    pub absolute: f64,
    /// Step limit.
    pub max_steps: usize,
}

impl Default for Tolerance {
    fn default() -> Self {
        Self { relative: 1e-12, absolute: 1e-13, max_steps: 100_000 }
    }
}

impl Tolerance {
    /// Checks that both tolerances are finite and non-negative, not both
    /// zero, and that `max_steps` is from 1 to [`crate::solver::MAX_COUNT`].
    ///
    /// # Example
    /// ```
    /// let t = flexure::ode::Tolerance { relative: 0.0, absolute: 0.0, max_steps: 10 };
    /// assert!(t.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<()> {
        let non_negative = |name: &'static str, v: f64| {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(Error::invalid(name, v, "must be a finite number, zero or greater"))
            }
        };
        non_negative("relative", self.relative)?;
        non_negative("absolute", self.absolute)?;
        if self.relative == 0.0 && self.absolute == 0.0 {
            return Err(Error::invalid("absolute", self.absolute, "and relative cannot both be zero"));
        }
        crate::error::count("max_steps", self.max_steps, crate::solver::MAX_COUNT, "must be from 1 to 1000000")?;
        Ok(())
    }
}

const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0.0, 0.0],
    [9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0.0],
    [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0],
];
/// Fifth-order weights minus the embedded fourth-order ones.
const E: [f64; 7] =
    [71.0 / 57600.0, 0.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0];

/// Integrates $dy/ds = f(s, y)$ from `s0` to `s1`, calling `observe` at the
/// start and after every accepted step; returns $y(s_1)$.
///
/// # Example
/// ```
/// use flexure::ode::{integrate, Tolerance};
/// // y' = y, y(0) = 1: y(1) = e.
/// let y = integrate(|_, y: &[f64; 1]| [y[0]], 0.0, 1.0, [1.0], &Tolerance::default(), |_, _| {}).unwrap();
/// assert!((y[0] - std::f64::consts::E).abs() < 1e-11);
/// ```
pub fn integrate<T: Scalar, const D: usize>(
    f: impl FnMut(f64, &[T; D]) -> [T; D],
    s0: f64,
    s1: f64,
    y0: [T; D],
    tol: &Tolerance,
    observe: impl FnMut(f64, &[T; D]),
) -> Result<[T; D]> {
    integrate_from(f, s0, s1, y0, tol, &mut 0.0, observe)
}

/// [`integrate`], trying `step` first (0: a hundredth of the span) and
/// leaving in it the step the integrator would take next, so that spans
/// integrated one after another (multiple shooting) do not each start small.
///
/// # Example
/// ```
/// use flexure::ode::{integrate_from, Tolerance};
/// let mut step = 0.0;
/// let tol = Tolerance::default();
/// let half = integrate_from(|_, y: &[f64; 1]| [y[0]], 0.0, 0.5, [1.0], &tol, &mut step, |_, _| {}).unwrap();
/// let one = integrate_from(|_, y: &[f64; 1]| [y[0]], 0.5, 1.0, half, &tol, &mut step, |_, _| {}).unwrap();
/// assert!(step > 0.0 && (one[0] - std::f64::consts::E).abs() < 1e-11);
/// ```
pub fn integrate_from<T: Scalar, const D: usize>(
    mut f: impl FnMut(f64, &[T; D]) -> [T; D],
    s0: f64,
    s1: f64,
    y0: [T; D],
    tol: &Tolerance,
    step: &mut f64,
    mut observe: impl FnMut(f64, &[T; D]),
) -> Result<[T; D]> {
    tol.validate()?;
    crate::error::finite("s0", s0)?;
    crate::error::finite("s1", s1)?;
    let span = s1 - s0;
    let mut s = s0;
    let mut y = y0;
    observe(s, &y);
    if span == 0.0 {
        return Ok(y);
    }
    let mut h = if step.is_finite() && *step != 0.0 { step.abs().min(span.abs()) * span.signum() } else { span * 1e-2 };
    let mut k = [[T::zero(); D]; 7];
    k[0] = f(s, &y);
    for _ in 0..tol.max_steps {
        // The last step is shortened to land on s1.
        let last = (s + h - s1) * span.signum() >= 0.0;
        let dh = if last { s1 - s } else { h };
        for stage in 1..7 {
            let mut yi = y;
            for (j, kj) in k.iter().enumerate().take(stage) {
                let a = A[stage][j];
                if a != 0.0 {
                    for (v, &d) in yi.iter_mut().zip(kj) {
                        *v += T::c(dh * a) * d;
                    }
                }
            }
            k[stage] = f(s + C[stage] * dh, &yi);
        }
        // The seventh stage was evaluated at the fifth-order solution.
        let mut y_new = y;
        for (j, kj) in k.iter().enumerate().take(6) {
            for (v, &d) in y_new.iter_mut().zip(kj) {
                *v += T::c(dh * A[6][j]) * d;
            }
        }
        let mut err = 0.0;
        for i in 0..D {
            let e: f64 = (0..7).map(|j| E[j] * k[j][i].re()).sum::<f64>() * dh;
            let sc = tol.absolute + tol.relative * y[i].re().abs().max(y_new[i].re().abs());
            err += (e / sc).powi(2);
        }
        let err = (err / D as f64).sqrt();
        if !err.is_finite() {
            return Err(Error::NoConvergence {
                unit: "relative",
                solver: "Dormand-Prince integrator (non-finite state)",
                iterations: 0,
                residual: f64::INFINITY, // the state blew up: no finite residual
            });
        }
        let factor = if err == 0.0 { 5.0 } else { (0.9 * err.powf(-0.2)).clamp(0.2, 5.0) };
        if err <= 1.0 {
            s = if last { s1 } else { s + dh };
            y = y_new;
            k[0] = k[6];
            observe(s, &y);
            if last {
                // The next span's first step: the longer of the proposal
                // and the grown last step (shortened only to land on s1).
                *step = if (dh * factor).abs() > h.abs() { dh * factor } else { h };
                return Ok(y);
            }
        }
        h = dh * factor;
        if (h / span).abs() < 1e-14 {
            break;
        }
    }
    Err(Error::NoConvergence {
        unit: "relative",
        solver: "Dormand-Prince integrator (step limit)",
        iterations: tol.max_steps,
        residual: f64::INFINITY, // no step met the tolerance
    })
}

/// [`integrate_from`] in pieces, restarting at each of `stops` that lies
/// strictly inside $(s_0, s_1)$ (increasing when $s_1 > s_0$): where the
/// right-hand side has a kink (a section's breakpoint), an adaptive step
/// that straddles it loses its order; landing on it does not. Each stop
/// is landed on exactly, so `observe` sees the state there with $s$ equal
/// to the stop; it sees $s_0$ once, at the start.
///
/// # Example
/// ```
/// use flexure::ode::{integrate_through, Tolerance};
/// // y' = |s − 0.3|: a kink at 0.3; y(1) = (0.09 + 0.49)/2 = 0.29.
/// let mut step = 0.0;
/// let mut seen = Vec::new();
/// let f = |s: f64, _: &[f64; 1]| [(s - 0.3).abs()];
/// let y = integrate_through(f, 0.0, 1.0, &[0.3], [0.0], &Tolerance::default(), &mut step, |s, _| seen.push(s))
///     .unwrap();
/// assert!((y[0] - 0.29).abs() < 1e-13 && seen.contains(&0.3));
/// ```
#[allow(clippy::too_many_arguments)]
pub fn integrate_through<T: Scalar, const D: usize>(
    mut f: impl FnMut(f64, &[T; D]) -> [T; D],
    s0: f64,
    s1: f64,
    stops: &[f64],
    y0: [T; D],
    tol: &Tolerance,
    step: &mut f64,
    mut observe: impl FnMut(f64, &[T; D]),
) -> Result<[T; D]> {
    let forward = s1 >= s0;
    let inside = |s: &&f64| if forward { **s > s0 && **s < s1 } else { **s < s0 && **s > s1 };
    let mut from = s0;
    let mut y = y0;
    let mut first = true;
    let ends = stops.iter().filter(inside).copied().chain(std::iter::once(s1));
    for to in ends {
        if (to - from) * (s1 - s0) <= 0.0 && to != s1 {
            continue; // stops out of order are skipped
        }
        let skip = !first;
        y = integrate_from(&mut f, from, to, y, tol, step, |s, y: &[T; D]| {
            if !(skip && s == from) {
                observe(s, y)
            }
        })?;
        (from, first) = (to, false);
    }
    Ok(y)
}
