//! The model's vibration modes about a loaded equilibrium
//! (`flexure::dynamics::modes`) against exact linear beam theory: the
//! cantilever's βL (converging in the order N), the tip-mass equation, a
//! massless flexure carrying a rigid body (its exact tip compliance), rotary
//! inertia, bent equilibria, and frequencies that fall to zero at buckling.

use flexure::dynamics::modes;
use flexure::inertia::RigidInertia;
use flexure::mass::{MassData, MassModel, update as update_mass};
use flexure::reference::vibration::frequencies;
use flexure::section::{Profile, Section};
use flexure::{Error, Flexure, TipConstraint, TipLoad, buckling_load};
use nalgebra::{DMatrix, Matrix2};

fn beam(order: usize, ei: Profile, mu: Option<f64>) -> Flexure {
    let mut s = Section::given(ei).unwrap();
    if let Some(mu) = mu {
        s = s.with_mass_per_length(Profile::Constant(mu)).unwrap();
    }
    Flexure::new(1.0, 1.0, order).unwrap().with_section(s).unwrap()
}

fn uniform(order: usize, mu: Option<f64>) -> Flexure {
    beam(order, Profile::Constant(1.0), mu)
}

fn compression(p: f64) -> TipLoad {
    TipLoad { moment: 0.0, fx: -p, fy: 0.0 }
}

/// The cantilever's βL from the exact reference (itself checked against the
/// frequency equation in `dynamics_vibration`). The model is a Rayleigh–Ritz
/// approximation with admissible shapes, so its frequencies lie above the
/// exact ones (less 1e-12 for rounding) and fall with N; the first mode is
/// within 2e-6 from N = 4 and 2e-10 from N = 6, all four within 1e-9 at N = 14
/// (measured: 1.5e-6, 8e-11 and 1.5e-10).
#[test]
fn distributed_mass_converges_in_order_to_the_cantilever() {
    let exact = frequencies(&uniform(3, Some(1.0)), None, 0.0, 4, &Default::default()).unwrap().omega;
    let mut previous = vec![f64::INFINITY; 4];
    for n in 2..=14 {
        let m = modes(&uniform(n, Some(1.0)), &TipLoad::default(), None, 4).unwrap();
        assert_eq!(m.omega.len(), n.min(4));
        assert_eq!(m.quasi_static, 0, "a flexure with mass has no massless direction");
        for (k, (w, e)) in m.omega.iter().zip(&exact).enumerate() {
            let error = w / e - 1.0;
            assert!(error > -1e-12, "N = {n}, mode {k}: below the exact frequency by {error:e}");
            assert!(error <= previous[k] + 1e-12, "N = {n}, mode {k}: error {error:e} grew from {:e}", previous[k]);
            previous[k] = error;
        }
        let first = m.omega[0] / exact[0] - 1.0;
        if n >= 4 {
            assert!(first < 2e-6, "N = {n}: first mode error {first:e}");
        }
        if n >= 6 {
            assert!(first < 2e-10, "N = {n}: first mode error {first:e}");
        }
    }
    assert!(previous.iter().all(|e| *e < 1e-9), "N = 14: {previous:?}");
}

/// A tip mass m/μL = 0.5, 1, 10 on the distributed beam: at N = 12 the model's
/// three lowest frequencies are within 1e-11 of the exact ones (measured 5e-13),
/// and at N = 4 the first is within 1e-6 (measured 2e-7).
#[test]
fn tip_mass_on_a_distributed_beam() {
    for r in [0.5, 1.0, 10.0] {
        let body = RigidInertia::new(r, 0.0, [0.0, 0.0]).unwrap();
        let exact = frequencies(&uniform(3, Some(1.0)), Some(&body), 0.0, 3, &Default::default()).unwrap().omega;
        let m = modes(&uniform(12, Some(1.0)), &TipLoad::default(), Some(&body), 3).unwrap();
        for (w, e) in m.omega.iter().zip(&exact) {
            assert!((w / e - 1.0).abs() < 1e-11, "m/μL = {r}: ω = {w} vs {e}");
        }
        let m = modes(&uniform(4, Some(1.0)), &TipLoad::default(), Some(&body), 1).unwrap();
        assert!((m.omega[0] / exact[0] - 1.0).abs() < 1e-6);
    }
}

