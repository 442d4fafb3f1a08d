//! The shifted-Legendre basis (Eq. 8) and its integrals (Eq. 10).

use flexure::basis::{angle_shapes, energy_weight, shifted_legendre};
use flexure::quadrature::GaussLegendre;

/// L²-orthogonality on [0, 1] (errata: not "under convolution"):
/// ∫P̃ₘP̃ₙ = δₘₙ/(2n+1), by a 20-point rule exact for these degrees.
#[test]
fn orthogonality() {
    let q = GaussLegendre::new(20).unwrap();
    let n = 10;
    let mut gram = vec![0.0; n * n];
    let mut p = vec![0.0; n];
    for (&t, &w) in q.nodes().iter().zip(q.weights()) {
        shifted_legendre(t, &mut p);
        for i in 0..n {
            for j in 0..n {
                gram[i * n + j] += w * p[i] * p[j];
            }
        }
    }
    for i in 0..n {
        for j in 0..n {
            let expected = if i == j { energy_weight(i) } else { 0.0 };
            assert!((gram[i * n + j] - expected).abs() < 1e-14, "({i},{j})");
        }
    }
}

/// ψₙ' = P̃ₙ (central differences, h = 1e-6: error ~1e-10), ψₙ(0) = 0, and
/// ψₙ(1) = 0 for n ≥ 1, so the tip angle is α₁ at any order (Eq. 11).
#[test]
fn angle_shapes_integrate_the_basis() {
    let n = 9;
    let (mut up, mut dn, mut p) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for t in [0.1, 0.37, 0.5, 0.83] {
        let h = 1e-6;
        angle_shapes(t + h, &mut up);
        angle_shapes(t - h, &mut dn);
        shifted_legendre(t, &mut p);
        for k in 0..n {
            assert!(((up[k] - dn[k]) / (2.0 * h) - p[k]).abs() < 1e-8, "n={k} t={t}");
        }
    }
    angle_shapes(0.0, &mut up);
    angle_shapes(1.0, &mut dn);
    assert!(up.iter().all(|v| v.abs() < 1e-15));
    assert!((dn[0] - 1.0).abs() < 1e-15 && dn[1..].iter().all(|v| v.abs() < 1e-14));
}
