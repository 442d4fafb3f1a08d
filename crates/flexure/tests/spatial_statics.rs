//! The spatial flexure's statics (`spatial::statics`): equilibrium under a
//! dead tip wrench, its stiffness, stability and compliance, each test
//! against its named reference.

use flexure::estimate::spatial::deflect_error;
use flexure::section::SpatialSection;
use flexure::spatial::{
    SpatialFlexure, SpatialKinematics, SpatialLoad, SpatialStatics, compliance, correct, deflect, energy_gradient,
    generalized_force, pose_root_tip, update,
};
use flexure::{Flexure, Level, StaticsData, TipLoad};
use nalgebra::{Matrix3, Vector3};

fn flexure(l: f64, [gj, ei_y, ei_z]: [f64; 3], orders: [usize; 3]) -> SpatialFlexure {
    SpatialFlexure::new(l, SpatialSection::uniform(gj, ei_y, ei_z).unwrap(), orders).unwrap()
}

/// The virtual work of `w` through the Magnus product's own body
/// Jacobian, $m\cdot\omega_a + f\cdot v_a$ with $(m, f) = (R^TM, R^TF)$:
/// the exact derivative of the discrete tip pose.
fn magnus_work(f: &SpatialFlexure, x: &[f64], w: &SpatialLoad) -> Vec<f64> {
    let mut k = SpatialKinematics::new(f);
    update(f, x, Level::Jacobian, &mut k);
    let m = k.rotation.tr_mul(&Vector3::from(w.moment));
    let fb = k.rotation.tr_mul(&Vector3::from(w.force));
    (0..f.coordinates())
        .map(|a| {
            let c = k.jacobian.column(a);
            m.dot(&Vector3::new(c[0], c[1], c[2])) + fb.dot(&Vector3::new(c[3], c[4], c[5]))
        })
        .collect()
}

fn load(moment: [f64; 3], force: [f64; 3]) -> SpatialLoad {
    SpatialLoad { moment, force }
}

/// Reference: the planar flexure (`flexure::deflect`) at the same order
/// under the same in-plane load (Mz, Fx, Fy). The two integrate the same
/// curvature by different rules (Gauss points of the closed form against
/// Magnus steps), so they meet to the smaller rule's error, 1e-9 here; the
/// out-of-plane coordinates stay zero to rounding (1e-13).
#[test]
fn in_plane_loads_meet_the_planar_flexure_at_the_same_order() {
    let (l, ei) = (1.2, 0.9);
    let f = flexure(l, [0.6, 2.0, ei], [3, 3, 3]).with_subintervals(32).unwrap();
    let planar = Flexure::with_points(l, ei, 3, 24).unwrap();
    let (mz, fx, fy) = (0.3, -0.2, 0.7);
    let mut data = SpatialStatics::new(&f);
    let eq = deflect(&f, &load([0.0, 0.0, mz], [fx, fy, 0.0]), &mut data, &Default::default()).unwrap();
    let mut p = StaticsData::new(&planar);
    flexure::deflect(&planar, &TipLoad { moment: mz, fx, fy }, &mut p, &Default::default()).unwrap();
    assert!(eq.stable);
    let a = data.alpha();
    for (i, v) in a[..6].iter().enumerate() {
        assert!(v.abs() < 1e-13, "out-of-plane coordinate {i} = {v}");
    }
    for (s, q) in a[6..].iter().zip(p.alpha()) {
        assert!((s - q).abs() < 1e-9, "κ_z coefficient {s} against the planar {q}");
    }
}

