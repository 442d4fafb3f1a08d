//! The spatial flexure's deformed shape (`spatial::shape`): against the
//! helix's closed form, its own tip pose, a refined integration and the
//! exact rod's shape under the Bathe–Bolourchi load.

use flexure::reference::rod::{self, Rod};
use flexure::section::{Profile, Shear, SpatialSection};
use flexure::spatial::{
    SpatialFlexure, SpatialLoad, SpatialPoint, SpatialStatics, deflect, pose_root_tip, shape, shape_at,
};
use flexure::{Error, Level};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

fn rotation(p: &SpatialPoint) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| p.rotation[i][j])
}

fn hat(w: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -w.z, w.y, w.z, 0.0, -w.x, -w.y, w.x, 0.0)
}

/// A flexure of length `l` with a unit section, orders 3.
fn flexure(l: f64) -> SpatialFlexure {
    SpatialFlexure::new(l, SpatialSection::uniform(0.7, 1.3, 1.0).unwrap(), [3, 3, 3]).unwrap()
}

/// Reference: the helix of constant curvature u = (τ, 0, κ), whose frame is
/// exp(s ξ̂) in closed form: R = I + sin θ ŵ + (1 − cos θ) ŵ² (Rodrigues,
/// θ = |u|s, w = u/|u|) and p = s(w·e₁)w + sin θ/|u| (e₁ − (w·e₁)w) +
/// (1 − cos θ)/|u| w × e₁. Every one of 41 sections, at orders 3 with the
/// higher coefficients zero, within 1e-12 of L (Magnus is exact for
/// constant curvature: the rest is rounding over 1.5 turns).
#[test]
fn helix_matches_its_closed_form() {
    let (l, tau, kappa) = (2.0, 1.3, 2.1);
    let f = flexure(l);
    let mut alpha = [0.0; 9];
    alpha[0] = tau * l;
    alpha[6] = kappa * l;
    let points = shape(&f, &alpha, 41).unwrap();
    assert_eq!(points.len(), 41);
    let u = Vector3::new(tau, 0.0, kappa);
    let (rate, w) = (u.norm(), u.normalize());
    let e1 = Vector3::x();
    let mut worst: f64 = 0.0;
    for (i, p) in points.iter().enumerate() {
        assert!((p.s - l * i as f64 / 40.0).abs() < 1e-15, "s {}", p.s);
        let theta = rate * p.s;
        let r = Matrix3::identity() + hat(&w) * theta.sin() + hat(&w) * hat(&w) * (1.0 - theta.cos());
        let along = w * w.dot(&e1);
        let x = along * p.s + (e1 - along) * (theta.sin() / rate) + w.cross(&e1) * ((1.0 - theta.cos()) / rate);
        let off = (Vector3::from(p.position) - x).norm().max((rotation(p) - r).abs().max() * l);
        worst = worst.max(off);
        let c = p.curvature;
        assert!((c[0] - tau).abs() < 1e-14 && c[1].abs() < 1e-14 && (c[2] - kappa).abs() < 1e-14, "{c:?}");
        assert!(p.stress.is_none());
    }
    assert!(worst < 1e-12 * l, "{worst}");
}

/// Coefficients of a shape whose curvature changes direction along it
/// (every component about a radian, tip turns of 0.7–1.1 rad).
const BENT: [f64; 9] = [0.9, -0.4, 0.3, -0.8, 0.5, 0.2, 1.1, 0.6, -0.5];

/// Reference: the tip pose (`pose_root_tip`, the same Magnus steps): the
/// last section equals it within 1e-12 of L (measured 1.0e-16 L), at
/// 8 subintervals and at 5, whatever the number of sections; the first is
/// the root frame exactly.
#[test]
fn last_section_is_the_tip() {
    let l = 0.3;
    for f in [flexure(l), flexure(l).with_subintervals(5).unwrap()] {
        let (r, p) = pose_root_tip(&f, &BENT);
        for k in [2, 3, 9, 17, 100] {
            let points = shape(&f, &BENT, k).unwrap();
            let (first, last) = (&points[0], &points[k - 1]);
            assert_eq!(last.s, l);
            let off = (Vector3::from(last.position) - p).norm();
            let turn = (rotation(last) - r).abs().max();
            assert!(off < 1e-12 * l && turn < 1e-12, "{k} points: {off}, {turn}");
            assert!(first.position == [0.0; 3] && rotation(first) == Matrix3::identity());
        }
    }
}

/// Reference: the same flexure integrated over 512 subintervals, converged
/// to rounding (the tip's error falls as M⁻⁶). Sections between the
/// flexure's own subinterval ends are as accurate as the tip: the largest
/// error over 61 sections is at most twice the tip's (measured: the error
/// grows along the length to 3.0e-8 L at the tip, 1.8e-8 in rotation).
#[test]
fn sections_are_as_accurate_as_the_tip() {
    let l = 0.3;
    let f = flexure(l);
    let fine = flexure(l).with_subintervals(512).unwrap();
    let (coarse, exact) = (shape(&f, &BENT, 61).unwrap(), shape(&fine, &BENT, 61).unwrap());
    let error = |a: &SpatialPoint, b: &SpatialPoint| {
        (Vector3::from(a.position) - Vector3::from(b.position)).norm().max((rotation(a) - rotation(b)).abs().max() * l)
    };
    let tip = error(&coarse[60], &exact[60]);
    assert!(tip > 1e-12 * l && tip < 1e-7 * l, "tip {tip}");
    let worst = coarse.iter().zip(&exact).map(|(a, b)| error(a, b)).fold(0.0, f64::max);
    assert!(worst <= 2.0 * tip, "worst {worst} against the tip's {tip}");
}

