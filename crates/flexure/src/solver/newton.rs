//! Damped Newton, on $r(x, \lambda) = 0$ at a fixed $\lambda$ or on the
//! bordered pseudo-arclength system of a continuation step.

use super::interrupt::interrupted;
use super::structured::structured_solve;
use super::{Problem, Settings, SolverWorkspace};
use crate::error::{Error, Result};
use crate::linalg;
use crate::scalar::Scalar;

/// Why a Newton solve stopped, as argmin's `TerminationReason` says why an
/// optimizer did ([`NewtonReport::stop`]).
///
/// A solve that returns stopped one way: its residual met the tolerance.
/// Every other end is an error saying what was reached:
/// [`Error::NoConvergence`] at [`Settings::max_iterations`], on a residual
/// that is not finite, on a line search that could not decrease the residual
/// or (in a continuation step) on a corrector that does not contract;
/// [`Error::Singular`] when no diagonal shift lets the Newton matrix factor;
/// [`Error::Interrupted`] when the hook of [`super::with_interrupt`] asks.
///
/// # Example
/// ```
/// use flexure::solver::{newton, NewtonStop, Problem, Settings, SolverWorkspace};
/// /// $r(x, \lambda) = x^2 - 2 - \lambda$: root $\sqrt{2 + \lambda}$.
/// struct Root;
/// impl Problem<f64> for Root {
///     fn dim(&self) -> usize { 1 }
///     fn evaluate(&mut self, x: &[f64], l: f64, r: &mut [f64], j: Option<&mut [f64]>, _: Option<&mut [f64]>)
///         -> flexure::Result<()> {
///         r[0] = x[0] * x[0] - 2.0 - l;
///         if let Some(j) = j { j[0] = 2.0 * x[0]; }
///         Ok(())
///     }
///     fn distance(&self, a: &[f64], b: &[f64]) -> f64 { (a[0] - b[0]).abs() }
///     fn scale(&self) -> f64 { 1.0 }
///     fn unit(&self) -> &'static str { "1" }
///     fn name(&self) -> &'static str { "root" }
/// }
/// let mut ws = SolverWorkspace::new(1);
/// ws.x[0] = 1.0;
/// let report = newton(&mut Root, &mut ws, 0.0, &Settings::default()).unwrap();
/// assert_eq!(report.stop, NewtonStop::Converged);
/// assert!(report.residual <= 1e-12 && (ws.x[0] - 2f64.sqrt()).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NewtonStop {
    /// $\max_i|r_i| \le$ [`Settings::tolerance`] $\times$ [`Problem::scale`]
    /// after at least the iterations asked (one for dual numbers, so their
    /// derivative parts pass through a Newton step).
    Converged,
}

/// What a Newton solve achieved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonReport {
    /// Why it stopped.
    pub stop: NewtonStop,
    /// Iterations taken.
    pub iterations: usize,
    /// Final $\max_i|r_i|$, in the problem's unit.
    pub residual: f64,
}

pub(super) fn amax<T: Scalar>(v: &[T]) -> f64 {
    v.iter().fold(0.0, |m: f64, x| if x.re().is_nan() { f64::NAN } else { m.max(x.re().abs()) })
}

/// Which system a Newton solve works on.
#[derive(Clone, Copy)]
pub(super) enum Mode {
    /// $r(x, \lambda) = 0$ at fixed $\lambda$.
    Fixed,
    /// $r(x, \lambda) = 0$ and $t^T W ((x,\lambda) - \text{anchor}) = 0$ (pseudo-arclength).
    Arclength,
}