/// Reference: the Magnus product's exact virtual work ([`magnus_work`],
/// through the body Jacobian of the discrete tip pose), which the
/// quadrature of the section moments must meet as fast as the Magnus rule
/// converges: at least 30× closer per halving of the subintervals
/// (sixth order: 64×; measured 62.5×, 63.7×, 64×, 64× from 5.3e-5 at 2),
/// and within 1e-11 relative at 32 subintervals (measured 3.3e-12), at a
/// 3-D shape of about a radian per component.
#[test]
fn the_generalized_force_is_the_magnus_products_virtual_work() {
    let w = load([0.2, -0.1, 0.3], [0.1, 0.4, -0.3]);
    let alpha = [0.5, -0.2, 0.1, 0.9, 0.3, -0.2, -1.1, 0.4, 0.2];
    let mut last = f64::NAN;
    for m in [2, 4, 8, 16, 32] {
        let f = flexure(1.0, [0.7, 1.3, 1.0], [3, 3, 3]).with_subintervals(m).unwrap();
        let q = generalized_force(&f, &w, &alpha).unwrap();
        let exact = magnus_work(&f, &alpha, &w);
        let scale = exact.iter().fold(0.0_f64, |s, v| s.max(v.abs()));
        let error = q.iter().zip(&exact).fold(0.0_f64, |e, (a, b)| e.max((a - b).abs())) / scale;
        if m < 32 {
            // Until rounding (1e-14) is reached, each halving gains the sixth order.
            assert!(m == 2 || last / error >= 30.0 || error < 1e-13, "M = {m}: {error:e} after {last:e}");
        } else {
            assert!(error < 1e-11, "M = 32: {error:e}");
        }
        last = error;
    }
}

/// Reference: central differences (step 1e-6) of the residual
/// ∇U − Q ([`generalized_force`]) at an equilibrium under a full 3-D
/// wrench, moment included: the loaded stiffness is its derivative to
/// 1e-8 relative to the largest entry with the default 8 subintervals
/// (measured 3.4e-10, the differences' own noise: its running integrals are
/// the quadrature's to the rule's error). The equilibrium is one of the
/// Magnus product's exact virtual work ([`magnus_work`]) to the rule's
/// error, 1.3e-8 of Q at 8 subintervals by the test above: within 5e-9
/// here (measured 7.7e-10).
#[test]
fn stiffness_is_the_derivative_of_the_residual() {
    let f = flexure(1.0, [0.7, 1.3, 1.0], [3, 3, 3]);
    let w = load([0.2, -0.1, 0.3], [0.1, 0.4, -0.3]);
    let mut data = SpatialStatics::new(&f);
    deflect(&f, &w, &mut data, &Default::default()).unwrap();
    let alpha = data.alpha().to_vec();
    let n = f.coordinates();
    let residual = |x: &[f64], work: &[f64]| {
        let mut r = vec![0.0; n];
        energy_gradient(&f, x, &mut r);
        r.iter_mut().zip(work).for_each(|(r, q)| *r -= q);
        r
    };
    let quadrature = |x: &[f64]| residual(x, &generalized_force(&f, &w, x).unwrap());
    let at = residual(&alpha, &magnus_work(&f, &alpha, &w));
    assert!(at.iter().all(|r| r.abs() < 5e-9), "not an equilibrium of the Magnus product: {at:?}");
    let largest = data.stiffness.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let h = 1e-6;
    for b in 0..n {
        let (mut up, mut down) = (alpha.clone(), alpha.clone());
        up[b] += h;
        down[b] -= h;
        let (ru, rd) = (quadrature(&up), quadrature(&down));
        for a in 0..n {
            let fd = (ru[a] - rd[a]) / (2.0 * h);
            assert!(
                (data.stiffness[(a, b)] - fd).abs() < 1e-8 * largest,
                "K[{a},{b}] {} vs {fd}",
                data.stiffness[(a, b)]
            );
        }
    }
}

/// Reference: a pure twist T turns the tip by TL/GJ about the tangent
/// (closed form; 1e-10 rad), and moves it nowhere.
#[test]
fn pure_twist_turns_the_tip_by_tl_over_gj() {
    let (l, gj, t) = (0.8, 0.25, 0.4);
    let f = flexure(l, [gj, 1.0, 1.0], [3, 3, 3]);
    let mut data = SpatialStatics::new(&f);
    deflect(&f, &load([t, 0.0, 0.0], [0.0; 3]), &mut data, &Default::default()).unwrap();
    let (r, p) = pose_root_tip(&f, data.alpha());
    let angle = r[(2, 1)].atan2(r[(1, 1)]);
    assert!((angle - t * l / gj).abs() < 1e-10, "{angle}");
    assert!((p - Vector3::new(l, 0.0, 0.0)).norm() < 1e-12);
}

