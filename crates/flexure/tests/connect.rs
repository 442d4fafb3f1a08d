//! Minimum-energy shapes (Sec. II-E) and the energy error η (Eq. 16) against the exact elastica.

use flexure::connect::{ConnectData, Connection, connect, connect_with};
use flexure::reference::elastica;
use flexure::{Error, Flexure, Kinematics, Level, Pose, energy_gradient, update_kinematics};
use std::f64::consts::FRAC_PI_2;

/// The stand-in for the paper's Fig. 4 pose (the paper does not print it).
const FIG4: Pose = Pose { phi: FRAC_PI_2, x: 0.55, y: 0.65 };

fn exact(c: &Connection, target: &Pose) -> elastica::ElasticaConnection {
    // The model's multipliers are the tip load; move the moment to the root.
    let m0 = c.load.moment + target.x * c.load.fy - target.y * c.load.fx;
    elastica::connect(&Flexure::new(1.0, 1.0, 3).unwrap(), target, [m0, c.load.fx, c.load.fy], &Default::default())
        .unwrap()
}

fn eta(f: &Flexure) -> f64 {
    let c = connect(f, &FIG4).unwrap();
    let anchor = connect(&Flexure::new(1.0, 1.0, 3).unwrap(), &FIG4).unwrap();
    c.energy / exact(&anchor, &FIG4).energy - 1.0
}

/// A circular arc's tip is reached by the arc itself: U* = EI a²/2L and η = 0
/// for the model at any order and for any chain (both contain the arc).
#[test]
fn an_arc_has_no_energy_error() {
    let a = 1.2_f64;
    let target = Pose { phi: a, x: a.sin() / a, y: (1.0 - a.cos()) / a };
    for f in [
        Flexure::new(1.0, 1.0, 3).unwrap(),
        Flexure::new(1.0, 1.0, 6).unwrap(),
        Flexure::segments(1.0, 1.0, 7).unwrap(),
    ] {
        let c = connect(&f, &target).unwrap();
        assert!((c.energy - a * a / 2.0).abs() < 1e-10, "{:?}", f.basis());
        // The holding load is the pure moment EI·a/L.
        assert!((c.load.moment - a).abs() < 1e-8 && c.load.fx.abs() < 1e-8 && c.load.fy.abs() < 1e-8);
    }
    let e = exact(&connect(&Flexure::new(1.0, 1.0, 3).unwrap(), &target).unwrap(), &target);
    assert!((e.energy - a * a / 2.0).abs() < 1e-10);
}

/// Eq. 16: η ≥ 0 since the elastica is the least-energy curve; the Legendre
/// spaces are nested, so η falls with N; N = 8 is within 1e-7.
#[test]
fn eta_falls_with_order() {
    let mut previous = f64::INFINITY;
    for n in 3..=8 {
        let e = eta(&Flexure::new(1.0, 1.0, n).unwrap());
        assert!(e >= -1e-12, "N={n}: η = {e} below zero");
        assert!(e < previous, "N={n}: not decreasing");
        previous = e;
    }
    assert!(previous < 1e-7);
}

/// Constant-curvature chains: η > 0, and the error of a piecewise-constant
/// curvature is O(h²), so doubling K divides η by 4 (±5 %).
#[test]
fn eta_of_chains_is_second_order() {
    let (e11, e22, e44) = (
        eta(&Flexure::segments(1.0, 1.0, 11).unwrap()),
        eta(&Flexure::segments(1.0, 1.0, 22).unwrap()),
        eta(&Flexure::segments(1.0, 1.0, 44).unwrap()),
    );
    assert!(e44 > 0.0 && e22 > e44 && e11 > e22);
    assert!((e11 / e22 / 4.0 - 1.0).abs() < 0.05, "{}", e11 / e22);
    assert!((e22 / e44 / 4.0 - 1.0).abs() < 0.05, "{}", e22 / e44);
}