/// The exact 2×2 answer for a massless flexure carrying a body: K_tip = C⁻¹ with
/// C the exact tip compliance in (w, θ), C = ∫₀ᴸ [[(L−s)², L−s], [L−s, 1]]/EI ds,
/// and M_b = [[m, m c_x], [m c_x, I_c + m|c|²]]; ω² the eigenvalues of M_b⁻¹K_tip.
fn two_by_two(flexure: &Flexure, body: &RigidInertia) -> Vec<f64> {
    let l = flexure.length();
    let c = flexure::quadrature::integrate(&[], 16, true, 0.0, 3, |t, out| {
        let (arm, ei) = (l * (1.0 - t), flexure.ei_at(t * l));
        out.copy_from_slice(&[arm * arm * l / ei, arm * l / ei, l / ei]);
    })
    .unwrap();
    let k = Matrix2::new(c[0], c[1], c[1], c[2]).try_inverse().unwrap();
    let m = Matrix2::new(body.mass, body.mass * body.com[0], body.mass * body.com[0], body.inertia_about_tip());
    // K v = ω² M v as M v = μ K v (M may be singular): ω = 1/√μ for μ > 0.
    let a = DMatrix::from_row_slice(2, 2, k.as_slice());
    let b = DMatrix::from_row_slice(2, 2, m.as_slice());
    let (mu, _) = flexure::linalg::generalized_symmetric(&a, &b).unwrap();
    let mut w: Vec<f64> = mu.iter().filter(|x| **x > 1e-12 * mu.amax()).map(|x| 1.0 / x.sqrt()).collect();
    w.sort_by(f64::total_cmp);
    w
}

/// Issue 12's validation: a massless flexure carrying a rigid body, in small
/// vibration, against exact linear beam theory. For a uniform EI the model's
/// tip compliance is exact from N = 2 (its curvature space holds the linear
/// moment of a tip force), so the frequencies agree to rounding (1e-10); M has
/// rank 2 at the straight shape and the other N − 2 directions are condensed
/// as quasi-static. The shooting reference agrees with the same 2×2 answer.
#[test]
fn massless_flexure_with_a_rigid_body() {
    let bodies = [
        RigidInertia::new(0.3, 0.0, [0.0, 0.0]).unwrap(),
        RigidInertia::new(0.3, 0.01, [0.0, 0.0]).unwrap(),
        RigidInertia::new(0.3, 0.002, [0.4, -0.1]).unwrap(),
    ];
    for body in &bodies {
        let exact = two_by_two(&uniform(3, None), body);
        let shot = frequencies(&uniform(3, None), Some(body), 0.0, 2, &Default::default()).unwrap().omega;
        for n in [2, 3, 6] {
            let m = modes(&uniform(n, None), &TipLoad::default(), Some(body), 4).unwrap();
            let finite = if body.inertia_about_tip() > 0.0 { 2 } else { 1 };
            assert_eq!((m.omega.len(), m.quasi_static), (finite, n - finite), "{body:?}, N = {n}");
            for (k, w) in m.omega.iter().enumerate() {
                assert!((w / exact[k] - 1.0).abs() < 1e-10, "{body:?}, N = {n}: ω = {w} vs {}", exact[k]);
                assert!((shot[k] / exact[k] - 1.0).abs() < 1e-9, "shooting: {} vs {}", shot[k], exact[k]);
            }
            // Shapes are mass-normalized, vᵀMv = 1, and the tip (the body) moves.
            let model = MassModel::new(&uniform(n, None), Some(body)).unwrap();
            let mut data = MassData::new(&model);
            update_mass(&model, &vec![0.0; n], None, &mut data);
            let gram = m.shapes.transpose() * &data.mass_matrix * &m.shapes;
            assert!((gram - DMatrix::identity(finite, finite)).amax() < 1e-12, "N = {n}: shapes not M-orthonormal");
        }
    }
}

/// With EI tapering 2:1 the model's tip compliance is no longer exact and
/// converges geometrically with N (measured: 1.5e-2 at N = 2, about 30 times
/// less per order, 3e-15 at N = 10): at least 10 times less per order up to
/// N = 9, and within 1e-12 of the 2×2 answer at N = 10.
#[test]
fn massless_tapered_flexure_converges() {
    let body = RigidInertia::new(0.3, 0.002, [0.2, 0.0]).unwrap();
    let ei = Profile::Linear { root: 2.0, tip: 1.0 };
    let exact = two_by_two(&beam(3, ei.clone(), None), &body);
    let error = |n: usize| {
        let m = modes(&beam(n, ei.clone(), None), &TipLoad::default(), Some(&body), 2).unwrap();
        m.omega.iter().zip(&exact).map(|(w, e)| (w / e - 1.0).abs()).fold(0.0, f64::max)
    };
    let errors: Vec<f64> = (2..=10).map(error).collect();
    assert!(errors[0] > 1e-3, "N = 2 is not exact ({:e}): the test must be able to tell", errors[0]);
    for (k, pair) in errors.windows(2).take(7).enumerate() {
        assert!(pair[1] < 0.1 * pair[0], "N = {}: {:e} after {:e}", k + 3, pair[1], pair[0]);
    }
    assert!(errors[8] < 1e-12, "N = 10: {:e}", errors[8]);
}

