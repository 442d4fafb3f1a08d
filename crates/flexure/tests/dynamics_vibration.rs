//! The exact linear vibration of a straight beam (`flexure::reference::vibration`,
//! counted by Wittrick–Williams and refined on the dynamic stiffness) against
//! closed forms: the cantilever's and the tip-mass frequency equations (solved
//! here independently) to mode 30 and the asymptote (2n − 1)π/2, the
//! clamped–clamped and clamped–pinned beams (a tip body of overwhelming
//! inertia), a massless beam carrying a rigid body (its tip compliance), a
//! massless column with a point mass and the massive beam-column under
//! compression or tension, the refusal past buckling, and the interrupt.

use flexure::inertia::RigidInertia;
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
        let body = RigidInertia::new(r, 0.0, [0.0, 0.0]).unwrap();
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
        RigidInertia::new(0.01, 2e-6, [0.0, 0.0]).unwrap(),
        RigidInertia::new(0.01, 1e-7, [0.015, 0.004]).unwrap(),
        RigidInertia::new(0.0, 3e-7, [0.0, 0.0]).unwrap(),
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
    let point = RigidInertia::new(0.02, 0.0, [0.0, 0.0]).unwrap();
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
    let body = RigidInertia::new(m, 0.0, [0.0, 0.0]).unwrap();
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
    let bad = RigidInertia { mass: -1.0, inertia: 0.0, com: [0.0, 0.0] };
    assert_eq!(name(frequencies(&f, Some(&bad), 0.0, 1, &Default::default())), "mass");
    let zero = RigidInertia::default();
    assert_eq!(name(frequencies(&beam(1.0, 1.0, None), Some(&zero), 0.0, 1, &Default::default())), "mass");
}

/// βL of the uniform cantilever to mode 30. Reference: the roots of
/// cos x cosh x = −1, solved here by bisection on 1/cosh x + cos x, within
/// 1e-11 relative (each root is refined to 1e-12; measured: at most 3e-13);
/// and the asymptote (2n − 1)π/2, whose own error is 2e^(−βL), within
/// 1e-6 relative from mode 5 (mode 5: 1.5e-6 absolute, 1e-7 relative). The old
/// single shot lost every mode past the 11th to cancellation (e^(2βL) terms).
#[test]
fn cantilever_to_mode_30_and_the_asymptote() {
    let own = roots(tip_mass_equation(0.0), 0.5, 95.0, 0.01);
    assert!(own.len() >= 30, "{} roots", own.len());
    let v = frequencies(&beam(1.0, 1.0, Some(1.0)), None, 0.0, 30, &Default::default()).unwrap();
    assert_eq!(v.scaled.len(), 30);
    for n in 1..=30 {
        let b = v.scaled[n - 1];
        assert!((b - own[n - 1]).abs() < 1e-11 * own[n - 1], "mode {n}: βL = {b} vs {}", own[n - 1]);
        if n >= 5 {
            let asymptote = (2 * n - 1) as f64 * std::f64::consts::FRAC_PI_2;
            assert!((b / asymptote - 1.0).abs() < 1e-6, "mode {n}: βL = {b} vs (2n − 1)π/2 = {asymptote}");
        }
        // ω = (βL)² for L = EI = μ = 1.
        assert!((v.omega[n - 1] - b * b).abs() < 1e-12 * b * b);
    }
}

/// A point mass at the tip to mode 30: the tip-mass frequency equation above,
/// solved here by bisection on a grid of 0.005 (roots are at least 2.5 apart),
/// within 1e-11 relative (as the cantilever's), for a light and a heavy mass.
#[test]
fn tip_mass_to_mode_30() {
    let f = beam(1.0, 1.0, Some(1.0));
    for r in [0.2, 10.0] {
        let own = roots(tip_mass_equation(r), 0.01, 95.0, 0.005);
        let body = RigidInertia::new(r, 0.0, [0.0, 0.0]).unwrap();
        let v = frequencies(&f, Some(&body), 0.0, 30, &Default::default()).unwrap();
        for k in 0..30 {
            assert!(
                (v.scaled[k] / own[k] - 1.0).abs() < 1e-11,
                "m/μL = {r}, mode {}: {} vs {}",
                k + 1,
                v.scaled[k],
                own[k]
            );
        }
    }
}

