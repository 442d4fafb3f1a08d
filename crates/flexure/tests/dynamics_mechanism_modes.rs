//! Vibration modes of mechanisms (`flexure::dynamics::mechanism::modes`)
//! about their loaded equilibrium, against linear beam theory: a massless
//! flexure carrying a rigid body (tip compliance), a flexure with
//! distributed mass (βL = 1.87510 and the exact shooting reference), a
//! column whose frequency falls to zero at the buckling load, and the
//! parallelogram stage (k = 2·12EI/L³, softened by 1 − P/P_cr).

use flexure::dynamics::mechanism::{MechanismSystem, modes};
use flexure::mechanism::buckling::buckle;
use flexure::mechanism::file::from_toml;
use flexure::mechanism::statics::Settings;
use flexure::mechanism::{JointKind, Mechanism};
use flexure::reference::vibration::frequencies;
use nalgebra::{Matrix2, SymmetricEigen};

/// A cantilever along x from the ground, `keys` added to the flexure, and a tip body.
fn cantilever(keys: &str, body: &str, extra: &str) -> Mechanism {
    let text = format!(
        "[[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.5\n{keys}\n\
         [[body]]\nname = \"tip\"\n{body}\n{extra}"
    );
    from_toml(&text).unwrap()
}

/// Massless flexure, point mass at the tip: ω² = 3EI/(mL³), the tip's
/// lateral stiffness (exact in the model from order 2: a tip force gives
/// linear curvature). Tolerance 1e-9: the eigensolver and the statics'
/// rounding. With rotary inertia I and the mass at the tip, the 2×2 problem
/// det(C⁻¹ − ω² diag(m, I)) = 0 from the tip compliance
/// C = [[L³/3EI, L²/2EI], [L²/2EI, L/EI]] gives both frequencies.
#[test]
fn massless_flexure_carrying_a_body() {
    let (l, ei, mass, inertia): (f64, f64, f64, f64) = (0.5, 2.0, 0.1, 4e-3);
    let m = cantilever("ei = 2.0\norder = 3", "mass = 0.1", "");
    let w = modes(&m, &Settings::default(), 5).unwrap();
    assert_eq!((w.omega.len(), w.quasi_static), (1, 2));
    let exact = (3.0 * ei / (mass * l * l * l)).sqrt();
    assert!((w.omega[0] - exact).abs() < 1e-9 * exact, "{} vs {exact}", w.omega[0]);

    let m = cantilever("ei = 2.0\norder = 4", "mass = 0.1\ninertia = 4e-3", "");
    let w = modes(&m, &Settings::default(), 5).unwrap();
    let c = Matrix2::new(l.powi(3) / (3.0 * ei), l * l / (2.0 * ei), l * l / (2.0 * ei), l / ei);
    let k = c.try_inverse().unwrap();
    // diag(m, I)^{-1/2} K diag(m, I)^{-1/2}: symmetric, eigenvalues ω².
    let s = Matrix2::new(1.0 / mass.sqrt(), 0.0, 0.0, 1.0 / inertia.sqrt());
    let mut exact: Vec<f64> = SymmetricEigen::new(s * k * s).eigenvalues.iter().map(|x| x.sqrt()).collect();
    exact.sort_by(f64::total_cmp);
    assert_eq!(w.omega.len(), 2);
    for (a, b) in w.omega.iter().zip(&exact) {
        assert!((a - b).abs() < 1e-9 * b, "{a} vs {b}");
    }
    // Shapes are M-normalized and M-orthogonal (unloaded: about the rest shape).
    let mass_matrix = MechanismSystem::new(&m).unwrap().mass_matrix(&m.rest()).unwrap();
    let gram = w.shapes.transpose() * mass_matrix * &w.shapes;
    assert!((gram - Matrix2::identity()).amax() < 1e-10, "VᵀMV is not the identity");
}

