//! Stages on n parallel flexure legs welded to one rigid stage, n = 2..8,
//! against closed forms. Every leg is fixed at the ground and guided at the
//! stage (it cannot turn: the other legs' inextensibility holds the stage's
//! angle), so the stage acts like n fixed–guided beams in parallel. With
//! three or more legs the closure equations are redundant (at rest the
//! along-leg rows are all proportional to the stage's rotation).

use flexure::mechanism::Mechanism;
use flexure::mechanism::buckling::buckle;
use flexure::mechanism::file::from_toml;
use flexure::mechanism::statics::{Settings, assemble_unloaded, compliance, solve};
use flexure::{Error, Flexure, TipConstraint, buckling_load};

const LENGTH: f64 = 0.05;
const EI: f64 = 2.0e-3;
const PITCH: f64 = 0.04;

/// `n` vertical legs of `order`, `PITCH` apart; the stage is the first
/// leg's tip frame (x along the legs), the others' tips are welded to it;
/// `force` (ground frame) acts at the centre of the legs' tips.
fn stage(n: usize, order: usize, force: [f64; 2]) -> Mechanism {
    let mut text = String::new();
    for k in 0..n {
        let child = if k == 0 { "stage".to_string() } else { format!("tip{k}") };
        text += &format!(
            "[[joint]]\nname = \"leg{k}\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"{child}\"\n\
             origin = [{}, 0.0, 1.5707963267948966]\nlength = {LENGTH}\nei = {EI}\norder = {order}\n",
            PITCH * k as f64
        );
        if k > 0 {
            text += &format!("[[weld]]\na = \"stage\"\na_origin = [0.0, {}, 0.0]\nb = \"tip{k}\"\n", -PITCH * k as f64);
        }
    }
    text += &format!(
        "[[force]]\nname = \"push\"\nbody = \"stage\"\nat = [0.0, {}]\nforce = [{}, {}]\n",
        -0.5 * PITCH * (n - 1) as f64,
        force[0],
        force[1]
    );
    from_toml(&text).unwrap()
}

fn centre(n: usize) -> [f64; 2] {
    [0.0, -0.5 * PITCH * (n - 1) as f64]
}

/// The model's guided buckling load of one leg (Table I: 10 EI/L² at N = 3).
fn guided(order: usize) -> f64 {
    buckling_load(&Flexure::new(LENGTH, EI, order).unwrap(), TipConstraint::Guided).unwrap().critical_load
}

/// Small-load lateral stiffness n·12EI/L³: a fixed–guided leg's curvature is
/// linear in s, so N = 3 holds it exactly (Eq. 36); the tolerance is rounding
/// through the null space and the Cholesky solve.
#[test]
fn lateral_stiffness_is_n_guided_legs() {
    for n in 2..=8 {
        let m = stage(n, 3, [0.0, -1.0]);
        let unloaded = assemble_unloaded(&m, &Settings::default()).unwrap();
        let c = compliance(&m, &unloaded, m.body("stage").unwrap(), centre(n).into()).unwrap();
        let expected = n as f64 * 12.0 * EI / LENGTH.powi(3);
        // World x is across the legs.
        assert!((1.0 / c[(1, 1)] / expected - 1.0).abs() < 1e-10, "n = {n}: {} vs {expected}", 1.0 / c[(1, 1)]);
    }
}

/// Axial compression buckles the stage at n times one guided leg's load:
/// the model's own (`buckling_load`, Guided) at N = 3 and N = 12, to
/// rounding; at N = 12 also Euler's π²EI/L² per leg, within the 1e-6 that
/// Rayleigh–Ritz reaches there (`tests/buckling.rs`: N = 12 is within 1e-6 of Euler).
#[test]
fn buckles_at_n_guided_legs() {
    let euler = std::f64::consts::PI.powi(2) * EI / (LENGTH * LENGTH);
    for n in 2..=8 {
        for order in [3, 12] {
            let push = 1.0;
            let b = buckle(&stage(n, order, [0.0, -push]), &Settings::default()).unwrap();
            let critical = b.load_factor * push;
            let expected = n as f64 * guided(order);
            assert!((critical / expected - 1.0).abs() < 1e-9, "n = {n}, N = {order}: {critical} vs {expected}");
            if order == 12 {
                assert!((critical / (n as f64 * euler) - 1.0).abs() < 1e-6, "n = {n}: {critical} vs Euler");
            }
        }
    }
}

/// Under a lateral load F plus an axial push P = P_cr/2, the loaded path
/// stays stable and the stage sways F/(k(1 − P/P_cr)): for N = 3 the
/// geometric stiffness of a guided leg is exactly k·P/P_cr at small sway,
/// and a sway of 1e-3·L changes it by about (1e-3)² (geometric
/// nonlinearity; 1.3e-6 here), hence the 1e-5 tolerance.
#[test]
fn lateral_and_axial_load() {
    for n in 2..=8 {
        let (k, critical) = (n as f64 * 12.0 * EI / LENGTH.powi(3), n as f64 * guided(3));
        let soft = k * 0.5;
        let lateral = soft * 1e-3 * LENGTH;
        let m = stage(n, 3, [lateral, -0.5 * critical]);
        let s = solve(&m, &Settings::default()).unwrap();
        assert!(s.stable && s.limit.is_none(), "n = {n}");
        let f = flexure::mechanism::statics::body_frames(&m, &s);
        let sway = f.bodies[m.body("stage").unwrap()].x;
        assert!((sway / (lateral / soft) - 1.0).abs() < 1e-5, "n = {n}: sway {sway} vs {}", lateral / soft);
    }
}

/// Pushed 1.25 times past the critical load, the straight path loses
/// stability at 1/1.25 = 80 % of the push, for any number of legs: the
/// stability test sees the legs share the push equally although, with
/// three or more, the closures leave the share statically indeterminate.
/// Tolerance: the √tolerance stability margin (≈1e-6) plus the bisection's
/// 1e-6. Past the limit the stage may snap to a stable buckled shape (an
/// answer, reported with its limit) or find none (an error at the limit);
/// either way the limit is what is checked.
#[test]
fn axial_overload_loses_stability_at_the_critical_load() {
    for n in [2, 3, 5, 8] {
        let critical = n as f64 * guided(3);
        match solve(&stage(n, 3, [0.0, -1.25 * critical]), &Settings::default()) {
            Err(Error::Unstable { load_fraction, .. }) => {
                assert!((load_fraction - 0.8).abs() < 1e-5, "n = {n}: {load_fraction}")
            }
            Ok(s) => assert!((s.limit.unwrap() - 0.8).abs() < 1e-5, "n = {n}: snapped through from {:?}", s.limit),
            Err(e) => panic!("n = {n}: {e}"),
        }
    }
}
