//! The exact linear vibration of a straight beam by shooting on the
//! frequency (`flexure::reference::vibration`) against closed forms: the
//! cantilever's and the tip-mass frequency equations (solved here
//! independently), a massless beam carrying a rigid body (its tip compliance),
//! and a massless column with a point mass under compression or tension.

use flexure::dynamics::Body;
use flexure::reference::vibration::frequencies;
use flexure::section::{Profile, Section};
use flexure::{Error, Flexure};

fn beam(length: f64, ei: f64, mu: Option<f64>) -> Flexure {
    let mut s = Section::given(Profile::Constant(ei)).unwrap();
    if let Some(mu) = mu {
        s = s.with_mass_per_length(Profile::Constant(mu)).unwrap();
    }
    Flexure::new(length, ei, 3).unwrap().with_section(s).unwrap()
}

/// The roots of `g` in (lo, hi), bracketed on a grid of `step` and bisected to rounding.
fn roots(g: impl Fn(f64) -> f64, lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut a = lo;
    while a < hi {
        let b = a + step;
        if g(a).signum() != g(b).signum() {
            let (mut x0, mut x1) = (a, b);
            for _ in 0..100 {
                let mid = 0.5 * (x0 + x1);
                if g(mid).signum() == g(x0).signum() { x0 = mid } else { x1 = mid }
            }
            out.push(0.5 * (x0 + x1));
        }
        a = b;
    }
    out
}

/// The tip-mass frequency equation with r = m_tip/(μL), divided by cosh βL:
/// (1 + cos x cosh x) + r x (cos x sinh x − sin x cosh x) = 0.
fn tip_mass_equation(r: f64) -> impl Fn(f64) -> f64 {
    move |x: f64| 1.0 / x.cosh() + x.cos() + r * x * (x.cos() * x.tanh() - x.sin())
}

/// βL of the uniform cantilever, published to five decimals (Blevins, "Formulas
/// for natural frequency and mode shape", Table 8-1): within 1e-5, the rounding
/// of the table. The same roots of cos βL cosh βL = −1 solved here by bisection:
/// within 1e-9 (the shooting's ODE tolerance is 1e-12). A beam with L, EI, μ ≠ 1
/// checks the scaling ω = (βL)² √(EI/μL⁴).
#[test]
fn uniform_cantilever_eigenvalues() {
    let published = [1.87510, 4.69409, 7.85476, 10.99554];
    let own = roots(tip_mass_equation(0.0), 0.5, 12.0, 0.01);
    assert_eq!(own.len(), 4);
    let (l, ei, mu) = (0.02, 1.4558e-3, 0.0157);
    let v = frequencies(&beam(l, ei, Some(mu)), None, 0.0, 4, &Default::default()).unwrap();
    for k in 0..4 {
        assert!((v.scaled[k] - published[k]).abs() < 1e-5, "mode {k}: βL = {}", v.scaled[k]);
        assert!((v.scaled[k] - own[k]).abs() < 1e-9, "mode {k}: βL = {} vs {}", v.scaled[k], own[k]);
        let omega = own[k].powi(2) * (ei / (mu * l.powi(4))).sqrt();
        assert!((v.omega[k] - omega).abs() < 1e-9 * omega, "mode {k}: ω = {} vs {omega}", v.omega[k]);
        assert!((v.frequency[k] - omega / std::f64::consts::TAU).abs() < 1e-9 * omega);
    }
}

/// A point mass m at the tip: the frequency equation above, solved here by
/// bisection, for m/μL from 0.01 to 10, three modes within 1e-9. The sign
/// convention is pinned down by the limit m → 0 (the cantilever's roots) and by
/// the known first root for m = μL, βL ≈ 1.2479 (Blevins, Table 8-8; 4 decimals).
#[test]
fn tip_mass_frequency_equation() {
    let f = beam(1.0, 1.0, Some(1.0));
    for r in [0.01, 0.2, 1.0, 10.0] {
        let own = roots(tip_mass_equation(r), 0.01, 9.0, 0.005);
        let body = Body::new(r, 0.0, [0.0, 0.0]).unwrap();
        let v = frequencies(&f, Some(&body), 0.0, 3, &Default::default()).unwrap();
        for k in 0..3 {
            assert!((v.scaled[k] - own[k]).abs() < 1e-9, "m/μL = {r}, mode {k}: {} vs {}", v.scaled[k], own[k]);
        }
        if r == 1.0 {
            assert!((v.scaled[0] - 1.2479).abs() < 1e-4, "{}", v.scaled[0]);
        }
    }
    let small = roots(tip_mass_equation(1e-9), 0.5, 5.0, 0.01);
    let cantilever = roots(tip_mass_equation(0.0), 0.5, 5.0, 0.01);
    assert!((small[0] - cantilever[0]).abs() < 1e-8 && (small[1] - cantilever[1]).abs() < 1e-8);
}