/// A thick steel strip (h/L = 1/20, density 7850) with rotary inertia ρI = μh²/12:
/// at N = 14 the model's three lowest modes agree with the exact Rayleigh beam to
/// 1e-11 (measured 1.5e-13), while leaving out rotary inertia moves the third by more than 1e-3 (so
/// the term is exercised).
#[test]
fn rotary_inertia_matches_the_rayleigh_beam() {
    let (l, h) = (0.02, 0.001);
    let section = |density: bool| {
        let s = Section::rectangle(200e9, None, Profile::Constant(0.01), Profile::Constant(h)).unwrap();
        if density { s.with_density(7850.0).unwrap() } else { s }
    };
    let f = Flexure::new(l, 1.0, 14).unwrap().with_section(section(true)).unwrap();
    let exact = frequencies(&f, None, 0.0, 3, &Default::default()).unwrap().omega;
    let m = modes(&f, &TipLoad::default(), None, 3).unwrap();
    for (w, e) in m.omega.iter().zip(&exact) {
        assert!((w / e - 1.0).abs() < 1e-11, "ω = {w} vs {e}");
    }
    // Euler–Bernoulli without rotary inertia: the same μ given directly, no thickness.
    let mu = 7850.0 * 0.01 * h;
    let ei = 200e9 * 0.01 * h.powi(3) / 12.0;
    let s = Section::given(Profile::Constant(ei)).unwrap().with_mass_per_length(Profile::Constant(mu)).unwrap();
    let bare = Flexure::new(l, ei, 14).unwrap().with_section(s).unwrap();
    let plain = frequencies(&bare, None, 0.0, 3, &Default::default()).unwrap().omega;
    assert!((plain[2] / exact[2] - 1.0) > 1e-3, "rotary inertia lowers the third mode: {} vs {}", plain[2], exact[2]);
}

/// About a bent equilibrium: a pure tip moment bends the flexure into an arc of
/// angle 1.5 rad, adding no load stiffness (a dead moment has no Hessian), so a
/// massless flexure with a point mass vibrates with ω² = eig(C_t⁻¹)/m, C_t the
/// translational block of the exact tip compliance of that arc (the compliance
/// ODE, Eq. 34, of a flexure at rest in the arc). Two finite modes now (the tip
/// can also move along the bent flexure); at N = 10 within 1e-10 (measured 1e-12).
#[test]
fn bent_equilibrium_against_the_exact_arc_compliance() {
    let a = 1.5;
    let m = 0.4;
    let body = RigidInertia::new(m, 0.0, [0.0, 0.0]).unwrap();
    let arc = Flexure::new(1.0, 1.0, 10).unwrap().with_rest(&[a, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]).unwrap();
    let c = flexure::reference::compliance::compliance_tip(&arc, &Default::default()).unwrap();
    let ct = Matrix2::new(c[(1, 1)], c[(1, 2)], c[(2, 1)], c[(2, 2)]);
    let mut exact: Vec<f64> =
        ct.symmetric_eigenvalues().iter().map(|compliance| (1.0 / (m * compliance)).sqrt()).collect();
    exact.sort_by(f64::total_cmp);
    let model = modes(&uniform(10, None), &TipLoad { moment: a, fx: 0.0, fy: 0.0 }, Some(&body), 3).unwrap();
    assert_eq!(model.omega.len(), 2);
    for (w, e) in model.omega.iter().zip(&exact) {
        assert!((w / e - 1.0).abs() < 1e-10, "ω = {w} vs {e}");
    }
}

/// Issue 12: frequencies fall to zero at the buckling load. Under an axial
/// compression P below the model's own buckling load P_cr (N = 6, Table I's
/// free case), the model's two lowest frequencies agree with the exact column
/// (shooting with the compression term) to 1e-8 and 1e-4 (the second mode's
/// error at N = 6, measured 1.4e-5, as unloaded). Near P_cr, ω₁² vanishes
/// linearly: ω₁²/((1 − P/P_cr)ω₁²(0)) is the same at 1 − P/P_cr = 1e-3 and 1e-4
/// to 1e-3 (it tends to 1.0859, Galef's 1 corrected for the mode shapes'
/// mismatch), and past P_cr the equilibrium is unstable, an error.
#[test]
fn frequency_falls_to_zero_at_buckling() {
    let f = uniform(6, Some(1.0));
    let p_cr = buckling_load(&f, TipConstraint::Free).unwrap().critical_load;
    assert!((p_cr / (std::f64::consts::PI.powi(2) / 4.0) - 1.0).abs() < 1e-9);
    let w0 = modes(&f, &TipLoad::default(), None, 1).unwrap().omega[0];
    for share in [0.1, 0.5, 0.9] {
        let p = share * p_cr;
        let model = modes(&f, &compression(p), None, 2).unwrap().omega;
        let exact = frequencies(&f, None, p, 2, &Default::default()).unwrap().omega;
        assert!((model[0] / exact[0] - 1.0).abs() < 1e-8, "P = {share} P_cr: {} vs {}", model[0], exact[0]);
        assert!((model[1] / exact[1] - 1.0).abs() < 1e-4, "P = {share} P_cr: {} vs {}", model[1], exact[1]);
    }
    let ratio = |gap: f64| {
        let w = modes(&f, &compression((1.0 - gap) * p_cr), None, 1).unwrap().omega[0];
        (w / w0).powi(2) / gap
    };
    let (r3, r4) = (ratio(1e-3), ratio(1e-4));
    assert!((r3 / r4 - 1.0).abs() < 1e-3 && (r4 - 1.0859).abs() < 1e-3, "{r3} {r4}");
    assert!(matches!(modes(&f, &compression(1.01 * p_cr), None, 1), Err(Error::Unstable { .. })));
}