/// A tip body of mass 1e8 μL and inertia 1e8 μL³ holds the tip still at the
/// beam's frequencies: after its own two modes on the beam's static tip
/// stiffness (EI/L³)[[12, −6], [−6, 4]] (ω² the roots of det(K − ω²M_b), the
/// beam's own inertia a 1e-8 correction), the clamped–clamped beam, the roots
/// of cos x cosh x = 1 (4.7300, 7.8532, …; solved here on 1/cosh x − cos x),
/// within 1e-6 relative (the body's residual motion, ~1e-8). A point mass
/// of 1e8 μL alone pins the tip: after its mode √(3EI/mL³), the
/// clamped–pinned roots of tan x = tanh x (3.9266, 7.0686, …).
#[test]
fn clamped_and_pinned_tips() {
    let f = beam(1.0, 1.0, Some(1.0));
    let big = 1e8;
    let clamped = roots(|x: f64| 1.0 / x.cosh() - x.cos(), 1.0, 40.0, 0.01);
    let v =
        frequencies(&f, Some(&RigidInertia::new(big, big, [0.0, 0.0]).unwrap()), 0.0, 12, &Default::default()).unwrap();
    // det(K − ω²m I) for K = [[12, −6], [−6, 4]], M_b = big·I.
    let (tr, det) = (16.0 / big, (48.0 - 36.0) / (big * big));
    let body = [0.5 * (tr - (tr * tr - 4.0 * det).sqrt()), 0.5 * (tr + (tr * tr - 4.0 * det).sqrt())];
    for k in 0..2 {
        let w = v.omega[k];
        assert!((w * w / body[k] - 1.0).abs() < 1e-6, "body mode {k}: ω² = {} vs {}", w * w, body[k]);
    }
    for k in 2..12 {
        assert!(
            (v.scaled[k] / clamped[k - 2] - 1.0).abs() < 1e-6,
            "mode {k}: {} vs clamped–clamped {}",
            v.scaled[k],
            clamped[k - 2]
        );
    }
    assert!((clamped[0] - 4.7300).abs() < 1e-4 && (clamped[1] - 7.8532).abs() < 1e-4);
    let pinned = roots(|x: f64| x.tan() - x.tanh(), 1.0, 40.0, 0.01)
        .into_iter()
        .filter(|x| (x.tan() - x.tanh()).abs() < 1e-6) // not tan's poles
        .collect::<Vec<_>>();
    let v =
        frequencies(&f, Some(&RigidInertia::new(big, 0.0, [0.0, 0.0]).unwrap()), 0.0, 11, &Default::default()).unwrap();
    let w0 = (3.0 / big).sqrt();
    assert!((v.omega[0] / w0 - 1.0).abs() < 1e-6, "{} vs {w0}", v.omega[0]);
    for k in 1..11 {
        assert!(
            (v.scaled[k] / pinned[k - 1] - 1.0).abs() < 1e-6,
            "mode {k}: {} vs clamped–pinned {}",
            v.scaled[k],
            pinned[k - 1]
        );
    }
    assert!((pinned[0] - 3.9266).abs() < 1e-4 && (pinned[1] - 7.0686).abs() < 1e-4);
}

/// The uniform beam-column w'''' + p w'' = λ w (L = EI = μ = 1), clamped at
/// 0, free at 1 (w'' = 0, w''' + p w' = 0): on the basis cosh αx, sinh αx,
/// cos γx, sin γx with α² = (√(p² + 4λ) − p)/2, γ² = (√(p² + 4λ) + p)/2, the
/// determinant of the four end conditions, each column divided by cosh α.
fn beam_column(p: f64) -> impl Fn(f64) -> f64 {
    move |b: f64| {
        let lambda = b.powi(4);
        let root = (p * p + 4.0 * lambda).sqrt();
        let (a, g) = (((root - p) / 2.0).sqrt(), ((root + p) / 2.0).sqrt());
        let e = 1.0 / a.cosh();
        let (ch, sh) = (1.0, a.tanh()); // cosh α and sinh α times e
        let (c, s) = (g.cos() * e, g.sin() * e);
        // Rows: w(0), w'(0), w''(1), w'''(1) + p w'(1); columns: the basis, times e.
        let m = [
            [e, 0.0, e, 0.0],
            [0.0, a * e, 0.0, g * e],
            [a * a * ch, a * a * sh, -g * g * c, -g * g * s],
            [(a.powi(3) + p * a) * sh, (a.powi(3) + p * a) * ch, (g.powi(3) - p * g) * s, (p * g - g.powi(3)) * c],
        ];
        let det3 = |m: [[f64; 3]; 3]| {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        };
        (0..4)
            .map(|j| {
                let minor = [1, 2, 3].map(|r| {
                    let cols: Vec<f64> = (0..4).filter(|&c| c != j).map(|c| m[r][c]).collect();
                    [cols[0], cols[1], cols[2]]
                });
                let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
                sign * m[0][j] * det3(minor)
            })
            .sum()
    }
}