/// A uniform flexure with distributed mass (given by `ei`: no rotary
/// inertia), free tip: βL = (μω²L⁴/EI)^¼ converges to 1.87510406871196 (the
/// cantilever's first root of cos βL cosh βL = −1) as the order grows, the
/// error falling by at least 100 per two orders (measured: 4.5e-3, 1.4e-6,
/// 8.8e-11 at orders 2, 4, 6); at order 8 within 1e-10. At order 10 the
/// second and third roots, 4.69409 and 7.85476, within 1e-6, and the
/// frequencies match the exact shooting reference (`reference::vibration`)
/// to 1e-6.
#[test]
fn distributed_mass_converges_to_the_cantilever_roots() {
    let (l, ei, mu) = (0.5_f64, 2.0, 0.3);
    let scaled = |w: f64| (mu * w * w * l.powi(4) / ei).powf(0.25);
    let mut errors = Vec::new();
    for order in [2, 4, 6] {
        let m = cantilever(&format!("ei = 2.0\nmass_per_length = 0.3\norder = {order}"), "", "");
        let w = modes(&m, &Settings::default(), 3).unwrap();
        assert_eq!(w.quasi_static, 0);
        errors.push((scaled(w.omega[0]) - 1.875_104_068_711_96).abs());
    }
    for pair in errors.windows(2) {
        assert!(pair[1] < pair[0] / 100.0, "βL errors {errors:?}");
    }
    let m = cantilever("ei = 2.0\nmass_per_length = 0.3\norder = 8", "", "");
    let error = (scaled(modes(&m, &Settings::default(), 1).unwrap().omega[0]) - 1.875_104_068_711_96).abs();
    assert!(error < 1e-10, "βL error at order 8: {error:e}");
    let m = cantilever("ei = 2.0\nmass_per_length = 0.3\norder = 10", "", "");
    let JointKind::Flexure(f) = &m.joints[0].kind else { unreachable!() };
    let reference = frequencies(f, None, 0.0, 3, &Default::default()).unwrap();
    assert!((reference.scaled[0] - 1.875_104_068_711_96).abs() < 1e-9);
    let w = modes(&m, &Settings::default(), 3).unwrap();
    for (k, exact) in [1.875_104_068_711_96, 4.694_091_132_974_2, 7.854_757_438_237_6].iter().enumerate() {
        assert!((scaled(w.omega[k]) - exact).abs() < 1e-6 * exact, "mode {k}: {}", scaled(w.omega[k]));
        assert!((w.omega[k] / reference.omega[k] - 1.0).abs() < 1e-6, "mode {k}");
    }
}

/// A column: a flexure with distributed and rotary inertia (a steel strip)
/// and a tip body, pushed along its axis by P. Against the exact linear beam
/// under compression (`reference::vibration`, shooting): the lowest
/// frequency within 1e-5 at P = 0.5 P_cr. Approaching the model's buckling
/// load (`mechanism::buckling`), ω² falls linearly to zero: extrapolating
/// from 0.99 and 0.995 P_cr lands on P_cr within 1e-3 of it.
#[test]
fn frequency_falls_to_zero_at_the_buckling_load() {
    let keys = "modulus = 2e11\nwidth = 0.01\nthickness = 1e-3\ndensity = 7850.0\norder = 8";
    let body = "mass = 0.05\ninertia = 1e-6";
    let push = |p: f64| format!("[[force]]\nname = \"push\"\nbody = \"tip\"\nat = [0.0, 0.0]\nforce = [{}, 0.0]\n", -p);
    let m1 = cantilever(keys, body, &push(1.0));
    let critical = buckle(&m1, &Settings::default()).unwrap().load_factor;
    let JointKind::Flexure(f) = &m1.joints[0].kind else { unreachable!() };
    let tip = flexure::inertia::RigidInertia::new(0.05, 1e-6, [0.0, 0.0]).unwrap();
    let omega2 = |p: f64| {
        let m = cantilever(keys, body, &push(p));
        modes(&m, &Settings::default(), 1).unwrap().omega[0].powi(2)
    };
    let half = 0.5 * critical;
    let exact = frequencies(f, Some(&tip), half, 1, &Default::default()).unwrap().omega[0];
    let model = omega2(half).sqrt();
    assert!((model / exact - 1.0).abs() < 1e-5, "ω at P_cr/2: {model} vs exact {exact}");
    let (a, b) = (0.99 * critical, 0.995 * critical);
    let (wa, wb) = (omega2(a), omega2(b));
    assert!(wb < wa && wb < 0.01 * omega2(0.0), "ω² = {wa}, {wb}");
    let zero = b - wb * (b - a) / (wb - wa);
    assert!((zero / critical - 1.0).abs() < 1e-3, "ω² extrapolates to zero at {zero}, P_cr = {critical}");
    // Past the buckling load the straight column is unstable: an error, not a frequency.
    let m = cantilever(keys, body, &push(1.01 * critical));
    assert!(modes(&m, &Settings::default(), 1).is_err());
}

