//! The spatial flexure's default subintervals, error estimate and
//! `--order auto` (`flexure::estimate::spatial`) against the exact
//! Kirchhoff rod (`reference::rod`) on the Bathe–Bolourchi 45° bend (R =
//! 100, unit square, E = 1e7, ν = 0, P = 600 along z; L = 78.54), set up as
//! in `spatial_validation.rs`.

use flexure::estimate::Accuracy;
use flexure::estimate::spatial::{deflect_auto, deflect_error, reference};
use flexure::reference::rod::{self, Rod};
use flexure::section::{Profile, Shear, SpatialSection};
use flexure::spatial::{SpatialFlexure, SpatialLoad, SpatialStatics, deflect, pose_root_tip};
use nalgebra::Vector3;
use std::f64::consts::PI;

const LOAD: SpatialLoad = SpatialLoad { moment: [0.0; 3], force: [0.0, 0.0, 600.0] };

fn length() -> f64 {
    PI * 100.0 / 4.0
}

fn section() -> SpatialSection {
    SpatialSection::rectangle(1e7, Shear::Poisson(0.0), Profile::Constant(1.0), Profile::Constant(1.0)).unwrap()
}

/// The bend at orders `n` per component, default subintervals.
fn bend(n: usize) -> SpatialFlexure {
    let mut rest = vec![0.0; 3 * n];
    rest[2 * n] = PI / 4.0;
    SpatialFlexure::new(length(), section(), [n; 3]).unwrap().with_rest(&rest).unwrap()
}

/// The exact rod's tip (integrator tolerance 1e-12: its tip to about 1e-12 L).
fn exact() -> Vector3<f64> {
    let l = length();
    let r = Rod::new(l, section()).unwrap().with_rest(move |_| [0.0, 0.0, PI / 4.0 / l]).unwrap();
    let w = SpatialLoad { moment: [0.0; 3], force: LOAD.force };
    rod::deflect(&r, &w, &rod::ShootingSettings::with_tolerance(1e-12)).unwrap().position
}

/// The model's equilibrium and its tip error against `exact`, over L.
fn solve(f: &SpatialFlexure, exact: &Vector3<f64>) -> (Vec<f64>, f64) {
    let mut data = SpatialStatics::new(f);
    deflect(f, &LOAD, &mut data, &Default::default()).unwrap();
    let (_, p) = pose_root_tip(f, data.alpha());
    (data.alpha().to_vec(), (p - exact).norm() / f.length())
}

/// Reference: the exact rod. At 8 subintervals orders 10 and 12 are worse
/// than orders 8 (measured 2.6e-7 and 1.1e-5 of L against 2.7e-8): the
/// discretization, not the order, limits them. With their defaults (36 and
/// 44 subintervals) they reach 1e-11 of L (measured 3.0e-12 and 8.9e-13),
/// and orders 3 keep 8.
#[test]
fn default_subintervals_follow_the_order() {
    let tip = exact();
    assert_eq!(bend(3).subintervals(), 8);
    for (n, m) in [(10, 36), (12, 44)] {
        let f = bend(n);
        assert_eq!(f.subintervals(), m);
        let (_, resolved) = solve(&f, &tip);
        assert!(resolved < 1e-11, "orders {n} at {m}: {resolved:e} L");
        let (_, coarse) = solve(&f.with_subintervals(8).unwrap(), &tip);
        assert!(coarse > 1e-7, "orders {n} at 8 must be discretization-limited: {coarse:e} L");
    }
}

