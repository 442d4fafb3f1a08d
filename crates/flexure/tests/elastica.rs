//! The exact elastica (`reference::elastica::deflect`) against closed forms
//! by elliptic integrals, loaded from rest along its path: tip forces in any
//! direction (Bisshopp–Drucker's transverse force, the imperfect and the
//! perfect column), Euler's load, the branch an imperfection picks, a
//! snap-through, and pure moments turning the tip by up to 450°.

use flexure::reference::elastica;
use flexure::{Error, Flexure, TipLoad};
use std::f64::consts::{FRAC_PI_2, PI};

/// The cantilever (length L, stiffness EI, no rest curvature) under a tip
/// force F pointing at angle β = π − δ, 0 < δ < π, and no tip moment, on the
/// branch that bends toward positive angles without an inflection.
///
/// Along the beam EI φ'' = F sin(φ − β) with φ(0) = 0, φ'(L) = 0. With
/// ϑ = φ + δ rising from δ to α = φ_L + δ, the first integral
/// φ'² = (2F/EI)(cos ϑ − cos α) and sin(ϑ/2) = k sin t, k = sin(α/2), give
/// L√(F/EI) = K(k) − F(t₀, k), sin t₀ = sin(δ/2)/k. The tip, along
/// u = (cos δ, −sin δ) and v = (sin δ, cos δ):
/// a = [2(E(k) − E(t₀, k)) − (K(k) − F(t₀, k))]/√(F/EI),
/// b = √(2(cos δ − cos α))/√(F/EI), and (x, y) = a u + b v.
/// δ = π/2 is Bisshopp–Drucker's transverse force; δ → 0 the column,
/// where t₀ → 0 and L√(P/EI) = K(k), k = sin(α₀/2).
///
/// The integrals are Bulirsch's, in the complementary modulus
/// k' = cos(α/2) (`ellip::cel1`, `cel2`, `el1`, `el2`): near α = π, where
/// large loads take the tip, k² = 1 − k'² would lose k' to rounding.
/// Returns (φ_L, x_L, y_L); k' by bisection on ln k' to machine precision.
fn tip_force_closed_form(length: f64, ei: f64, force: f64, delta: f64) -> [f64; 3] {
    let c = (force / ei).sqrt();
    let half = delta / 2.0;
    // (K − F(t₀), E − E(t₀)) at k' = kc.
    let parts = |kc: f64| {
        let kc2 = kc * kc;
        let tan_t0 = half.sin() / (half.cos().powi(2) - kc2).sqrt();
        let f = ellip::cel1(kc).unwrap() - ellip::el1(tan_t0, kc).unwrap();
        let e = ellip::cel2(kc, 1.0, kc2).unwrap() - ellip::el2(tan_t0, kc, 1.0, kc2).unwrap();
        (f, e)
    };
    // K − F(t₀) falls from ≈ 120 at k' = e⁻¹²⁰ (α ≈ π) to 0 at k' = cos(δ/2) (α = δ).
    let (mut lo, mut hi) = (-120.0_f64, half.cos().ln());
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if parts(mid.exp()).0 > c * length { lo = mid } else { hi = mid }
    }
    let kc = (0.5 * (lo + hi)).exp();
    let alpha = 2.0 * kc.acos();
    let (f, e) = parts(kc);
    let a = (2.0 * e - f) / c;
    // cos δ − cos α with cos α = 2k'² − 1.
    let b = (2.0 * (delta.cos() + 1.0 - 2.0 * kc * kc)).sqrt() / c;
    let (sd, cd) = delta.sin_cos();
    [alpha - delta, a * cd + b * sd, -a * sd + b * cd]
}

/// The tip force of magnitude `force` at angle π − δ.
fn tip_force(force: f64, delta: f64) -> TipLoad {
    TipLoad { moment: 0.0, fx: -force * delta.cos(), fy: force * delta.sin() }
}

fn assert_pose(s: &elastica::ElasticaSolution, closed: [f64; 3], tolerance: f64, what: &str) {
    let got = [s.pose.phi, s.pose.x, s.pose.y];
    for (i, name) in ["φ", "x", "y"].iter().enumerate() {
        assert!((got[i] - closed[i]).abs() < tolerance, "{what}: {name} = {} vs {} (closed form)", got[i], closed[i]);
    }
}