/// Reference: an in-plane moment 2πEI/L bends the flexure into a full
/// circle, its tip back at the root with the root's orientation (closed
/// form; 1e-9 of L).
#[test]
fn a_moment_of_two_pi_ei_over_l_closes_the_circle() {
    let (l, ei) = (0.5, 2.0);
    let f = flexure(l, [1.0, 3.0, ei], [3, 3, 3]).with_subintervals(16).unwrap();
    let mut data = SpatialStatics::new(&f);
    deflect(&f, &load([0.0, 0.0, 2.0 * std::f64::consts::PI * ei / l], [0.0; 3]), &mut data, &Default::default())
        .unwrap();
    let (r, p) = pose_root_tip(&f, data.alpha());
    assert!(p.norm() < 1e-9 * l, "tip at {p}");
    assert!((r - Matrix3::identity()).norm() < 1e-9);
}

/// Reference: under a dead tip moment M (no force) a rod's tangent
/// precesses about M at the rate |M|/EI, so its centreline is a helix,
/// p(L) = (e₁·M̂)M̂L + sin(ωL)/ω e⊥ + (1 − cos ωL)/ω M̂×e⊥ with ω = |M|/EI,
/// e⊥ = e₁ − (e₁·M̂)M̂ (closed form). With GJ = EI the body curvature is
/// constant, which the model holds exactly: 1e-9 of L. With GJ ≠ EI it
/// turns in the body frame, and order 8 meets the closed form to 1e-6 of L.
#[test]
fn a_skew_moment_winds_a_round_rod_into_a_helix() {
    let (l, ei): (f64, f64) = (1.0, 1.0);
    let m: Vector3<f64> = Vector3::new(0.6, 0.9, -1.2);
    let w: f64 = m.norm() / ei;
    let axis = m / m.norm();
    let e1 = Vector3::x();
    let across = e1 - axis * e1.dot(&axis);
    let exact =
        axis * e1.dot(&axis) * l + across * ((w * l).sin() / w) + axis.cross(&across) * ((1.0 - (w * l).cos()) / w);
    for (gj, orders, tolerance) in [(ei, [3, 3, 3], 1e-9), (0.6 * ei, [8, 8, 8], 1e-6)] {
        let f = flexure(l, [gj, ei, ei], orders).with_subintervals(32).unwrap();
        let mut data = SpatialStatics::new(&f);
        deflect(&f, &load(m.into(), [0.0; 3]), &mut data, &Default::default()).unwrap();
        let (_, p) = pose_root_tip(&f, data.alpha());
        assert!((p - exact).norm() < tolerance * l, "GJ = {gj}: tip {p} against the helix's {exact}");
    }
}

/// Reference: the cantilever's compliance closed forms (Eqs. 34–36 per
/// axis): twist L/GJ, bending L/EI, the coupling L²/2EI and a tip force's
/// L³/3EI, about both bending axes; the model is exact for them from order
/// 2, so to 1e-12 relative.
#[test]
fn rest_compliance_is_the_cantilevers_closed_forms() {
    let (l, gj, ei_y, ei_z) = (1.3, 0.4, 2.5, 0.7);
    let f = flexure(l, [gj, ei_y, ei_z], [2, 3, 3]);
    let mut data = SpatialStatics::new(&f);
    correct(&f, &SpatialLoad::default(), f.rest(), &mut data, &Default::default()).unwrap();
    let c = compliance(&f, &data).unwrap();
    let close = |got: f64, want: f64| (got - want).abs() <= 1e-12 * want.abs().max(1e-300);
    assert!(close(c[(0, 0)], l / gj));
    assert!(close(c[(1, 1)], l / ei_y) && close(c[(2, 2)], l / ei_z));
    // A force along y turns the tip about z, one along z about −y.
    assert!(close(c[(2, 4)], l * l / (2.0 * ei_z)) && close(c[(1, 5)], -l * l / (2.0 * ei_y)));
    assert!(close(c[(4, 4)], l.powi(3) / (3.0 * ei_z)) && close(c[(5, 5)], l.powi(3) / (3.0 * ei_y)));
    // Axially rigid: no stretch.
    assert!(c[(3, 3)].abs() < 1e-14);
    // Symmetric (Maxwell–Betti) without a moment.
    assert!((c - c.transpose()).norm() < 1e-12 * c.norm());
}

