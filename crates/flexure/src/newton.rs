//! A small Newton minimizer and a damped Newton root finder.
//!
//! Our own rather than argmin or levenberg-marquardt: those still depend on
//! nalgebra 0.34, a second, incompatible nalgebra. The minimizer is generic
//! over [`Scalar`] so that `num-dual` differentiates through the iterations,
//! and it works in caller-owned buffers so the hot path does not allocate.

use crate::error::{Error, Result};
use crate::linalg;
use crate::scalar::Scalar;
use nalgebra::{SMatrix, SVector};

/// Stopping rules.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Stop when $\lVert\nabla f\rVert_\infty$ is at most this (absolute, in the objective's units).
    pub tolerance: f64,
    /// Iteration limit.
    pub max_iterations: usize,
}

/// A smooth function with exact gradient and Hessian.
pub trait Objective<T: Scalar> {
    /// Returns $f(x)$ and writes $\nabla f$ and the column-major Hessian.
    fn evaluate(&mut self, x: &[T], gradient: &mut [T], hessian: &mut [T]) -> T;
}

/// Buffers for [`minimize`]; `x` holds the start and, after success, the minimizer.
#[derive(Debug, Clone)]
pub struct Workspace<T: Scalar> {
    n: usize,
    /// Current point.
    pub x: Vec<T>,
    /// Gradient at `x`.
    pub gradient: Vec<T>,
    /// Column-major Hessian at `x`.
    pub hessian: Vec<T>,
    factor: Vec<T>,
    step: Vec<T>,
    trial_x: Vec<T>,
    trial_gradient: Vec<T>,
    trial_hessian: Vec<T>,
}

impl<T: Scalar> Workspace<T> {
    /// Buffers for an `n`-dimensional problem.
    pub fn new(n: usize) -> Self {
        let z = T::zero();
        Self {
            n,
            x: vec![z; n],
            gradient: vec![z; n],
            hessian: vec![z; n * n],
            factor: vec![z; n * n],
            step: vec![z; n],
            trial_x: vec![z; n],
            trial_gradient: vec![z; n],
            trial_hessian: vec![z; n * n],
        }
    }
}

/// What [`minimize`] achieved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Report {
    /// Newton iterations taken.
    pub iterations: usize,
    /// Final $\lVert\nabla f\rVert_\infty$.
    pub residual: f64,
    /// Whether the Hessian at the solution is positive definite (a strict local minimum).
    pub positive_definite: bool,
}

fn norm_inf<T: Scalar>(v: &[T]) -> f64 {
    v.iter().fold(0.0, |m, x| if x.re().abs() > m || x.re().is_nan() { x.re().abs() } else { m })
}

/// Newton's method with a Levenberg shift where the Hessian is indefinite
/// and an Armijo backtracking line search on $f$.
///
/// A full step is also accepted when the Hessian is positive definite and the
/// gradient shrinks, since near the solution $f$ changes below its rounding.
/// Without convergence it returns [`Error::NoConvergence`] with the residual.
pub fn minimize<T: Scalar, O: Objective<T>>(
    objective: &mut O,
    ws: &mut Workspace<T>,
    settings: &Settings,
) -> Result<Report> {
    let n = ws.n;
    let mut f = objective.evaluate(&ws.x, &mut ws.gradient, &mut ws.hessian);
    for iteration in 0..=settings.max_iterations {
        let residual = norm_inf(&ws.gradient);
        ws.factor.copy_from_slice(&ws.hessian);
        let positive_definite = linalg::cholesky(&mut ws.factor, n);
        if residual <= settings.tolerance {
            return Ok(Report { iterations: iteration, residual, positive_definite });
        }
        if iteration == settings.max_iterations || !residual.is_finite() {
            return Err(Error::NoConvergence {
                unit: "gradient units",
                solver: "Newton minimizer",
                iterations: iteration,
                residual,
            });
        }
        if !positive_definite {
            shift_until_positive_definite(ws);
        }
        for (p, &g) in ws.step.iter_mut().zip(&ws.gradient) {
            *p = -g;
        }
        linalg::cholesky_solve(&ws.factor, n, &mut ws.step);
        let slope: f64 = ws.step.iter().zip(&ws.gradient).map(|(p, g)| p.re() * g.re()).sum();
        let mut t = 1.0;
        loop {
            for ((xt, &x), &p) in ws.trial_x.iter_mut().zip(&ws.x).zip(&ws.step) {
                *xt = x + T::c(t) * p;
            }
            let ft = objective.evaluate(&ws.trial_x, &mut ws.trial_gradient, &mut ws.trial_hessian);
            let armijo = ft.re() <= f.re() + 1e-4 * t * slope;
            let shrinking = positive_definite && t == 1.0 && norm_inf(&ws.trial_gradient) < residual;
            if armijo || shrinking {
                f = ft;
                break;
            }
            t *= 0.5;
            if t < 1e-12 {
                return Err(Error::NoConvergence {
                    unit: "gradient units",
                    solver: "Newton line search",
                    iterations: iteration,
                    residual,
                });
            }
        }
        std::mem::swap(&mut ws.x, &mut ws.trial_x);
        std::mem::swap(&mut ws.gradient, &mut ws.trial_gradient);
        std::mem::swap(&mut ws.hessian, &mut ws.trial_hessian);
    }
    unreachable!("the loop returns at max_iterations")
}

