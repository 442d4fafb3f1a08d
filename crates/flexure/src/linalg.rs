//! The library's linear algebra, in one place: in-place Cholesky and LU on
//! column-major slices (the solvers' hot path, generic so dual numbers pass
//! through), the one definiteness test, and null spaces by SVD.

use crate::scalar::Scalar;
use nalgebra::DMatrix;

/// Overwrites the lower triangle of the $n\times n$ column-major `a` with
/// $L$, $A = LL^T$. Returns `false` (leaving `a` partly overwritten) unless
/// $A$ is positive definite.
///
/// # Example
/// ```
/// let mut a = [4.0, 2.0, 2.0, 3.0];
/// assert!(flexure::linalg::cholesky(&mut a, 2));
/// let mut b = [2.0, 1.0];
/// flexure::linalg::cholesky_solve(&a, 2, &mut b);
/// assert!((b[0] - 0.5).abs() < 1e-15 && b[1].abs() < 1e-15);
/// ```
pub fn cholesky<T: Scalar>(a: &mut [T], n: usize) -> bool {
    // Left-looking, by columns: column j of A less L_jk times column k of
    // L, for k = 0, …, j−1 in turn, then scaled. Each entry sees the same
    // operations in the same order as the dot-product form
    // $l_{ij} = (a_{ij} - \sum_k l_{ik}l_{jk})/l_{jj}$ (so the same factor
    // to the bit, tested), but the inner loop runs down contiguous columns.
    // Four columns of L per pass over the target (still k ascending for
    // each entry): a quarter of the loads and stores of column j.
    let a = &mut a[..n * n];
    for j in 0..n {
        let (left, right) = a.split_at_mut(j * n);
        let target = &mut right[j..n];
        let mut quads = left.chunks_exact(4 * n);
        for quad in &mut quads {
            let (c0, rest) = quad.split_at(n);
            let (c1, rest) = rest.split_at(n);
            let (c2, c3) = rest.split_at(n);
            let (l0, l1, l2, l3) = (c0[j], c1[j], c2[j], c3[j]);
            let columns = c0[j..].iter().zip(&c1[j..]).zip(&c2[j..]).zip(&c3[j..]);
            for (t, (((&a0, &a1), &a2), &a3)) in target.iter_mut().zip(columns) {
                let mut v = *t;
                v -= a0 * l0;
                v -= a1 * l1;
                v -= a2 * l2;
                v -= a3 * l3;
                *t = v;
            }
        }
        for column in quads.remainder().chunks_exact(n) {
            let l = column[j];
            for (t, &c) in target.iter_mut().zip(&column[j..]) {
                *t -= c * l;
            }
        }
        let (d, below) = target.split_first_mut().expect("j < n");
        if d.re().is_nan() || d.re() <= 0.0 {
            return false;
        }
        *d = d.sqrt();
        let d = *d;
        for t in below.iter_mut() {
            *t /= d;
        }
    }
    true
}