/// The parallelogram stage (`examples/parallelogram.toml`: two massless
/// flexures, L = 0.05, EI = 2e-3, welded to a stage) carrying 0.1 kg:
/// unloaded, the sway ω = √(k/m) with k = 2·12EI/L³ = 384 N/m (a guided
/// beam's curvature is linear, exact in the model); under the file's 1 N
/// axial push, k falls by 1 − P/P_cr = 1 − 1/16 (the model's buckling load,
/// as `tests/mechanism.rs` checks). The stage's inertia adds nothing: it
/// does not turn to first order. Tolerance 1e-8.
#[test]
fn parallelogram_sway_mode() {
    let file =
        std::fs::read_to_string(format!("{}/../../examples/parallelogram.toml", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let stage = "[[body]]\nname = \"stage\"\nmass = 0.1\ninertia = 2e-5\ncom = [0.0, -0.02]\n";
    let (l, ei, mass) = (0.05_f64, 2.0e-3, 0.1);
    let k = 24.0 * ei / l.powi(3);
    let unloaded =
        from_toml(&format!("{}\n{stage}", file.replace("force = [0.0, -1.0]", "force = [0.0, 0.0]"))).unwrap();
    let w = modes(&unloaded, &Settings::default(), 4).unwrap();
    assert_eq!(w.omega.len(), 1, "{:?}", w.omega);
    assert!((w.omega[0] - (k / mass).sqrt()).abs() < 1e-8 * w.omega[0], "{}", w.omega[0]);
    // The shape moves both flexures alike (coordinates 0..3 and 3..6).
    let v = w.shapes.column(0);
    assert!((v[0] - v[3]).abs() < 1e-8 * v.amax());
    let loaded = from_toml(&format!("{file}\n{stage}")).unwrap();
    let w = modes(&loaded, &Settings::default(), 4).unwrap();
    let softened = (k * (1.0 - 1.0 / 16.0) / mass).sqrt();
    assert!((w.omega[0] - softened).abs() < 1e-8 * softened, "{} vs {softened}", w.omega[0]);
    assert_eq!(w.limit, None, "1 N of 16 N: the loading path stays stable");
}

/// Pushed at 20 N, past the stage's 16 N buckling load (above), the loading
/// path snaps through to a stable state: `Modes::limit` says where, at
/// 16/20 of the load, and agrees with the equilibrium's own report
/// (`statics::solve`). Tolerance 1e-3: the continuation places a limit to
/// within its step (the CLI's and Python's tests use the same bound).
#[test]
fn snap_through_is_reported() {
    let file =
        std::fs::read_to_string(format!("{}/../../examples/parallelogram.toml", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let text = file.replace("force = [0.0, -1.0]", "force = [0.0, -20.0]");
    let m = from_toml(&format!("{text}\n[[body]]\nname = \"stage\"\nmass = 0.1\n")).unwrap();
    let w = modes(&m, &Settings::default(), 1).unwrap();
    let limit = w.limit.expect("the path snaps through");
    assert!((limit - 0.8).abs() < 1e-3, "16 N of 20 N: {limit}");
    let solved = flexure::mechanism::statics::solve(&m, &Settings::default()).unwrap().limit;
    assert_eq!(solved, Some(limit));
}

/// Errors: no mass at all names `mass`; `count` = 0 names `count`.
#[test]
fn modes_errors() {
    let m = cantilever("ei = 2.0", "", "");
    let e = modes(&m, &Settings::default(), 3).unwrap_err().to_string();
    assert!(e.contains("mass"), "{e}");
    let m = cantilever("ei = 2.0", "mass = 1.0", "");
    let e = modes(&m, &Settings::default(), 0).unwrap_err().to_string();
    assert!(e.contains("count"), "{e}");
}