/// Tip forces in five directions, from a tenth of Euler's load to 4000
/// times it (L√(F/EI) up to 100, the largest the solver accepts), on a beam
/// with L = 1.3, EI = 0.7: the pose agrees with the closed form to 1e-10
/// (6e-12 seen; the integrator's tolerance is 1e-12 per step, Newton's 1e-12
/// of the moment scale), and every shape is stable. The directions: the
/// imperfect column (δ = 0.01, the tip turning toward 180°), backward-up
/// (δ = π/4, past 90°), transverse (Bisshopp–Drucker), forward-up (δ = 2, 3:
/// tension).
#[test]
fn tip_force_in_any_direction() {
    let (l, ei) = (1.3, 0.7);
    let f = Flexure::new(l, ei, 3).unwrap();
    for delta in [0.01, PI / 4.0, FRAC_PI_2, 2.0, 3.0] {
        for p in [0.25, 1.0, 4.0, 30.0, 300.0, 1e4] {
            let force = p * ei / (l * l);
            let s = elastica::deflect(&f, &tip_force(force, delta), &Default::default()).unwrap();
            let what = format!("F = {p} EI/L² at π − {delta}");
            assert_pose(&s, tip_force_closed_form(l, ei, force, delta), 1e-10, &what);
            assert!(s.stable && s.limit.is_none(), "{what}: {s:?}");
        }
    }
}

/// Euler's load of the clamped–free column, P = π²EI/4L² (L = 1.3,
/// EI = 0.7): below it the straight column is stable; at 1.25 times it the
/// perfect column stays straight (nothing breaks the symmetry) and the
/// continuation reports where stability was lost, at 1/1.25 of the load to
/// 1e-5 (the bisection of the step stops at min_step = 1e-6 of the load).
#[test]
fn euler_load_of_the_straight_column() {
    let (l, ei) = (1.3, 0.7);
    let f = Flexure::new(l, ei, 3).unwrap();
    let euler = PI * PI * ei / (4.0 * l * l);
    let below =
        elastica::deflect(&f, &TipLoad { moment: 0.0, fx: -0.9 * euler, fy: 0.0 }, &Default::default()).unwrap();
    assert!(below.stable && below.limit.is_none() && below.pose.y == 0.0, "{below:?}");
    let above =
        elastica::deflect(&f, &TipLoad { moment: 0.0, fx: -1.25 * euler, fy: 0.0 }, &Default::default()).unwrap();
    assert!(!above.stable && above.pose.y == 0.0, "{above:?}");
    let limit = above.limit.expect("stability is lost at Euler's load");
    assert!((limit - 1.0 / 1.25).abs() < 1e-5, "limit at {limit} of the load, Euler at {}", 1.0 / 1.25);
}

/// The post-buckled column by complete elliptic integrals: P L²/EI = K(k)²,
/// k = sin(α₀/2), α₀ the tip angle. A side force of 10⁻⁶ of the axial one
/// (δ = 1e-6) makes the loaded column buckle toward it; its pose then
/// matches the imperfect column's closed form to 1e-10, and its tip angle
/// the perfect column's α₀ to 25δ (the side force moves the tip by about
/// δ/(P/P_E − 1): 18δ at α₀ = 0.5, where P = 1.03 P_E; under δ elsewhere).
#[test]
fn post_buckled_column_by_elliptic_integrals() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let delta = 1e-6;
    for alpha0 in [0.5, 1.5, 2.5, 3.0_f64] {
        let k = (alpha0 / 2.0).sin();
        let p = ellip::ellipk(k * k).unwrap().powi(2);
        let s = elastica::deflect(&f, &tip_force(p, delta), &Default::default()).unwrap();
        let what = format!("P = {p:.4} EI/L², α₀ = {alpha0}");
        assert_pose(&s, tip_force_closed_form(1.0, 1.0, p, delta), 1e-10, &what);
        assert!((s.pose.phi - alpha0).abs() < 25.0 * delta, "{what}: φ = {}", s.pose.phi);
        assert!(s.stable, "{what}");
    }
}

/// The cases, where shooting at the full load landed on the other
/// branch. `--fx -37.83 --fy 0.0444`: the mirror-image buckled shape
/// (φ = −3.126) was returned as stable; loading from rest gives the closed
/// form's φ = +3.1234 (to 1e-10). `--fx -3 --fy 1e-9`: the unstable straight
/// column was returned; loading from rest buckles it toward the side force
/// (φ = 1.2245). Reversing the side force mirrors the shape (to 1e-10).
#[test]
fn an_imperfection_decides_the_branch() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    for (fx, fy) in [(-37.83_f64, 0.0444_f64), (-3.0, 1e-9)] {
        let s = elastica::deflect(&f, &TipLoad { moment: 0.0, fx, fy }, &Default::default()).unwrap();
        let closed = tip_force_closed_form(1.0, 1.0, fx.hypot(fy), fy.atan2(-fx));
        assert_pose(&s, closed, 1e-10, &format!("fx = {fx}, fy = {fy}"));
        assert!(s.stable && s.pose.phi > 1.2, "{s:?}");
        // The side force reversed: the mirror image.
        let m = elastica::deflect(&f, &TipLoad { moment: 0.0, fx, fy: -fy }, &Default::default()).unwrap();
        assert!((m.pose.phi + s.pose.phi).abs() < 1e-10 && (m.pose.y + s.pose.y).abs() < 1e-10, "{m:?}");
    }
}

