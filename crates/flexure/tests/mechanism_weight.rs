//! The weight of flexures with mass in the statics: a flexure's distributed
//! weight against beam theory and Greenhill's heavy column, its derivatives
//! against central differences, and the dynamics starting at rest on the
//! statics' equilibrium.

use flexure::dynamics::integrate::MotionSettings as Motion;
use flexure::dynamics::{SimulationSettings, Start, simulate};
use flexure::mechanism::buckling::buckle;
use flexure::mechanism::file::from_toml;
use flexure::mechanism::lagrangian::lagrangian;
use flexure::mechanism::statics::{Settings, solve};
use flexure::mechanism::{Loads, Mechanism};
use nalgebra::{DMatrix, DVector};

/// One flexure of length `l`, EI and mass per length `mu` from the ground
/// at angle `angle`, of order `order`, under gravity (0, −g), with a
/// massless body at its tip.
fn heavy(angle: f64, l: f64, ei: f64, mu: f64, g: f64, order: usize) -> Mechanism {
    from_toml(&format!(
        "gravity = [0.0, {:?}]\n[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\n\
         origin = [0.0, 0.0, {angle:?}]\nlength = {l:?}\nei = {ei:?}\nmass_per_length = {mu:?}\norder = {order}\n",
        -g
    ))
    .unwrap()
}

/// A horizontal cantilever under its own weight q = μg, in linear theory
/// (the bending moment q(L − s)²/2, so the curvature is quadratic in s and
/// the order-3 model holds it exactly): tip deflection qL⁴/8EI and tip
/// angle qL³/6EI, both downward. At qL³/EI = 1e-4 the large-deflection
/// correction is of relative order θ² ≈ 3e-10; tolerance 1e-8.
#[test]
fn cantilever_sags_by_beam_theory() {
    let (l, ei, mu, g): (f64, f64, f64, f64) = (0.05, 2e-3, 0.015, 9.81);
    let q = mu * g;
    let scale = q * l.powi(3) / ei;
    let m = heavy(0.0, l, ei, mu * 1e-4 / scale, g, 3);
    let q = q * 1e-4 / scale;
    let s = solve(&m, &Settings::default()).unwrap();
    let tip = flexure::mechanism::kinematics::frames(&m, &s.q).bodies[1];
    let (deflection, angle) = (q * l.powi(4) / (8.0 * ei), q * l.powi(3) / (6.0 * ei));
    assert!((tip.y + deflection).abs() < 1e-8 * deflection, "{} vs −{deflection}", tip.y);
    assert!((tip.phi + angle).abs() < 1e-8 * angle, "{} vs −{angle}", tip.phi);
}

/// The first positive zero of $J_{-1/3}$, from its power series (Γ by the
/// recursion from Γ(2/3)), by bisection on [1.5, 2.5].
fn bessel_zero() -> f64 {
    const GAMMA_TWO_THIRDS: f64 = 1.354_117_939_426_400_4;
    let j = |z: f64| {
        let (mut sum, mut gamma, mut factorial) = (0.0, GAMMA_TWO_THIRDS, 1.0);
        for k in 0..40 {
            if k > 0 {
                gamma *= k as f64 - 1.0 / 3.0;
                factorial *= k as f64;
            }
            sum += (-1f64).powi(k) * (z / 2.0).powf(2.0 * k as f64 - 1.0 / 3.0) / (factorial * gamma);
        }
        sum
    };
    let (mut a, mut b) = (1.5, 2.5);
    assert!(j(a) * j(b) < 0.0);
    for _ in 0..100 {
        let c = 0.5 * (a + b);
        if j(a) * j(c) <= 0.0 {
            b = c;
        } else {
            a = c;
        }
    }
    0.5 * (a + b)
}

/// Greenhill (1881): an upright column clamped at its foot buckles under
/// its own weight q when qL³/EI = (9/4)z², z the first zero of J₋₁/₃
/// (7.8373). The model's linear buckling load is a Ritz value, from above,
/// converging with the order: within 1e-6 by N = 8.
#[test]
fn upright_column_buckles_under_its_weight_at_greenhill_s_load() {
    let z = bessel_zero();
    let exact = 2.25 * z * z;
    assert!((exact - 7.837).abs() < 1e-3, "Greenhill's constant {exact}");
    let mut previous = f64::INFINITY;
    for order in [3, 4, 6, 8] {
        let m = heavy(std::f64::consts::FRAC_PI_2, 1.0, 1.0, 1.0 / 9.81, 9.81, order);
        let factor = buckle(&m, &Settings::default()).unwrap().load_factor;
        assert!(factor >= exact * (1.0 - 1e-12) && factor <= previous, "N = {order}: {factor} (exact {exact})");
        previous = factor;
    }
    assert!((previous / exact - 1.0).abs() < 1e-6, "N = 8: {previous} vs {exact}");
}

