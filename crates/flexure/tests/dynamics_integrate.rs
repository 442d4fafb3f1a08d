//! The time integrator (`flexure::dynamics::integrate`, three-stage Radau
//! IIA) on small systems written here, against independent references: a
//! rigid pendulum's large-amplitude period (complete elliptic integral), a
//! double pendulum (classical RK4 on its closed-form equations), a stiff
//! spring–mass pair and a massless node (exact linear modes), a pendulum in
//! Cartesian coordinates with a closure (the angle form), energy over a
//! hundred periods, and the settings' validation.

use flexure::dynamics::System;
use flexure::dynamics::integrate::{MotionSettings, Trajectory, integrate};
use flexure::{Error, Result};

const G: f64 = 9.81;

fn settings(duration: f64, every: f64, tolerance: f64) -> MotionSettings {
    MotionSettings { duration, every, tolerance, absolute: tolerance, ..Default::default() }
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
    assert!(((quarter - exact) / exact).abs() < 10.0 * tol, "{quarter} vs {exact}");
    assert!(((full - exact) / exact).abs() < 10.0 * tol, "{full} vs {exact}");
    assert!((run.q(4)[0] - theta0).abs() < 10.0 * tol);
}

/// A double pendulum of point masses `m1`, `m2` on rods `l1`, `l2`, angles
/// from the downward vertical, in the mass-matrix form of its Lagrange
/// equations; the tangents by central differences (they need only make
/// Newton converge).
struct DoublePendulum {
    m1: f64,
    m2: f64,
    l1: f64,
    l2: f64,
}

impl DoublePendulum {
    fn force(&self, q: &[f64], v: &[f64]) -> [f64; 2] {
        let (m1, m2, l1, l2) = (self.m1, self.m2, self.l1, self.l2);
        let s = (q[0] - q[1]).sin();
        [
            -m2 * l1 * l2 * s * v[1] * v[1] - (m1 + m2) * G * l1 * q[0].sin(),
            m2 * l1 * l2 * s * v[0] * v[0] - m2 * G * l2 * q[1].sin(),
        ]
    }
}

impl System for DoublePendulum {
    fn dim(&self) -> usize {
        2
    }
    fn closures(&self) -> usize {
        0
    }
    fn dynamics(&mut self, q: &[f64], v: &[f64], _: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
        let (m1, m2, l1, l2) = (self.m1, self.m2, self.l1, self.l2);
        let c = m2 * l1 * l2 * (q[0] - q[1]).cos();
        mass.copy_from_slice(&[(m1 + m2) * l1 * l1, c, c, m2 * l2 * l2]);
        force.copy_from_slice(&self.force(q, v));
        Ok(())
    }
    fn tangent(&mut self, q: &[f64], v: &[f64], _: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
        let e = 1e-6;
        for j in 0..2 {
            let (mut qp, mut qm, mut vp, mut vm) = ([q[0], q[1]], [q[0], q[1]], [v[0], v[1]], [v[0], v[1]]);
            qp[j] += e;
            qm[j] -= e;
            vp[j] += e;
            vm[j] -= e;
            let (fqp, fqm) = (self.force(&qp, v), self.force(&qm, v));
            let (fvp, fvm) = (self.force(q, &vp), self.force(q, &vm));
            for i in 0..2 {
                k[j * 2 + i] = -(fqp[i] - fqm[i]) / (2.0 * e);
                d[j * 2 + i] = -(fvp[i] - fvm[i]) / (2.0 * e);
            }
        }
        Ok(())
    }
    fn energy(&mut self, q: &[f64], v: &[f64], _: f64) -> Result<f64> {
        let (m1, m2, l1, l2) = (self.m1, self.m2, self.l1, self.l2);
        let t = 0.5 * (m1 + m2) * (l1 * v[0]).powi(2)
            + 0.5 * m2 * (l2 * v[1]).powi(2)
            + m2 * l1 * l2 * v[0] * v[1] * (q[0] - q[1]).cos();
        Ok(t - (m1 + m2) * G * l1 * q[0].cos() - m2 * G * l2 * q[1].cos())
    }
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        (a[0] - b[0]).abs().max((a[1] - b[1]).abs())
    }
}

