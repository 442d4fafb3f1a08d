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

/// Harmonic oscillator integrated over ten spans one after another, carrying
/// the step: the same closed form to ~1e-10, in fewer steps than restarting
/// each span from a hundredth of its length (the restarts' ramp-up).
#[test]
fn spans_carry_the_step() {
    use flexure::ode::integrate_from;
    let tol = Tolerance::default();
    let f = |_: f64, y: &[f64; 2]| [y[1], -y[0]];
    let (mut carried, mut restarted) = ([1.0, 0.0], [1.0, 0.0]);
    let (mut step, mut steps_carried, mut steps_restarted) = (0.0, 0, 0);
    for i in 0..10 {
        let (s0, s1) = (i as f64, i as f64 + 1.0);
        carried = integrate_from(f, s0, s1, carried, &tol, &mut step, |_, _| steps_carried += 1).unwrap();
        restarted = integrate(f, s0, s1, restarted, &tol, |_, _| steps_restarted += 1).unwrap();
    }
    for y in [carried, restarted] {
        assert!((y[0] - 10f64.cos()).abs() < 1e-10 && (y[1] + 10f64.sin()).abs() < 1e-10);
    }
    assert!(step > 0.0 && steps_carried < steps_restarted, "{steps_carried} vs {steps_restarted}");
}

/// Tolerances that cannot be met, or no steps, are refused by name.
#[test]
fn bad_tolerances_are_refused() {
    let base = Tolerance::default();
    for (name, tol) in [
        ("relative", Tolerance { relative: -1.0, ..base }),
        ("absolute", Tolerance { absolute: f64::NAN, ..base }),
        ("absolute", Tolerance { relative: 0.0, absolute: 0.0, ..base }),
        ("max_steps", Tolerance { max_steps: 0, ..base }),
    ] {
        let r = integrate(|_, y: &[f64; 1]| [y[0]], 0.0, 1.0, [1.0], &tol, |_, _| {});
        assert!(matches!(r, Err(flexure::Error::InvalidParameter { name: n, .. }) if n == name), "{name}: {r:?}");
    }
}
