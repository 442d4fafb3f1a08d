//! Error estimates against true errors: closed forms and the exact elastica.

use flexure::estimate::{Accuracy, deflect_auto, deflect_error, tendon_error};
use flexure::reference::elastica;
use flexure::tendon::{TendonData, TendonOffsets, pull};
use flexure::{Flexure, Pose, StaticsData, TipLoad, deflect};

fn unit(order: usize) -> Flexure {
    Flexure::new(1.0, 1.0, order).unwrap()
}

/// (estimate, true error) of the tip position for one load, the truth from the exact elastica.
fn estimate_and_truth(f: &Flexure, load: &TipLoad) -> (f64, f64, bool) {
    let mut data = StaticsData::new(f);
    deflect(f, load, &mut data, &Default::default()).unwrap();
    let e = deflect_error(f, load, data.alpha(), &Accuracy::default()).unwrap();
    let exact = elastica::deflect(f, load, &Default::default()).unwrap().pose;
    let p = data.pose_root_tip();
    (e.position, (p.x - exact.x).hypot(p.y - exact.y), e.flagged)
}

/// Pure moments: the exact shape is a circle, $\phi = Ms/EI$, so the true
/// error is the model's quadrature error alone (the basis is exact). The
/// reference integrates to rounding, so the estimate equals the truth to
/// 1e-6 relative (the reference's Newton tolerance).
#[test]
fn pure_moment_quadrature_error_is_caught() {
    let f = unit(3);
    for m in [2.0, 8.0, 14.0, 20.0, -23.0] {
        let mut data = StaticsData::new(&f);
        let load = TipLoad { moment: m, fx: 0.0, fy: 0.0 };
        deflect(&f, &load, &mut data, &Default::default()).unwrap();
        let e = deflect_error(&f, &load, data.alpha(), &Accuracy::default()).unwrap();
        let p = data.pose_root_tip();
        let truth = (p.x - m.sin() / m).hypot(p.y - (1.0 - m.cos()) / m);
        assert!((e.position - truth).abs() <= 1e-6 * truth.max(1e-9), "M = {m}: estimate {} truth {truth}", e.position);
        assert_eq!(e.flagged, truth > 0.01, "M = {m}: flagged iff the true error exceeds 1 % of L");
    }
}

/// Transverse and oblique forces up to and past 90°: basis truncation is
/// the error here. The estimate is within a factor 3 of the true error
/// (the acceptance bound of the Trust issue) wherever that exceeds 1e-3 L.
#[test]
fn truncation_error_is_caught() {
    let f = unit(3);
    for (p, theta) in [(3.0, 0.0), (10.0, 0.0), (30.0, 0.0), (6.0, 2.0), (12.0, 2.8), (20.0, -1.0)] {
        let (estimate, truth, flagged) = estimate_and_truth(&f, &TipLoad::polar(0.0, p, theta));
        if truth > 1e-3 {
            let ratio = estimate / truth;
            assert!((1.0 / 3.0..=3.0).contains(&ratio), "P = {p}, θ = {theta}: estimate {estimate} truth {truth}");
        }
        assert!(truth <= 0.03 || flagged, "P = {p}: a true error of {truth} L must be flagged");
    }
}

/// Order 6 meets the 1 % target where order 3 does not, and `deflect_auto`
/// finds an order whose true error meets it.
#[test]
fn auto_order_meets_the_target_in_truth() {
    let load = TipLoad::polar(0.0, 30.0, 0.3);
    let (f, alpha, e) = deflect_auto(&unit(3), &load, &Accuracy::default()).unwrap();
    assert!(f.order() > 3 && !e.flagged);
    let exact = elastica::deflect(&f, &load, &Default::default()).unwrap().pose;
    let p = flexure::pose_root_tip(&f, &alpha);
    assert!((p.x - exact.x).hypot(p.y - exact.y) < 0.01 && (p.phi - exact.phi).abs() < 1f64.to_radians());
}