/// Classical fourth-order Runge–Kutta with a fixed step on $\dot y = F(y)$.
fn rk4<const D: usize>(f: impl Fn(&[f64; D]) -> [f64; D], y0: [f64; D], duration: f64, steps: usize) -> [f64; D] {
    let h = duration / steps as f64;
    let mut y = y0;
    let add = |y: &[f64; D], k: &[f64; D], s: f64| std::array::from_fn(|i| y[i] + s * k[i]);
    for _ in 0..steps {
        let k1 = f(&y);
        let k2 = f(&add(&y, &k1, h / 2.0));
        let k3 = f(&add(&y, &k2, h / 2.0));
        let k4 = f(&add(&y, &k3, h));
        y = std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    y
}

/// The double pendulum's explicit closed-form accelerations (solved by
/// hand, independent of the mass-matrix form above), integrated by RK4 at
/// 2e-5 s (its error, of order h⁴, is below 1e-12 here). Over 3 s of large
/// swings at tolerance 1e-10 the integrator must agree to ten times the
/// tolerance in angles and rates, and keep the energy to 1e-9 relative.
#[test]
fn double_pendulum_matches_rk4_on_the_closed_form() {
    let dp = DoublePendulum { m1: 1.2, m2: 0.8, l1: 0.5, l2: 0.4 };
    let (m1, m2, l1, l2) = (dp.m1, dp.m2, dp.l1, dp.l2);
    let explicit = |y: &[f64; 4]| {
        let (t1, t2, w1, w2) = (y[0], y[1], y[2], y[3]);
        let den = 2.0 * m1 + m2 - m2 * (2.0 * t1 - 2.0 * t2).cos();
        let a1 = (-G * (2.0 * m1 + m2) * t1.sin()
            - m2 * G * (t1 - 2.0 * t2).sin()
            - 2.0 * (t1 - t2).sin() * m2 * (w2 * w2 * l2 + w1 * w1 * l1 * (t1 - t2).cos()))
            / (l1 * den);
        let a2 = 2.0
            * (t1 - t2).sin()
            * (w1 * w1 * l1 * (m1 + m2) + G * (m1 + m2) * t1.cos() + w2 * w2 * l2 * m2 * (t1 - t2).cos())
            / (l2 * den);
        [w1, w2, a1, a2]
    };
    let (q0, v0) = ([1.6, -0.4], [0.0, 2.0]);
    let duration = 3.0;
    let reference = rk4(explicit, [q0[0], q0[1], v0[0], v0[1]], duration, 150_000);
    let mut sys = dp;
    let e0 = sys.energy(&q0, &v0, 0.0).unwrap();
    let run = integrate(&mut sys, &q0, &v0, &settings(duration, 1.0, 1e-10)).unwrap();
    let last = run.time.len() - 1;
    assert!(((run.energy[last] - e0) / e0).abs() < 1e-9);
    let err = (0..2).map(|i| (run.q(last)[i] - reference[i]).abs()).fold(0.0, f64::max);
    let verr = (0..2).map(|i| (run.v(last)[i] - reference[2 + i]).abs()).fold(0.0, f64::max);
    assert!(err < 1e-9, "angles differ by {err}");
    assert!(verr < 1e-9, "rates differ by {verr}");
}

/// Linear springs, dampers and masses: $M\ddot q = -Kq - D\dot q$, with
/// a constant (possibly singular) $M$ and no closures.
struct Linear {
    n: usize,
    m: Vec<f64>,
    k: Vec<f64>,
    d: Vec<f64>,
}

impl System for Linear {
    fn dim(&self) -> usize {
        self.n
    }
    fn closures(&self) -> usize {
        0
    }
    fn dynamics(&mut self, q: &[f64], v: &[f64], _: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
        mass.copy_from_slice(&self.m);
        for (r, f) in force.iter_mut().enumerate() {
            *f = -(0..self.n).map(|c| self.k[c * self.n + r] * q[c] + self.d[c * self.n + r] * v[c]).sum::<f64>();
        }
        Ok(())
    }
    fn tangent(&mut self, _: &[f64], _: &[f64], _: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
        k.copy_from_slice(&self.k);
        d.copy_from_slice(&self.d);
        Ok(())
    }
    fn energy(&mut self, q: &[f64], v: &[f64], _: f64) -> Result<f64> {
        let quad = |a: &[f64], x: &[f64]| {
            (0..self.n).map(|r| (0..self.n).map(|c| x[r] * a[c * self.n + r] * x[c]).sum::<f64>()).sum::<f64>()
        };
        Ok(0.5 * quad(&self.m, v) + 0.5 * quad(&self.k, q))
    }
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
    }
}

/// Two unit masses, the first tied to the wall by k = 1 N/m, the second to
/// the first by K = 1e6 N/m (stiffness ratio 1e6, frequencies 0.707 and
/// 1414 rad/s), started in the slow mode with the fast one excited at 1e-10
/// m, below the tolerance (1e-8), so the error control need not resolve it.
/// Exact: $q = A\phi_s\cos\omega_st + \epsilon\phi_f\cos\omega_ft$. Over
/// three slow periods the slow amplitude must match to ten times the
/// tolerance, the fast one must not grow (L-stability damps what the steps
/// do not resolve), and it must take a tenth of the 18 800 steps an
/// explicit method needs at its stability limit h = 2/ω_f.
#[test]
fn stiff_pair_is_stable_and_follows_the_slow_mode() {
    let (k, ks): (f64, f64) = (1.0, 1e6);
    let kmat = vec![k + ks, -ks, -ks, ks];
    let sum = k + 2.0 * ks;
    let disc = (sum * sum - 4.0 * k * ks).sqrt();
    // The slow root without cancellation: λ_s λ_f = k K.
    let (lf, ls) = ((sum + disc) / 2.0, 2.0 * k * ks / (sum + disc));
    // Mode shapes from the second row: -K x1 + (K - λ) x2 = 0.
    let shape = |l: f64| {
        let x = [(ks - l) / ks, 1.0];
        let norm = (x[0] * x[0] + x[1] * x[1]).sqrt();
        [x[0] / norm, x[1] / norm]
    };
    let (ps, pf) = (shape(ls), shape(lf));
    let (ws, wf) = (ls.sqrt(), lf.sqrt());
    let (a, eps) = (0.1, 1e-10);
    let q0 = [a * ps[0] + eps * pf[0], a * ps[1] + eps * pf[1]];
    let duration = 3.0 * 2.0 * std::f64::consts::PI / ws;
    let mut sys = Linear { n: 2, m: vec![1.0, 0.0, 0.0, 1.0], k: kmat, d: vec![0.0; 4] };
    let run = integrate(&mut sys, &q0, &[0.0, 0.0], &settings(duration, duration / 30.0, 1e-8)).unwrap();
    let mut worst: f64 = 0.0;
    let mut fast: f64 = 0.0;
    for (j, t) in run.time.iter().enumerate() {
        let q = run.q(j);
        // Modal amplitudes by M-orthogonality (M = I, shapes orthonormal).
        let slow = q[0] * ps[0] + q[1] * ps[1];
        worst = worst.max((slow - a * (ws * t).cos()).abs());
        fast = fast.max((q[0] * pf[0] + q[1] * pf[1]).abs());
    }
    assert!(worst < 1e-7, "slow amplitude off by {worst}");
    assert!(fast <= eps * (1.0 + 1e-6), "fast mode grew to {fast}");
    // An explicit method is stable only for h < 2/ω_f.
    let explicit = duration * wf / 2.0;
    assert!((run.steps as f64) < explicit / 10.0, "{} steps", run.steps);
}

