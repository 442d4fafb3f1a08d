//! Non-uniform sections: the stiffness matrix K = (1/L)∫EI P̃ᵢP̃ⱼ dt against
//! closed forms and an independent rule (composite Simpson), the energy
//! against ½∫EI(ω̂ − ω̂₀)² ds, derivatives three ways, the notch hinge
//! against Paros–Weisbord, stress against beam theory, and bad input.

use flexure::section::{Notch, Profile, Section};
use flexure::{Error, Flexure, TipLoad, energy, energy_gradient};
use num_dual::{Dual64, HyperDual64};

/// Composite Simpson on [a, b] with `panels` (even) panels: error
/// (b−a)h⁴max|f⁗|/180, independent of the library's Gauss rules.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let h = (b - a) / panels as f64;
    let inner: f64 = (1..panels).map(|k| f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 }).sum();
    (f(a) + f(b) + inner) * h / 3.0
}

fn legendre(n: usize, t: f64) -> f64 {
    let mut p = vec![0.0; n + 1];
    flexure::basis::shifted_legendre(t, &mut p);
    p[n]
}

/// K by Simpson on the pieces between `ends` (t values including 0 and 1),
/// with one Richardson step (16S₂ₙ − Sₙ)/15: error O(h⁶).
fn simpson_stiffness(section: &Section, length: f64, n: usize, ends: &[f64]) -> Vec<f64> {
    let mut k = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            let g = |t: f64| section.ei(t, length) * legendre(i, t) * legendre(j, t);
            let richardson = |a: f64, b: f64| (16.0 * simpson(g, a, b, 4000) - simpson(g, a, b, 2000)) / 15.0;
            k[i * n + j] = ends.windows(2).map(|w| richardson(w[0], w[1])).sum::<f64>() / length;
        }
    }
    k
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

