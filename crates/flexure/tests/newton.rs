//! The Newton minimizer and root finder on problems with known answers.

use flexure::Error;
use flexure::newton::{Objective, Settings, Workspace, find_root, minimize};
use nalgebra::{SMatrix, SVector};

/// Rosenbrock's function, minimum at (1, 1), with an indefinite Hessian on
/// the way from (−1.2, 1).
struct Rosenbrock;
impl Objective<f64> for Rosenbrock {
    fn evaluate(&mut self, x: &[f64], g: &mut [f64], h: &mut [f64]) -> f64 {
        let (a, b) = (x[0], x[1]);
        g[0] = -2.0 * (1.0 - a) - 400.0 * a * (b - a * a);
        g[1] = 200.0 * (b - a * a);
        h[0] = 2.0 - 400.0 * (b - 3.0 * a * a);
        h[1] = -400.0 * a;
        h[2] = -400.0 * a;
        h[3] = 200.0;
        (1.0 - a).powi(2) + 100.0 * (b - a * a).powi(2)
    }
}

#[test]
fn rosenbrock() {
    let mut ws = Workspace::new(2);
    ws.x.copy_from_slice(&[-1.2, 1.0]);
    let r = minimize(&mut Rosenbrock, &mut ws, &Settings { tolerance: 1e-12, max_iterations: 100 }).unwrap();
    assert!((ws.x[0] - 1.0).abs() < 1e-10 && (ws.x[1] - 1.0).abs() < 1e-10);
    assert!(r.positive_definite && r.residual <= 1e-12);
}

#[test]
fn iteration_limit_is_reported() {
    let mut ws = Workspace::new(2);
    ws.x.copy_from_slice(&[-1.2, 1.0]);
    let e = minimize(&mut Rosenbrock, &mut ws, &Settings { tolerance: 1e-12, max_iterations: 2 }).unwrap_err();
    assert!(matches!(e, Error::NoConvergence { residual, .. } if residual > 1e-12));
}

/// x² = 2, y = x³: the root (√2, 2√2).
#[test]
fn square_root() {
    let f = |x: &SVector<f64, 2>| {
        Ok((
            SVector::from([x[0] * x[0] - 2.0, x[1] - x[0].powi(3)]),
            SMatrix::<f64, 2, 2>::new(2.0 * x[0], 0.0, -3.0 * x[0] * x[0], 1.0),
        ))
    };
    let r = find_root(f, SVector::from([1.0, 0.0]), 1e-14, 50).unwrap();
    assert!((r.x[0] - 2f64.sqrt()).abs() < 1e-13 && (r.x[1] - 2f64.powf(1.5)).abs() < 1e-12);
}
