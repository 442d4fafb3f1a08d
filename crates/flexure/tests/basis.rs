//! The shifted-Legendre basis (Eq. 8) and its integrals (Eq. 10).

use flexure::basis::{angle_shape_rms, angle_shapes, energy_weight, shifted_legendre};
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

/// The integrator's error weights: √(∫ψₙ²/∫ψ₀²) by a 20-point rule, exact
/// for these degrees (ψ₁₂² is of degree 26 < 40), against the closed form
/// to 1e-13; they fall about as n^(-3/2).
#[test]
fn angle_shape_rms_is_the_quadrature_of_the_shapes() {
    let q = GaussLegendre::new(20).unwrap();
    let n = 13;
    let mut squares = vec![0.0; n];
    let mut psi = vec![0.0; n];
    for (&t, &w) in q.nodes().iter().zip(q.weights()) {
        angle_shapes(t, &mut psi);
        for k in 0..n {
            squares[k] += w * psi[k] * psi[k];
        }
    }
    for k in 0..n {
        let expected = (squares[k] / squares[0]).sqrt();
        assert!(
            (angle_shape_rms(k) - expected).abs() < 1e-13 * expected,
            "n={k}: {} vs {expected}",
            angle_shape_rms(k)
        );
    }
    let slope = (angle_shape_rms(12) / angle_shape_rms(6)).ln() / 2f64.ln();
    assert!((slope + 1.5).abs() < 0.1, "slope {slope}");
}