fn largest(a: &[f64]) -> f64 {
    a.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

fn rectangle(width: Profile, thickness: Profile) -> Section {
    Section::rectangle(200e9, Some(0.3), width, thickness).unwrap()
}

/// Closed form for EI = a + (b − a)t: with x = 2t − 1 and
/// xP̃ᵢ = ((i+1)P̃ᵢ₊₁ + iP̃ᵢ₋₁)/(2i+1), ∫₀¹P̃ᵢP̃ⱼ = δᵢⱼ/(2i+1) gives
/// K = (1/L)[(a+b)/2 · δᵢⱼ/(2i+1) + (b−a)/2 · ∫xP̃ᵢP̃ⱼ], tridiagonal.
/// Tolerance 1e-14 relative: Gauss is exact for these polynomials.
#[test]
fn linear_ei_taper_matches_the_closed_form() {
    let (a, b, l, n) = (2.0, 0.5, 0.3, 7);
    let f = Flexure::new(l, 1.0, n)
        .unwrap()
        .with_section(Section::given(Profile::Linear { root: a, tip: b }).unwrap())
        .unwrap();
    let x_moment = |i: usize, j: usize| {
        let up = if j == i + 1 { (i + 1) as f64 / (2 * i + 1) as f64 / (2 * j + 1) as f64 } else { 0.0 };
        let down = if j + 1 == i { i as f64 / (2 * i + 1) as f64 / (2 * j + 1) as f64 } else { 0.0 };
        up + down
    };
    let expected: Vec<f64> = (0..n * n)
        .map(|ij| {
            let (i, j) = (ij / n, ij % n);
            let diagonal = if i == j { 0.5 * (a + b) / (2 * i + 1) as f64 } else { 0.0 };
            (diagonal + 0.5 * (b - a) * x_moment(i, j)) / l
        })
        .collect();
    let k = f.stiffness_matrix();
    assert!(largest_difference(k, &expected) < 1e-14 * largest(&expected), "{k:?}");
    assert!((f.ei() - 0.5 * (a + b)).abs() < 1e-15);
}

/// Width and thickness both tapered (EI a quartic in t) and a table with a
/// kink at t = 0.3: exact by Gauss on each piece, so they agree with
/// Simpson (4000 panels per piece and a Richardson step) to 1e-13.
#[test]
fn tapers_and_tables_match_simpson() {
    let l = 0.04;
    let cases = [
        (
            rectangle(Profile::Linear { root: 0.01, tip: 0.006 }, Profile::Linear { root: 4e-4, tip: 2e-4 }),
            vec![0.0, 1.0],
        ),
        (
            rectangle(Profile::Constant(0.01), Profile::Table(vec![[0.0, 4e-4], [0.3, 1.5e-4], [1.0, 3e-4]])),
            vec![0.0, 0.3, 1.0],
        ),
    ];
    for (section, ends) in cases {
        let f = Flexure::new(l, 1.0, 6).unwrap().with_section(section.clone()).unwrap();
        let expected = simpson_stiffness(&section, l, 6, &ends);
        let k = f.stiffness_matrix();
        assert!(largest_difference(k, &expected) < 1e-13 * largest(&expected), "{k:?}\n{expected:?}");
        // Symmetric by construction, and not diagonal: the taper couples the modes.
        assert!(k[1] != 0.0 && k[1] == k[6]);
    }
}

/// A constant rectangle is the uniform flexure of the same EI (Eq. 25), exactly.
#[test]
fn a_constant_rectangle_is_the_uniform_flexure() {
    let section = rectangle(Profile::Constant(0.01), Profile::Constant(2e-4));
    let ei = flexure::bending_stiffness(200e9, 0.01, 2e-4, Some(0.3)).unwrap();
    let f = Flexure::new(0.02, 1.0, 4).unwrap().with_section(section).unwrap();
    let g = Flexure::new(0.02, ei, 4).unwrap();
    assert_eq!(f.stiffness_matrix(), g.stiffness_matrix());
}

/// The notch hinge: K by Simpson on [0, L/2 − a], [L/2 − a, L/2 + a] and
/// [L/2 + a, L], with the notch's edge a = √(R² − (R − (H − h)/2)²) in
/// closed form; the adaptive integral must meet the 1e-10.
#[test]
fn notch_stiffness_is_accurate_to_1e_10() {
    let (l, r, h, blank) = (0.02, 0.004, 3e-4, 2e-3);
    let section = rectangle(Profile::Constant(0.01), Profile::Constant(blank))
        .with_notch(Notch { radius: r, min_thickness: h })
        .unwrap();
    let a = (r * r - (r - 0.5 * (blank - h)).powi(2)).sqrt() / l;
    let f = Flexure::new(l, 1.0, 8).unwrap().with_section(section.clone()).unwrap();
    let expected = simpson_stiffness(&section, l, 8, &[0.0, 0.5 - a, 0.5 + a, 1.0]);
    let k = f.stiffness_matrix();
    assert!(largest_difference(k, &expected) < 1e-10 * largest(&expected), "{k:?}\n{expected:?}");
    assert_eq!(section.breakpoints(l).len(), 2);
}

/// Paros & Weisbord (1965), the circular hinge (L = 2R) under a moment:
/// Δφ/M = 3/(2EbR²) · 1/(2β+β²) · [(3+4β+2β²)/((1+β)(2β+β²)) + 6(1+β)/(2β+β²)^{3/2} · atan √((2+β)/β)],
/// β = h/(2R): the exact ∫ds/EI. The model's C_φφ is a Ritz bound from
/// below, converging as the order grows; at order 24 it is within 1 %.
#[test]
fn notch_hinge_compliance_converges_to_paros_weisbord() {
    let (e, b, r, h): (f64, f64, f64, f64) = (70e9, 0.01, 0.005, 5e-4);
    let beta = h / (2.0 * r);
    let q = 2.0 * beta + beta * beta;
    let closed = 3.0 / (2.0 * e * b * r * r) / q
        * ((3.0 + 4.0 * beta + 2.0 * beta * beta) / ((1.0 + beta) * q)
            + 6.0 * (1.0 + beta) / q.powf(1.5) * ((2.0 + beta) / beta).sqrt().atan());
    let section = Section::rectangle(e, None, Profile::Constant(b), Profile::Constant(2.0 * r + h))
        .unwrap()
        .with_notch(Notch { radius: r, min_thickness: h })
        .unwrap();
    let mut last = f64::INFINITY;
    for order in [4, 8, 16, 24] {
        let f = Flexure::new(2.0 * r, 1.0, order).unwrap().with_section(section.clone()).unwrap();
        let c = flexure::compliance_tip_rest(&f)[(0, 0)];
        let error = (closed - c) / closed;
        assert!(error > -1e-12, "a Ritz model is stiffer than the exact beam: order {order}, error {error:e}");
        assert!(error < last, "order {order} did not improve: {error:e} after {last:e}");
        last = error;
    }
    assert!(last < 0.01, "order 24 is {last:e} off");
}

/// U = ½∫EI(ω̂ − ω̂₀)² ds by Simpson (the kink at t = 0.4 a panel edge), at
/// seeded random coordinates and rest shapes; 1e-11 relative.
#[test]
fn energy_is_the_integral_of_ei_times_curvature_squared() {
    let l = 0.05;
    let section = rectangle(
        Profile::Linear { root: 0.012, tip: 0.008 },
        Profile::Table(vec![[0.0, 3e-4], [0.4, 2e-4], [1.0, 2.5e-4]]),
    );
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for _ in 0..5 {
        let kappa: Vec<f64> = (0..5).map(|_| next()).collect();
        let alpha: Vec<f64> = (0..5).map(|_| 2.0 * next()).collect();
        let f = Flexure::new(l, 1.0, 5).unwrap().with_rest(&kappa).unwrap().with_section(section.clone()).unwrap();
        let d: Vec<f64> = alpha.iter().zip(&kappa).map(|(a, k)| a - k).collect();
        let g = |t: f64| 0.5 * section.ei(t, l) * flexure::basis::curvature(&d, l, t * l).powi(2) * l;
        let expected = simpson(g, 0.0, 0.4, 4000) + simpson(g, 0.4, 1.0, 4000);
        assert!((energy(&f, &alpha) - expected).abs() < 1e-11 * expected);
    }
}

/// Gradient and Hessian of the full quadratic form three ways: central
/// differences (h = 1e-5; exact for a quadratic up to rounding, so 1e-7 of
/// the gradient's scale), num-dual (to rounding), and the Hessian is K, symmetric.
#[test]
fn derivatives_of_the_tapered_energy() {
    let section = Section::given(Profile::Table(vec![[0.0, 3.0], [0.5, 1.0], [1.0, 2.0]])).unwrap();
    let f =
        Flexure::new(0.5, 1.0, 4).unwrap().with_rest(&[0.3, -0.2, 0.1, 0.05]).unwrap().with_section(section).unwrap();
    let alpha = [1.1, 0.4, -0.3, 0.2];
    let mut g = [0.0; 4];
    energy_gradient(&f, &alpha, &mut g);
    let h = 1e-5;
    for i in 0..4 {
        let (mut up, mut dn) = (alpha, alpha);
        up[i] += h;
        dn[i] -= h;
        assert!((g[i] - (energy(&f, &up) - energy(&f, &dn)) / (2.0 * h)).abs() < 1e-7 * largest(&g));
        let d: Vec<Dual64> = (0..4).map(|m| Dual64::new(alpha[m], (m == i) as u8 as f64)).collect();
        assert!((g[i] - energy(&f, &d).eps).abs() < 1e-13);
        for j in 0..4 {
            let d: Vec<HyperDual64> =
                (0..4).map(|m| HyperDual64::new(alpha[m], (m == i) as u8 as f64, (m == j) as u8 as f64, 0.0)).collect();
            let kij = flexure::energy::stiffness(&f, i, j);
            assert!((energy(&f, &d).eps1eps2 - kij).abs() < 1e-13, "Hessian ({i},{j})");
            assert_eq!(kij, flexure::energy::stiffness(&f, j, i));
        }
    }
}

/// Beam theory, small load: a tip force F on a cantilever bends it by
/// ω(s) = F(L − s)/EI(s), so σ(s) = 6F(L − s)/(b h(s)²), whatever the
/// modulus. For a thickness taper h = h₀ + (h₁ − h₀)s/L the derivative of
/// (L − s)/h² vanishes at s* = L(2h₁ − h₀)/(h₁ − h₀): mid-span for h₁ = h₀/3.
/// The model at order 12 meets the peak to 1e-4 (relative; the load is
/// 1e-4 of EI/L², so geometric nonlinearity is 1e-8).
#[test]
fn tapered_cantilever_stress_matches_beam_theory() {
    let (l, b, h0, h1) = (0.05, 0.01, 6e-4, 2e-4);
    let section = rectangle(Profile::Constant(b), Profile::Linear { root: h0, tip: h1 });
    let f = Flexure::new(l, 1.0, 12).unwrap().with_section(section).unwrap();
    let force = 1e-4 * f.ei() / (l * l);
    let mut data = flexure::StaticsData::new(&f);
    let eq =
        flexure::deflect(&f, &TipLoad { moment: 0.0, fx: 0.0, fy: force }, &mut data, &Default::default()).unwrap();
    assert!(eq.stable);
    let s_star = l * (2.0 * h1 - h0) / (h1 - h0);
    assert!((s_star - 0.5 * l).abs() < 1e-15);
    let h_star = h0 + (h1 - h0) * s_star / l;
    let expected = 6.0 * force * (l - s_star) / (b * h_star * h_star);
    let peak = flexure::stress::peak_stress(&f, data.alpha()).unwrap();
    assert!((peak.value - expected).abs() < 1e-4 * expected, "{} vs {expected}", peak.value);
    assert!((peak.at - s_star).abs() < 0.02 * l, "at {} vs {s_star}", peak.at);
}

/// Every bad section is an error naming the field.
#[test]
fn bad_sections_name_the_field() {
    let name = |r: Result<Section, Error>| match r {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("expected an invalid parameter, got {other:?}"),
    };
    let c = Profile::Constant;
    assert_eq!(name(Section::rectangle(1e9, None, c(0.0), c(1e-3))), "width");
    assert_eq!(name(Section::rectangle(1e9, None, c(0.01), Profile::Linear { root: 1e-3, tip: -1e-3 })), "thickness");
    assert_eq!(name(Section::rectangle(1e9, None, c(0.01), c(f64::NAN))), "thickness");
    assert_eq!(name(Section::given(Profile::Table(vec![[0.1, 1.0], [1.0, 1.0]]))), "ei");
    assert_eq!(name(Section::given(Profile::Table(vec![[0.0, 1.0], [0.5, 1.0], [0.5, 2.0], [1.0, 1.0]]))), "ei");
    assert_eq!(name(Section::given(Profile::Table(vec![[0.0, 1.0], [0.9, 1.0]]))), "ei");
    assert_eq!(name(Section::given(Profile::Table(vec![[0.0, 1.0]]))), "ei");
    let plate = Section::rectangle(1e9, None, c(0.01), c(1e-3)).unwrap();
    assert_eq!(name(plate.clone().with_notch(Notch { radius: 1e-3, min_thickness: 1e-3 })), "notch.min_thickness");
    assert_eq!(name(plate.clone().with_notch(Notch { radius: 1e-4, min_thickness: 1e-4 })), "notch.radius");
    assert_eq!(name(plate.clone().with_notch(Notch { radius: f64::INFINITY, min_thickness: 1e-4 })), "notch.radius");
    assert_eq!(name(plate.with_density(-1.0)), "density");
    assert_eq!(name(Section::uniform(1.0).unwrap().with_notch(Notch { radius: 1e-3, min_thickness: 1e-4 })), "notch");
    assert_eq!(name(Section::uniform(1.0).unwrap().with_density(7850.0)), "density");
    // EI out of range somewhere along the flexure: named, with where.
    let thin = Section::rectangle(1.0, None, c(1e-9), Profile::Linear { root: 1e-3, tip: 1e-9 }).unwrap();
    match Flexure::new(1.0, 1.0, 3).unwrap().with_section(thin) {
        Err(Error::InvalidParameter { name: "ei", value, .. }) => assert!(value.contains("at s ="), "{value}"),
        other => panic!("{other:?}"),
    }
}

/// A tip force bends a uniform cantilever most at the root (M = F·L there):
/// the peak is reported at s = 0 exactly, not a rounding error inside.
#[test]
fn a_root_peak_is_reported_at_the_root() {
    let f = Flexure::new(0.05, 1.0, 12).unwrap();
    let mut data = flexure::StaticsData::new(&f);
    flexure::deflect(&f, &TipLoad { moment: 0.0, fx: 0.0, fy: 10.0 }, &mut data, &Default::default()).unwrap();
    let p = flexure::stress::peak_curvature(&f, data.alpha());
    assert_eq!(p.at, 0.0);
    assert_eq!(p.value, flexure::stress::curvature_change(&f, data.alpha(), 0.0).abs());
}

/// A rectangle thicker than its flexure is long is refused wherever it is
/// thickest (a taper's tip, a table's point), naming the thickness, its
/// value and the length; a thickness equal to the length is accepted, and a
/// notch hinge is held to its neck.
#[test]
fn a_thickness_above_the_length_is_refused() {
    let c = Profile::Constant;
    let rect = |h: Profile| Section::rectangle(1e9, None, c(0.01), h).unwrap();
    for (h, at) in [
        (c(0.02), "0.02 m at t = 0"),
        (Profile::Linear { root: 1e-3, tip: 0.015 }, "0.015 m at t = 1"),
        (Profile::Table(vec![[0.0, 1e-3], [0.5, 0.03], [1.0, 1e-3]]), "0.03 m at t = 0.5"),
    ] {
        match Flexure::new(0.01, 1.0, 3).unwrap().with_section(rect(h)) {
            Err(Error::InvalidParameter { name: "thickness", value, .. }) => {
                assert!(value.contains(at) && value.contains("length 0.01 m"), "{value}")
            }
            other => panic!("{other:?}"),
        }
    }
    assert!(Flexure::new(0.01, 1.0, 3).unwrap().with_section(rect(c(0.01))).is_ok());
    // A notch hinge is held to its thinnest section: the Paros–Weisbord hinge cut into a
    // 10.5 mm blank over its 10 mm length is accepted, a 6 mm neck on a 5 mm flexure is not.
    let hinge = |h: f64, min: f64| rect(c(h)).with_notch(Notch { radius: 0.005, min_thickness: min }).unwrap();
    assert!(Flexure::new(0.01, 1.0, 3).unwrap().with_section(hinge(0.0105, 5e-4)).is_ok());
    match Flexure::new(0.005, 1.0, 3).unwrap().with_section(hinge(0.0105, 0.006)) {
        Err(Error::InvalidParameter { name: "notch.min_thickness", value, .. }) => {
            assert!(value.contains("0.006 m") && value.contains("length 0.005 m"), "{value}")
        }
        other => panic!("{other:?}"),
    }
}

/// `FlexureSpec::build` is the hand-built flexure to the last bit (a
/// uniform rectangle through Eq. 25, a taper through its section, mass and
/// rest curvature), and its errors name the parameter that does not fit.
#[test]
fn a_spec_builds_what_the_steps_build() {
    use flexure::FlexureSpec;
    use flexure::section::SectionSpec;
    let c = Profile::Constant;
    let rect = SectionSpec {
        modulus: Some(200e9),
        width: Some(c(0.01)),
        thickness: Some(c(2e-4)),
        poisson: Some(0.29),
        density: Some(7850.0),
        ..Default::default()
    };
    let spec = FlexureSpec { length: 0.02, section: rect, order: 4, quadrature: Some(9), kappa: Some(vec![0.1; 4]) };
    let section = Section::rectangle(200e9, Some(0.29), c(0.01), c(2e-4)).unwrap().with_density(7850.0).unwrap();
    let by_hand = Flexure::new(0.02, flexure::bending_stiffness(200e9, 0.01, 2e-4, Some(0.29)).unwrap(), 4)
        .unwrap()
        .with_section(section)
        .unwrap()
        .with_quadrature(9)
        .unwrap()
        .with_rest(&[0.1; 4])
        .unwrap();
    assert_eq!(spec.build().unwrap(), by_hand);
    let taper = SectionSpec { ei: Some(Profile::Linear { root: 2.0, tip: 1.0 }), ..Default::default() };
    let by_hand = Flexure::new(0.5, 1.0, 3).unwrap().with_section(Section::given(taper.ei.clone().unwrap()).unwrap());
    assert_eq!(FlexureSpec { length: 0.5, section: taper, ..Default::default() }.build().unwrap(), by_hand.unwrap());
    let name = |section: SectionSpec| match (FlexureSpec { section, ..Default::default() }).build() {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("{other:?}"),
    };
    assert_eq!(name(SectionSpec { ei: Some(c(1.0)), modulus: Some(1e9), ..Default::default() }), "modulus");
    assert_eq!(name(SectionSpec { width: Some(c(0.01)), ..Default::default() }), "width");
    assert_eq!(name(SectionSpec { modulus: Some(1e9), width: Some(c(0.01)), ..Default::default() }), "thickness");
    assert_eq!(name(SectionSpec { ei: Some(c(1.0)), density: Some(1.0), ..Default::default() }), "density");
    let both = SectionSpec { density: Some(1.0), mass_per_length: Some(c(1.0)), ..Default::default() };
    assert_eq!(name(both), "mass_per_length");
    assert_eq!(name(SectionSpec { ei: Some(c(-1.0)), ..Default::default() }), "ei");
}
