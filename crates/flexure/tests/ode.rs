//! The Dormand–Prince integrator against closed-form solutions, and
//! differentiated through with num-dual.

use flexure::ode::{Tolerance, integrate};
use num_dual::Dual64;

/// Harmonic oscillator: y = (cos s, −sin s); at s = 10 to ~1e-10 (tolerance 1e-12 per step).
#[test]
fn harmonic_oscillator() {
    let mut steps = 0;
    let y = integrate(|_, y: &[f64; 2]| [y[1], -y[0]], 0.0, 10.0, [1.0, 0.0], &Tolerance::default(), |_, _| steps += 1)
        .unwrap();
    assert!((y[0] - 10f64.cos()).abs() < 1e-10 && (y[1] + 10f64.sin()).abs() < 1e-10);
    assert!(steps > 10, "adaptive steps were taken");
}

/// y' = a y: y(1) = e^a and dy/da = e^a, through a dual number.
#[test]
fn derivative_through_the_integrator() {
    let a = Dual64::new(0.7, 1.0);
    let y = integrate(
        move |_, y: &[Dual64; 1]| [a * y[0]],
        0.0,
        1.0,
        [Dual64::from(1.0)],
        &Tolerance::default(),
        |_, _| {},
    )
    .unwrap();
    assert!((y[0].re - 0.7f64.exp()).abs() < 1e-11);
    assert!((y[0].eps - 0.7f64.exp()).abs() < 1e-10);
}

/// Blow-up is reported, never returned as a number.
#[test]
fn blow_up_is_an_error() {
    let r = integrate(|_, y: &[f64; 1]| [y[0] * y[0]], 0.0, 2.0, [1.0], &Tolerance::default(), |_, _| {});
    assert!(r.is_err());
}
