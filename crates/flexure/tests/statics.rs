//! Equilibrium under tip loads (Eq. 22) against the exact elastica (Figs. 7–8),
//! and the loaded stiffness (Eq. 32) against differentiation through the solver.

use flexure::reference::elastica;
use flexure::{Error, Flexure, Settings, StabilityLimit, StaticsData, TipLoad, compliance_tip, deflect};
use num_dual::Dual64;
use std::f64::consts::FRAC_PI_2;

fn unit() -> Flexure {
    Flexure::new(1.0, 1.0, 3).unwrap()
}

/// The force magnitude P, at angle θ with extra moment M, that bends the
/// exact elastica's tip to 90° (secant on P).
fn exact_load_for_right_angle(moment: f64, theta: f64, mut p0: f64, mut p1: f64) -> f64 {
    let f = unit();
    let angle =
        |p| elastica::deflect(&f, &TipLoad::polar(moment, p, theta), &Default::default()).unwrap().pose.phi - FRAC_PI_2;
    let (mut a0, mut a1) = (angle(p0), angle(p1));
    for _ in 0..50 {
        let p2 = p1 - a1 * (p1 - p0) / (a1 - a0);
        (p0, a0, p1) = (p1, a1, p2);
        a1 = angle(p1);
        if a1.abs() < 1e-12 {
            break;
        }
    }
    p1
}

/// Figs. 7–8: up to a 90° tip angle the model stays within 1 % of L in
/// position and 1° in angle of the exact elastica (paper Sec. III-C).
fn check_path(name: &str, load_at: impl Fn(f64) -> TipLoad) {
    let f = unit();
    let mut data = StaticsData::new(&f);
    for i in 1..=10 {
        let load = load_at(i as f64 / 10.0);
        let eq = deflect(&f, &load, &mut data, &Default::default()).unwrap();
        let exact = elastica::deflect(&f, &load, &Default::default()).unwrap().pose;
        let model = data.pose_root_tip();
        let position = (model.x - exact.x).hypot(model.y - exact.y);
        let angle = (model.phi - exact.phi).abs().to_degrees();
        assert!(eq.stable, "{name} step {i}: the equilibrium must be stable");
        assert!(position < 0.01, "{name} step {i}: position error {position} ≥ 1 % of L");
        assert!(angle < 1.0, "{name} step {i}: angle error {angle}° ≥ 1°");
    }
}

#[test]
fn case_a_pure_moment() {
    check_path("A", |s| TipLoad { moment: s * FRAC_PI_2, fx: 0.0, fy: 0.0 });
}

#[test]
fn case_b_pure_force() {
    // A force at θ = 45°, scaled to bend the exact tip to 90° (P ≈ 3.8477).
    let p = exact_load_for_right_angle(0.0, 45f64.to_radians(), 3.5, 3.9);
    assert!((p - 3.8477).abs() < 1e-3, "the load used by the speed benchmark: {p}");
    check_path("B", |s| TipLoad::polar(0.0, s * p, 45f64.to_radians()));
}

#[test]
fn case_c_force_opposed_by_moment() {
    // Case A's moment reversed, and a force at 45° large enough for 90°.
    let p = exact_load_for_right_angle(-FRAC_PI_2, 45f64.to_radians(), 6.0, 7.0);
    check_path("C", |s| TipLoad::polar(-s * FRAC_PI_2, s * p, 45f64.to_radians()));
}

/// The pure moment's exact answer is an arc with α = (ML/EI, 0, 0): the model
/// contains it, so Newton must land on it to the solver tolerance.
#[test]
fn pure_moment_is_exact() {
    let f = Flexure::new(0.4, 2.5, 5).unwrap();
    let mut data = StaticsData::new(&f);
    deflect(&f, &TipLoad { moment: 7.0, fx: 0.0, fy: 0.0 }, &mut data, &Default::default()).unwrap();
    let expected = 7.0 * 0.4 / 2.5;
    assert!((data.alpha()[0] - expected).abs() < 1e-12);
    assert!(data.alpha()[1..].iter().all(|a| a.abs() < 1e-12));
}