/// Reference: Michell (1899): a narrow cantilever strip under an end force
/// along its stiff direction buckles sideways at P = 4.0126·√(EI_z·GJ)/L²
/// when bending about y is rigid. Here EI_y = 1e4·EI_z, whose pre-buckling
/// bending raises the load by the factor 1/√((1 − EI_z/EI_y)(1 − GJ/EI_y))
/// = 1.000115; the model meets Michell to 2e-4 at orders 6 (measured:
/// 1.00014 at 6 and 8, 1.0095 at 3, 1.0011 at 4). With EI_y only 10·EI_z
/// the pre-buckling bending raises the load further (1.188 measured, the
/// exact rod's conjugate point to 2e-6: tests/spatial_validation.rs).
#[test]
fn a_narrow_strip_buckles_sideways_at_michells_load() {
    let (l, gj, ei_z): (f64, f64, f64) = (1.0, 1.3, 1.0);
    let michell = 4.0126 * (ei_z * gj).sqrt() / (l * l);
    // Followed past it, the path names the load fraction where stability was
    // lost (located as finely as `stability_limit`'s bisection, which costs
    // some thirty such paths: 1.000137 both ways at orders 6).
    let lost = |ei_y: f64| {
        let f = flexure(l, [gj, ei_y, ei_z], [6, 6, 6]);
        let mut data = SpatialStatics::new(&f);
        let eq = deflect(&f, &load([0.0; 3], [0.0, 0.0, 1.5 * michell]), &mut data, &Default::default()).unwrap();
        assert!(!eq.stable);
        1.5 * eq.limit.expect("the straight strip must lose stability on the way")
    };
    let rigid = lost(1e4 * ei_z);
    assert!((rigid - 1.0).abs() < 2e-4, "{rigid}");
    let finite = lost(10.0 * ei_z);
    assert!(finite > rigid, "{finite} vs {rigid}");
}

/// Reference: the model at twice the order (the estimate's own reference
/// is a refined model, so the truth here is a third, finer one: orders
/// 14, 64 subintervals). The estimate must be within a factor 3 of the
/// true tip error of a low-order answer under a 3-D load.
#[test]
fn the_error_estimate_tracks_the_true_error() {
    let s = [0.8, 1.2, 1.0];
    let w = load([0.1, 0.2, 0.4], [0.3, 0.8, 0.6]);
    let f = flexure(1.0, s, [2, 2, 2]);
    let mut data = SpatialStatics::new(&f);
    deflect(&f, &w, &mut data, &Default::default()).unwrap();
    let e = deflect_error(&f, &w, data.alpha(), &Default::default()).unwrap();
    let truth = flexure(1.0, s, [14, 14, 14]).with_subintervals(64).unwrap();
    let mut exact = SpatialStatics::new(&truth);
    deflect(&truth, &w, &mut exact, &Default::default()).unwrap();
    let (_, pa) = pose_root_tip(&f, data.alpha());
    let (_, pb) = pose_root_tip(&truth, exact.alpha());
    let error = (pa - pb).norm();
    assert!(error > 1e-6, "the low order must err for this test to mean anything: {error}");
    assert!(e.position / error > 1.0 / 3.0 && e.position / error < 3.0, "{} vs {error}", e.position);
}

/// Bad input names the component: a NaN force along z, an infinite moment.
#[test]
fn bad_loads_are_refused_by_name() {
    let f = flexure(1.0, [1.0, 1.0, 1.0], [3, 3, 3]);
    let mut data = SpatialStatics::new(&f);
    let e = deflect(&f, &load([0.0; 3], [0.0, 0.0, f64::NAN]), &mut data, &Default::default()).unwrap_err();
    assert!(e.to_string().contains("fz"), "{e}");
    let e = deflect(&f, &load([f64::INFINITY, 0.0, 0.0], [0.0; 3]), &mut data, &Default::default()).unwrap_err();
    assert!(e.to_string().contains("mx"), "{e}");
    let other = flexure(1.0, [1.0, 1.0, 1.0], [2, 2, 2]);
    assert!(deflect(&other, &SpatialLoad::default(), &mut data, &Default::default()).is_err());
}

