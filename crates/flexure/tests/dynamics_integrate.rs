//! The time integrator (`flexure::dynamics::integrate`, three-stage Radau
//! IIA) on small systems written here, against independent references: a
//! rigid pendulum's large-amplitude period (complete elliptic integral), a
//! double pendulum (classical RK4 on its closed-form equations), a stiff
//! spring–mass pair and a massless node (exact linear modes), a pendulum in
//! Cartesian coordinates with a closure (the angle form), energy over a
//! hundred periods, and the settings' validation.

use flexure::dynamics::System;
use flexure::dynamics::integrate::{Settings, Trajectory, integrate};
use flexure::{Error, Result};

const G: f64 = 9.81;

fn settings(duration: f64, every: f64, tolerance: f64) -> Settings {
    Settings { duration, every, tolerance, absolute: tolerance, ..Default::default() }
}

/// A rigid pendulum of mass `m` on a massless rod of length `l`, angle θ
/// from the downward vertical: $ml^2\ddot\theta = -mgl\sin\theta - c\dot\theta$.
struct Pendulum {
    m: f64,
    l: f64,
    c: f64,
}

impl System for Pendulum {
    fn dim(&self) -> usize {
        1
    }
    fn closures(&self) -> usize {
        0
    }
    fn dynamics(&mut self, q: &[f64], v: &[f64], _: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
        mass[0] = self.m * self.l * self.l;
        force[0] = -self.m * G * self.l * q[0].sin() - self.c * v[0];
        Ok(())
    }
    fn tangent(&mut self, q: &[f64], _: &[f64], _: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
        k[0] = self.m * G * self.l * q[0].cos();
        d[0] = self.c;
        Ok(())
    }
    fn energy(&mut self, q: &[f64], v: &[f64], _: f64) -> Result<f64> {
        Ok(0.5 * self.m * (self.l * v[0]).powi(2) - self.m * G * self.l * q[0].cos())
    }
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        (a[0] - b[0]).abs()
    }
}

/// The exact period of a pendulum released from rest at θ₀:
/// $T = 4\sqrt{l/g}\,K(\sin^2(\theta_0/2))$ (parameter $m = k^2$).
fn pendulum_period(l: f64, theta0: f64) -> f64 {
    4.0 * (l / G).sqrt() * ellip::ellipk((theta0 / 2.0).sin().powi(2)).unwrap()
}

/// Released from rest at θ₀ = 2.5 rad (143°, where the period is 1.6 times
/// the small-amplitude one) and sampled at a quarter and a whole exact
/// period: the numerical zero crossing and return, corrected to first
/// order by the sampled velocity and acceleration, give the period. At
/// tolerance 1e-9 it must agree to 1e-8 relative: the global error of an
/// error-per-step controller is a small multiple of the tolerance.
#[test]
fn pendulum_period_matches_the_elliptic_integral() {
    let (l, theta0) = (0.7, 2.5);
    let exact = pendulum_period(l, theta0);
    let tol = 1e-9;
    let mut p = Pendulum { m: 0.3, l, c: 0.0 };
    let run = integrate(&mut p, &[theta0], &[0.0], &settings(exact, exact / 4.0, tol)).unwrap();
    assert_eq!(run.time.len(), 5);
    assert_eq!(run.time[4], exact);
    // Quarter period: θ = 0 crossed downward.
    let (th, om) = (run.q(1)[0], run.v(1)[0]);
    let quarter = 4.0 * (exact / 4.0 - th / om);
    // Full period: back at rest, θ̇ = θ̈ (t − T).
    let full = exact - run.v(4)[0] / (-(G / l) * run.q(4)[0].sin());
    println!("quarter {:e} full {:e} steps {} rejected {}", (quarter - exact) / exact, (full - exact) / exact, run.steps, run.rejected);
    assert!(((quarter - exact) / exact).abs() < 10.0 * tol, "{quarter} vs {exact}");
    assert!(((full - exact) / exact).abs() < 10.0 * tol, "{full} vs {exact}");
    assert!((run.q(4)[0] - theta0).abs() < 10.0 * tol);
}