/// Eq. 32 by the implicit function theorem: dα/dF_y = K⁻¹ J_yᵀ, so the tip's
/// response is column y of C = J K⁻¹ Jᵀ. Checked against num-dual carried
/// through the whole solver (exact to its tolerance) and central differences
/// of the solver (h = 1e-5: error ~1e-8).
#[test]
fn loaded_compliance_is_the_solvers_derivative() {
    let f = unit();
    let load = TipLoad::polar(0.3, 2.0, 0.6);
    let mut data = StaticsData::new(&f);
    deflect(&f, &load, &mut data, &Default::default()).unwrap();
    let c = compliance_tip(&data.kinematics, &data.stiffness).unwrap();

    let mut dual = StaticsData::<Dual64>::new(&f);
    let dload = TipLoad { moment: Dual64::from(load.moment), fx: Dual64::from(load.fx), fy: Dual64::new(load.fy, 1.0) };
    deflect(&f, &dload, &mut dual, &Default::default()).unwrap();
    let p = dual.pose_root_tip();
    for (r, d) in [p.phi.eps, p.x.eps, p.y.eps].into_iter().enumerate() {
        assert!((c[(r, 2)] - d).abs() < 1e-9, "C[{r},y] vs num-dual through deflect");
    }

    let h = 1e-5;
    let mut up = StaticsData::new(&f);
    let mut dn = StaticsData::new(&f);
    deflect(&f, &TipLoad { fx: load.fx + h, ..load }, &mut up, &Default::default()).unwrap();
    deflect(&f, &TipLoad { fx: load.fx - h, ..load }, &mut dn, &Default::default()).unwrap();
    let (pu, pd) = (up.pose_root_tip(), dn.pose_root_tip());
    let fd = [(pu.phi - pd.phi) / (2.0 * h), (pu.x - pd.x) / (2.0 * h), (pu.y - pd.y) / (2.0 * h)];
    for r in 0..3 {
        assert!((c[(r, 1)] - fd[r]).abs() < 1e-7, "C[{r},x] vs central differences");
        // Maxwell–Betti: the loaded compliance is symmetric.
        assert!((c[(r, 1)] - c[(1, r)]).abs() < 1e-12);
    }
}

/// Compression along the axis: the straight shape is always an equilibrium;
/// below Euler's π²/4 it is stable, above it the solver says it is not.
#[test]
fn instability_is_reported() {
    let f = unit();
    let mut data = StaticsData::new(&f);
    assert!(deflect(&f, &TipLoad { moment: 0.0, fx: -2.4, fy: 0.0 }, &mut data, &Default::default()).unwrap().stable);
    assert!(!deflect(&f, &TipLoad { moment: 0.0, fx: -2.5, fy: 0.0 }, &mut data, &Default::default()).unwrap().stable);
    assert!(compliance_tip(&data.kinematics, &data.stiffness).is_err(), "an unstable equilibrium has no compliance");
}

#[test]
fn bad_load_is_named() {
    let f = unit();
    let mut data = StaticsData::new(&f);
    let err = deflect(&f, &TipLoad { moment: 0.0, fx: f64::NAN, fy: 0.0 }, &mut data, &Default::default()).unwrap_err();
    assert!(matches!(err, Error::InvalidParameter { name: "fx", .. }), "{err}");
}

/// A solver starved of iterations and steps reports how far it got.
#[test]
fn a_stalled_continuation_reports_the_load_reached() {
    let f = unit();
    let mut data = StaticsData::new(&f);
    let settings = Settings { max_iterations: 1, min_step: 0.5, ..Default::default() };
    match deflect(&f, &TipLoad::polar(0.0, 20.0, 0.3), &mut data, &settings) {
        Err(Error::ContinuationStalled { residual, load_fraction, .. }) => {
            assert!(residual.is_finite() && residual > 0.0 && (0.0..1.0).contains(&load_fraction))
        }
        other => panic!("expected ContinuationStalled, got {other:?}"),
    }
    // A moment of 1e12 N·m would turn the tip by 1e12 rad: the step limit ends it.
    let settings = Settings { max_steps: 50, ..Default::default() };
    match deflect(&f, &TipLoad { moment: 1e12, fx: 0.0, fy: 0.0 }, &mut data, &settings) {
        Err(Error::ContinuationStalled { steps, load_fraction, .. }) => {
            assert!(steps == 50 && load_fraction > 0.0 && load_fraction < 1e-9, "{steps} {load_fraction}")
        }
        other => panic!("expected ContinuationStalled, got {other:?}"),
    }
}