/// `--moment=-5.155527614759166 --fy=7.2595493570994885`: loaded from rest,
/// the beam turns clockwise until a limit load, snaps through, and ends on
/// its one stable equilibrium at φ ≈ −5.70. Checked independently: one
/// shot from the root with the reported root moment (a separate
/// integration) reproduces the pose and balances the tip moment (to 1e-8:
/// that shot's sensitivity to M₀ is e^{L√(F/EI)} ≈ 15), the Jacobi test
/// passes, and the model of order 8 reaches the same shape (within 1e-5,
/// its discretization error here). Below the reported limit fraction the
/// path stays stable.
#[test]
fn snap_through_reaches_the_stable_shape_and_reports_the_limit() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let load = TipLoad { moment: -5.155527614759166, fx: 0.0, fy: 7.2595493570994885 };
    let s = elastica::deflect(&f, &load, &Default::default()).unwrap();
    assert!(s.stable && (s.pose.phi + 5.70).abs() < 0.01, "{s:?}");
    let limit = s.limit.expect("the path loses stability at a limit load");
    assert!(limit > 0.0 && limit < 1.0, "{limit}");

    let tip = elastica::shoot(&f, s.root_moment, load.fx, load.fy, &Default::default(), |_, _| {}).unwrap();
    assert!((tip[0] - s.pose.phi).abs() < 1e-8 && (tip[1] - s.pose.x).abs() < 1e-8 && (tip[2] - s.pose.y).abs() < 1e-8);
    let tip_moment = s.root_moment - load.fy * tip[1] + load.fx * tip[2];
    assert!((tip_moment - load.moment).abs() < 1e-8, "tip moment {tip_moment}");
    assert!(elastica::is_stable(&f, s.root_moment, load.fx, load.fy, &Default::default()).unwrap());

    let model = Flexure::new(1.0, 1.0, 8).unwrap();
    let mut data = flexure::StaticsData::new(&model);
    let eq = flexure::deflect(&model, &load, &mut data, &Default::default()).unwrap();
    assert!(eq.stable && (data.pose_root_tip().phi - s.pose.phi).abs() < 1e-5);

    let scaled = |x: f64| TipLoad { moment: x * load.moment, fx: 0.0, fy: x * load.fy };
    let before = elastica::deflect(&f, &scaled(0.98 * limit), &Default::default()).unwrap();
    assert!(before.stable && before.limit.is_none() && before.pose.phi > -2.0, "{before:?}");
}

/// A pure moment bends the beam into a circle of curvature M/EI, however
/// far the tip turns (here up to 450°, L = 0.8, EI = 1.7): pose to 1e-10.
#[test]
fn pure_moment_circle_past_a_full_turn() {
    let (l, ei) = (0.8, 1.7);
    let f = Flexure::new(l, ei, 3).unwrap();
    for turn in [PI / 4.0, FRAC_PI_2, PI, 1.5 * PI, 2.5 * PI, -1.5 * PI] {
        let m = turn * ei / l;
        let s = elastica::deflect(&f, &TipLoad { moment: m, fx: 0.0, fy: 0.0 }, &Default::default()).unwrap();
        let r = l / turn;
        let closed = [turn, r * turn.sin(), r * (1.0 - turn.cos())];
        assert_pose(&s, closed, 1e-10, &format!("tip turned by {turn}"));
        assert!(s.stable && (s.root_moment - m).abs() < 1e-9);
    }
}

/// Bad input and too large a force are refused by name.
#[test]
fn refusals_name_the_parameter() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let bad = elastica::deflect(&f, &TipLoad { moment: f64::NAN, fx: 0.0, fy: 0.0 }, &Default::default());
    assert!(matches!(bad, Err(Error::InvalidParameter { name: "moment", .. })), "{bad:?}");
    let mut settings = elastica::ShootingSettings::default();
    settings.ode.max_steps = 0;
    let bad = elastica::deflect(&f, &TipLoad::default(), &settings);
    assert!(matches!(bad, Err(Error::InvalidParameter { name: "max_steps", .. })), "{bad:?}");
    // L√(|F|/EI) = 101 > 100.
    let bad = elastica::deflect(&f, &TipLoad { moment: 0.0, fx: 0.0, fy: 101.0 * 101.0 }, &Default::default());
    assert!(matches!(bad, Err(Error::InvalidParameter { name: "force", .. })), "{bad:?}");
}