/// The stiff pair with stiffness-proportional damping D = βK (β = 1e-3 s,
/// a flexure's material damping: damping ratios βω/2 = 0.71 for the fast
/// mode and 3.5e-4 for the slow one), the fast mode now excited at 1e-3 m,
/// far above the tolerance. Each mode is an exact damped oscillator,
/// $e^{-\zeta\omega t}(\cos\omega_dt + \frac{\zeta}{\sqrt{1-\zeta^2}}\sin\omega_dt)$:
/// both modal amplitudes must match it to ten times the tolerance at every
/// sample over three slow periods.
#[test]
fn stiff_pair_with_material_damping_matches_the_damped_modes() {
    let (k, ks, beta): (f64, f64, f64) = (1.0, 1e6, 1e-3);
    let kmat = vec![k + ks, -ks, -ks, ks];
    let sum = k + 2.0 * ks;
    let disc = (sum * sum - 4.0 * k * ks).sqrt();
    let (lf, ls) = ((sum + disc) / 2.0, 2.0 * k * ks / (sum + disc));
    let shape = |l: f64| {
        let x = [(ks - l) / ks, 1.0];
        let norm = (x[0] * x[0] + x[1] * x[1]).sqrt();
        [x[0] / norm, x[1] / norm]
    };
    let (ps, pf) = (shape(ls), shape(lf));
    let (a, b) = (0.1, 1e-3);
    let q0 = [a * ps[0] + b * pf[0], a * ps[1] + b * pf[1]];
    let damped = |lambda: f64, t: f64| {
        let w = lambda.sqrt();
        let z = beta * w / 2.0;
        let wd = w * (1.0 - z * z).sqrt();
        (-z * w * t).exp() * ((wd * t).cos() + z / (1.0 - z * z).sqrt() * (wd * t).sin())
    };
    let duration = 3.0 * 2.0 * std::f64::consts::PI / ls.sqrt();
    let d = kmat.iter().map(|x| beta * x).collect();
    let mut sys = Linear { n: 2, m: vec![1.0, 0.0, 0.0, 1.0], k: kmat, d };
    let tol = 1e-8;
    let run = integrate(&mut sys, &q0, &[0.0, 0.0], &settings(duration, duration / 30.0, tol)).unwrap();
    for (j, &t) in run.time.iter().enumerate() {
        let q = run.q(j);
        let slow = q[0] * ps[0] + q[1] * ps[1];
        let fast = q[0] * pf[0] + q[1] * pf[1];
        assert!((slow - a * damped(ls, t)).abs() < 10.0 * tol, "slow mode at t = {t}: {slow}");
        assert!((fast - b * damped(lf, t)).abs() < 10.0 * tol, "fast mode at t = {t}: {fast}");
    }
}

/// A unit mass held by two springs in series, k1 = 3000 and k2 = 1000 N/m,
/// through a massless node: $M = \mathrm{diag}(0, 1)$ is singular. The node
/// follows its quasi-static equilibrium $x_n = k_2x_m/(k_1 + k_2)$ and the
/// mass oscillates at $\omega = \sqrt{k_1k_2/(k_1+k_2)}$. Started on that
/// equilibrium, or off it (the first step projects onto it), both must
/// follow $x_m = \cos\omega t$ to 1e-7 (ten times the tolerance) over five
/// periods.
#[test]
fn massless_node_follows_its_quasi_static_equilibrium() {
    let (k1, k2): (f64, f64) = (3000.0, 1000.0);
    let w = (k1 * k2 / (k1 + k2)).sqrt();
    let duration = 5.0 * 2.0 * std::f64::consts::PI / w;
    for node in [k2 / (k1 + k2), 0.0] {
        let mut sys = Linear { n: 2, m: vec![0.0, 0.0, 0.0, 1.0], k: vec![k1 + k2, -k2, -k2, k2], d: vec![0.0; 4] };
        let run = integrate(&mut sys, &[node, 1.0], &[0.0, 0.0], &settings(duration, duration / 20.0, 1e-8)).unwrap();
        let mut worst: f64 = 0.0;
        for (j, t) in run.time.iter().enumerate().skip(1) {
            let exact = (w * t).cos();
            worst = worst.max((run.q(j)[1] - exact).abs()).max((run.q(j)[0] - k2 / (k1 + k2) * exact).abs());
        }
        assert!(worst < 1e-7, "start {node}: off by {worst}");
    }
}

/// A mass $m$ on coordinate $a$, tied by a spring $k_2$ to two massless
/// nodes $b$ and $c$ held to the ground by springs $k_1$, $k_3$ and to each
/// other by the closure $b - c = 0$, a force $F$ pulling $c$. The nodes
/// follow $b = c = (F + k_2a)/(K + k_2)$ with $K = k_1 + k_3$, and the mass,
/// released from rest at $a = 0$, moves as $a = (F/K)(1 - \cos\omega t)$
/// with $\omega^2 = Kk_2/((K + k_2)m)$.
struct TiedNodes {
    m: f64,
    k: [f64; 3],
    force: f64,
}