/// The massless beam's tip compliance in (w, θ), C = [[L³/3, L²/2], [L²/2, L]]/EI
/// (Euler–Bernoulli), with the body's mass matrix about the tip,
/// M_b = [[m, m c_x], [m c_x, I_c + m|c|²]]: ω² are the roots of
/// det(C⁻¹ − ω²M_b) = 0, a quadratic. Within 1e-9; a point mass has one mode,
/// ω = √(3EI/mL³), however many are asked.
#[test]
fn massless_beam_with_rigid_body() {
    let (l, ei) = (0.03, 2e-3);
    let f = beam(l, ei, None);
    for body in [
        Body::new(0.01, 2e-6, [0.0, 0.0]).unwrap(),
        Body::new(0.01, 1e-7, [0.015, 0.004]).unwrap(),
        Body::new(0.0, 3e-7, [0.0, 0.0]).unwrap(),
    ] {
        let c = [l.powi(3) / (3.0 * ei), l * l / (2.0 * ei), l / ei];
        let det_c = c[0] * c[2] - c[1] * c[1];
        let k = [c[2] / det_c, -c[1] / det_c, c[0] / det_c];
        let m = [body.mass, body.mass * body.com[0], body.inertia_about_tip()];
        // det(K − λM) = aλ² + bλ + d.
        let a = m[0] * m[2] - m[1] * m[1];
        let b = -(k[0] * m[2] + k[2] * m[0] - 2.0 * k[1] * m[1]);
        let d = k[0] * k[2] - k[1] * k[1];
        let mut exact: Vec<f64> = if a.abs() > 1e-12 * m[0].max(m[2]).powi(2) {
            let disc = (b * b - 4.0 * a * d).sqrt();
            vec![(-b - disc) / (2.0 * a), (-b + disc) / (2.0 * a)]
        } else {
            vec![-d / b]
        };
        exact.iter_mut().for_each(|x| *x = x.sqrt());
        let v = frequencies(&f, Some(&body), 0.0, 3, &Default::default()).unwrap();
        assert_eq!(v.omega.len(), exact.len(), "{body:?}");
        for (w, e) in v.omega.iter().zip(&exact) {
            assert!((w - e).abs() < 1e-9 * e, "{body:?}: ω = {w} vs {e}");
        }
    }
    let point = Body::new(0.02, 0.0, [0.0, 0.0]).unwrap();
    let v = frequencies(&f, Some(&point), 0.0, 3, &Default::default()).unwrap();
    let exact = (3.0 * ei / (0.02 * l.powi(3))).sqrt();
    assert!(v.omega.len() == 1 && (v.omega[0] - exact).abs() < 1e-9 * exact);
}

/// A massless column under an axial compression P carrying a point mass: its
/// lateral tip stiffness is k = P/(L(tan κL/κL − 1)), κ = √(P/EI) (Timoshenko &
/// Gere, beam-columns), and under tension T, k = T/(L(1 − tanh κL/κL)); ω² = k/m.
/// Within 1e-9, up to 0.99 of the Euler load π²EI/4L², where ω falls to zero.
#[test]
fn massless_column_under_axial_load() {
    let (l, ei, m) = (0.5, 3.0, 0.2);
    let f = beam(l, ei, None);
    let body = Body::new(m, 0.0, [0.0, 0.0]).unwrap();
    let euler = std::f64::consts::PI.powi(2) * ei / (4.0 * l * l);
    for share in [-2.0, -0.3, 0.3, 0.8, 0.99] {
        let p = share * euler;
        let x = (p.abs() / ei).sqrt() * l;
        let k = if p > 0.0 { p / (l * (x.tan() / x - 1.0)) } else { -p / (l * (1.0 - x.tanh() / x)) };
        let exact = (k / m).sqrt();
        let v = frequencies(&f, Some(&body), p, 1, &Default::default()).unwrap();
        assert!((v.omega[0] - exact).abs() < 1e-9 * exact, "P = {share} P_cr: ω = {} vs {exact}", v.omega[0]);
    }
}

#[test]
fn bad_input_is_named() {
    let f = beam(1.0, 1.0, Some(1.0));
    let name = |r: Result<_, Error>| match r {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("expected an invalid parameter, got {other:?}"),
    };
    assert_eq!(name(frequencies(&f, None, 0.0, 0, &Default::default())), "count");
    assert_eq!(name(frequencies(&f, None, f64::NAN, 1, &Default::default())), "compression");
    assert_eq!(name(frequencies(&beam(1.0, 1.0, None), None, 0.0, 1, &Default::default())), "mass");
    let bad = Body { mass: -1.0, inertia: 0.0, com: [0.0, 0.0] };
    assert_eq!(name(frequencies(&f, Some(&bad), 0.0, 1, &Default::default())), "mass");
    let zero = Body::default();
    assert_eq!(name(frequencies(&beam(1.0, 1.0, None), Some(&zero), 0.0, 1, &Default::default())), "mass");
}