/// The tendon joint's estimate against the same joint at order 12 with 40
/// points (converged to 1e-9 L, far below the order-3 error measured).
#[test]
fn tendon_estimate_matches_a_converged_model() {
    let ei = flexure::bending_stiffness(200e9, 0.01, 0.0002, Some(0.29)).unwrap();
    let t = TendonOffsets { root_offset: 0.005, tip_offset: 0.005 };
    let f = Flexure::new(0.015, ei, 3).unwrap();
    let fine = Flexure::new(0.015, ei, 12).unwrap().with_quadrature(40).unwrap();
    for tension in [10.0, 28.0, 45.0] {
        let (mut d, mut dfine) = (TendonData::new(&f), TendonData::new(&fine));
        pull(&f, &t, tension, &mut d).unwrap();
        pull(&fine, &t, tension, &mut dfine).unwrap();
        let (a, b): (Pose, Pose) =
            (flexure::pose_root_tip(&f, d.alpha()), flexure::pose_root_tip(&fine, dfine.alpha()));
        let truth = (a.x - b.x).hypot(a.y - b.y);
        let e = tendon_error(&f, &t, tension, d.alpha(), &Accuracy::default()).unwrap();
        assert!((e.position / truth - 1.0).abs() < 0.5, "tension {tension}: estimate {} truth {truth}", e.position);
    }
}

/// A bad accuracy target is named.
#[test]
fn bad_accuracy_is_named() {
    let f = unit(3);
    let bad = Accuracy { position: 0.0, ..Default::default() };
    let err = deflect_error(&f, &TipLoad::default(), &[0.0; 3], &bad).unwrap_err();
    assert!(err.to_string().contains("accuracy"), "{err}");
}

/// The validation sweep (`examples/validation.rs`, which writes
/// VALIDATION.md), on 300 of its seeded cases: against the exact elastica,
/// the estimate is within 3× of the true error in at least 90 % of the
/// cases whose true error exceeds 1e-3 L (the Trust issue's bound), and no
/// answer truly outside 1 % L or 1° goes unflagged.
#[path = "../examples/validation.rs"]
#[allow(dead_code)]
mod validation;

#[test]
fn validation_sweep_is_honest() {
    let sweep = validation::sweep(300);
    let (compared, left_out) = sweep.counts();
    assert!(compared >= 290, "{compared} compared, {left_out} left out");
    let (large, honest) = sweep.honesty();
    assert!(large >= 100 && honest as f64 >= 0.9 * large as f64, "{honest} of {large} within 3x");
    assert_eq!(sweep.missed(&Accuracy::default()), 0, "answers outside the target left unflagged");
}

/// The peak-curvature part of the estimate against the exact elastica: under
/// a tip force (and no moment) the bending moment F × (r_tip − r(s)) is
/// largest at the root, so the exact peak curvature is |M₀|/EI, M₀ the exact
/// root moment. For forces of 1 to 8 EI/L² in three directions the estimate
/// of the order-3 model's peak error is within 3× of the true error (the
/// honesty bound VALIDATION.md uses for positions), and the flag agrees with
/// the 1 % target wherever the truth is clearly on one side of it.
#[test]
fn peak_curvature_estimate_is_honest() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    for p in [1.0, 2.0, 4.0, 8.0] {
        for theta in [20f64.to_radians(), 60f64.to_radians(), 100f64.to_radians()] {
            let load = TipLoad::polar(0.0, p, theta);
            let mut data = StaticsData::new(&f);
            deflect(&f, &load, &mut data, &Default::default()).unwrap();
            let exact = flexure::reference::elastica::deflect(&f, &load, &Default::default()).unwrap();
            let exact_peak = exact.root_moment.abs() / f.ei();
            let model_peak = flexure::stress::peak_curvature(&f, data.alpha()).value;
            let truth = (model_peak - exact_peak).abs();
            let e = deflect_error(&f, &load, data.alpha(), &Accuracy::default()).unwrap();
            let ratio = e.curvature / truth;
            assert!(
                (1.0 / 3.0..=3.0).contains(&ratio),
                "P = {p}, θ = {theta}: estimate {} vs true {truth}",
                e.curvature
            );
            let relative = truth / exact_peak;
            if relative > 0.015 {
                assert!(e.flagged, "P = {p}, θ = {theta}: peak off by {relative}");
            }
            if relative < 0.005 && e.position < 0.005 && e.angle < 0.5f64.to_radians() {
                assert!(!e.flagged, "P = {p}, θ = {theta}: peak off by only {relative}");
            }
        }
    }
}