impl System for TiedNodes {
    fn dim(&self) -> usize {
        3
    }
    fn closures(&self) -> usize {
        1
    }
    fn dynamics(&mut self, q: &[f64], _: &[f64], _: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
        let [k1, k2, k3] = self.k;
        mass.fill(0.0);
        mass[0] = self.m;
        force.copy_from_slice(&[-k2 * (q[0] - q[1]), k2 * (q[0] - q[1]) - k1 * q[1], self.force - k3 * q[2]]);
        Ok(())
    }
    fn tangent(&mut self, _: &[f64], _: &[f64], _: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
        let [k1, k2, k3] = self.k;
        k.copy_from_slice(&[k2, -k2, 0.0, -k2, k1 + k2, 0.0, 0.0, 0.0, k3]);
        d.fill(0.0);
        Ok(())
    }
    fn closure(&mut self, q: &[f64], c: &mut [f64], g: &mut [f64]) -> Result<()> {
        c[0] = q[1] - q[2];
        g.copy_from_slice(&[0.0, 1.0, -1.0]);
        Ok(())
    }
    fn energy(&mut self, q: &[f64], v: &[f64], _: f64) -> Result<f64> {
        let [k1, k2, k3] = self.k;
        Ok(0.5 * (self.m * v[0] * v[0] + k1 * q[1] * q[1] + k2 * (q[0] - q[1]).powi(2) + k3 * q[2] * q[2]))
    }
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        (a[0] - b[0]).abs()
    }
}

/// Started at rest with every coordinate zero, off the nodes' equilibrium
/// under $F$: the run must start on it (the t = 0 sample at
/// $F/(K + k_2)$ to 1e-14, a closed form the solver does not use) and
/// follow the closed form to ten times the tolerance over five periods,
/// down to tolerance 1e-12, where a start off the equilibrium stalls an
/// integrator that leaves the jump to its first step (its error does not
/// shrink with the step). Mass, stiffness and force scaled together by
/// 1e3 and 1e6 give the same motion: the start's Newton matrix, with
/// stiffness blocks of 1e8 N/m beside closure rows of 1, must still hold
/// the closure (unbalanced, a least-squares solve dropped it).
#[test]
fn massless_nodes_start_on_their_equilibrium_and_follow_the_closed_form() {
    let (m, k, force): (f64, [f64; 3], f64) = (0.02, [300.0, 100.0, 200.0], 1.5);
    let big_k = k[0] + k[2];
    let w = (big_k * k[1] / ((big_k + k[1]) * m)).sqrt();
    let duration = 5.0 * 2.0 * std::f64::consts::PI / w;
    for (tolerance, scale) in [(1e-8, 1.0), (1e-12, 1.0), (1e-8, 1e3), (1e-8, 1e6)] {
        let mut sys = TiedNodes { m: m * scale, k: k.map(|x| x * scale), force: force * scale };
        let run = integrate(&mut sys, &[0.0; 3], &[0.0; 3], &settings(duration, duration / 20.0, tolerance)).unwrap();
        let start = force / (big_k + k[1]);
        assert!((run.q(0)[1] - start).abs() < 1e-14 && (run.q(0)[2] - start).abs() < 1e-14, "start {:?}", run.q(0));
        let mut worst: f64 = 0.0;
        for (j, t) in run.time.iter().enumerate() {
            let a = force / big_k * (1.0 - (w * t).cos());
            let node = (force + k[1] * a) / (big_k + k[1]);
            let q = run.q(j);
            worst = worst.max((q[0] - a).abs()).max((q[1] - node).abs()).max((q[2] - node).abs());
        }
        assert!(
            worst < 10.0 * tolerance * (1.0 + force / big_k),
            "tolerance {tolerance}, scale {scale}: off by {worst:.3e}"
        );
        assert!(run.violation < 1e-14, "violation {:.3e}", run.violation);
    }
}

/// A unit oscillator beside two massless springs, one of 1e12 N/m and one
/// of 1 N/m, started off their equilibrium at 0 (1e-6 and 1): the start
/// must put both at 0 (to 1e-12) although the stiffnesses differ by 1e12,
/// beyond a least-squares cut-off at 1e-10, and the oscillator must then
/// follow $0.1\cos t$ to 1e-6.
#[test]
fn a_soft_massless_direction_beside_a_stiff_one_starts_on_its_equilibrium() {
    let mut k = vec![0.0; 9];
    (k[0], k[4], k[8]) = (1.0, 1e12, 1.0);
    let mut m = vec![0.0; 9];
    m[0] = 1.0;
    let mut sys = Linear { n: 3, m, k, d: vec![0.0; 9] };
    let run = integrate(&mut sys, &[0.1, 1e-6, 1.0], &[0.0; 3], &settings(3.0, 0.5, 1e-8)).unwrap();
    assert!(run.q(0)[1].abs() < 1e-12 && run.q(0)[2].abs() < 1e-12, "start {:?}", run.q(0));
    for (j, t) in run.time.iter().enumerate() {
        assert!((run.q(j)[0] - 0.1 * t.cos()).abs() < 1e-6, "t = {t}: {:?}", run.q(j));
    }
}

/// Two uncoupled unit-frequency oscillators, of mass 1 and 1e-11 (a
/// milligram body's rotary inertia, kg·m², beside a kilogram): the light
/// one has inertia and a free initial value. Both released from 0.1 must
/// follow $0.1\cos t$ to 1e-6 over 3 s; a mass ratio taken for masslessness
/// would move the light one to its equilibrium at 0 and hold it there.
#[test]
fn a_light_mass_keeps_its_start_and_its_motion() {
    let mut sys = Linear { n: 2, m: vec![1.0, 0.0, 0.0, 1e-11], k: vec![1.0, 0.0, 0.0, 1e-11], d: vec![0.0; 4] };
    let run = integrate(&mut sys, &[0.1, 0.1], &[0.0, 0.0], &settings(3.0, 0.5, 1e-8)).unwrap();
    assert_eq!(run.q(0), &[0.1, 0.1]);
    for (j, t) in run.time.iter().enumerate() {
        for (i, q) in run.q(j).iter().enumerate() {
            assert!((q - 0.1 * t.cos()).abs() < 1e-6, "oscillator {i} at t = {t}: {q}");
        }
    }
}