/// Evaluates the residual (and the Newton matrix, if `matrix`) of the
/// system `mode` at the unknowns `z` ($x$, then $\lambda$ in arclength mode),
/// with the load derivative in arclength mode or if `load_derivative`.
#[allow(clippy::too_many_arguments)]
fn system<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    mode: Mode,
    z: &[T],
    lambda: f64,
    tangent: &[T],
    anchor: &[T],
    lambda_weight: f64,
    load_derivative: bool,
    residual: &mut [T],
    jacobian: Option<(&mut [T], &mut [T], &mut [T])>,
) -> Result<()> {
    let n = problem.dim();
    let lam = match mode {
        Mode::Fixed => lambda,
        Mode::Arclength => z[n].re(),
    };
    let (x, r) = (&z[..n], &mut residual[..n]);
    match jacobian {
        None => problem.evaluate(x, lam, r, None, None)?,
        Some((jac, dlambda, matrix)) => {
            let dlambda_wanted = load_derivative || matches!(mode, Mode::Arclength);
            problem.evaluate(x, lam, r, Some(&mut *jac), dlambda_wanted.then_some(&mut *dlambda))?;
            // In fixed mode the Newton matrix is the Jacobian itself, read
            // from `jac` ([`correct`]); only the bordered one is assembled.
            if let Mode::Arclength = mode {
                let m = n + 1;
                for c in 0..n {
                    matrix[c * m..c * m + n].copy_from_slice(&jac[c * n..c * n + n]);
                }
                matrix[n * m..n * m + n].copy_from_slice(dlambda);
                for c in 0..n {
                    matrix[c * m + n] = tangent[c] * T::c(problem.weight(c).powi(2));
                }
                matrix[n * m + n] = tangent[n] * T::c(lambda_weight * lambda_weight);
            }
        }
    }
    if let Mode::Arclength = mode {
        let mut s = T::zero();
        for c in 0..n {
            s += tangent[c] * T::c(problem.weight(c).powi(2)) * (z[c] - anchor[c]);
        }
        s += tangent[n] * T::c(lambda_weight * lambda_weight) * (z[n] - anchor[n]);
        residual[n] = s;
    }
    Ok(())
}

/// Damped Newton on `mode`'s system, from and into `ws.trial` (length $n$ or $n+1$).
/// In fixed mode `ws.dlambda` is left at the solution only if `load_derivative`.
#[allow(clippy::too_many_arguments)]
pub(super) fn correct<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    ws: &mut SolverWorkspace<T>,
    mode: Mode,
    lambda: f64,
    lambda_weight: f64,
    settings: &Settings,
    min_iterations: usize,
    contraction: bool,
    load_derivative: bool,
) -> Result<NewtonReport> {
    let n = ws.n;
    let m = match mode {
        Mode::Fixed => n,
        Mode::Arclength => n + 1,
    };
    let tolerance = settings.tolerance * problem.scale();
    let (name, unit) = (problem.name(), problem.unit());
    let SolverWorkspace {
        trial,
        trial_residual,
        jacobian,
        dlambda,
        matrix,
        pivots,
        step,
        tangent,
        anchor,
        scratch,
        aux,
        evaluations,
        ..
    } = ws;
    let matrix = &mut matrix[..m * m];
    let sys = |problem: &mut P, z: &[T], r: &mut [T], jac: Option<(&mut [T], &mut [T], &mut [T])>| {
        system(problem, mode, z, lambda, tangent, anchor, lambda_weight, load_derivative, r, jac)
    };
    *evaluations += 1;
    sys(problem, &trial[..m], trial_residual, Some((jacobian, dlambda, matrix)))?;
    let mut residual = amax(&trial_residual[..m]);
    // Size of the first Newton step, for the contraction test.
    let mut first = 0.0;
    for iteration in 0..=settings.max_iterations {
        if interrupted() {
            return Err(Error::Interrupted { load_fraction: lambda });
        }
        if residual <= tolerance && iteration >= min_iterations {
            return Ok(NewtonReport { stop: NewtonStop::Converged, iterations: iteration, residual });
        }
        let fail = |iterations| Error::NoConvergence { solver: name, iterations, residual, unit };
        if iteration == settings.max_iterations || !residual.is_finite() {
            return Err(fail(iteration));
        }
        for (s, r) in step[..m].iter_mut().zip(&trial_residual[..m]) {
            *s = -*r;
        }
        // Newton step: by the problem's own factorization if it has one;
        // else by LU, where a singular matrix (a free motion, a bifurcation
        // point) is shifted along its diagonal until it factors. The Newton
        // matrix is ∂x r itself in fixed mode, else the bordered one.
        let newton: &[T] = match mode {
            Mode::Fixed => &jacobian[..m * m],
            Mode::Arclength => &matrix[..m * m],
        };
        if !(problem.factor(jacobian) && structured_solve(problem, newton, n, m, &mut step[..m], aux)) {
            // The shift, relative to the largest diagonal entry; that scale
            // is found only when the unshifted matrix does not factor.
            let (mut shift, mut diag) = (0.0, 0.0);
            loop {
                scratch_copy(newton, scratch, m, shift * diag);
                if linalg::lu(&mut scratch[..m * m], m, &mut pivots[..m]) {
                    break;
                }
                if shift == 0.0 {
                    diag = (0..m).map(|i| newton[i * m + i].re().abs()).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
                }
                shift = if shift == 0.0 { 1e-12 } else { shift * 100.0 };
                if shift > 1e2 {
                    return Err(Error::Singular {
                        what: format!(
                            "{name}: the Newton matrix is singular after {iteration} iterations (residual {residual:.3e} {unit}): a motion nothing resists, or constraints that cannot all be met"
                        ),
                    });
                }
            }
            for (s, r) in step[..m].iter_mut().zip(&trial_residual[..m]) {
                *s = -*r;
            }
            linalg::lu_solve(&scratch[..m * m], m, &pivots[..m], &mut step[..m]);
        }
        if contraction && iteration <= 1 {
            // A continuation step must land in the quadratic basin of the
            // branch it follows (Deuflhard's contraction test): the second
            // Newton step at most half the first, and no damping. Otherwise
            // the step is too long and is retried shorter. (Only the first
            // two steps' sizes are compared.)
            let size = (0..m)
                .map(|i| (step[i].re() * if i < n { problem.weight(i) } else { lambda_weight }).powi(2))
                .sum::<f64>()
                .sqrt();
            match iteration {
                0 => first = size,
                1 if size > CONTRACTION * first && first > 0.0 => {
                    return Err(Error::NoConvergence { solver: name, iterations: iteration, residual, unit });
                }
                _ => {}
            }
        }
        // Backtrack on the residual norm; near the tolerance accept a full
        // step that does not grow the residual much (rounding).
        let mut t = 1.0;
        loop {
            for i in 0..m {
                trial[i] += step[i] * T::c(t);
            }
            // The trial is evaluated with its Jacobian: accepted trials (most)
            // then need no second evaluation.
            *evaluations += 1;
            let ok = sys(problem, &trial[..m], trial_residual, Some((jacobian, dlambda, matrix))).is_ok();
            let rt = amax(&trial_residual[..m]);
            if ok
                && (rt <= (1.0 - 1e-4 * t) * residual
                    || (t == 1.0 && residual < 1e3 * tolerance && rt < 10.0 * residual))
            {
                break;
            }
            // Undo this trial and halve.
            for i in 0..m {
                trial[i] -= step[i] * T::c(t);
            }
            t *= 0.5;
            if t < 1e-9 || contraction {
                return Err(fail(iteration));
            }
        }
        residual = amax(&trial_residual[..m]);
    }
    unreachable!("the loop returns at max_iterations")
}

