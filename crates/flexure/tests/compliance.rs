//! Small-load compliance (Eq. 36) against the compliance ODE (Eq. 34).

use flexure::reference::compliance::compliance_tip;
use flexure::{Flexure, compliance_tip_rest};
use std::f64::consts::PI;

fn arc(curvature: f64) -> Flexure {
    Flexure::new(1.0, 1.0, 3).unwrap().with_rest(&[curvature, 0.0, 0.0]).unwrap()
}

/// Eq. 37: the ODE's compliance for ω₀ = π, as printed (4 decimals: ±5e-5).
// These are the paper's printed digits, not approximations of 1/π.
#[allow(clippy::approx_constant)]
#[test]
fn eq_37() {
    let printed = [[1.0000, -0.3183, -0.2026], [-0.3183, 0.1520, 0.0645], [-0.2026, 0.0645, 0.0507]];
    let c = compliance_tip(&arc(PI), &Default::default()).unwrap();
    for i in 0..3 {
        for j in 0..3 {
            assert!((c[(i, j)] - printed[i][j]).abs() < 5e-5, "({i},{j}): {}", c[(i, j)]);
        }
    }
}

/// Fig. 13: over constant rest curvature 0..π, the model's largest
/// elementwise error is 7.33e-4 (3 digits printed: ±5e-7), at the largest curvature.
#[test]
fn fig_13_maximum_error() {
    let errors: Vec<f64> = (0..=60)
        .map(|i| {
            let f = arc(PI * i as f64 / 60.0);
            (compliance_tip_rest(&f) - compliance_tip(&f, &Default::default()).unwrap()).amax()
        })
        .collect();
    let (at, max) = errors.iter().enumerate().fold((0, 0.0), |m, (i, &e)| if e > m.1 { (i, e) } else { m });
    assert!((max - 7.33e-4).abs() < 5e-7, "max error {max}");
    assert_eq!(at, 60, "the largest error is at ω₀ = π");
}

/// Straight cantilever, closed form: C = [[L, 0, L²/2], [0, 0, 0], [L²/2, 0, L³/3]]/EI.
#[test]
fn straight_cantilever_closed_form() {
    let f = Flexure::new(0.3, 0.02, 4).unwrap();
    let (l, ei): (f64, f64) = (0.3, 0.02);
    let exact = nalgebra::Matrix3::new(l, 0.0, l * l / 2.0, 0.0, 0.0, 0.0, l * l / 2.0, 0.0, l.powi(3) / 3.0) / ei;
    assert!((compliance_tip_rest(&f) - exact).amax() < 1e-12 * exact.amax());
    assert!((compliance_tip(&f, &Default::default()).unwrap() - exact).amax() < 1e-10 * exact.amax());
}