/// Reference: the exact rod. The estimate of an answer limited by its
/// discretization (orders 10 at 8 subintervals, true error 2.6e-7 L) sees
/// that error, because the reference is resolved (orders 20 at their own
/// default 95 subintervals, more than twice 8): within 1 % of the true
/// error (measured 2.59e-7 both; the reference's own tip error is 1.6e-13 L).
#[test]
fn the_estimate_includes_the_discretization() {
    let tip = exact();
    let f = bend(10).with_subintervals(8).unwrap();
    let (alpha, truth) = solve(&f, &tip);
    let r = reference(&f, &alpha).unwrap();
    assert_eq!((r.orders(), r.subintervals()), ([20; 3], 95));
    let e = deflect_error(&f, &LOAD, &alpha, &Accuracy::default()).unwrap();
    let estimate = e.position / f.length();
    assert!((estimate / truth - 1.0).abs() < 0.01, "estimate {estimate:e} L, true {truth:e} L");
}

/// Reference: the exact rod. At 1e-3 of L and 1e-3 rad (the curvature's
/// peak not targeted), `--order auto` from orders 3 answers orders 3 at 2
/// subintervals (a quarter of the default's cost): true tip error 2.0e-4 L
/// (estimate the same), while 1 subinterval misses (2.6e-3 L). At 1e-6 it
/// answers orders 6 at 8 (true 8.1e-8 L). Each answer's true error is
/// within the accuracy.
#[test]
fn auto_picks_the_fewest_subintervals_that_meet_the_accuracy() {
    let tip = exact();
    for (accuracy, orders, m) in [(1e-3, 3, 2), (1e-6, 6, 8)] {
        let target = Accuracy { position: accuracy, angle: accuracy, stress: 1.0, ..Default::default() };
        let (f, alpha, e) = deflect_auto(&bend(3), &LOAD, &target).unwrap();
        assert_eq!((f.orders(), f.subintervals()), ([orders; 3], m), "accuracy {accuracy:e}");
        let (_, p) = pose_root_tip(&f, &alpha);
        let truth = (p - tip).norm() / f.length();
        assert!(!e.flagged && truth < accuracy, "accuracy {accuracy:e}: true {truth:e} L");
        let fewer = f.with_subintervals(m / 2).unwrap();
        let (alpha, _) = solve(&fewer, &tip);
        assert!(deflect_error(&fewer, &LOAD, &alpha, &target).unwrap().flagged, "accuracy {accuracy:e} at {}", m / 2);
    }
}

/// Reference: the exact rod. Targeting the curvature's peak as well (1e-3
/// of L, rad and of the peak) takes orders 6 at 4 subintervals (true tip
/// error 1.2e-6 L; the peak change, at the root, estimated 3.1e-4 off, and
/// 3.1e-4 from the rod's root moment over the stiffnesses: within 1e-3 and
/// within 20 % of its estimate).
#[test]
fn auto_with_the_curvature_target() {
    let target = Accuracy { position: 1e-3, angle: 1e-3, stress: 1e-3, ..Default::default() };
    let (f, alpha, e) = deflect_auto(&bend(3), &LOAD, &target).unwrap();
    assert_eq!((f.orders(), f.subintervals()), ([6; 3], 4));
    let (_, p) = pose_root_tip(&f, &alpha);
    let truth = (p - exact()).norm() / f.length();
    assert!(!e.flagged && e.peak < 1e-3 && truth < 1e-3, "true {truth:e} L, peak {:e}", e.peak);
    let l = length();
    let r = Rod::new(l, section()).unwrap().with_rest(move |_| [0.0, 0.0, PI / 4.0 / l]).unwrap();
    let w = SpatialLoad { moment: [0.0; 3], force: LOAD.force };
    let m = rod::deflect(&r, &w, &rod::ShootingSettings::with_tolerance(1e-12)).unwrap().root_moment;
    let k = section().stiffness(0.0);
    let rod_root = Vector3::new(m.x / k[0], m.y / k[1], m.z / k[2]).norm();
    let change: Vec<f64> = alpha.iter().zip(f.rest()).map(|(a, k)| a - k).collect();
    let root = Vector3::from(f.curvature(&change, 0.0)).norm();
    let off = (root / rod_root - 1.0).abs();
    assert!(off < 1e-3 && (off / e.peak - 1.0).abs() < 0.2, "root curvature {off:e} off, estimated {:e}", e.peak);
}