/// A system that checks the [`System::tangent`] contract: tangents are
/// asked at the state last passed to [`System::dynamics`] (a system may
/// cache what `dynamics` computed there).
struct Contract<S> {
    inner: S,
    last: Vec<f64>,
    tangents: usize,
    broken: usize,
}

impl<S: System> System for Contract<S> {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn closures(&self) -> usize {
        self.inner.closures()
    }
    fn dynamics(&mut self, q: &[f64], v: &[f64], t: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
        self.last = [q, v, &[t]].concat();
        self.inner.dynamics(q, v, t, mass, force)
    }
    fn tangent(&mut self, q: &[f64], v: &[f64], t: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
        self.tangents += 1;
        if self.last != [q, v, &[t]].concat() {
            self.broken += 1;
        }
        self.inner.tangent(q, v, t, k, d)
    }
    fn closure(&mut self, q: &[f64], c: &mut [f64], g: &mut [f64]) -> Result<()> {
        self.inner.closure(q, c, g)
    }
    fn energy(&mut self, q: &[f64], v: &[f64], t: f64) -> Result<f64> {
        self.inner.energy(q, v, t)
    }
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        self.inner.distance(a, b)
    }
}

/// The double pendulum released from 2 rad and 1 rad over 10 s at 1e-9,
/// where steps are rejected after the Newton matrix's data were kept: every
/// tangent must be asked at the state `dynamics` last saw.
#[test]
fn tangents_are_asked_where_dynamics_was_last_evaluated() {
    let inner = DoublePendulum { m1: 1.2, m2: 0.8, l1: 0.5, l2: 0.4 };
    let mut sys = Contract { inner, last: Vec::new(), tangents: 0, broken: 0 };
    let run = integrate(&mut sys, &[2.0, 1.0], &[0.0, 0.0], &settings(10.0, 1.0, 1e-9)).unwrap();
    assert!(run.rejected > 0 && sys.tangents > 1, "{} rejected, {} tangents", run.rejected, sys.tangents);
    assert_eq!(sys.broken, 0, "{} of {} tangents away from the last dynamics state", sys.broken, sys.tangents);
}

/// The pendulum in Cartesian coordinates of its mass, with the closure
/// $x^2 + y^2 - l^2 = 0$ (index 3): $m\ddot x = -2x\lambda$,
/// $m\ddot y = -mg - 2y\lambda$.
struct CartesianPendulum {
    m: f64,
    l: f64,
}

impl System for CartesianPendulum {
    fn dim(&self) -> usize {
        2
    }
    fn closures(&self) -> usize {
        1
    }
    fn dynamics(&mut self, _: &[f64], _: &[f64], _: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
        mass.copy_from_slice(&[self.m, 0.0, 0.0, self.m]);
        force.copy_from_slice(&[0.0, -self.m * G]);
        Ok(())
    }
    fn tangent(&mut self, _: &[f64], _: &[f64], _: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
        k.fill(0.0);
        d.fill(0.0);
        Ok(())
    }
    fn closure(&mut self, q: &[f64], c: &mut [f64], g: &mut [f64]) -> Result<()> {
        c[0] = q[0] * q[0] + q[1] * q[1] - self.l * self.l;
        g.copy_from_slice(&[2.0 * q[0], 2.0 * q[1]]);
        Ok(())
    }
    fn energy(&mut self, q: &[f64], v: &[f64], _: f64) -> Result<f64> {
        Ok(0.5 * self.m * (v[0] * v[0] + v[1] * v[1]) + self.m * G * q[1])
    }
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        (a[0].atan2(-a[1]) - b[0].atan2(-b[1])).abs()
    }
}

/// Released from rest at θ₀ = 1.2 rad, the Cartesian pendulum must follow
/// the angle form $\ddot\theta = -(g/l)\sin\theta$ (RK4 at 1e-5 s, error
/// below 1e-12) to ten times the tolerance (1e-8 m) over 2 s at tolerance
/// 1e-9, with the closure held to 1e-11 m² at every step: the index-3 stages
/// solve it, up to Newton's stopping test (3e-5 of the tolerance here) and
/// rounding.
#[test]
fn cartesian_pendulum_with_a_closure_matches_the_angle_form() {
    let (m, l, theta0): (f64, f64, f64) = (0.5, 0.8, 1.2);
    let mut sys = CartesianPendulum { m, l };
    let q0 = [l * theta0.sin(), -l * theta0.cos()];
    let duration = 2.0;
    let run = integrate(&mut sys, &q0, &[0.0, 0.0], &settings(duration, 0.5, 1e-9)).unwrap();
    let mut worst: f64 = 0.0;
    for (j, &t) in run.time.iter().enumerate() {
        let steps = (t / 1e-5).round().max(1.0) as usize;
        let [th, _] = rk4(|y: &[f64; 2]| [y[1], -(G / l) * y[0].sin()], [theta0, 0.0], t, steps);
        let q = run.q(j);
        worst = worst.max((q[0] - l * th.sin()).abs()).max((q[1] + l * th.cos()).abs());
    }
    assert!(worst < 1e-8, "off the angle form by {worst} m");
    assert!(run.violation < 1e-11, "closure violated by {}", run.violation);
}

