//! Energy (Eq. 9), gradient (Eq. 18) and Hessian (Eq. 28 with the errata's 1/3).

use flexure::{Flexure, energy, energy_gradient};
use num_dual::{Dual64, HyperDual64};

/// Eq. 9 against Eq. 5 integrated directly: (EI/2)∫(ω̂(α) − ω̂(κ))² ds by a
/// 40-point rule, exact for these polynomials up to rounding.
#[test]
fn energy_is_the_integral_of_eq_5() {
    let kappa = [0.3, -0.2, 0.1, 0.05];
    let f = Flexure::new(0.5, 3.0, 4).unwrap().with_rest(&kappa).unwrap();
    let alpha = [1.1, 0.4, -0.3, 0.2];
    let q = flexure::quadrature::GaussLegendre::new(40).unwrap();
    let diff: Vec<f64> = alpha.iter().zip(&kappa).map(|(a, k)| a - k).collect();
    let integral: f64 = q
        .nodes()
        .iter()
        .zip(q.weights())
        .map(|(&t, &w)| w * 0.5 * flexure::basis::curvature(&diff, 0.5, t * 0.5).powi(2))
        .sum::<f64>()
        * 0.5;
    assert!((energy(&f, &alpha) - 3.0 * integral).abs() < 1e-13);
}

/// Gradient and Hessian three ways: central differences (h = 1e-5, error
/// ~1e-9 for this quadratic), num-dual (exact), symmetry (diagonal).
#[test]
fn derivatives() {
    let f = Flexure::new(0.5, 3.0, 4).unwrap().with_rest(&[0.3, -0.2, 0.1, 0.05]).unwrap();
    let alpha = [1.1, 0.4, -0.3, 0.2];
    let mut g = [0.0; 4];
    energy_gradient(&f, &alpha, &mut g);
    let h = 1e-5;
    for i in 0..4 {
        let (mut up, mut dn) = (alpha, alpha);
        up[i] += h;
        dn[i] -= h;
        assert!((g[i] - (energy(&f, &up) - energy(&f, &dn)) / (2.0 * h)).abs() < 1e-8);
        let d: Vec<Dual64> = (0..4).map(|m| Dual64::new(alpha[m], (m == i) as u8 as f64)).collect();
        assert!((g[i] - energy(&f, &d).eps).abs() < 1e-14);
        for j in 0..4 {
            let d: Vec<HyperDual64> =
                (0..4).map(|m| HyperDual64::new(alpha[m], (m == i) as u8 as f64, (m == j) as u8 as f64, 0.0)).collect();
            let expected = if i == j { flexure::energy::stiffness(&f, i, i) } else { 0.0 };
            assert!((energy(&f, &d).eps1eps2 - expected).abs() < 1e-13, "Hessian ({i},{j})");
        }
    }
    // Errata for Eq. 28: the middle entry is (EI/L)/3, not 0.
    assert!((flexure::energy::stiffness(&f, 1, 1) - 6.0 / 3.0).abs() < 1e-15);
}