/// Solves $LL^T x = b$ in place, with `l` from [`cholesky`].
pub fn cholesky_solve<T: Scalar>(l: &[T], n: usize, b: &mut [T]) {
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

/// The one definiteness test: whether the symmetric column-major $n\times n$
/// matrix `a` is positive definite, by Cholesky on a copy (`scratch`, length
/// $n^2$), with every pivot $d_j$ required to exceed $10^{-12}\max_i a_{ii}$
/// so that a matrix singular to rounding counts as not definite.
///
/// # Example
/// ```
/// let mut scratch = [0.0; 4];
/// assert!(flexure::linalg::positive_definite(&[2.0, 1.0, 1.0, 2.0], 2, &mut scratch));
/// assert!(!flexure::linalg::positive_definite(&[1.0, 1.0, 1.0, 1.0], 2, &mut scratch));
/// ```
pub fn positive_definite<T: Scalar>(a: &[T], n: usize, scratch: &mut [T]) -> bool {
    let scale = (0..n).map(|i| a[i * n + i].re()).fold(0.0_f64, f64::max);
    if n == 0 {
        return true;
    }
    if !(scale > 0.0 && scale.is_finite()) {
        return false;
    }
    scratch.copy_from_slice(a);
    for i in 0..n {
        scratch[i * n + i] -= T::c(1e-12 * scale);
    }
    cholesky(scratch, n)
}

/// [`positive_definite`] for an owned matrix (allocates its scratch copy).
pub fn is_positive_definite(a: &DMatrix<f64>) -> bool {
    let n = a.nrows();
    let mut scratch = vec![0.0; n * n];
    positive_definite(a.as_slice(), n, &mut scratch)
}

/// LU factorization with partial pivoting of the $n\times n$ column-major
/// `a`, in place; `pivots[k]` is the row swapped into place at step $k$.
/// Returns `false` if a pivot is zero or not finite (a singular matrix).
pub fn lu<T: Scalar>(a: &mut [T], n: usize, pivots: &mut [usize]) -> bool {
    // Small systems (one flexure's KKT system, a short chain) by the same
    // operations at a size known to the compiler: unrolled, no bounds checks.
    match n {
        2 => return lu_fixed::<T, 2>(a, pivots),
        3 => return lu_fixed::<T, 3>(a, pivots),
        4 => return lu_fixed::<T, 4>(a, pivots),
        5 => return lu_fixed::<T, 5>(a, pivots),
        6 => return lu_fixed::<T, 6>(a, pivots),
        7 => return lu_fixed::<T, 7>(a, pivots),
        8 => return lu_fixed::<T, 8>(a, pivots),
        _ => {}
    }
    lu_any(a, n, pivots)
}

/// [`lu`] for any $n$: left-looking, column by column. Column $j$ takes
/// the earlier steps' row swaps, then their updates
/// $a_{ij} \mathrel{-}= l_{ik}u_{kj}$ for $k = 0, \dots, j-1$ in turn
/// (skipped where $u_{kj} = 0$), then its own pivot. Each entry sees the
/// same operations in the same order as in the right-looking form (a swap
/// of rows at or below $k$ commutes with step $k$'s update), so the same
/// factors to the bit (tested); but four steps pass over the column at once.
fn lu_any<T: Scalar>(a: &mut [T], n: usize, pivots: &mut [usize]) -> bool {
    let a = &mut a[..n * n];
    let pivots = &mut pivots[..n];
    let nonzero = |f: T| f.re() != 0.0 || f != T::zero();
    for j in 0..n {
        let (left, right) = a.split_at_mut(j * n);
        let column = &mut right[..n];
        for (k, &p) in pivots[..j].iter().enumerate() {
            column.swap(k, p);
        }
        let mut k = 0;
        while k < j {
            if k + 4 <= j {
                let l = |c: usize| &left[(k + c) * n..(k + c + 1) * n];
                let (l0, l1, l2, l3) = (l(0), l(1), l(2), l(3));
                // The rows of the four steps themselves, in order: u_kj as they become final.
                let f0 = column[k];
                if nonzero(f0) {
                    column[k + 1] -= l0[k + 1] * f0;
                    column[k + 2] -= l0[k + 2] * f0;
                    column[k + 3] -= l0[k + 3] * f0;
                }
                let f1 = column[k + 1];
                if nonzero(f1) {
                    column[k + 2] -= l1[k + 2] * f1;
                    column[k + 3] -= l1[k + 3] * f1;
                }
                let f2 = column[k + 2];
                if nonzero(f2) {
                    column[k + 3] -= l2[k + 3] * f2;
                }
                let f3 = column[k + 3];
                let below = k + 4;
                if nonzero(f0) && nonzero(f1) && nonzero(f2) && nonzero(f3) {
                    let ls = l0[below..].iter().zip(&l1[below..]).zip(&l2[below..]).zip(&l3[below..]);
                    for (t, (((&a0, &a1), &a2), &a3)) in column[below..].iter_mut().zip(ls) {
                        let mut v = *t;
                        v -= a0 * f0;
                        v -= a1 * f1;
                        v -= a2 * f2;
                        v -= a3 * f3;
                        *t = v;
                    }
                } else {
                    for (f, l) in [(f0, l0), (f1, l1), (f2, l2), (f3, l3)] {
                        if nonzero(f) {
                            for (t, &l) in column[below..].iter_mut().zip(&l[below..]) {
                                *t -= l * f;
                            }
                        }
                    }
                }
                k += 4;
            } else {
                let f = column[k];
                if nonzero(f) {
                    for (t, &l) in column[k + 1..].iter_mut().zip(&left[k * n + k + 1..(k + 1) * n]) {
                        *t -= l * f;
                    }
                }
                k += 1;
            }
        }
        // The first entry of largest magnitude at or below the diagonal
        // (a NaN never wins a comparison).
        let (mut p, mut largest) = (j, column[j].re().abs());
        for (i, v) in column.iter().enumerate().skip(j + 1) {
            if v.re().abs() > largest {
                (p, largest) = (i, v.re().abs());
            }
        }
        let pivot = column[p].re();
        if !(pivot.is_finite() && pivot != 0.0) {
            return false;
        }
        pivots[j] = p;
        if p != j {
            for c in left.chunks_exact_mut(n) {
                c.swap(j, p);
            }
            column.swap(j, p);
        }
        let (d, below) = column[j..].split_first_mut().expect("j < n");
        let d = *d;
        for l in below.iter_mut() {
            *l /= d;
        }
    }
    true
}

/// [`lu`] for $N\times N$ ($N \le 8$): the same operations in the same
/// order (so the same factors to the bit), with every step's size known to
/// the compiler, so that all loops unroll.
#[inline(always)]
fn lu_fixed<T: Scalar, const N: usize>(a: &mut [T], pivots: &mut [usize]) -> bool {
    let columns: &mut [[T; N]; N] = a[..N * N].as_chunks_mut::<N>().0.try_into().expect("N columns");
    let pivots: &mut [usize; N] = (&mut pivots[..N]).try_into().expect("N pivots");
    // The steps spelled out, k a constant in each.
    macro_rules! steps {
        ($($k:literal)*) => {
            $(if $k < N && !lu_step::<T, N>(columns, pivots, $k) {
                return false;
            })*
        };
    }
    steps!(0 1 2 3 4 5 6 7);
    true
}

/// Step `k` of [`lu_fixed`]: pivot, swap, scale column `k`, update the rest.
#[inline(always)]
fn lu_step<T: Scalar, const N: usize>(columns: &mut [[T; N]; N], pivots: &mut [usize; N], k: usize) -> bool {
    let (mut p, mut largest) = (k, columns[k][k].re().abs());
    for i in k + 1..N {
        if columns[k][i].re().abs() > largest {
            (p, largest) = (i, columns[k][i].re().abs());
        }
    }
    let pivot = columns[k][p].re();
    if !(pivot.is_finite() && pivot != 0.0) {
        return false;
    }
    pivots[k] = p;
    if p != k {
        for column in columns.iter_mut() {
            column.swap(k, p);
        }
    }
    let d = columns[k][k];
    for i in k + 1..N {
        columns[k][i] /= d;
    }
    let l = columns[k];
    for column in columns[k + 1..].iter_mut() {
        let f = column[k];
        if f.re() != 0.0 || f != T::zero() {
            for i in k + 1..N {
                column[i] -= l[i] * f;
            }
        }
    }
    true
}

/// Solves $Ax = b$ in place with the factors from [`lu`].
///
/// # Example
/// ```
/// use flexure::linalg::{lu, lu_solve};
/// let mut a = [0.0, 1.0, 2.0, 3.0]; // columns (0, 1) and (2, 3)
/// let mut piv = [0; 2];
/// assert!(lu(&mut a, 2, &mut piv));
/// let mut b = [4.0, 5.0];
/// lu_solve(&a, 2, &piv, &mut b);
/// assert!((b[0] + 1.0).abs() < 1e-15 && (b[1] - 2.0).abs() < 1e-15);
/// ```
pub fn lu_solve<T: Scalar>(a: &[T], n: usize, pivots: &[usize], b: &mut [T]) {
    lu_forward(a, n, pivots, b);
    lu_backward(a, n, b);
}

/// The first half of [`lu_solve`]: $b \leftarrow L^{-1}Pb$.
pub fn lu_forward<T: Scalar>(a: &[T], n: usize, pivots: &[usize], b: &mut [T]) {
    match n {
        0 => return,
        2 => return lu_forward_fixed::<T, 2>(a, pivots, b),
        3 => return lu_forward_fixed::<T, 3>(a, pivots, b),
        4 => return lu_forward_fixed::<T, 4>(a, pivots, b),
        5 => return lu_forward_fixed::<T, 5>(a, pivots, b),
        6 => return lu_forward_fixed::<T, 6>(a, pivots, b),
        7 => return lu_forward_fixed::<T, 7>(a, pivots, b),
        8 => return lu_forward_fixed::<T, 8>(a, pivots, b),
        _ => {}
    }
    lu_forward_any(a, n, pivots, b);
}

/// [`lu_forward`] for any $n \ge 1$.
fn lu_forward_any<T: Scalar>(a: &[T], n: usize, pivots: &[usize], b: &mut [T]) {
    let (a, pivots, b) = (&a[..n * n], &pivots[..n], &mut b[..n]);
    for (k, &p) in pivots.iter().enumerate() {
        b.swap(k, p);
    }
    for (j, column) in a.chunks_exact(n).enumerate() {
        let (head, tail) = b.split_at_mut(j + 1);
        let bj = head[j];
        for (bi, &l) in tail.iter_mut().zip(&column[j + 1..]) {
            *bi -= l * bj;
        }
    }
}

/// The second half of [`lu_solve`]: $b \leftarrow U^{-1}b$.
pub fn lu_backward<T: Scalar>(a: &[T], n: usize, b: &mut [T]) {
    match n {
        0 => return,
        2 => return lu_backward_fixed::<T, 2>(a, b),
        3 => return lu_backward_fixed::<T, 3>(a, b),
        4 => return lu_backward_fixed::<T, 4>(a, b),
        5 => return lu_backward_fixed::<T, 5>(a, b),
        6 => return lu_backward_fixed::<T, 6>(a, b),
        7 => return lu_backward_fixed::<T, 7>(a, b),
        8 => return lu_backward_fixed::<T, 8>(a, b),
        _ => {}
    }
    lu_backward_any(a, n, b);
}

/// [`lu_backward`] for any $n \ge 1$.
fn lu_backward_any<T: Scalar>(a: &[T], n: usize, b: &mut [T]) {
    let (a, b) = (&a[..n * n], &mut b[..n]);
    for (j, column) in a.chunks_exact(n).enumerate().rev() {
        let (head, tail) = b.split_at_mut(j);
        let (bj, _) = tail.split_first_mut().expect("j < n");
        *bj /= column[j];
        let bj = *bj;
        for (bi, &u) in head.iter_mut().zip(column) {
            *bi -= u * bj;
        }
    }
}

/// [`lu_forward`] for $N\times N$, by the same operations.
#[inline(always)]
fn lu_forward_fixed<T: Scalar, const N: usize>(a: &[T], pivots: &[usize], b: &mut [T]) {
    let columns: &[[T; N]; N] = a[..N * N].as_chunks::<N>().0.try_into().expect("N columns");
    let b: &mut [T; N] = (&mut b[..N]).try_into().expect("N values");
    for (k, &p) in pivots[..N].iter().enumerate() {
        b.swap(k, p);
    }
    for j in 0..N {
        let bj = b[j];
        for i in j + 1..N {
            b[i] -= columns[j][i] * bj;
        }
    }
}

/// [`lu_backward`] for $N\times N$, by the same operations.
#[inline(always)]
fn lu_backward_fixed<T: Scalar, const N: usize>(a: &[T], b: &mut [T]) {
    let columns: &[[T; N]; N] = a[..N * N].as_chunks::<N>().0.try_into().expect("N columns");
    let b: &mut [T; N] = (&mut b[..N]).try_into().expect("N values");
    for j in (0..N).rev() {
        b[j] /= columns[j][j];
        let bj = b[j];
        for i in 0..j {
            b[i] -= columns[j][i] * bj;
        }
    }
}

/// An orthonormal basis of the null space of the $m\times n$ matrix `g`
/// (the identity when $m = 0$), from its singular value decomposition:
/// singular values at most $10^{-10}\sigma_{max}$ count as zero. Working on
/// $G$ itself, not $G^TG$, keeps the condition number unsquared, so
/// redundant closure equations (many parallel legs) are told from real ones.
///
/// # Example
/// ```
/// use nalgebra::DMatrix;
/// // Two equal rows: one constraint on three coordinates leaves two motions.
/// let g = DMatrix::from_row_slice(2, 3, &[1.0, 1.0, 0.0, 1.0, 1.0, 0.0]);
/// let z = flexure::linalg::null_space(&g);
/// assert_eq!(z.ncols(), 2);
/// assert!((&g * &z).amax() < 1e-14);
/// ```
pub fn null_space(g: &DMatrix<f64>) -> DMatrix<f64> {
    null_space_below(g, 1e-10)
}

/// [`null_space`] with singular values at most `relative` $\sigma_{max}$
/// counting as zero.
///
/// # Example
/// ```
/// use nalgebra::DMatrix;
/// // A 1e-12 mass beside a 1 kg one: massive at 1e-13, massless at 1e-10.
/// let m = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 1e-12]);
/// assert_eq!(flexure::linalg::null_space_below(&m, 1e-13).ncols(), 0);
/// assert_eq!(flexure::linalg::null_space_below(&m, 1e-10).ncols(), 1);
/// ```
pub fn null_space_below(g: &DMatrix<f64>, relative: f64) -> DMatrix<f64> {
    let (m, n) = g.shape();
    if m == 0 {
        return DMatrix::identity(n, n);
    }
    // Pad to at least n rows so the decomposition returns all n right singular vectors.
    let rows = m.max(n);
    let mut padded = DMatrix::zeros(rows, n);
    padded.view_mut((0, 0), (m, n)).copy_from(g);
    let svd = nalgebra::SVD::new(padded, false, true);
    let Some(v_t) = svd.v_t else { return DMatrix::zeros(n, 0) };
    let top = svd.singular_values.amax();
    let keep: Vec<usize> =
        (0..n).filter(|&i| svd.singular_values[i] <= relative * top || svd.singular_values[i].is_nan()).collect();
    if top == 0.0 {
        return DMatrix::identity(n, n);
    }
    DMatrix::from_fn(n, keep.len(), |r, c| v_t[(keep[c], r)])
}

/// Whether the $m$ columns of the $n\times m$ column-major `a` are
/// independent by a wide margin: $A^TA - 10^{-12}\operatorname{tr}(A^TA)\thinspace I$
/// positive definite, so the smallest singular value exceeds
/// $10^{-6}\sigma_{max}$, far above the cut-off of [`null_space`]
/// ($10^{-10}\sigma_{max}$): a true answer is one the singular values would
/// give too, for the cost of an $m\times m$ Cholesky in `gram` ($m^2$ values).
/// False leaves the decision to the singular values.
///
/// # Example
/// ```
/// let mut gram = [0.0; 4];
/// // Columns (1, 0, 0) and (1, 1, 0): independent; (1, 1, 0) twice: not.
/// assert!(flexure::linalg::columns_independent(&[1.0, 0.0, 0.0, 1.0, 1.0, 0.0], 3, 2, &mut gram));
/// assert!(!flexure::linalg::columns_independent(&[1.0, 1.0, 0.0, 1.0, 1.0, 0.0], 3, 2, &mut gram));
/// ```
pub fn columns_independent(a: &[f64], n: usize, m: usize, gram: &mut [f64]) -> bool {
    let gram = &mut gram[..m * m];
    for i in 0..m {
        for k in 0..m {
            gram[k * m + i] = (0..n).map(|r| a[i * n + r] * a[k * n + r]).sum();
        }
    }
    let trace: f64 = (0..m).map(|i| gram[i * m + i]).sum();
    if !(trace > 0.0 && trace.is_finite()) {
        return false;
    }
    for i in 0..m {
        gram[i * m + i] -= 1e-12 * trace;
    }
    cholesky(gram, m)
}

/// An orthonormal basis of the null space of $A^T$, for the $n\times m$
/// column-major `a` of independent columns ([`columns_independent`]): the
/// last $n - m$ columns of $Q$ in $A = QR$ by Householder reflections,
/// written to `z` ($n\times(n-m)$, column-major). `a` is overwritten by
/// $R$ and `v` ($nm$ values) by the reflections. Spans the space of
/// [`null_space`]$(A^T)$ for $O(nm(n-m) + nm^2)$ work and no allocation.
///
/// # Example
/// ```
/// // G = [1 1 0]: its null space is spanned by (1, −1, 0)/√2 and (0, 0, 1).
/// let (mut a, mut z, mut v) = ([1.0, 1.0, 0.0], [0.0; 6], [0.0; 3]);
/// flexure::linalg::null_space_of_transpose(&mut a, 3, 1, &mut z, &mut v);
/// for c in 0..2 {
///     assert!((z[3 * c] + z[3 * c + 1]).abs() < 1e-15); // G z = 0
///     assert!(((0..3).map(|r| z[3 * c + r] * z[3 * c + r]).sum::<f64>() - 1.0).abs() < 1e-15);
/// }
/// ```
pub fn null_space_of_transpose(a: &mut [f64], n: usize, m: usize, z: &mut [f64], v: &mut [f64]) {
    let p = n - m;
    for k in 0..m {
        let v = &mut v[k * n..(k + 1) * n];
        v[..k].fill(0.0);
        v[k..].copy_from_slice(&a[k * n + k..(k + 1) * n]);
        let norm = v[k..].iter().map(|x| x * x).sum::<f64>().sqrt();
        v[k] += if v[k] >= 0.0 { norm } else { -norm };
        let size = v[k..].iter().map(|x| x * x).sum::<f64>().sqrt();
        if size == 0.0 {
            // No reflection: H = I.
            v[k..].fill(0.0);
            continue;
        }
        v[k..].iter_mut().for_each(|x| *x /= size);
        // H = I − 2vvᵀ on rows k.. of the columns k.. of a.
        for j in k..m {
            let col = &mut a[j * n..(j + 1) * n];
            let w: f64 = (k..n).map(|i| v[i] * col[i]).sum();
            for i in k..n {
                col[i] -= 2.0 * v[i] * w;
            }
        }
    }
    // Z = H_0 H_1 ⋯ H_{m−1} E, E the last n − m columns of I.
    let z = &mut z[..n * p];
    z.fill(0.0);
    for j in 0..p {
        z[j * n + m + j] = 1.0;
    }
    for k in (0..m).rev() {
        let v = &v[k * n..(k + 1) * n];
        for j in 0..p {
            let col = &mut z[j * n..(j + 1) * n];
            let w: f64 = (k..n).map(|i| v[i] * col[i]).sum();
            for i in k..n {
                col[i] -= 2.0 * v[i] * w;
            }
        }
    }
}

/// The least-squares solution of $Ax = b$ of least norm, by SVD: singular
/// values at most $10^{-10}\sigma_{max}$ count as zero (the cut-off of [`null_space`]), so a rank-deficient
/// $A$ (a straight flexure's tip Jacobian has a zero row) gives the
/// minimal answer instead of failing.
///
/// # Example
/// ```
/// use nalgebra::{DMatrix, DVector};
/// // x + y = 2 twice: the least-norm answer is (1, 1).
/// let a = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]);
/// let x = flexure::linalg::least_squares(&a, &DVector::from_vec(vec![2.0, 2.0]));
/// assert!((x[0] - 1.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14);
/// ```
pub fn least_squares(a: &DMatrix<f64>, b: &nalgebra::DVector<f64>) -> nalgebra::DVector<f64> {
    let svd = nalgebra::SVD::new(a.clone(), true, true);
    let cutoff = 1e-10 * svd.singular_values.amax();
    svd.solve(b, cutoff).unwrap_or_else(|_| nalgebra::DVector::zeros(a.ncols()))
}

/// Eigenpairs of $B v = \mu A v$ for symmetric $A$ (positive definite) and $B$,
/// by reduction with $A = LL^T$ to the standard problem for $L^{-1}BL^{-T}$.
/// Eigenvalues unsorted (nalgebra's order); eigenvectors (columns) in the
/// original coordinates. `None` if $A$ is not positive definite.
///
/// # Example
/// ```
/// use nalgebra::DMatrix;
/// let a = DMatrix::from_row_slice(2, 2, &[2.0, 0.0, 0.0, 1.0]);
/// let b = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 3.0]);
/// let (mu, _) = flexure::linalg::generalized_symmetric(&a, &b).unwrap();
/// let mut mu: Vec<f64> = mu.iter().copied().collect();
/// mu.sort_by(f64::total_cmp);
/// assert!((mu[0] - 0.5).abs() < 1e-14 && (mu[1] - 3.0).abs() < 1e-14);
/// ```
pub fn generalized_symmetric(a: &DMatrix<f64>, b: &DMatrix<f64>) -> Option<(nalgebra::DVector<f64>, DMatrix<f64>)> {
    let a = (a + a.transpose()) * 0.5;
    if !is_positive_definite(&a) {
        return None;
    }
    let l = nalgebra::Cholesky::new(a)?.l();
    let linv = l.try_inverse()?;
    let m = &linv * b * linv.transpose();
    let eig = nalgebra::SymmetricEigen::new((&m + m.transpose()) * 0.5);
    Some((eig.eigenvalues, linv.transpose() * eig.eigenvectors))
}

/// The eigenvector of the smallest eigenvalue of the symmetric `a`
/// (nalgebra returns them unsorted), with that eigenvalue.
pub fn softest_mode(a: &DMatrix<f64>) -> Option<(f64, nalgebra::DVector<f64>)> {
    let eig = nalgebra::SymmetricEigen::new((a + a.transpose()) * 0.5);
    let (i, &value) = eig.eigenvalues.iter().enumerate().min_by(|x, y| x.1.total_cmp(y.1))?;
    Some((value, eig.eigenvectors.column(i).into_owned()))
}

/// An orthonormal basis of rows, grown by Gram–Schmidt.
#[derive(Default)]
pub(crate) struct Basis {
    rows: Vec<Vec<f64>>,
}

impl Basis {
    /// What of `row` the basis leaves.
    pub(crate) fn rest(&self, row: &[f64]) -> Vec<f64> {
        let mut rest = row.to_vec();
        for b in &self.rows {
            let along: f64 = rest.iter().zip(b).map(|(x, y)| x * y).sum();
            rest.iter_mut().zip(b).for_each(|(x, y)| *x -= along * y);
        }
        rest
    }

    /// Adds `row` where more than $10^{-9}$ of it is left.
    pub(crate) fn add(&mut self, row: &[f64]) {
        let rest = self.rest(row);
        let left = norm(&rest);
        if left > 1e-9 * norm(row) {
            self.rows.push(rest.iter().map(|x| x / left).collect());
        }
    }
}

/// The Euclidean length of `row`.
pub(crate) fn norm(row: &[f64]) -> f64 {
    row.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The principal directions of one or two rows $r_k$: the unit
/// eigenvectors $w$ of $r_ir_j$, largest first, and the size of each
/// combination $\lvert\sum_k w_kr_k\rvert$.
fn principal(rows: &[Vec<f64>]) -> (Vec<Vec<f64>>, Vec<f64>) {
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    match rows {
        [a, b] => {
            let (p, q, r) = (dot(a, a), dot(a, b), dot(b, b));
            // The larger eigenvalue's direction, (cos φ, sin φ) with tan 2φ = 2q/(p − r).
            let phi = 0.5 * (2.0 * q).atan2(p - r);
            let (c, s) = (phi.cos(), phi.sin());
            let directions = vec![vec![c, s], vec![-s, c]];
            let parts = directions
                .iter()
                .map(|w| norm(&a.iter().zip(b).map(|(x, y)| w[0] * x + w[1] * y).collect::<Vec<_>>()))
                .collect();
            (directions, parts)
        }
        _ => (rows.iter().map(|_| vec![1.0]).collect(), rows.iter().map(|r| norm(r)).collect()),
    }
}

/// A stuck contact's tangential `rows` (along the world vectors `units`)
/// split along the principal directions of what `basis` leaves of them
/// ([`principal`]): the units turned to those directions, largest first,
/// and whether each is kept, its part above $10^{-9}$ of `size`. The kept
/// combinations of the rows join the basis.
pub(crate) fn turn_rows(
    basis: &mut Basis,
    rows: &[Vec<f64>],
    units: &[[f64; 3]],
    size: f64,
) -> (Vec<[f64; 3]>, Vec<bool>) {
    let left: Vec<Vec<f64>> = rows.iter().map(|r| basis.rest(r)).collect();
    let (directions, parts) = principal(&left);
    let kept: Vec<bool> = parts.iter().map(|&p| p > 1e-9 * size).collect();
    let n = rows.first().map_or(0, Vec::len);
    for (w, _) in directions.iter().zip(&kept).filter(|(_, k)| **k) {
        basis.add(&(0..n).map(|j| w.iter().zip(rows).map(|(a, r)| a * r[j]).sum()).collect::<Vec<_>>());
    }
    let turned =
        directions.iter().map(|w| std::array::from_fn(|i| w.iter().zip(units).map(|(a, u)| a * u[i]).sum())).collect();
    (turned, kept)
}

/// Seeded uniform numbers in [-1, 1) (xorshift*): the random matrices
/// of the to-the-bit tests, the same on every machine.
#[cfg(test)]
pub(crate) fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_dual::Dual64;

    /// The dot-product form of [`cholesky`] (its former code): row by row
    /// of each column, the sum over $k$ ascending, strided.
    fn cholesky_dot<T: Scalar>(a: &mut [T], n: usize) -> bool {
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

    /// [`cholesky`] against its dot-product form on seeded random
    /// symmetric matrices $BB^T + sI$ of 1 to 40 unknowns, shifts $s$ from
    /// definite to indefinite, in `f64` and in dual numbers: the same
    /// verdict and, where it factors, the same lower triangle to the bit
    /// (the exact reference: the same operations in the same order).
    #[test]
    fn cholesky_is_the_dot_product_form_to_the_bit() {
        let mut next = crate::linalg::uniform(0x853C_49E6_748F_EA9B_u64);
        let lower = |a: &[Dual64], n: usize| -> Vec<u64> {
            (0..n)
                .flat_map(|j| (j..n).map(move |i| (j, i)))
                .flat_map(|(j, i)| [a[j * n + i].re.to_bits(), a[j * n + i].eps.to_bits()])
                .collect()
        };
        let (mut definite, mut not) = (0, 0);
        for n in 1..=40 {
            for shift in [1.0, 0.0, -0.5, -3.0] {
                let b: Vec<Dual64> = (0..n * n).map(|_| Dual64::new(next(), next())).collect();
                let mut a = vec![Dual64::new(0.0, 0.0); n * n];
                for c in 0..n {
                    for r in 0..n {
                        let mut s = Dual64::new(0.0, 0.0);
                        for k in 0..n {
                            s += b[k * n + r] * b[k * n + c];
                        }
                        a[c * n + r] = s + Dual64::new(if r == c { shift * n as f64 } else { 0.0 }, 0.0);
                    }
                }
                let (mut fast, mut dot) = (a.clone(), a.clone());
                let ok = cholesky_dot(&mut dot, n);
                assert_eq!(cholesky(&mut fast, n), ok, "dual, n = {n}, shift {shift}");
                if ok {
                    assert_eq!(lower(&fast, n), lower(&dot, n), "dual, n = {n}, shift {shift}");
                }
                let plain: Vec<f64> = a.iter().map(|v| v.re).collect();
                let (mut fast, mut dot) = (plain.clone(), plain);
                let ok = cholesky_dot(&mut dot, n);
                assert_eq!(cholesky(&mut fast, n), ok, "f64, n = {n}, shift {shift}");
                if ok {
                    let bits = |v: &[f64]| {
                        (0..n).flat_map(|j| (j..n).map(move |i| v[j * n + i].to_bits())).collect::<Vec<_>>()
                    };
                    assert_eq!(bits(&fast), bits(&dot), "f64, n = {n}, shift {shift}");
                    definite += 1;
                } else {
                    not += 1;
                }
            }
        }
        // Both verdicts are exercised: the shifts 1 and 0 factor, −3 never does.
        assert!(definite >= 40 && not >= 40, "{definite} definite, {not} not");
    }

    /// Factors, pivots, verdict and solution by the dispatching entries
    /// (`fast`) and by the any-size paths they shortcut, as bit patterns.
    fn both<T: Scalar>(
        a: &[T],
        b: &[T],
        n: usize,
        bits: impl Fn(&[T]) -> Vec<u64>,
    ) -> [(bool, Vec<usize>, Vec<u64>); 2] {
        let (mut fast, mut general) = (a.to_vec(), a.to_vec());
        let (mut pf, mut pg) = (vec![0; n], vec![0; n]);
        let (ok_f, ok_g) = (lu(&mut fast, n, &mut pf), lu_any(&mut general, n, &mut pg));
        let (mut xf, mut xg) = (b.to_vec(), b.to_vec());
        if ok_g {
            lu_solve(&fast, n, &pf, &mut xf);
            lu_forward_any(&general, n, &pg, &mut xg);
            lu_backward_any(&general, n, &mut xg);
        }
        // The factors and solution where both factor; where not, what is left is unspecified.
        let ok = ok_f && ok_g;
        let kept = |f: &[T], x: &[T]| if ok { [bits(f), bits(x)].concat() } else { Vec::new() };
        [(ok_f, pf, kept(&fast, &xf)), (ok_g, pg, kept(&general, &xg))]
    }

    /// The right-looking form of [`lu_any`] (its former code): at each
    /// step, pivot, swap the rows in every column, scale, and update every
    /// later column.
    fn lu_right_looking<T: Scalar>(a: &mut [T], n: usize, pivots: &mut [usize]) -> bool {
        for k in 0..n {
            let (mut p, mut largest) = (k, a[k * n + k].re().abs());
            for i in k + 1..n {
                if a[k * n + i].re().abs() > largest {
                    (p, largest) = (i, a[k * n + i].re().abs());
                }
            }
            let pivot = a[k * n + p].re();
            if !(pivot.is_finite() && pivot != 0.0) {
                return false;
            }
            pivots[k] = p;
            if p != k {
                for c in 0..n {
                    a.swap(c * n + k, c * n + p);
                }
            }
            let d = a[k * n + k];
            for i in k + 1..n {
                a[k * n + i] /= d;
            }
            for c in k + 1..n {
                let f = a[c * n + k];
                if f.re() != 0.0 || f != T::zero() {
                    for i in k + 1..n {
                        let l = a[k * n + i];
                        a[c * n + i] -= l * f;
                    }
                }
            }
        }
        true
    }

    /// [`lu`] (left-looking beyond 8 unknowns) against its right-looking
    /// form, the exact reference of the same operations in another order
    /// of loops, on seeded random matrices of 1 to 40 unknowns in `f64` and
    /// dual numbers, with zeros that skip updates (some within a group of
    /// four steps), exact ties of pivot candidates, a singular column, a
    /// NaN and an infinity: the same verdict and pivots, and where it
    /// factors the same factors to the bit.
    #[test]
    fn lu_is_the_right_looking_form_to_the_bit() {
        let mut next = crate::linalg::uniform(0x1234_5678_9ABC_DEF1_u64);
        let mut factored = 0;
        for n in 1..=40 {
            for case in 0..7 {
                let mut a: Vec<Dual64> = (0..n * n).map(|_| Dual64::new(next(), next())).collect();
                match case {
                    1 => a.iter_mut().step_by(3).for_each(|v| *v = Dual64::new(0.0, 0.0)),
                    2 => a.iter_mut().for_each(|v| *v = Dual64::new((v.re * 4.0).round(), v.eps)),
                    3 => a[..n].iter_mut().for_each(|v| *v = Dual64::new(0.0, v.eps)),
                    4 => a[n * n / 2].re = f64::NAN,
                    5 => a[n * n - 1].re = f64::INFINITY,
                    // Upper-triangular zeros: u_kj = 0 for some but not all steps of a group.
                    6 => (0..n).for_each(|c| {
                        (0..c).filter(|r| (r + c) % 5 == 0).for_each(|r| a[c * n + r] = Dual64::new(0.0, 0.0))
                    }),
                    _ => {}
                }
                let dual_bits =
                    |v: &[Dual64]| v.iter().flat_map(|x| [x.re.to_bits(), x.eps.to_bits()]).collect::<Vec<_>>();
                let (mut fast, mut reference) = (a.clone(), a.clone());
                let (mut pf, mut pr) = (vec![0; n], vec![0; n]);
                let (ok_f, ok_r) = (lu(&mut fast, n, &mut pf), lu_right_looking(&mut reference, n, &mut pr));
                assert_eq!((ok_f, &pf), (ok_r, &pr), "dual, n = {n}, case {case}");
                if ok_r {
                    assert_eq!(dual_bits(&fast), dual_bits(&reference), "dual, n = {n}, case {case}");
                }
                let plain: Vec<f64> = a.iter().map(|v| v.re).collect();
                let (mut fast, mut reference) = (plain.clone(), plain);
                let (ok_f, ok_r) = (lu(&mut fast, n, &mut pf), lu_right_looking(&mut reference, n, &mut pr));
                assert_eq!((ok_f, &pf), (ok_r, &pr), "f64, n = {n}, case {case}");
                if ok_r {
                    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&fast), bits(&reference), "f64, n = {n}, case {case}");
                    factored += 1;
                }
            }
        }
        // Cases 3 and 5 (and most NaNs) are singular by design, some small rounded ones too.
        assert!(factored >= 140, "only {factored} of 280 matrices factored");
    }

    /// The fixed-size paths of [`lu`], [`lu_forward`] and [`lu_backward`]
    /// against the any-size ones they shortcut, on seeded random matrices
    /// of 1 to 10 unknowns (with zeros that skip updates, exact ties of
    /// pivot candidates, a singular column, a NaN, an infinity), in `f64`
    /// and in dual numbers (value and derivative parts): the same factors,
    /// pivots, verdicts and solutions to the bit.
    #[test]
    fn fixed_sizes_are_the_general_path_to_the_bit() {
        let mut state = 0x2545_F491_4F6C_DD1D_u64;
        let mut next = || {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            (state.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        };
        let dual_bits = |v: &[Dual64]| v.iter().flat_map(|x| [x.re.to_bits(), x.eps.to_bits()]).collect();
        let plain_bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect();
        let mut factored = 0;
        for n in 1..=10 {
            for case in 0..8 {
                let mut a: Vec<Dual64> = (0..n * n).map(|_| Dual64::new(next(), next())).collect();
                match case {
                    1 => a.iter_mut().step_by(3).for_each(|v| *v = Dual64::new(0.0, 0.0)),
                    2 => a.iter_mut().for_each(|v| *v = Dual64::new((v.re * 4.0).round(), v.eps)),
                    3 => a[..n].iter_mut().for_each(|v| *v = Dual64::new(0.0, v.eps)),
                    4 => a[n * n / 2].re = f64::NAN,
                    5 => a[n * n - 1].re = f64::INFINITY,
                    _ => {}
                }
                let b: Vec<Dual64> = (0..n).map(|_| Dual64::new(next(), next())).collect();
                let [fast, general] = both(&a, &b, n, dual_bits);
                assert_eq!(fast, general, "dual, n = {n}, case {case}");
                let (a, b): (Vec<f64>, Vec<f64>) = (a.iter().map(|v| v.re).collect(), b.iter().map(|v| v.re).collect());
                let [fast, general] = both(&a, &b, n, plain_bits);
                assert_eq!(fast, general, "f64, n = {n}, case {case}");
                factored += usize::from(general.0);
            }
        }
        // Cases 3 and 5 (and some NaNs) are singular by design; the rest must factor.
        assert!(factored >= 40, "only {factored} of 80 matrices factored");
    }
}