/// The 69-case taper sweep (issue 21): a pure tip moment $M$ on a flexure
/// of $L = 1$ whose $EI$ falls linearly from 1 at the root to $r$ at the tip,
/// for 23 end ratios $r = 10^{-6k/22}$ ($k = 0\ldots22$, 1 down to $10^{-6}$)
/// and $M \in \lbrace 0.1, 0.3, 1\rbrace$ N·m. Reference: the closed form
/// $\phi = M\int_0^L ds/EI = ML\ln r/(r - 1)$ (the moment is the same in
/// every section). Every answer of `--order auto` ([`deflect_auto`]) must
/// either meet the angle target (1°, the default) against it, or be
/// refused as missing it even at order 64; and order 64 itself, whose
/// estimate is against the exact elastica, must be flagged wherever it is
/// more than 1° off (never a false 0).
#[test]
#[ignore = "long: the 69-case taper sweep, each case up to order 64; run by .ci/run (cargo test -- --ignored)"]
fn taper_sweep_is_met_or_flagged() {
    use flexure::section::{Profile, Section};
    let target = Accuracy::default();
    let (mut met, mut refused, mut cap_flagged, mut cap_off) = (0, 0, 0, 0);
    for k in 0..23 {
        let r = 10f64.powf(-6.0 * k as f64 / 22.0);
        let section = Section::given(Profile::Linear { root: 1.0, tip: r }).unwrap();
        let f = Flexure::new(1.0, 1.0, 3).unwrap().with_section(section).unwrap();
        for m in [0.1, 0.3, 1.0] {
            let exact = if k == 0 { m } else { m * r.ln() / (r - 1.0) };
            let load = TipLoad { moment: m, fx: 0.0, fy: 0.0 };
            let case = format!("EI 1 → {r:.3e}, M = {m}: φ = {exact:.6}");
            match deflect_auto(&f, &load, &target) {
                Ok((used, alpha, e)) => {
                    let phi = flexure::pose_root_tip(&used, &alpha).phi;
                    assert!(!e.flagged, "{case}");
                    assert!((phi - exact).abs() <= target.angle, "{case}: order {} gives {phi:.6}", used.order());
                    met += 1;
                }
                Err(flexure::Error::InvalidParameter { name: "order", .. }) => refused += 1,
                Err(e) => panic!("{case}: {e}"),
            }
            // Order 64, estimated against the exact elastica: flagged wherever it misses.
            let cap = Flexure::new(1.0, 1.0, 64).unwrap().with_section(f.section().clone()).unwrap();
            let mut data = StaticsData::new(&cap);
            deflect(&cap, &load, &mut data, &Default::default()).unwrap();
            let e = deflect_error(&cap, &load, data.alpha(), &target).unwrap();
            let miss = (data.pose_root_tip().phi - exact).abs();
            assert!(e.exact, "{case}: order 64 is estimated against the elastica");
            assert!(miss <= target.angle || e.flagged, "{case}: order 64 is {miss:.3e} rad off, unflagged");
            // The elastica is the exact answer: its estimate is the true angle error.
            assert!((e.angle - miss).abs() <= 1e-6 * exact, "{case}: estimate {:.6e}, truth {miss:.6e}", e.angle);
            cap_flagged += usize::from(e.flagged);
            cap_off += usize::from(miss > target.angle);
        }
    }
    eprintln!(
        "taper sweep: {met} met by --order auto, {refused} refused at order 64; \
         order 64 more than 1° off in {cap_off}, flagged in {cap_flagged}"
    );
    assert_eq!(met + refused, 69);
}