/// Every setting is validated: zero, negative or non-finite is an error naming it.
#[test]
fn settings_are_validated() {
    let f = unit();
    let mut data = StaticsData::new(&f);
    let load = TipLoad { moment: 1.0, fx: 0.0, fy: 0.0 };
    let base = Settings::default();
    let bad = [
        ("tolerance", Settings { tolerance: 0.0, ..base }),
        ("tolerance", Settings { tolerance: f64::NAN, ..base }),
        ("max_iterations", Settings { max_iterations: 0, ..base }),
        ("max_steps", Settings { max_steps: 0, ..base }),
        ("min_step", Settings { min_step: 0.0, ..base }),
        ("min_step", Settings { min_step: -1.0, ..base }),
        ("max_rotation_per_step", Settings { max_rotation_per_step: 0.0, ..base }),
        ("max_rotation_per_step", Settings { max_rotation_per_step: f64::INFINITY, ..base }),
    ];
    for (name, settings) in bad {
        match deflect(&f, &load, &mut data, &settings) {
            Err(Error::InvalidParameter { name: got, .. }) => assert_eq!(got, name),
            other => panic!("{name}: expected InvalidParameter, got {other:?}"),
        }
    }
}

/// Large loads: both solvers follow the loading path from rest. A full
/// Newton step at PL²/EI = 15 can land on a far root with the tip turned
/// past −180°; continuation must not. The exact angle is 1.5018 rad
/// (elliptic integrals, see tests/reference.rs); the model stays within 1°
/// and 1 % of L.
#[test]
fn large_load_stays_on_the_loading_branch() {
    let f = unit();
    let load = TipLoad { moment: 0.0, fx: 0.0, fy: 15.0 };
    let mut data = StaticsData::new(&f);
    deflect(&f, &load, &mut data, &Default::default()).unwrap();
    let exact = elastica::deflect(&f, &load, &Default::default()).unwrap().pose;
    let model = data.pose_root_tip();
    assert!((exact.phi - 1.5018401541771547).abs() < 1e-8);
    assert!((model.phi - exact.phi).abs().to_degrees() < 1.0, "{} vs {}", model.phi, exact.phi);
    assert!((model.x - exact.x).hypot(model.y - exact.y) < 0.01);
}

/// Beyond 90°: a force at 45° with PL²/EI = 6 turns the exact tip past a
/// right angle; the model converges there too, to a stable equilibrium that
/// agrees with the elastica's angle within 2° (the paper's 1° claim stops at 90°).
#[test]
fn converges_beyond_a_right_angle() {
    let f = unit();
    let load = TipLoad::polar(0.0, 6.0, 45f64.to_radians());
    let mut data = StaticsData::new(&f);
    let eq = deflect(&f, &load, &mut data, &Default::default()).unwrap();
    let exact = elastica::deflect(&f, &load, &Default::default()).unwrap().pose;
    assert!(exact.phi > FRAC_PI_2 + 0.1, "exact tip {}", exact.phi);
    assert!(eq.stable && eq.residual < 1e-11);
    assert!((data.pose_root_tip().phi - exact.phi).abs().to_degrees() < 2.0);
}