/// Reference: the exact Kirchhoff rod (`reference::rod`, whose tip meets
/// the published Bathe–Bolourchi tip to 0.02: tests/rod.rs) under the
/// Bathe–Bolourchi load (45° bend of R = 100, unit square, E = 1e7, ν = 0,
/// P = 600 along z), compared at the rod's own arc lengths (its
/// integrator's steps, 1325 of them). The model's sections converge to the
/// rod's with order, each step at least 4 times closer; at orders 6 they are
/// within 5e-6 of L in position and 5e-5 in rotation (the largest entry of
/// R − R_rod; measured 1.2e-4 L
/// and 6.5e-4 at orders 4, 2.5e-6 L and 2.6e-5 at 6, 4.7e-7 L and 6.2e-6
/// at 8, worst near mid-span). The interior is not as close as the tip,
/// 6.6e-8 L at orders 6 (tests/spatial_validation.rs): the tip of the
/// Ritz solution converges faster than its sections do.
#[test]
fn bathe_bolourchi_shape_converges_to_the_rod() {
    let (r, e) = (100.0, 1e7);
    let l = PI * r / 4.0;
    let section =
        SpatialSection::rectangle(e, Shear::Poisson(0.0), Profile::Constant(1.0), Profile::Constant(1.0)).unwrap();
    let load = SpatialLoad { moment: [0.0; 3], force: [0.0, 0.0, 600.0] };
    let bend = 1.0 / r;
    let rod = Rod::new(l, section.clone()).unwrap().with_rest(move |_| [0.0, 0.0, bend]).unwrap();
    let w = load;
    let exact = rod::deflect(&rod, &w, &Default::default()).unwrap();
    let at: Vec<f64> = exact.shape.iter().map(|frame| frame.s.min(l)).collect();
    assert!(at.len() >= 100 && at[at.len() - 1] == l, "{} frames", at.len());
    let mut last = (f64::INFINITY, f64::INFINITY);
    for n in [4, 6, 8] {
        let mut rest = vec![0.0; 3 * n];
        rest[2 * n] = PI / 4.0;
        let f = SpatialFlexure::new(l, section.clone(), [n, n, n]).unwrap().with_rest(&rest).unwrap();
        let mut data = SpatialStatics::new(&f);
        deflect(&f, &load, &mut data, &Default::default()).unwrap();
        let model = shape_at(&f, data.alpha(), &at).unwrap();
        let (mut position, mut turn): (f64, f64) = (0.0, 0.0);
        for (p, frame) in model.iter().zip(&exact.shape) {
            position = position.max((Vector3::from(p.position) - frame.position).norm() / l);
            turn = turn.max((rotation(p) - frame.rotation).abs().max());
        }
        assert!(position < last.0 / 4.0 && turn < last.1 / 4.0, "orders {n}: {position} L, {turn} after {last:?}");
        if n == 6 {
            assert!(position < 5e-6 && turn < 5e-5, "orders 6: {position} L, {turn} rad");
        }
        // A rectangle has a stress at every section.
        assert!(model.iter().all(|p| p.stress.is_some_and(|s| s >= 0.0)));
        last = (position, turn);
    }
}

/// Reference: the planar circle of constant κ_z through `update`'s pose at
/// every section — a flexure cut at s is the first s of the whole one only
/// for constant curvature, where the tip of a flexure of length s with the
/// same κ_z is the section at s, to 1e-13 of L.
#[test]
fn sections_of_a_circle_are_the_tips_of_shorter_circles() {
    let (l, kappa) = (1.5, 2.4);
    let f = SpatialFlexure::new(l, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [1, 1, 1]).unwrap();
    for p in shape(&f, &[0.0, 0.0, kappa * l], 11).unwrap().iter().skip(1) {
        let short = SpatialFlexure::new(p.s, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [1, 1, 1]).unwrap();
        let mut k = flexure::spatial::SpatialKinematics::new(&short);
        flexure::spatial::update(&short, &[0.0, 0.0, kappa * p.s], Level::Pose, &mut k);
        assert!((Vector3::from(p.position) - k.position).norm() < 1e-13 * l, "at {}", p.s);
        assert!((rotation(p) - k.rotation).abs().max() < 1e-13, "at {}", p.s);
    }
}

/// Bad input names its parameter: `points` out of 2..=10000, `alpha` of the
/// wrong length or not finite, `at` outside [0, L] or decreasing.
#[test]
fn bad_input_names_the_parameter() {
    let f = flexure(1.0);
    let name = |r: flexure::Result<Vec<SpatialPoint>>| match r {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("expected an invalid parameter, got {other:?}"),
    };
    for k in [0, 1, 10_001] {
        assert_eq!(name(shape(&f, &[0.0; 9], k)), "points");
    }
    assert_eq!(shape(&f, &[0.0; 9], 10_000).unwrap().len(), 10_000);
    assert_eq!(name(shape(&f, &[0.0; 8], 5)), "alpha");
    let mut nan = [0.0; 9];
    nan[4] = f64::NAN;
    assert_eq!(name(shape(&f, &nan, 5)), "alpha");
    for at in [vec![], vec![-0.1], vec![1.0 + 1e-9], vec![0.5, 0.2], vec![f64::NAN]] {
        assert_eq!(name(shape_at(&f, &[0.0; 9], &at)), "at", "{at:?}");
    }
}