/// The massive uniform beam-column under compression (0.5, 0.9 and 1 − 1e-6
/// of the Euler load π²EI/4L²) and tension (5 EI/L²): three modes against the
/// roots of [`beam_column`]'s determinant, λ = (βL)⁴ within 1e-10 of the
/// larger of itself and the unloaded first λ (near buckling λ₁ is a
/// difference of stiffnesses of that size, so the absolute error is what
/// carries over); and the first frequency falling to zero as the compression
/// nears the buckling load: ω₁ at 1 − 1e-6 of it below 1e-2 of the unloaded
/// (the closed form: 1.04e-3 of it).
#[test]
fn beam_column_under_axial_load() {
    let f = beam(1.0, 1.0, Some(1.0));
    let euler = std::f64::consts::PI.powi(2) / 4.0;
    let unloaded = frequencies(&f, None, 0.0, 1, &Default::default()).unwrap().omega[0];
    let lambda0 = unloaded * unloaded; // λ = ω² for L = EI = μ = 1
    for p in [0.5 * euler, 0.9 * euler, -5.0, (1.0 - 1e-6) * euler] {
        let own = roots(beam_column(p), 0.02, 12.0, 0.002);
        let v = frequencies(&f, None, p, 3, &Default::default()).unwrap();
        for k in 0..3 {
            let (got, want) = (v.scaled[k].powi(4), own[k].powi(4));
            let scale = want.max(lambda0);
            assert!((got - want).abs() < 1e-10 * scale, "P = {p}, mode {}: λ = {got} vs {want}", k + 1);
        }
    }
    let near = frequencies(&f, None, (1.0 - 1e-6) * euler, 1, &Default::default()).unwrap().omega[0];
    assert!(near < 1e-2 * unloaded, "ω₁ = {near} near buckling vs {unloaded} unloaded");
}

/// A compression past the buckling load is refused, naming the parameter and
/// the load π²EI/4L² of the uniform column, with a distributed mass or a tip
/// mass alone; a huge compression is refused as promptly (the old scan ran for
/// a minute), and one just below the load is answered.
#[test]
fn compression_past_buckling_is_refused() {
    let (l, ei) = (0.5, 3.0);
    let euler = std::f64::consts::PI.powi(2) * ei / (4.0 * l * l);
    for (mu, body) in [(Some(1.0), None), (None, Some(RigidInertia::new(0.2, 0.0, [0.0, 0.0]).unwrap()))] {
        let f = beam(l, ei, mu);
        for p in [1.0001 * euler, 1.4 * euler, 1e6, 1e12] {
            match frequencies(&f, body.as_ref(), p, 2, &Default::default()) {
                Err(Error::InvalidParameter { name: "compression", value, .. }) => {
                    assert!(value.contains(&format!("{euler}")), "{value}");
                }
                other => panic!("P = {p}: expected a refusal, got {other:?}"),
            }
        }
        assert!(frequencies(&f, body.as_ref(), 0.999 * euler, 1, &Default::default()).is_ok());
    }
}

/// The interrupt hook stops the count: `Interrupted`, with the fraction of the
/// modes found (none yet, at the first element).
#[test]
fn interrupt_stops_the_search() {
    let f = beam(1.0, 1.0, Some(1.0));
    let r = flexure::solver::with_interrupt(|| true, || frequencies(&f, None, 0.0, 30, &Default::default()));
    match r {
        Err(Error::Interrupted { load_fraction }) => assert_eq!(load_fraction, 0.0),
        other => panic!("expected an interruption, got {other:?}"),
    }
}

/// A tapered column, EI from 2 at the root to 1 at the tip: the count at
/// ω = 0 turns at the shooting reference's buckling load
/// (`reference::column::buckling_load`, bisected to rounding): answered
/// at 0.999 of it, with a first frequency below that of 0.99 of it, and refused
/// at 1.001 of it, naming that load.
#[test]
fn tapered_column_refused_past_its_own_buckling_load() {
    let s = Section::given(Profile::Linear { root: 2.0, tip: 1.0 })
        .unwrap()
        .with_mass_per_length(Profile::Constant(1.0))
        .unwrap();
    let f = Flexure::new(1.0, 1.5, 3).unwrap().with_section(s).unwrap();
    let load =
        flexure::reference::column::buckling_load(&f, flexure::TipConstraint::Free, &Default::default()).unwrap();
    let at = |share: f64| frequencies(&f, None, share * load, 1, &Default::default()).map(|v| v.omega[0]);
    let (softer, stiffer) = (at(0.999).unwrap(), at(0.99).unwrap());
    assert!(0.0 < softer && softer < stiffer, "{softer} vs {stiffer}");
    match at(1.001) {
        Err(Error::InvalidParameter { name: "compression", value, .. }) => {
            assert!(value.contains(&format!("{load}")), "{value}")
        }
        other => panic!("expected a refusal, got {other:?}"),
    }
}