/// A massless column with a point mass under compression: the model's condensed
/// lateral stiffness against the beam-column's k = P/(L(tan κL/κL − 1)) (as in
/// `dynamics_vibration`), up to 0.99 of the Euler load: the curvature under
/// compression is trigonometric, so the model converges super-geometrically
/// (measured at 0.99: 7e-3 at N = 3, 2e-9 at N = 6, 5e-15 at N = 8); within
/// 1e-12 at N = 8, while N = 3 is off by more than 1e-6 (so the test can tell).
#[test]
fn massless_column_frequency_under_compression() {
    let body = RigidInertia::new(0.2, 0.0, [0.0, 0.0]).unwrap();
    for share in [0.3, 0.9, 0.99] {
        let p = share * std::f64::consts::PI.powi(2) / 4.0;
        let x = p.sqrt();
        let exact = (p / (x.tan() / x - 1.0) / 0.2).sqrt();
        let error =
            |n: usize| modes(&uniform(n, None), &compression(p), Some(&body), 1).unwrap().omega[0] / exact - 1.0;
        let (e3, e8) = (error(3), error(8));
        assert!(e8.abs() < 1e-12, "P = {share} P_cr, N = 8: {e8:e}");
        assert!(e3 > 1e-6, "P = {share} P_cr, N = 3: {e3:e}");
    }
}

#[test]
fn bad_input_is_named() {
    let name = |r: Result<_, Error>| match r {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("expected an invalid parameter, got {other:?}"),
    };
    let none = TipLoad::default();
    assert_eq!(name(modes(&uniform(3, None), &none, None, 2)), "mass");
    assert_eq!(name(modes(&uniform(3, None), &none, Some(&RigidInertia::default()), 2)), "mass");
    assert_eq!(name(modes(&uniform(3, Some(1.0)), &none, None, 0)), "count");
    let bad = RigidInertia { mass: 1.0, inertia: 0.0, com: [f64::INFINITY, 0.0] };
    assert_eq!(name(modes(&uniform(3, Some(1.0)), &none, Some(&bad), 1)), "com");
    assert_eq!(name(modes(&uniform(3, Some(1.0)), &compression(f64::NAN), None, 1)), "fx");
}

/// Non-uniform sections, distributed mass: a steel strip tapering 0.4 to 0.2 mm
/// (EI ∝ h³, μ ∝ h, ρI ∝ h³) and a flexure whose mass per length is a table
/// with kinks at t = 0.3 and 0.7 (integrated piecewise by both sides). The
/// model at N = 16 against the exact shooting with EI(s), μ(s), ρI(s): the taper's
/// three modes to 1e-11 (measured 2.4e-13); the table's kinks slow the
/// convergence to algebraic (the exact shape's fourth derivative jumps there),
/// its modes within 1e-6 (measured 3.6e-7 for the third).
#[test]
fn non_uniform_sections_against_the_exact_beam() {
    let taper = Section::rectangle(200e9, None, Profile::Constant(0.01), Profile::Linear { root: 4e-4, tip: 2e-4 })
        .unwrap()
        .with_density(7850.0)
        .unwrap();
    let table = Section::given(Profile::Constant(1.0))
        .unwrap()
        .with_mass_per_length(Profile::Table(vec![[0.0, 1.0], [0.3, 2.0], [0.7, 0.5], [1.0, 1.0]]))
        .unwrap();
    for (name, section, length, tolerance) in [("taper", taper, 0.02, 1e-11), ("table", table, 1.0, 1e-6)] {
        let f = Flexure::new(length, 1.0, 16).unwrap().with_section(section).unwrap();
        let exact = frequencies(&f, None, 0.0, 3, &Default::default()).unwrap().omega;
        let model = modes(&f, &TipLoad::default(), None, 3).unwrap().omega;
        for (w, e) in model.iter().zip(&exact) {
            assert!((w / e - 1.0).abs() < tolerance, "{name}: ω = {w} vs {e}");
        }
    }
}