/// Stability limit along a load path: axial compression loses stability at
/// the model's free buckling load (Table I, 2.4677 EI/L²; ±5e-5), and a
/// load that only bends never does.
#[test]
fn stability_limit_matches_buckling() {
    let f = unit();
    let limit = flexure::statics::stability_limit(&f, &TipLoad { moment: 0.0, fx: -2.0, fy: 0.0 }, 100.0).unwrap();
    let StabilityLimit::Lost { factor } = limit else { panic!("{limit:?}") };
    assert!((2.0 * factor - 2.4677).abs() < 5e-5, "{}", 2.0 * factor);
    let bend = flexure::statics::stability_limit(&f, &TipLoad { moment: 1.0, fx: 0.0, fy: 0.0 }, 4.0).unwrap();
    assert_eq!(bend, StabilityLimit::StableUpTo { factor: 4.0, stalled: None });
}

/// `--limit` answers on every load that solves (issue 20's grid of unit-flexure
/// loads: 32 of these 60 used to fail with a stalled probe). Each answer is
/// checked against the definition of the limit, independently of the search:
/// `deflect` at 0.999 of a lost factor is stable, and the path to 1.01 of it
/// loses stability (or cannot be followed stably); a path stable up to a
/// bound is stable at 0.999 of the bound.
#[test]
fn stability_limit_answers_on_the_whole_grid() {
    let f = unit();
    let stable_at = |load: &TipLoad, factor: f64| {
        let scaled = TipLoad { moment: factor * load.moment, fx: factor * load.fx, fy: factor * load.fy };
        let mut data = StaticsData::new(&f);
        deflect(&f, &scaled, &mut data, &Default::default()).map(|e| e.stable && e.limit.is_none())
    };
    for moment in [0.0, 0.2, 0.5, 1.0, 2.0] {
        for fx in [-1.0, 0.0, 1.0] {
            for fy in [0.0, 0.3, 1.0, 3.0] {
                let load = TipLoad { moment, fx, fy };
                if load == TipLoad::default() {
                    continue;
                }
                let limit =
                    flexure::statics::stability_limit(&f, &load, 1000.0).unwrap_or_else(|e| panic!("{load:?}: {e}"));
                let factor = limit.factor();
                assert!(factor.is_finite() && factor > 0.0, "{load:?}: {limit:?}");
                assert_eq!(stable_at(&load, 0.999 * factor), Ok(true), "{load:?}: {limit:?}");
                if let StabilityLimit::Lost { .. } = limit {
                    assert_ne!(stable_at(&load, 1.01 * factor), Ok(true), "{load:?}: {limit:?}");
                }
            }
        }
    }
}

/// Long steps far from instability: the paper's 90° case (Fig. 6's load,
/// 3.8477 EI/L² at 45°) is reached in one continuation step, because every
/// state on the way keeps more than half its elastic stiffness; the answer
/// is the equilibrium the short-step path reaches (max_rotation_per_step
/// pinned small enough that the long steps are not allowed), to Newton's tolerance.
#[test]
fn far_from_instability_the_continuation_takes_long_steps() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let load = TipLoad::polar(0.0, 3.8477, 45f64.to_radians());
    let mut data = StaticsData::new(&f);
    let long = deflect(&f, &load, &mut data, &Settings::default()).unwrap();
    let alpha = data.alpha().to_vec();
    let short_settings = Settings { max_rotation_per_step: 0.5 / flexure::solver::FAR_STEP, ..Default::default() };
    let short = deflect(&f, &load, &mut data, &short_settings).unwrap();
    assert_eq!(long.load_steps, 1, "{long:?}");
    assert!(short.load_steps > 4, "{short:?}");
    assert!(long.stable && short.stable);
    for (a, b) in alpha.iter().zip(data.alpha()) {
        assert!((a - b).abs() < 1e-10, "{alpha:?} vs {:?}", data.alpha());
    }
}