/// An undamped Duffing oscillator $\ddot x = -x - x^3$ from x = 1 at rest
/// (period 4.8 s): over 100·2π s (more than 100 periods) at tolerance 1e-10
/// the energy $\tfrac12\dot x^2 + \tfrac12x^2 + \tfrac14x^4$ must stay within
/// 1e-6 of its start, the bound.
#[test]
fn energy_drifts_less_than_1e6_over_100_periods() {
    struct Duffing;
    impl System for Duffing {
        fn dim(&self) -> usize {
            1
        }
        fn closures(&self) -> usize {
            0
        }
        fn dynamics(&mut self, q: &[f64], _: &[f64], _: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
            mass[0] = 1.0;
            force[0] = -q[0] - q[0].powi(3);
            Ok(())
        }
        fn tangent(&mut self, q: &[f64], _: &[f64], _: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
            k[0] = 1.0 + 3.0 * q[0] * q[0];
            d[0] = 0.0;
            Ok(())
        }
        fn energy(&mut self, q: &[f64], v: &[f64], _: f64) -> Result<f64> {
            Ok(0.5 * v[0] * v[0] + 0.5 * q[0] * q[0] + 0.25 * q[0].powi(4))
        }
        fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
            (a[0] - b[0]).abs()
        }
    }
    let duration = 100.0 * 2.0 * std::f64::consts::PI;
    let run = integrate(&mut Duffing, &[1.0], &[0.0], &settings(duration, 1.0, 1e-10)).unwrap();
    let e0 = run.energy[0];
    let drift = run.energy.iter().map(|e| ((e - e0) / e0).abs()).fold(0.0, f64::max);
    assert!(drift <= 1e-6, "energy drifted by {drift}");
}

fn bad(s: MotionSettings) -> &'static str {
    let mut p = Pendulum { m: 1.0, l: 1.0, c: 0.0 };
    match integrate(&mut p, &[0.1], &[0.0], &s) {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("expected an invalid parameter, got {other:?}"),
    }
}

/// A duration, interval or tolerance that is zero, negative or not a
/// number, and an initial state of the wrong length, are errors naming
/// them (the CLI's `--duration`, `--every`, `--tolerance`).
#[test]
fn bad_settings_name_the_parameter() {
    let good = settings(1.0, 0.1, 1e-8);
    assert_eq!(bad(MotionSettings { duration: 0.0, ..good }), "duration");
    assert_eq!(bad(MotionSettings { duration: -1.0, ..good }), "duration");
    assert_eq!(bad(MotionSettings { duration: f64::NAN, ..good }), "duration");
    assert_eq!(bad(MotionSettings { every: 0.0, ..good }), "every");
    assert_eq!(bad(MotionSettings { every: -0.1, ..good }), "every");
    assert_eq!(bad(MotionSettings { every: 1e-9, ..good }), "every");
    assert_eq!(bad(MotionSettings { tolerance: 0.0, ..good }), "tolerance");
    assert_eq!(bad(MotionSettings { tolerance: -1e-8, ..good }), "tolerance");
    assert_eq!(bad(MotionSettings { tolerance: 2.0, ..good }), "tolerance");
    assert_eq!(bad(MotionSettings { absolute: 0.0, ..good }), "absolute");
    assert_eq!(bad(MotionSettings { max_step: 0.0, ..good }), "max_step");
    assert_eq!(bad(MotionSettings { max_rotation_per_step: -1.0, ..good }), "max_rotation_per_step");
    assert_eq!(bad(MotionSettings { max_steps: Some(0), ..good }), "max_steps");
    let mut p = Pendulum { m: 1.0, l: 1.0, c: 0.0 };
    let e = integrate(&mut p, &[0.1, 0.2], &[0.0], &good).unwrap_err();
    assert!(matches!(e, Error::InvalidParameter { name: "initial", .. }), "{e}");
    let e = integrate(&mut p, &[0.1], &[f64::NAN], &good).unwrap_err();
    assert!(matches!(e, Error::InvalidParameter { name: "initial_velocity", .. }), "{e}");
}

/// Samples fall at 0, Δt, 2Δt, … and T exactly, also when T is no multiple
/// of Δt; `max_step` and the rotation bound are honoured (counted: the
/// steps must at least cover the duration in steps of `max_step`, and the
/// swing's travel, read off the samples, in turns of the bound).
#[test]
fn samples_steps_and_rotation_bound() {
    let mut p = Pendulum { m: 1.0, l: 1.0, c: 0.0 };
    let run = integrate(&mut p, &[1.0], &[0.0], &settings(1.05, 0.25, 1e-6)).unwrap();
    assert_eq!(run.time, [0.0, 0.25, 0.5, 0.75, 1.0, 1.05]);
    let loose = integrate(&mut p, &[1.0], &[0.0], &settings(2.0, 2.0, 1e-4)).unwrap();
    let capped =
        integrate(&mut p, &[1.0], &[0.0], &MotionSettings { max_step: 0.01, ..settings(2.0, 2.0, 1e-4) }).unwrap();
    assert!(capped.steps >= 200 && capped.steps > loose.steps, "{} vs {}", capped.steps, loose.steps);
    let bound = 0.02;
    let turned = integrate(
        &mut p,
        &[1.0],
        &[0.0],
        &MotionSettings { max_rotation_per_step: bound, ..settings(2.0, 0.01, 1e-4) },
    )
    .unwrap();
    let travel: f64 = (1..turned.time.len()).map(|k| (turned.q(k)[0] - turned.q(k - 1)[0]).abs()).sum();
    assert!(turned.steps as f64 >= travel / bound, "{} steps for {travel} rad", turned.steps);
}

