//! Solves by a problem's own factorization ([`super::Problem::factor`]),
//! bordered systems by block elimination, each checked against the dense
//! matrix.

use super::Problem;
use crate::scalar::Scalar;

/// The largest componentwise backward error (Oettli–Prager) a structured
/// solve may leave, after at most one step of iterative refinement, before
/// the solver falls back to dense LU: a Newton step this accurate still
/// cuts the residual by $10^{11}$, well past the default tolerance.
const STRUCTURED_ERROR: f64 = 1e-11;

/// Solves `matrix` $\cdot y$ = `y` in place ($m\times m$, column-major),
/// whose top-left $n\times n$ block is $\partial_x r$, just factored by
/// the problem: directly when $m = n$; when $m = n + 1$ by block
/// elimination of the border,
/// $$\begin{bmatrix} J & c\cr b^T & e\end{bmatrix}\begin{bmatrix} x\cr y_\lambda\end{bmatrix}
/// = \begin{bmatrix} f\cr g\end{bmatrix}:\quad J a = f,\ J w = c,
/// \ y_\lambda = \frac{g - b^Ta}{e - b^Tw},\ x = a - y_\lambda w.$$
/// Block elimination loses accuracy near a fold, where $J$ is nearly
/// singular: the answer is checked against `matrix`, refined once if
/// needed, and refused (`false`, `y` unspecified) unless its
/// componentwise backward error is at most [`STRUCTURED_ERROR`]. `aux`
/// holds $5m$ values.
pub(super) fn structured_solve<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    matrix: &[T],
    n: usize,
    m: usize,
    y: &mut [T],
    aux: &mut [T],
) -> bool {
    let (rhs, rest) = aux.split_at_mut(m);
    let (correction, rest) = rest.split_at_mut(m);
    let (bound, work) = rest.split_at_mut(m);
    rhs.copy_from_slice(&y[..m]);
    if !bordered(problem, matrix, n, m, y, work) {
        return false;
    }
    for refinement in 0..2 {
        // correction = rhs − M y, and the Oettli–Prager bound |M||y| + |rhs|.
        for i in 0..m {
            correction[i] = rhs[i];
            bound[i] = T::c(rhs[i].re().abs());
        }
        for c in 0..m {
            let yc = y[c];
            for r in 0..m {
                let a = matrix[c * m + r];
                correction[r] -= a * yc;
                bound[r] += T::c((a.re() * yc.re()).abs());
            }
        }
        let mut error = 0.0_f64;
        for i in 0..m {
            let (c, b) = (correction[i].re().abs(), bound[i].re());
            if !(c.is_finite() && b.is_finite()) {
                return false;
            }
            if c > 0.0 {
                error = error.max(c / b);
            }
        }
        if error <= STRUCTURED_ERROR {
            return true;
        }
        if refinement == 1 || !bordered(problem, matrix, n, m, correction, work) {
            return false;
        }
        for i in 0..m {
            y[i] += correction[i];
        }
    }
    false
}

/// One structured solve of [`structured_solve`]'s system, in place; `work` holds $2m$ values.
fn bordered<T: Scalar, P: Problem<T>>(
    problem: &mut P,
    matrix: &[T],
    n: usize,
    m: usize,
    y: &mut [T],
    work: &mut [T],
) -> bool {
    if m == n {
        problem.solve_factored(&mut y[..n]);
        return y[..n].iter().all(|v| v.re().is_finite());
    }
    let (a, w) = work.split_at_mut(m);
    a[..n].copy_from_slice(&y[..n]);
    problem.solve_factored(&mut a[..n]);
    w[..n].copy_from_slice(&matrix[n * m..n * m + n]);
    problem.solve_factored(&mut w[..n]);
    let (mut ba, mut bw) = (T::zero(), T::zero());
    for i in 0..n {
        ba += matrix[i * m + n] * a[i];
        bw += matrix[i * m + n] * w[i];
    }
    let den = matrix[n * m + n] - bw;
    if !(den.re().is_finite() && den.re() != 0.0) {
        return false;
    }
    let last = (y[n] - ba) / den;
    for i in 0..n {
        y[i] = a[i] - w[i] * last;
    }
    y[n] = last;
    y[..m].iter().all(|v| v.re().is_finite())
}