/// A long first step must not land past a fold: a column under 8.7× its
/// Euler load with a side force and rest curvature buckles to φ ≈ 3.13; a
/// single step to the full load lands on the unstable near-straight state
/// (φ ≈ 0.20) instead. The answer must be the stable buckled state, within
/// 0.01 rad of the exact elastica's (the order-3 model's own error here).
#[test]
fn a_long_step_does_not_land_past_a_fold() {
    let kappa = [0.13682064279451467, 0.1878018480661532, 0.2852641999269957];
    let f = Flexure::new(1.0, 1.0, 3).unwrap().with_rest(&kappa).unwrap();
    let load = TipLoad { moment: 0.0, fx: -21.53936555702723, fy: 0.14229491318230522 };
    let mut data = StaticsData::new(&f);
    let eq = deflect(&f, &load, &mut data, &Settings::default()).unwrap();
    let exact = flexure::reference::elastica::deflect(&f, &load, &Default::default()).unwrap();
    assert!(eq.stable && exact.stable, "{eq:?}");
    assert!((data.alpha()[0] - exact.pose.phi).abs() < 0.01, "{} vs {}", data.alpha()[0], exact.pose.phi);
}

/// Loads (unit length and stiffness) whose long first continuation step
/// was corrected onto another branch (issue 39 item 3; the first is the
/// issue's, the others from a sweep of 10⁵ random loads up to 10 N·m and
/// 20 N): (order, load, the exact elastica's tip angle on its loading path).
const BRANCH_JUMPS: [(usize, TipLoad, f64); 7] = [
    (6, TipLoad { moment: -6.258888285291928, fx: -15.501008696246453, fy: 5.017976184775733 }, -4.97073),
    (3, TipLoad { moment: -6.608546493588971, fx: -18.780090814673574, fy: 4.520130381568261 }, -4.90476),
    (6, TipLoad { moment: -7.3547943620570795, fx: -19.442183948754057, fy: 5.362514833885679 }, -5.14028),
    (3, TipLoad { moment: 3.7537456692686644, fx: -11.660610997809044, fy: -2.5080300693818947 }, 4.18978),
    (3, TipLoad { moment: 3.107264311321034, fx: -12.504423257550776, fy: -2.068755851497306 }, 3.94816),
    (6, TipLoad { moment: 5.432602775959607, fx: -13.647381773974455, fy: -3.8682944085638438 }, 4.73601),
    (3, TipLoad { moment: -5.2327385859714575, fx: -16.032059063432452, fy: 3.4120670180487966 }, -4.55591),
];

/// The right branch at any order (issue 39 item 3): under each of
/// [`BRANCH_JUMPS`] the model's answer is the exact elastica's, within the
/// model's own error at its order (1 % of L and 0.01 rad at order 3, 0.1 %
/// and 0.001 rad at order 6; seen: 0.84 % and 0.0055 rad, 0.017 % and
/// 0.0003 rad), where the first step used to land on a branch 0.9 to 1 L
/// away (the issue's: φ = 0.744 against −4.971). It is also the end of the
/// model's own path followed in steps of at most 0.02 rad, to 1e-9.
#[test]
fn a_long_step_does_not_jump_to_another_branch() {
    for (order, load, phi) in BRANCH_JUMPS {
        let f = Flexure::new(1.0, 1.0, order).unwrap();
        let mut data = StaticsData::new(&f);
        let eq = deflect(&f, &load, &mut data, &Settings::default()).unwrap();
        let exact = elastica::deflect(&f, &load, &Default::default()).unwrap();
        assert!(exact.stable && (exact.pose.phi - phi).abs() < 1e-5, "{load:?}: exact {exact:?}");
        let (model, e) = (data.pose_root_tip(), exact.pose);
        let tolerance = if order < 6 { 0.01 } else { 0.001 };
        assert!(eq.stable, "order {order}, {load:?}: {eq:?}");
        assert!((model.phi - e.phi).abs() < tolerance, "order {order}, {load:?}: φ = {} vs {}", model.phi, e.phi);
        assert!((model.x - e.x).hypot(model.y - e.y) < tolerance, "order {order}, {load:?}: {model:?} vs {e:?}");
        let alpha = data.alpha().to_vec();
        let short = Settings { max_rotation_per_step: 0.02, ..Default::default() };
        deflect(&f, &load, &mut data, &short).unwrap();
        for (a, b) in alpha.iter().zip(data.alpha()) {
            assert!((a - b).abs() < 1e-9, "order {order}, {load:?}: {alpha:?} vs {:?}", data.alpha());
        }
    }
}

