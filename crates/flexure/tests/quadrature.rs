//! Gauss–Legendre rules for any count.

use flexure::quadrature::GaussLegendre;

/// The Appendix's 5-point weights and nodes (15 digits printed).
#[test]
fn appendix_table() {
    let q = GaussLegendre::new(5).unwrap();
    let delta = [0.118463442528095, 0.239314335249683, 0.284444444444444, 0.239314335249683, 0.118463442528095];
    let nodes = [0.046910077030668, 0.230765344947158, 0.5, 0.769234655052842, 0.953089922969332];
    for k in 0..5 {
        assert!((q.weights()[k] - delta[k]).abs() < 1e-15);
        assert!((q.nodes()[k] - nodes[k]).abs() < 1e-15);
    }
}

/// A Q-point rule integrates t^d exactly (1/(d+1)) for d ≤ 2Q − 1, and not d = 2Q.
#[test]
fn polynomial_exactness() {
    for points in [1, 2, 5, 9, 17, 40] {
        let q = GaussLegendre::new(points).unwrap();
        let integral = |d: i32| q.nodes().iter().zip(q.weights()).map(|(t, w)| w * t.powi(d)).sum::<f64>();
        for d in 0..(2 * points as i32) {
            assert!((integral(d) - 1.0 / (d as f64 + 1.0)).abs() < 1e-14, "Q={points}, degree {d}");
        }
        // The error at degree 2Q shrinks like 4^-Q; visible above rounding for small Q.
        let d = 2 * points as i32;
        if points <= 9 {
            assert!((integral(d) - 1.0 / (d as f64 + 1.0)).abs() > 1e-13, "Q={points} is not exact at degree 2Q");
        }
    }
}

/// The default rule is the paper's 5 points at N = 3, and N + 2 in general.
#[test]
fn default_rule() {
    assert_eq!(GaussLegendre::default_points(3), 5);
    assert_eq!(GaussLegendre::default_points(10), 12);
    assert!(GaussLegendre::new(0).is_err());
}
