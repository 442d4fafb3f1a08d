//! The solver's buffers, allocated once per problem size.

use super::NewtonReport;
#[cfg(doc)]
use super::{Path, Problem, Settings, continuation, newton};
use crate::scalar::Scalar;

/// Buffers for [`newton`](fn@newton) and [`continuation`](fn@continuation) on an $n$-unknown problem;
/// nothing is allocated once they exist.
#[derive(Debug, Clone)]
pub struct SolverWorkspace<T: Scalar> {
    pub(super) n: usize,
    /// The current state $x$: the start on entry, the solution on success.
    pub x: Vec<T>,
    /// $\lambda$ of the current state.
    pub lambda: f64,
    /// Jacobian $\partial_x r$ at the solution (column-major $n\times n$).
    pub jacobian: Vec<T>,
    /// Set by a caller that has just converged `x` at $\lambda = 0$ by
    /// [`newton`](fn@newton) on the same problem and tested its stability (the value):
    /// the next [`continuation`](fn@continuation) then starts from `x` as it stands, with the
    /// Jacobian and load derivative that solve left, instead of solving and
    /// testing again. Every continuation resets it; it is ignored unless
    /// the last call on this workspace was that [`newton`](fn@newton) at $\lambda = 0$.
    pub start_stable: Option<bool>,
    /// What the last [`newton`](fn@newton) reached, if it was at $\lambda = 0$.
    pub(super) start: Option<NewtonReport>,
    pub(super) dlambda: Vec<T>,
    /// Augmented $(n+1)$ system and its factors.
    pub(super) matrix: Vec<T>,
    pub(super) pivots: Vec<usize>,
    pub(super) step: Vec<T>,
    pub(super) trial: Vec<T>,
    pub(super) trial_residual: Vec<T>,
    /// Tangent $(t_x, t_\lambda)$ and the previous one, in unscaled units.
    pub(super) tangent: Vec<T>,
    pub(super) previous_tangent: Vec<T>,
    pub(super) anchor: Vec<T>,
    pub(super) scratch: Vec<T>,
    /// Five vectors of length $n+1$ for structured solves ([`Problem::factor`]).
    pub(super) aux: Vec<T>,
    /// A Jacobian, its LU factors and pivots, and whether they are valid
    /// and finite: kept for the first tangent of the next continuation
    /// from the same start (the first tangent along the load).
    pub(super) factored: Vec<T>,
    pub(super) factors: Vec<T>,
    pub(super) factor_pivots: Vec<usize>,
    pub(super) factors_valid: bool,
    /// Evaluations of the problem with its Jacobian made on these buffers
    /// so far: the work count that [`Settings::max_evaluations`] bounds.
    pub(super) evaluations: usize,
}

impl<T: Scalar> SolverWorkspace<T> {
    /// Buffers for an `n`-unknown problem.
    pub fn new(n: usize) -> Self {
        let z = T::zero();
        let m = n + 1;
        Self {
            n,
            x: vec![z; n],
            lambda: 0.0,
            jacobian: vec![z; n * n],
            start_stable: None,
            start: None,
            dlambda: vec![z; n],
            matrix: vec![z; m * m],
            pivots: vec![0; m],
            step: vec![z; m],
            trial: vec![z; m],
            trial_residual: vec![z; m],
            tangent: vec![z; m],
            previous_tangent: vec![z; m],
            anchor: vec![z; m],
            scratch: vec![z; m * m],
            aux: vec![z; 5 * m],
            factored: vec![z; n * n],
            factors: vec![z; n * n],
            factor_pivots: vec![0; n],
            factors_valid: false,
            evaluations: 0,
        }
    }

    /// Number of unknowns the buffers are sized for.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// $\partial_\lambda r$ at the current state, as left by the last
    /// evaluation: for a caller that restores a start ([`SolverWorkspace::restore_start`]).
    pub fn dlambda_mut(&mut self) -> &mut [T] {
        &mut self.dlambda
    }

    /// Declares `x` a start at $\lambda = 0$ that [`newton`](fn@newton) on the same
    /// problem reached as `report` says, with stability `stable`: what
    /// [`SolverWorkspace::start_stable`] does after that solve, for a caller that
    /// kept the solve's result and has put back `x`, [`SolverWorkspace::jacobian`]
    /// and [`SolverWorkspace::dlambda_mut`] exactly as that solve left them.
    pub fn restore_start(&mut self, report: NewtonReport, stable: bool) {
        self.lambda = 0.0;
        self.start = Some(report);
        self.start_stable = Some(stable);
    }
}