/// The weight's terms alone (the Lagrangian under gravity less the one
/// without) against central differences of its potential, on a chain where
/// they dominate: two heavy, soft flexures with a revolute and a slider
/// between them, at seeded random states and gravity directions. Step 1e-5;
/// tolerance 1e-6 relative (the difference error, about h²).
#[test]
fn weight_gradient_and_hessian_against_central_differences() {
    let m = from_toml(
        "[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b1\"\norigin = [0.01, 0.02, 0.3]\n\
         length = 0.05\nei = 1e-4\nmass_per_length = [0.2, 0.05]\norder = 4\n\
         [[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"b1\"\nchild = \"b2\"\norigin = [0.01, 0.0, 0.0]\n\
         [[joint]]\nname = \"slide\"\nkind = \"prismatic\"\nparent = \"b2\"\nchild = \"b3\"\norigin = [0.0, 0.01, 0.5]\n\
         [[joint]]\nname = \"c\"\nkind = \"flexure\"\nparent = \"b3\"\nchild = \"b4\"\norigin = [0.02, 0.0, -0.4]\n\
         length = 0.04\nei = 5e-5\nmass_per_length = 0.1\n",
    )
    .unwrap();
    let h = 1e-5;
    let mut rng = crate::seeded::Rng(7);
    for _ in 0..5 {
        let q: Vec<f64> = (0..m.dof()).map(|_| 0.6 * rng.next()).collect();
        let weighed = Loads { gravity: nalgebra::Vector2::new(10.0 * rng.next(), 10.0 * rng.next()), ..m.loads() };
        let terms = |q: &[f64]| {
            let (a, b) = (lagrangian(&m, q, &[], &weighed).unwrap(), lagrangian(&m, q, &[], &m.loads()).unwrap());
            (a.potential - b.potential, a.gradient - b.gradient, a.hessian - b.hessian)
        };
        let (_, gradient, hessian) = terms(&q);
        let mut numeric_gradient = DVector::zeros(q.len());
        let mut numeric_hessian = DMatrix::zeros(q.len(), q.len());
        for i in 0..q.len() {
            let (mut a, mut b) = (q.clone(), q.clone());
            a[i] += h;
            b[i] -= h;
            let (pa, ga, _) = terms(&a);
            let (pb, gb, _) = terms(&b);
            numeric_gradient[i] = (pa - pb) / (2.0 * h);
            numeric_hessian.set_column(i, &((ga - gb) / (2.0 * h)));
        }
        let relative = |a: &DMatrix<f64>, b: &DMatrix<f64>| (a - b).amax() / a.amax();
        let g = DMatrix::from_column_slice(q.len(), 1, gradient.as_slice());
        let ng = DMatrix::from_column_slice(q.len(), 1, numeric_gradient.as_slice());
        assert!(gradient.amax() > 1e-3, "the weight terms are there: {gradient}");
        assert!(relative(&g, &ng) < 1e-6, "gradient {gradient} vs {numeric_gradient}");
        assert!(relative(&hessian, &numeric_hessian) < 1e-6, "Hessian {hessian} vs {numeric_hessian}");
        assert!(relative(&hessian, &hessian.transpose()) < 1e-12, "the Hessian is symmetric");
    }
}

/// A heavy flexure holding a body out sideways under gravity, started at the
/// statics' equilibrium: the dynamics weigh every section too, so it stays
/// at rest. Over 0.2 s (several periods of its first mode) no coordinate
/// moves by more than 1e-9 of its value.
#[test]
fn simulation_started_at_the_statics_equilibrium_stays_there() {
    let m = from_toml(
        "gravity = [0.0, -9.81]\n[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"arm\"\n\
         length = 0.05\nei = 2e-3\nmass_per_length = 0.05\n\
         [[body]]\nname = \"arm\"\nmass = 0.002\ninertia = 1e-7\ncom = [0.01, 0.0]\n",
    )
    .unwrap();
    let motion = Motion { duration: 0.2, every: 0.05, tolerance: 1e-10, absolute: 1e-12, ..Default::default() };
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Equilibrium).unwrap();
    let start = run.q(0).to_vec();
    assert!(start[0] < -1e-3, "it sags: {start:?}");
    for k in 1..run.time.len() {
        for (a, b) in run.q(k).iter().zip(&start) {
            assert!((a - b).abs() <= 1e-9 * b.abs().max(1e-6), "t = {}: {:?} vs {start:?}", run.time[k], run.q(k));
        }
    }
}