/// The progress hook hears once per accepted step, with the fraction of the
/// duration reached: increasing, ending at exactly 1, and silent outside
/// `with_progress`.
#[test]
fn progress_is_reported_per_step_up_to_one() {
    use flexure::dynamics::integrate::with_progress;
    use std::sync::Mutex;
    static SEEN: Mutex<Vec<f64>> = Mutex::new(Vec::new());
    let mut p = Pendulum { m: 1.0, l: 1.0, c: 0.0 };
    let run = with_progress(
        |f| SEEN.lock().unwrap().push(f),
        || integrate(&mut p, &[1.0], &[0.0], &settings(2.0, 0.5, 1e-6)).unwrap(),
    );
    integrate(&mut p, &[1.0], &[0.0], &settings(2.0, 0.5, 1e-6)).unwrap();
    let seen = SEEN.lock().unwrap().clone();
    assert_eq!(seen.len(), run.steps, "one report per accepted step");
    assert!(seen.windows(2).all(|w| w[1] > w[0]) && seen[0] > 0.0, "{seen:?}");
    assert_eq!(*seen.last().unwrap(), 1.0);
}

/// A system that cannot be evaluated past q = -1 (falling at 1 m/s² from
/// rest at 0, it gets there at t = √2): the run stalls there and says so,
/// with the time reached; an interrupt stops it at once.
#[test]
fn failures_say_what_was_reached() {
    struct Fall;
    impl System for Fall {
        fn dim(&self) -> usize {
            1
        }
        fn closures(&self) -> usize {
            0
        }
        fn dynamics(&mut self, q: &[f64], _: &[f64], _: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
            if q[0] < -1.0 {
                return Err(Error::Singular { what: "beyond the floor".into() });
            }
            mass[0] = 1.0;
            force[0] = -1.0;
            Ok(())
        }
        fn tangent(&mut self, _: &[f64], _: &[f64], _: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
            k[0] = 0.0;
            d[0] = 0.0;
            Ok(())
        }
        fn energy(&mut self, q: &[f64], v: &[f64], _: f64) -> Result<f64> {
            Ok(0.5 * v[0] * v[0] + q[0])
        }
        fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
            (a[0] - b[0]).abs()
        }
    }
    let e = integrate(&mut Fall, &[0.0], &[0.0], &settings(3.0, 0.5, 1e-8)).unwrap_err();
    match &e {
        Error::IntegrationStalled { time, duration, cause, .. } => {
            assert!((time - 2f64.sqrt()).abs() < 1e-6, "{e}");
            assert_eq!(*duration, 3.0);
            assert!(cause.contains("beyond the floor"), "{e}");
        }
        other => panic!("{other}"),
    }
    let mut p = Pendulum { m: 1.0, l: 1.0, c: 0.0 };
    let e = flexure::solver::with_interrupt(|| true, || integrate(&mut p, &[1.0], &[0.0], &settings(1.0, 0.1, 1e-6)));
    assert!(matches!(e, Err(Error::InterruptedAt { time: 0.0, duration: 1.0 })), "{e:?}");
}

/// With damping the energy only falls (sampled), and the run ends near rest.
#[test]
fn damped_pendulum_loses_energy() {
    let mut p = Pendulum { m: 1.0, l: 1.0, c: 2.0 };
    let run: Trajectory = integrate(&mut p, &[2.0], &[0.0], &settings(10.0, 0.1, 1e-8)).unwrap();
    assert!(run.energy.windows(2).all(|e| e[1] <= e[0] + 1e-12), "{:?}", run.energy);
    assert!(run.q(run.time.len() - 1)[0].abs() < 1e-2);
}

/// The optimized integrator (kept Newton matrix, extrapolated Newton start)
/// on a flexure with distributed mass (order 4, 0.3 kg/m, EI = 2 N·m²,
/// 0.5 m) carrying a 0.1 kg tip body, released at rest from its first mode
/// shape (`dynamics::mechanism::modes`, an independent generalized
/// eigenproblem about the rest shape) scaled to a tip angle of 1e-3 rad,
/// for ten periods 2π/ω₁, sampled every quarter period so the steps are
/// the error control's own:
///
/// - the frequency: were it ω₁(1 + δ), the tip angle's rate after ten
///   periods would be −ε ω₁ sin(20πδ), so δ = −v/(20π ω₁ ε) is measured
///   from that sample; |δ| < 2e-6 (the amplitude's nonlinear shift, of
///   order ε² = 1e-6, and the tolerance);
/// - at tolerance 1e-6 (absolute 1e-6 of the amplitude) every sample
///   agrees with a run at 1e-11 to 2e-5 of the amplitude: the local
///   tolerance accumulated over ten periods of error-controlled steps.
///
/// Measured: δ = 1.0e-8, 3.5e-7 of the amplitude (501 and 34718 steps).
#[test]
fn flexure_vibration_matches_its_mode_and_a_tight_run() {
    use flexure::dynamics::mechanism::{MechanismSystem, modes};
    use flexure::mechanism::file::from_toml;
    let m = from_toml(
        "[[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.5\n\
         ei = 2.0\nmass_per_length = 0.3\norder = 4\n[[body]]\nname = \"tip\"\nmass = 0.1\ncom = [0.0, 0.0]\n",
    )
    .unwrap();
    let w = modes(&m, &flexure::mechanism::statics::Settings::default(), 1).unwrap();
    let (omega, shape) = (w.omega[0], w.shapes.column(0));
    let period = std::f64::consts::TAU / omega;
    // The tip angle is the first coordinate (Legendre basis: ∂φ_tip/∂α = (1, 0, …)).
    let amplitude = 1e-3;
    let q0: Vec<f64> = shape.iter().map(|s| amplitude * s / shape[0]).collect();
    let v0 = vec![0.0; q0.len()];
    let run = |tolerance: f64| {
        let s = MotionSettings {
            duration: 10.0 * period,
            every: period / 4.0,
            tolerance,
            absolute: amplitude * tolerance,
            ..Default::default()
        };
        integrate(&mut MechanismSystem::new(&m).unwrap(), &q0, &v0, &s).unwrap()
    };
    let (coarse, tight) = (run(1e-6), run(1e-11));
    let last = coarse.time.len() - 1;
    assert_eq!(last, 40);
    let delta = -coarse.v(last)[0] / (20.0 * std::f64::consts::PI * omega * amplitude);
    assert!(delta.abs() < 2e-6, "frequency off by {delta:.3e} of ω₁ = {omega}");
    let worst = (0..coarse.time.len())
        .map(|k| coarse.q(k).iter().zip(tight.q(k)).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max);
    assert!(worst < 2e-5 * amplitude, "tolerance 1e-6 vs 1e-11: {:.3e} of the amplitude", worst / amplitude);
}