/// The multipliers are the tip load that holds the shape: Eq. 22's
/// generalized force ∇U − 𝒥ᵀ(M, Fx, Fy), rebuilt here from the kinematics,
/// vanishes there. (Deflecting from rest under that load need not return the
/// same shape: a large load has several equilibria.)
#[test]
fn multipliers_hold_the_shape() {
    // Unit and other EI/L (the start's multipliers solved outright), and a
    // rest curvature (where they are not: the start iterates from zero).
    for f in [
        Flexure::new(1.0, 1.0, 5).unwrap(),
        Flexure::segments(1.0, 1.0, 12).unwrap(),
        Flexure::new(1.0, 2.5, 4).unwrap(),
        Flexure::segments(1.0, 0.7, 8).unwrap(),
        Flexure::new(1.0, 1.0, 4).unwrap().with_rest(&[0.4, -0.2, 0.1, 0.0]).unwrap(),
    ] {
        let c = connect(&f, &FIG4).unwrap();
        let mut k = Kinematics::new(&f);
        update_kinematics(&f, &c.alpha, &mut k, Level::Jacobian);
        let mut g = vec![0.0; f.order()];
        energy_gradient(&f, &c.alpha, &mut g);
        for i in 0..f.order() {
            let j = k.jacobian_root_tip.column(i);
            let tau = g[i] - (c.load.moment * j[0] + c.load.fx * j[1] + c.load.fy * j[2]);
            assert!(tau.abs() < 1e-9 * f.ei(), "{:?} τ[{i}] = {tau}", f.basis());
        }
        let p = k.pose_root_tip;
        assert!((p.phi - FIG4.phi).abs() < 1e-12 && (p.x - FIG4.x).abs() < 1e-12 && (p.y - FIG4.y).abs() < 1e-12);
    }
}

#[test]
fn unreachable_pose_is_an_error() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    let err = connect(&f, &Pose { phi: 0.0, x: 0.9, y: 0.5 }).unwrap_err();
    assert!(matches!(err, Error::InvalidParameter { name: "pose", .. }), "{err}");
    assert!(
        connect(&Flexure::new(1.0, 1.0, 2).unwrap(), &FIG4).is_err(),
        "two coordinates cannot meet three constraints"
    );
}

/// Reused buffers keep no state between solves: a sequence of poses (with an
/// unreachable one and a failed solve's leftovers between them) gives, to
/// the bit, what fresh buffers give for each pose alone.
#[test]
fn reused_buffers_give_the_fresh_answer() {
    let poses = [
        FIG4,
        Pose { phi: 1.2, x: 1.2f64.sin() / 1.2, y: (1.0 - 1.2f64.cos()) / 1.2 },
        Pose { phi: -0.7, x: 0.6, y: -0.3 },
        Pose { phi: 0.0, x: 0.9, y: 0.5 },
        FIG4,
    ];
    for f in [Flexure::new(1.0, 1.0, 4).unwrap(), Flexure::segments(1.0, 1.0, 9).unwrap()] {
        let mut data = ConnectData::new(&f);
        for (i, p) in poses.iter().enumerate() {
            let found = connect_with(&f, p, &mut data);
            assert_eq!(found.is_ok(), i != 3, "{:?} {p:?}: {found:?}", f.basis());
            assert_eq!(found, connect(&f, p), "{:?} {p:?}", f.basis());
        }
    }
}

/// Buffers made for another flexure are refused with an error naming them.
#[test]
fn buffers_of_another_flexure_are_an_error() {
    let mut data = ConnectData::new(&Flexure::new(1.0, 1.0, 4).unwrap());
    for f in [Flexure::new(1.0, 1.0, 3).unwrap(), Flexure::segments(1.0, 1.0, 4).unwrap()] {
        let err = connect_with(&f, &FIG4, &mut data).unwrap_err();
        assert!(matches!(err, Error::InvalidParameter { name: "data", .. }), "{err}");
    }
}
