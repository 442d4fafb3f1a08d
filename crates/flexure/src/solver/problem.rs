//! The problem the solver core solves: a family of square systems in the
//! load factor, with its stability tests and optional structured solves.

use crate::error::Result;
use crate::scalar::Scalar;
#[cfg(doc)]
use {
    super::{FAR_STEP, Settings},
    crate::linalg,
};

/// A family of square systems $r(x, \lambda) = 0$.
pub trait Problem<T: Scalar> {
    /// Number of unknowns $n$.
    fn dim(&self) -> usize;

    /// Writes $r(x, \lambda)$ and, when asked, the column-major
    /// $n\times n$ Jacobian $\partial_x r$ and the load derivative
    /// $\partial_\lambda r$. An `Err` marks a state that cannot be evaluated.
    fn evaluate(
        &mut self,
        x: &[T],
        lambda: f64,
        residual: &mut [T],
        jacobian: Option<&mut [T]>,
        dlambda: Option<&mut [T]>,
    ) -> Result<()>;

    /// Whether the state just evaluated (with its Jacobian) is stable.
    /// Potential problems, whose Jacobian is the Hessian of the potential,
    /// test its definiteness ([`linalg::positive_definite`]); problems with
    /// no notion of stability keep the default, `true`.
    fn stable(&mut self, _x: &[T], _lambda: f64, _jacobian: &[T]) -> bool {
        true
    }

    /// Whether the state just evaluated is far from any loss of stability:
    /// its Jacobian stays positive definite with a margin, so no fold or
    /// bifurcation is near and the continuation may take steps
    /// [`FAR_STEP`] times longer. The default, `false`, keeps every step
    /// within [`Settings::max_rotation_per_step`].
    fn far_from_instability(&mut self, _x: &[T], _lambda: f64, _jacobian: &[T]) -> bool {
        false
    }

    /// Factors $\partial_x r$ (the `jacobian` of the last evaluation) by
    /// the problem's own structure, for [`Problem::solve_factored`]; a
    /// mechanism's tree, for one, factors in $O(n)$ where dense LU costs
    /// $O(n^3)$. The default, `false`, leaves the solver to its dense LU,
    /// as does a `false` answer (a singular pivot). The solver checks
    /// every structured solve by its residual against the dense matrix
    /// (and falls back to LU if it is not accurate), solves bordered
    /// systems by block elimination with two such solves, and factors
    /// again before each use: [`Problem::stable`] and
    /// [`Problem::far_from_instability`] may use the same buffers.
    fn factor(&mut self, _jacobian: &[T]) -> bool {
        false
    }

    /// Solves $\partial_x r\thinspace y = b$ in place (`b` in, $y$ out) with
    /// the last factorization for which [`Problem::factor`] returned `true`.
    fn solve_factored(&mut self, _b: &mut [T]) {}

    /// How far apart two states are, in radians: the largest rotation of a
    /// cross-section or body between them. Bounds the continuation's steps.
    fn distance(&self, a: &[T], b: &[T]) -> f64;

    /// The residual's scale: Newton stops when $\max_i |r_i| \le$
    /// tolerance × scale.
    fn scale(&self) -> f64;

    /// The residual's unit, for messages.
    fn unit(&self) -> &'static str;

    /// The problem's name, for messages.
    fn name(&self) -> &'static str;

    /// Weight of unknown `i` in the arc length (default 1: radians and
    /// dimensionless coordinates).
    fn weight(&self, _i: usize) -> f64 {
        1.0
    }
}

/// Asserts a problem's Jacobian and load derivative at `(x, λ)` against
/// central differences of its residual: step 1e-6 (truncation about
/// 1e-12, rounding about 1e-10 of residuals of order 1), so they agree to
/// 1e-6 absolute. Every problem's derivative test calls it.
#[cfg(test)]
pub(crate) fn assert_derivatives<P: Problem<f64>>(problem: &mut P, x: &[f64], lambda: f64) {
    let n = problem.dim();
    let (mut r, mut jac, mut dl) = (vec![0.0; n], vec![0.0; n * n], vec![0.0; n]);
    problem.evaluate(x, lambda, &mut r, Some(&mut jac), Some(&mut dl)).unwrap();
    let h = 1e-6;
    let mut residual_at = |x: &[f64], lambda: f64| {
        let mut r = vec![0.0; n];
        problem.evaluate(x, lambda, &mut r, None, None).unwrap();
        r
    };
    for col in 0..n {
        let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
        xp[col] += h;
        xm[col] -= h;
        let (rp, rm) = (residual_at(&xp, lambda), residual_at(&xm, lambda));
        for row in 0..n {
            let fd = (rp[row] - rm[row]) / (2.0 * h);
            assert!((jac[col * n + row] - fd).abs() < 1e-6, "J[{row},{col}] {} vs {fd}", jac[col * n + row]);
        }
    }
    let (rp, rm) = (residual_at(x, lambda + h), residual_at(x, lambda - h));
    for row in 0..n {
        let fd = (rp[row] - rm[row]) / (2.0 * h);
        assert!((dl[row] - fd).abs() < 1e-6, "∂r{row}/∂λ {} vs {fd}", dl[row]);
    }
}