/// A mechanism of one flexure under the same tip loads follows the same
/// path: `solve` (its own problem on the shared continuation, with its own
/// far-from-instability test) reaches [`deflect`]'s answer at each of
/// [`BRANCH_JUMPS`], to 1e-9 in every coefficient.
#[test]
fn one_flexure_mechanism_reaches_the_same_branch() {
    use flexure::mechanism::file::from_toml;
    use flexure::mechanism::statics::solve;
    for (order, load, _) in BRANCH_JUMPS {
        let text = format!(
            "[[joint]]\nname = \"blade\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\n\
             length = 1.0\nei = 1.0\norder = {order}\n\
             [[force]]\nbody = \"tip\"\nat = [0.0, 0.0]\nforce = [{:?}, {:?}]\nmoment = {:?}\n",
            load.fx, load.fy, load.moment
        );
        let m = from_toml(&text).unwrap();
        let s = solve(&m, &flexure::mechanism::statics::Settings::default()).unwrap();
        let f = Flexure::new(1.0, 1.0, order).unwrap();
        let mut data = StaticsData::new(&f);
        deflect(&f, &load, &mut data, &Settings::default()).unwrap();
        assert!(s.stable, "order {order}, {load:?}");
        for (a, b) in s.q.iter().zip(data.alpha()) {
            assert!((a - b).abs() < 1e-9, "order {order}, {load:?}: {:?} vs {:?}", s.q, data.alpha());
        }
    }
}

/// An overflowing load is an error at once, never an endless loop of halvings.
#[test]
fn an_overflowing_step_is_an_error() {
    let f = Flexure::new(2.0339121109392635, 1.6035678019230033, 6).unwrap().with_quadrature(3).unwrap();
    let load = TipLoad { moment: 1.9659202388348458, fx: 4.437708090274985, fy: 1e300 };
    let settings = Settings { max_rotation_per_step: f64::MAX, ..Default::default() };
    assert!(deflect(&f, &load, &mut StaticsData::new(&f), &settings).is_err());
}

/// Buffers made for another flexure are refused by name, never a panic:
/// another order, or the same order with another quadrature rule (a
/// three-segment chain has three coordinates but 15 nodes, not 5), for
/// `deflect`, `correct` and the tendon's `pull`.
#[test]
fn buffers_of_another_flexure_are_an_error_naming_data() {
    use flexure::tendon::{TendonData, TendonOffsets, pull};
    let load = TipLoad { moment: 0.5, fx: 0.0, fy: 0.0 };
    let chain = Flexure::segments(1.0, 1.0, 3).unwrap();
    for other in [Flexure::new(1.0, 1.0, 4).unwrap(), chain.clone()] {
        let mut data = StaticsData::new(&unit());
        let e = deflect(&other, &load, &mut data, &Settings::default()).unwrap_err();
        assert!(matches!(e, Error::InvalidParameter { name: "data", .. }), "{e}");
        let e = flexure::statics::correct(&other, &load, &vec![0.0; other.order()], &mut data, &Settings::default())
            .unwrap_err();
        assert!(matches!(e, Error::InvalidParameter { name: "data", .. }), "{e}");
        let tendon = TendonOffsets { root_offset: 0.01, tip_offset: 0.01 };
        let e = pull(&other, &tendon, 1.0, &mut TendonData::new(&unit())).unwrap_err();
        assert!(matches!(e, Error::InvalidParameter { name: "data", .. }), "{e}");
    }
    // Any flexure of the same order and rule may share them.
    let mut data = StaticsData::new(&unit());
    assert!(deflect(&Flexure::new(2.0, 3.0, 3).unwrap(), &load, &mut data, &Settings::default()).is_ok());
    assert!(deflect(&chain, &load, &mut StaticsData::new(&chain), &Settings::default()).is_ok());
}