/// The largest ratio of the second Newton step to the first that a
/// continuation step accepts: Deuflhard's $\bar\Theta = 1/2$.
const CONTRACTION: f64 = 0.5;

fn scratch_copy<T: Scalar>(matrix: &[T], scratch: &mut [T], m: usize, shift: f64) {
    scratch[..m * m].copy_from_slice(matrix);
    if shift != 0.0 {
        for i in 0..m {
            scratch[i * m + i] += T::c(shift);
        }
    }
}

/// Damped Newton on $r(x, \lambda) = 0$ at fixed $\lambda$, from `ws.x`
/// (updated in place; `ws.jacobian` holds $\partial_x r$ at the solution).
///
/// Each step solves $\partial_x r\thinspace\delta = -r$ by LU (shifting a singular
/// matrix along its diagonal), then halves until $\max|r|$ decreases.
/// Stops with [`Error::NoConvergence`] at the iteration limit.
pub fn newton<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    ws: &mut SolverWorkspace<T>,
    lambda: f64,
    settings: &Settings,
) -> Result<NewtonReport> {
    settings.validate()?;
    check_dim(problem, ws)?;
    let n = ws.n;
    ws.start = None;
    ws.trial[..n].copy_from_slice(&ws.x);
    let min_iterations = if T::is_value() { 0 } else { 1 };
    let report = correct(problem, ws, Mode::Fixed, lambda, 1.0, settings, min_iterations, false, true)?;
    ws.x.copy_from_slice(&ws.trial[..n]);
    ws.lambda = lambda;
    ws.start = (lambda == 0.0).then_some(report);
    Ok(report)
}

pub(super) fn check_dim<T: Scalar, P: Problem<T>>(problem: &P, ws: &SolverWorkspace<T>) -> Result<()> {
    if problem.dim() != ws.n {
        return Err(Error::invalid("workspace", ws.n, "was made for a problem of another size"));
    }
    Ok(())
}
