//! The definiteness test's Cholesky at the size of the spatial chain's
//! stability tests (`spatial_mechanism/chain_10`: 90 coordinates), against
//! its former dot-product form (strided inner loops) and nalgebra's, on the
//! same matrix.

use criterion::Criterion;
use nalgebra::DMatrix;
use std::hint::black_box;

/// A seeded symmetric positive definite $n\times n$ matrix, $BB^T + nI$.
fn definite(n: usize) -> DMatrix<f64> {
    let b = DMatrix::from_column_slice(n, n, &crate::inputs(n, n));
    &b * b.transpose() + DMatrix::identity(n, n) * n as f64
}

/// `flexure::linalg::cholesky` as it was: each entry's sum over $k$ read
/// along a row of the column-major matrix (stride $n$).
fn cholesky_dot(a: &mut [f64], n: usize) -> bool {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[k * n + j] * a[k * n + j];
        }
        if d.is_nan() || d <= 0.0 {
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

pub fn run(c: &mut Criterion) {
    let mut g = c.benchmark_group("linalg");
    let a = definite(90);
    let mut scratch = a.as_slice().to_vec();
    g.bench_function("cholesky_90", |b| {
        b.iter(|| {
            scratch.copy_from_slice(black_box(a.as_slice()));
            assert!(flexure::linalg::cholesky(&mut scratch, 90));
        })
    });
    g.bench_function("cholesky_90_dot", |b| {
        b.iter(|| {
            scratch.copy_from_slice(black_box(a.as_slice()));
            assert!(cholesky_dot(&mut scratch, 90));
        })
    });
    g.bench_function("cholesky_90_nalgebra", |b| {
        b.iter(|| assert!(black_box(a.clone()).cholesky().is_some()));
    });
    g.finish();
}