/// The estimates' fast peak of the curvature change (scan, then Newton on
/// $p^{\prime}$) against [`flexure::stress::peak_curvature`] (scan, then
/// golden section), over seeded random coordinates of orders 1 to 64 with a
/// rest shape: equal to 1e-12 of the peak (both find the same stationary
/// point; golden section places it to about $\sqrt{\epsilon}$, which moves
/// the value at a smooth maximum by rounding only).
#[test]
fn fast_peak_curvature_agrees_with_the_scan() {
    use flexure::stress::{peak_curvature, peak_curvature_legendre};
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for order in [1, 2, 3, 4, 6, 9, 12, 24, 48, 64] {
        for _ in 0..20 {
            let rest: Vec<f64> = (0..order).map(|_| 0.1 * next()).collect();
            // Coefficients falling with the order, as an answer's do.
            let alpha: Vec<f64> = (0..order).map(|i| 3.0 * next() / (1.0 + i as f64)).collect();
            let f = Flexure::new(0.7, 1.0, order).unwrap().with_rest(&rest).unwrap();
            let (slow, fast) = (peak_curvature(&f, &alpha).value, peak_curvature_legendre(&f, &alpha));
            assert!((fast - slow).abs() <= 1e-12 * slow, "order {order}: {fast} vs {slow}");
        }
    }
}

/// The estimate's reference follows the loading path (issue 39 item 3).
/// At order 6, under $M = -6.2589$, $F = (-15.501, 5.0180)$ (unit length
/// and stiffness), `deflect` reaches the exact elastica's branch
/// ($\varphi = -4.971$), and its estimate is the true error against the
/// exact elastica within 1 % (both 4.7e-5 L), unflagged. An answer on
/// another branch, as `deflect` used to give (Newton from its coefficients,
/// rounded: $\varphi = 0.744$, stable), is not estimated against itself
/// (the reference corrected from it lands on its branch, 2e-5): the
/// estimate is the distance to the reference's path end, within 1 % of the
/// true error (0.99 L), and flagged.
#[test]
fn an_answer_off_the_loading_path_is_flagged() {
    let load = TipLoad { moment: -6.258888285291928, fx: -15.501008696246453, fy: 5.017976184775733 };
    let f = unit(6);
    let exact = elastica::deflect(&f, &load, &Default::default()).unwrap().pose;
    assert!((exact.phi + 4.971).abs() < 1e-3, "{exact:?}");
    let (estimate, truth, flagged) = estimate_and_truth(&f, &load);
    assert!(truth < 1e-3, "the answer is on the exact path's branch: {truth}");
    assert!(!flagged && (estimate / truth - 1.0).abs() < 0.01, "estimate {estimate} against {truth}");
    let mut data = StaticsData::new(&f);
    let start = [0.744, -6.750, 0.066, -0.319, -0.256, 0.255];
    let eq = flexure::statics::correct(&f, &load, &start, &mut data, &Default::default()).unwrap();
    let p = data.pose_root_tip();
    assert!(eq.stable && (p.phi - 0.744).abs() < 1e-3, "{eq:?}, {p:?}");
    let e = deflect_error(&f, &load, data.alpha(), &Accuracy::default()).unwrap();
    let truth = (p.x - exact.x).hypot(p.y - exact.y);
    assert!(truth > 0.9, "the answer is on another branch: {truth}");
    assert!(e.flagged && (e.position / truth - 1.0).abs() < 0.01, "estimate {} against {truth}", e.position);
}
