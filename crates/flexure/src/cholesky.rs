//! In-place Cholesky factorization on column-major slices.
//!
//! Used on the solver's hot path, where nalgebra's owned decompositions
//! would allocate; generic so dual numbers pass through.

use crate::scalar::Scalar;

/// Overwrites the lower triangle of the $n\times n$ column-major `a` with
/// $L$, $A = LL^T$. Returns `false` (leaving `a` partly overwritten) unless
/// $A$ is positive definite.
///
/// # Example
/// ```
/// let mut a = [4.0, 2.0, 2.0, 3.0];
/// assert!(flexure::cholesky::factor(&mut a, 2));
/// let mut b = [2.0, 1.0];
/// flexure::cholesky::solve(&a, 2, &mut b);
/// assert!((b[0] - 0.5).abs() < 1e-15 && b[1].abs() < 1e-15);
/// ```
pub fn factor<T: Scalar>(a: &mut [T], n: usize) -> bool {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[k * n + j] * a[k * n + j];
        }
        if d.re().is_nan() || d.re() <= 0.0 {
            return false;
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[j * n + i];
            for k in 0..j {
                s -= a[k * n + i] * a[k * n + j];
            }
            a[j * n + i] = s / d;
        }
    }
    true
}

/// Solves $LL^T x = b$ in place, with `l` from [`factor`].
pub fn solve<T: Scalar>(l: &[T], n: usize, b: &mut [T]) {
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[k * n + i] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[i * n + k] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
}