/// Factors $H + \tau I$ with the least $\tau = 10^k\tau_0$ that is positive definite.
fn shift_until_positive_definite<T: Scalar>(ws: &mut Workspace<T>) {
    let n = ws.n;
    let scale = (0..n).map(|i| ws.hessian[i * n + i].re().abs()).fold(0.0, f64::max).max(1e-300);
    let mut tau = 1e-6 * scale;
    loop {
        ws.factor.copy_from_slice(&ws.hessian);
        for i in 0..n {
            ws.factor[i * n + i] += T::c(tau);
        }
        if linalg::cholesky(&mut ws.factor, n) {
            return;
        }
        tau *= 10.0;
        if !tau.is_finite() {
            // Non-finite Hessian: fall back to steepest descent.
            ws.factor.fill(T::zero());
            for i in 0..n {
                ws.factor[i * n + i] = T::one();
            }
            return;
        }
    }
}

/// Outcome of [`find_root`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Root<const D: usize> {
    /// The root.
    pub x: SVector<f64, D>,
    /// Iterations taken.
    pub iterations: usize,
    /// Final $\lVert F\rVert_\infty$.
    pub residual: f64,
}

/// Damped Newton for a square system $F(x) = 0$ whose Jacobian the caller
/// supplies (for shooting, from dual numbers through the integrator).
///
/// A step is halved until $\lVert F\rVert$ decreases or $F$ can be evaluated.
pub fn find_root<const D: usize>(
    mut f: impl FnMut(&SVector<f64, D>) -> Result<(SVector<f64, D>, SMatrix<f64, D, D>)>,
    x0: SVector<f64, D>,
    tolerance: f64,
    max_iterations: usize,
) -> Result<Root<D>> {
    let mut x = x0;
    let (mut r, mut jac) = f(&x)?;
    for iteration in 0..=max_iterations {
        let residual = r.amax();
        if residual <= tolerance {
            return Ok(Root { x, iterations: iteration, residual });
        }
        let fail =
            Error::NoConvergence { unit: "residual units", solver: "Newton shooting", iterations: iteration, residual };
        if iteration == max_iterations || !residual.is_finite() {
            return Err(fail);
        }
        // Dynamic LU: nalgebra's fixed-size LU needs typenum bounds on D.
        let lu = nalgebra::DMatrix::from_column_slice(D, D, jac.as_slice()).lu();
        let step = lu.solve(&nalgebra::DVector::from_column_slice((-r).as_slice())).ok_or(fail.clone())?;
        let step = SVector::<f64, D>::from_column_slice(step.as_slice());
        let mut t = 1.0;
        loop {
            let trial = x + step * t;
            if let Ok((rt, jt)) = f(&trial)
                && (rt.amax() < residual || (t == 1.0 && rt.amax() < 2.0 * residual && residual < 1e3 * tolerance))
            {
                x = trial;
                r = rt;
                jac = jt;
                break;
            }
            t *= 0.5;
            if t < 1e-6 {
                return Err(fail);
            }
        }
    }
    unreachable!("the loop returns at max_iterations")
}
