//! The exact elastica's loading path, integrated loosely
//! (`ShootingSettings::path_tolerance`, 1e-6 by default) and refined at its end,
//! against the same path integrated at the full tolerance (`path_tolerance`
//! 0), in the same run; and the load family of the `reference/elastica_*`
//! benches, whose tip angles the exact solver itself checks.

use flexure::reference::elastica::{self, ShootingSettings};
use flexure::{Error, Flexure, TipLoad};

/// The benches' family (`crates/flexure-bench/benches/speed/reference.rs`):
/// tip moment σ EI/L with axial compression σ EI/L² on L = EI = 1, and the
/// σ that turns the exact tip by 45°, 90°, 180° and 270°.
const FAMILY: [(f64, f64); 4] =
    [(45.0, 0.625533351650362), (90.0, 1.1040855403497616), (180.0, 2.4266552501655885), (270.0, 5.073997874961178)];

fn family(sigma: f64) -> TipLoad {
    TipLoad { moment: sigma, fx: -sigma, fy: 0.0 }
}

/// The benches' constants turn the exact tip by their angles to 1e-6 rad
/// (the tip angle moves by 0.7 to 1.7 rad per unit σ, and σ is given to 16
/// digits), on a stable path without a limit point. A secant search on σ
/// with the solver itself finds them again to 1e-9 (its own convergence).
#[test]
fn bench_loads_turn_the_tip_by_their_angles() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let tip = |sigma: f64| elastica::deflect(&f, &family(sigma), &Default::default()).unwrap();
    for (degrees, sigma) in FAMILY {
        let target = degrees.to_radians();
        let s = tip(sigma);
        assert!((s.pose.phi - target).abs() < 1e-6, "{degrees}°: φ = {}", s.pose.phi.to_degrees());
        assert!(s.stable && s.limit.is_none(), "{degrees}°: {s:?}");
        // Secant from σ ± 10 %.
        let (mut a, mut b) = (0.9 * sigma, 1.1 * sigma);
        let (mut fa, mut fb) = (tip(a).pose.phi - target, tip(b).pose.phi - target);
        for _ in 0..30 {
            if fb.abs() < 1e-13 {
                break;
            }
            let c = b - fb * (b - a) / (fb - fa);
            (a, fa) = (b, fb);
            b = c;
            fb = tip(b).pose.phi - target;
        }
        assert!((b - sigma).abs() < 1e-9 * sigma, "{degrees}°: σ = {b} by secant vs {sigma}");
    }
}

fn assert_same(loose: &elastica::ElasticaSolution, full: &elastica::ElasticaSolution, what: &str) {
    let (a, b) = (loose.pose, full.pose);
    let d = (a.phi - b.phi).abs().max((a.x - b.x).abs()).max((a.y - b.y).abs());
    assert!(d < 1e-10, "{what}: loose path {a:?} vs full {b:?}");
    assert_eq!(loose.stable, full.stable, "{what}: stability");
}

/// Loose and full paths end on the same equilibrium to 1e-10 (both refine
/// it to the same integrator and Newton tolerances, 1e-12; 1e-12 seen), with
/// the same stability verdict, over: the benches' family; tip forces in
/// four directions from 0.3 to 10⁴ EI/L² (compression, transverse,
/// tension); a moment with a force on a beam with rest curvature; and a
/// column 1e-6 off axis just past Euler's load, where the path must follow
/// the side force's branch.
#[test]
fn loose_path_ends_where_the_full_path_does() {
    let full = ShootingSettings { path_tolerance: 0.0, ..Default::default() };
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let mut cases: Vec<(Flexure, TipLoad)> = FAMILY.iter().map(|&(_, s)| (f.clone(), family(s))).collect();
    for delta in [0.01, std::f64::consts::FRAC_PI_2, 2.0, 3.0_f64] {
        for p in [0.3, 4.0, 300.0, 1e4] {
            cases.push((f.clone(), TipLoad { moment: 0.0, fx: -p * delta.cos(), fy: p * delta.sin() }));
        }
    }
    let curved = Flexure::new(1.3, 0.8, 3).unwrap().with_rest(&[0.4, -0.2, 0.1]).unwrap();
    cases.push((curved, TipLoad { moment: 0.7, fx: -9.0, fy: 4.0 }));
    cases.push((f.clone(), TipLoad { moment: 0.0, fx: -2.5463, fy: 2.5463e-6 }));
    for (flexure, load) in &cases {
        let what = format!("{load:?}");
        let loose = elastica::deflect(flexure, load, &Default::default()).unwrap();
        let reference = elastica::deflect(flexure, load, &full).unwrap();
        assert_same(&loose, &reference, &what);
        assert_eq!(loose.limit, None, "{what}");
        assert_eq!(reference.limit, None, "{what}");
    }
}

/// Where the path loses stability both find the same limit: the
/// snap-through of `elastica.rs` (a fold, its load fraction interpolated
/// between steps: to 1e-4 of the load, the accuracy of that Hermite
/// estimate) and the perfect column 1.25 times past Euler's load (a
/// bifurcation, located by halving the step: to 1e-5, as the closed-form
/// test asks).
#[test]
fn loose_path_reports_the_same_limits() {
    let full = ShootingSettings { path_tolerance: 0.0, ..Default::default() };
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let snap = TipLoad { moment: -5.155527614759166, fx: 0.0, fy: 7.2595493570994885 };
    let euler = std::f64::consts::PI.powi(2) / 4.0;
    let column = TipLoad { moment: 0.0, fx: -1.25 * euler, fy: 0.0 };
    for (load, tolerance) in [(snap, 1e-4), (column, 1e-5)] {
        let what = format!("{load:?}");
        let loose = elastica::deflect(&f, &load, &Default::default()).unwrap();
        let reference = elastica::deflect(&f, &load, &full).unwrap();
        assert_same(&loose, &reference, &what);
        let (a, b) = (loose.limit.expect("a limit"), reference.limit.expect("a limit"));
        assert!((a - b).abs() < tolerance, "{what}: limit {a} vs {b}");
    }
}

/// A path tolerance that is not a number from 0 to 1e-4 is refused by name.
#[test]
fn bad_path_tolerance_is_refused() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    for bad in [f64::NAN, -1e-6, 1e-2] {
        let settings = ShootingSettings { path_tolerance: bad, ..Default::default() };
        let r = elastica::deflect(&f, &TipLoad { moment: 1.0, fx: 0.0, fy: 0.0 }, &settings);
        assert!(matches!(r, Err(Error::InvalidParameter { name: "path_tolerance", .. })), "{bad}: {r:?}");
    }
}