/// Reference: a round rod of diameter d under a tip moment (bending M_b and
/// twist T, no force) carries the uniform σ = 32M_b/(πd³) and τ = 16T/(πd³)
/// everywhere (closed forms, whatever E and G), so its peak von Mises stress
/// is √(σ² + 3τ²); 1e-9 relative after the solve.
#[test]
fn a_round_rods_peak_stress_is_the_closed_form() {
    use flexure::section::Profile;
    use flexure::spatial::peak_stress;
    let d = 2e-3;
    let section = SpatialSection::circle(200e9, 0.3, Profile::Constant(d)).unwrap();
    let f = SpatialFlexure::new(0.05, section, [3, 3, 3]).unwrap();
    let (t, mb) = (0.05, 0.08);
    let mut data = SpatialStatics::new(&f);
    deflect(&f, &load([t, 0.0, mb], [0.0; 3]), &mut data, &Default::default()).unwrap();
    let p = peak_stress(&f, data.alpha()).unwrap();
    let pi_d3 = std::f64::consts::PI * d.powi(3);
    let (sigma, tau) = (32.0 * mb / pi_d3, 16.0 * t / pi_d3);
    let exact = (sigma * sigma + 3.0 * tau * tau).sqrt();
    assert!((p.stress.von_mises - exact).abs() < 1e-9 * exact, "{} vs {exact}", p.stress.von_mises);
    assert!((p.stress.shear - tau).abs() < 1e-9 * tau);
    // A section given by its stiffnesses alone has no geometry for stress.
    let bare = flexure(0.05, [1.0, 1.0, 1.0], [3, 3, 3]);
    assert!(peak_stress(&bare, bare.rest()).unwrap_err().to_string().contains("section"));
}

/// Why `stable` under a dead moment is Euler's static test and not the
/// sign of the real parts of the eigenvalues of ∂r (issue 39 item 4).
/// Reference: a change of coordinates α = Pβ turns ∂r into Pᵀ∂r P and the
/// elastic stiffness K into PᵀKP, so K⁻¹∂r becomes P⁻¹K⁻¹∂r P, of the same
/// eigenvalues, while those of ∂r itself move. Under the twisting
/// moment 10 EI/L (GJ = EI, orders 6) the Legendre coordinates' ∂r has an
/// eigenvalue of real part −0.23 and the orthonormal ones' (P = diag √(2i+1))
/// none below 0.38: the old test called one equilibrium both unstable and
/// stable. K⁻¹∂r has the same spectrum in both, to 1e-9 of its largest
/// eigenvalue, with no real eigenvalue at or below zero, and the model
/// reports it stable.
#[test]
fn the_static_test_does_not_depend_on_the_coordinates() {
    use nalgebra::{Complex, DMatrix};
    let f = flexure(1.0, [1.0, 1.0, 1.0], [6, 6, 6]);
    let n = f.coordinates();
    let mut data = SpatialStatics::new(&f);
    let eq = deflect(&f, &load([10.0, 0.0, 0.0], [0.0; 3]), &mut data, &Default::default()).unwrap();
    assert!(eq.stable && eq.limit.is_none(), "{eq:?}");
    let j = data.stiffness.clone();
    let k = DMatrix::from_row_slice(n, n, f.stiffness_matrix());
    let p = DMatrix::from_fn(n, n, |a, b| if a == b { ((2 * (a % 6) + 1) as f64).sqrt() } else { 0.0 });
    let least = |m: &DMatrix<f64>| m.complex_eigenvalues().iter().map(|e| e.re).fold(f64::INFINITY, f64::min);
    let (jp, kp) = (p.transpose() * &j * &p, p.transpose() * &k * &p);
    assert!(least(&j) < -0.2 && least(&jp) > 0.3, "{} and {}", least(&j), least(&jp));
    let spectrum = |k: &DMatrix<f64>, j: &DMatrix<f64>| {
        let mut e: Vec<Complex<f64>> = k.clone().lu().solve(j).unwrap().complex_eigenvalues().iter().copied().collect();
        e.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
        e
    };
    let (a, b) = (spectrum(&k, &j), spectrum(&kp, &jp));
    let size = a.iter().map(|e| e.norm()).fold(0.0, f64::max);
    assert!(a.iter().zip(&b).all(|(x, y)| (x - y).norm() < 1e-9 * size), "{a:?} vs {b:?}");
    assert!(a.iter().all(|e| e.im.abs() > 1e-9 * size || e.re > 0.0), "{a:?}");
}