/// A mechanism's equations with the error test of a system that does not
/// weigh its coordinates ([`System::error_weights`]'s default): each
/// coordinate against its own size, as before the weights.
struct Unweighted<S>(S);

impl<S: System> System for Unweighted<S> {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    fn closures(&self) -> usize {
        self.0.closures()
    }
    fn dynamics(&mut self, q: &[f64], v: &[f64], t: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
        self.0.dynamics(q, v, t, mass, force)
    }
    fn tangent(&mut self, q: &[f64], v: &[f64], t: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
        self.0.tangent(q, v, t, k, d)
    }
    fn energy(&mut self, q: &[f64], v: &[f64], t: f64) -> Result<f64> {
        self.0.energy(q, v, t)
    }
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        self.0.distance(a, b)
    }
    fn jumps(&self) -> Vec<f64> {
        self.0.jumps()
    }
}

/// The steel strip of `scripts/strip_release.toml` (BENCHMARKS.md, "The
/// strip release") at `order`, released from 60 N over 0.01 s (about 1.6
/// swings), at `tolerance`: its tip's positions at the 21 samples and the
/// steps taken, with the mechanism's error weights or without.
fn strip_release(order: usize, tolerance: f64, weighted: bool) -> (Vec<[f64; 2]>, usize) {
    use flexure::dynamics::schedule::ScheduledSystem;
    use flexure::dynamics::simulation::{Start, initial_state};
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scripts/strip_release.toml")).unwrap();
    assert_eq!(text.matches("order = 6").count(), 1, "scripts/strip_release.toml no longer has order 6");
    let m = flexure::mechanism::file::from_toml(&text.replace("order = 6", &format!("order = {order}"))).unwrap();
    let (q0, v0) = initial_state(&m, &Default::default(), Start::Equilibrium).unwrap();
    let s = MotionSettings { absolute: tolerance, ..settings(0.01, 5e-4, tolerance) };
    let system = ScheduledSystem::new(&m).unwrap();
    let run = match weighted {
        true => integrate(&mut { system }, &q0, &v0, &s),
        false => integrate(&mut Unweighted(system), &q0, &v0, &s),
    }
    .unwrap();
    assert_eq!(run.time.len(), 21);
    let tips = (0..21)
        .map(|k| {
            let tip = &flexure::mechanism::kinematics::frames(&m, run.q(k)).bodies[1];
            [tip.x, tip.y]
        })
        .collect();
    (tips, run.steps)
}

/// The largest distance between two tip histories, over L = 0.05 m.
fn tip_distance(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    a.iter().zip(b).map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1])).fold(0.0, f64::max) / 0.05
}

/// The error test in radians of section turn (module docs of `integrate`):
/// the strip released from a large deflection excites its truncation's top
/// mode, whose frequency grows with the order (46 kHz at order 6, 248 kHz
/// at 10). Weighed per coordinate, the steps at tolerance 1e-3 grow with
/// the order (resolving that mode); weighed by section turn they do not:
/// at most 1.2× per order added from 6 to 10 (BENCHMARKS.md's target;
/// measured 3,043 steps at order 6 and 2,998 at 10), and under a third of
/// the unweighted ones at order 10 (measured 23,467). The reference is the
/// same motion converged: the unweighted run at 1e-7 (the weighted and
/// unweighted runs converge together: order 10 at 1e-7 and 1e-5 agree to
/// 1.6e-7 L over 0.05 s). The weighted run at 1e-3 is within 1e-4 L of it
/// (measured 3.2e-5 L), and the error estimate `simulate` makes (a run at a
/// tenth of the tolerance) sees that error to within a factor of 2
/// (measured 0.94). Orders 6 and 10 differ by the order's error (measured
/// 7.3e-4 L; held to 2e-3).
#[test]
fn a_release_that_excites_the_top_mode_does_not_resolve_it() {
    let (tips6, steps6) = strip_release(6, 1e-3, true);
    let (tips10, steps10) = strip_release(10, 1e-3, true);
    let (_, unweighted10) = strip_release(10, 1e-3, false);
    assert!(
        (steps10 as f64) <= 1.2f64.powi(4) * steps6 as f64 && 3 * steps10 < unweighted10,
        "steps: order 6 {steps6}, order 10 {steps10}, order 10 unweighted {unweighted10}"
    );
    let (reference, _) = strip_release(6, 1e-7, false);
    let (tighter, _) = strip_release(6, 1e-4, true);
    let (error, estimate) = (tip_distance(&tips6, &reference), tip_distance(&tips6, &tighter));
    assert!(
        error < 1e-4 && estimate > 0.5 * error && estimate < 2.0 * error,
        "error {error:.3e} L, estimate {estimate:.3e} L"
    );
    assert!(tip_distance(&tips10, &tips6) < 2e-3, "orders 6 and 10 differ by {:.3e} L", tip_distance(&tips10, &tips6));
}
