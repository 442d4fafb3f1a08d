//! Dynamics: one second of the finger example's motion after its tendon is
//! ramped in, and the finger's vibration modes; one evaluation of the
//! equations of motion of Simo and Vu-Quoc's right-angle cantilever
//! (`cantilever`: two spatial flexures of order 4 with their own mass, 24
//! coordinates), against the former evaluation.
//!
//! The finger (`examples/finger.toml`) is given steel flexures (E = 200 GPa,
//! ν = 0.29, 0.2 mm thick, density 7850 kg/m³; widths 10 mm and 6.87 mm keep
//! the example's EI = 1.4558e-3 and 1.0e-3 N·m²) with light material damping
//! β = 1e-5 s (D = βK: a damping ratio βω/2 of 3.4e-4 in the first mode, 68
//! rad/s, the order of steel's loss factor), and 5 g links (slender rods:
//! the proximal 30 mm, the distal 25 mm to the fingertip). The flexor tendon
//! rises linearly from 0 to the example's 6 N over the first 0.1 s, the tip
//! force staying on; the motion starts at rest from the equilibrium under
//! the loads at t = 0 and is integrated for 1 s at tolerance 1e-6 (relative
//! and absolute), sampled every 10 ms.
//!
//! The strip release (issue 37, items 3 and 6): `scripts/strip_release.toml`,
//! a 50 × 10 × 0.5 mm steel strip held by a 60 N (or 6 N) tip force and
//! released, 0.05 s sampled every 0.5 ms, at the order and tolerance that
//! reach 1e-3 L against the reference of `scripts/mujoco_peer.py` (which
//! times MuJoCo's hinge chains beside it; BENCHMARKS.md). The run alone,
//! without the error estimate `simulate` adds.
//!
//! The right-angle cantilever in motion (issue 37, item 2):
//! `examples/right_angle_cantilever.toml` as it is (order 4, Simo and
//! Vu-Quoc's rotary inertia), 30 s from rest sampled every 0.05 s at
//! tolerance 1e-4 (`right_angle_cantilever_30s`): faster than real time
//! when under 30 s. The run alone, as the strip's.

use criterion::Criterion;
use flexure::dynamics::integrate::{MotionSettings, Trajectory, integrate};
use flexure::dynamics::mechanism::modes;
use flexure::dynamics::schedule::ScheduledSystem;
use flexure::dynamics::simulation::{Start, initial_state};
use flexure::dynamics::system::System;
use flexure::dynamics::{MechanismSystem, mechanism::Dynamics};
use flexure::mechanism::file::from_toml;
use flexure::mechanism::file::spatial_from_toml;
use flexure::mechanism::statics;
use flexure::mechanism::{JointKind, Mechanism};
use flexure::space::Spatial;
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;

/// The finger with steel flexures and 5 g links, its tendon at the
/// example's 6 N for statics, and for the motion ramped from 0 to 6 N over
/// the first 0.1 s by a `[[schedule]]`, then held.
fn finger() -> Mechanism {
    let path = format!("{}/../../examples/finger.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).unwrap();
    let steel = |width: f64| {
        format!("modulus = 200e9\nwidth = {width}\nthickness = 2e-4\npoisson = 0.29\ndensity = 7850.0\ndamping = 1e-5")
    };
    let edits = [("ei = 1.4558e-3", steel(0.01)), ("ei = 1.0e-3", steel(0.01 * 1.0e-3 / 1.4558e-3))];
    let mut text = text;
    for (from, to) in edits {
        assert_eq!(text.matches(from).count(), 1, "examples/finger.toml no longer has {from:?}");
        text = text.replace(from, &to);
    }
    assert_eq!(text.matches("tension = 6.0").count(), 1, "examples/finger.toml no longer pulls its tendon at 6 N");
    let rod = |mass: f64, length: f64| mass * length * length / 12.0;
    text += &format!(
        "\n[[body]]\nname = \"proximal\"\nmass = 0.005\ninertia = {:?}\ncom = [0.015, 0.0]\n\
         \n[[body]]\nname = \"distal\"\nmass = 0.005\ninertia = {:?}\ncom = [0.0125, 0.0]\n\
         \n[[schedule]]\nload = \"tendon.flexor.tension\"\npoints = [[0.0, 0.0], [0.1, 6.0]]\n",
        rod(0.005, 0.03),
        rod(0.005, 0.025)
    );
    let m = from_toml(&text).unwrap();
    // The edits took: EI as in the example.
    for (joint, ei) in m.joints.iter().zip([1.4558e-3, 1.0e-3]) {
        let JointKind::Flexure(f) = &joint.kind else { panic!("{}: not a flexure", joint.name) };
        assert!((f.ei_at(0.5 * f.length()) - ei).abs() < 1e-7, "{}: EI changed", joint.name);
    }
    m
}

/// One second of the ramped finger's motion from `start` (at rest).
fn finger_1s(m: &Mechanism, start: &[f64]) -> Trajectory {
    let settings = MotionSettings { duration: 1.0, every: 0.01, tolerance: 1e-6, absolute: 1e-6, ..Default::default() };
    let mut system = ScheduledSystem::new(m).unwrap();
    let run = integrate(&mut system, start, &vec![0.0; start.len()], &settings).unwrap();
    assert!(run.time.len() == 101 && run.time[100] == 1.0, "the run did not reach 1 s");
    assert!(run.coordinates.iter().chain(&run.energy).all(|x| x.is_finite()), "a sample is not finite");
    run
}

/// The strip of `scripts/strip_release.toml` held at `force` (N), its flexure at `order`.
fn strip(force: f64, order: usize) -> Mechanism {
    let path = format!("{}/../../scripts/strip_release.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).unwrap();
    assert_eq!(text.matches("60.0").count(), 3, "scripts/strip_release.toml no longer holds 60 N");
    assert_eq!(text.matches("order = 6").count(), 1, "scripts/strip_release.toml no longer has order 6");
    from_toml(&text.replace("60.0", &format!("{force:?}")).replace("order = 6", &format!("order = {order}"))).unwrap()
}

/// The release: 0.05 s from the held equilibrium `start`, sampled every 0.5 ms.
fn strip_release(m: &Mechanism, start: &[f64], tolerance: f64) -> Trajectory {
    let settings = MotionSettings { duration: 0.05, every: 5e-4, tolerance, absolute: tolerance, ..Default::default() };
    let mut system = ScheduledSystem::new(m).unwrap();
    let run = integrate(&mut system, start, &vec![0.0; start.len()], &settings).unwrap();
    assert!(run.time.len() == 101 && run.time[100] == 0.05, "the run did not reach 0.05 s");
    assert!(run.coordinates.iter().all(|x| x.is_finite()), "a sample is not finite");
    run
}

/// The strip releases, at the order and tolerance that reach 1e-3 L (BENCHMARKS.md).
fn strip_releases(c: &mut Criterion) {
    let mut g = c.benchmark_group("dynamics");
    g.sample_size(10);
    for (name, force, order, tolerance) in
        [("strip_release_60n", 60.0, STRIP_60N.0, STRIP_60N.1), ("strip_release_6n", 6.0, STRIP_6N.0, STRIP_6N.1)]
    {
        let m = strip(force, order);
        let (start, _) = initial_state(&m, &statics::Settings::default(), Start::Equilibrium).unwrap();
        // Held: the tip is off the axis; released: it swings back past it.
        let first = strip_release(&m, &start, tolerance);
        assert!(first.q(0)[0] > 0.1, "the strip is not held deflected: {:?}", first.q(0));
        assert!(first.q(50)[0] != first.q(0)[0], "the strip was not released");
        g.bench_function(name, |b| b.iter(|| strip_release(black_box(&m), &start, tolerance)));
    }
    g.finish();
}

/// Order and tolerance of the 60 N release that reach 1e-3 L (`scripts/mujoco_peer.py`).
const STRIP_60N: (usize, f64) = (7, 1e-3);
/// Order and tolerance of the 6 N release that reach 1e-3 L.
const STRIP_6N: (usize, f64) = (6, 1e-3);

/// 30 s of `examples/right_angle_cantilever.toml` from rest at tolerance 1e-4 (its elbow's z at each sample).
fn right_angle_30s(m: &flexure::mechanism::spatial::SpatialMechanism) -> Vec<f64> {
    use flexure::dynamics::simulation::{SimulationSettings, simulate};
    let motion = MotionSettings { duration: 30.0, every: 0.05, tolerance: 1e-4, absolute: 1e-4, ..Default::default() };
    let run = simulate(m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none() && run.time.len() == 601, "the run did not reach 30 s: {:?}", run.stopped);
    run.bodies[0].position.iter().map(|p| p[2]).collect()
}

/// The right-angle cantilever's 30 s (issue 37, item 2).
fn right_angle(c: &mut Criterion) {
    let path = format!("{}/../../examples/right_angle_cantilever.toml", env!("CARGO_MANIFEST_DIR"));
    let m = spatial_from_toml(&std::fs::read_to_string(path).unwrap()).unwrap();
    assert_eq!(m.dof(), 24, "two flexures of order 4");
    // The elbow swings as tests/right_angle_cantilever.rs checks: down to about −4.06 near t = 10.85.
    let elbow = right_angle_30s(&m);
    assert!((elbow[217] + 4.06).abs() < 0.02, "the elbow at t = 10.85: {}", elbow[217]);
    let mut g = c.benchmark_group("dynamics");
    g.sample_size(10);
    g.bench_function("right_angle_cantilever_30s", |b| b.iter(|| right_angle_30s(black_box(&m))));
    g.finish();
}

pub fn run(c: &mut Criterion) {
    right_angle(c);
    strip_releases(c);
    let m = finger();
    // The equilibrium under the loads at t = 0: the tendon slack, the tip force on.
    let (start, _) = initial_state(&m, &statics::Settings::default(), Start::Equilibrium).unwrap();
    let first = finger_1s(&m, &start);
    // The tendon did its work: the finger ends flexed further than it began.
    let last = first.time.len() - 1;
    assert!(first.q(last)[0] > start[0] + 0.1, "the tendon did not flex the finger: {:?}", first.q(last));
    let mut g = c.benchmark_group("dynamics");
    g.sample_size(10);
    g.bench_function("finger_1s", |b| b.iter(|| finger_1s(black_box(&m), &start)));
    g.sample_size(100);
    // Statics take the file's loads: the modes are about the 6 N equilibrium.
    g.bench_function("modes_finger", |b| {
        b.iter(|| {
            let w = modes(black_box(&m), &statics::Settings::default(), 10).unwrap();
            assert!(w.omega.len() == m.dof() && w.omega[0] > 0.0, "modes: {:?}", w.omega);
            w
        })
    });
    g.finish();
    equations(c);
}

/// Simo and Vu-Quoc's right-angle cantilever as issue 37 gives it (Comput.
/// Methods Appl. Mech. Eng. 66, 1988): two legs of 10 at a right angle,
/// clamped at one end, EI = GJ = 1e3 and mass 1 per length (no rotary
/// inertia), struck out of its plane at the elbow by a triangular pulse of
/// 50 over 0 ≤ t ≤ 2; consistent units. Without the published rotary
/// inertia (the evaluation's cost does not depend on it): the benchmark
/// itself, with it, is `examples/right_angle_cantilever.toml` (above).
fn cantilever() -> String {
    let leg = |name: &str, parent: &str, child: &str, turn: f64| {
        format!(
            "[[joint]]\nname = \"{name}\"\nkind = \"flexure\"\nparent = \"{parent}\"\nchild = \"{child}\"\n\
             rpy_deg = [0.0, 0.0, {turn:?}]\nlength = 10.0\ngj = 1e3\nei_y = 1e3\nei = 1e3\nmass_per_length = 1.0\norder = 4\n"
        )
    };
    format!(
        "dimension = 3\n{}{}[[force]]\nname = \"pulse\"\nbody = \"elbow\"\nat = [0.0, 0.0, 0.0]\nforce = [0.0, 0.0, 0.0]\n\
         [[schedule]]\nload = \"force.pulse.fz\"\npoints = [[0.0, 0.0], [1.0, 50.0], [2.0, 0.0]]\n",
        leg("first", "ground", "elbow", 0.0),
        leg("second", "elbow", "tip", 90.0)
    )
}

/// The former evaluation's velocity products, rebuilt from the public
/// mass matrix: central differences of $M$ along each coordinate (step
/// $10^{-5}(1 + \lvert q_i\rvert)$), $h = \sum_i\dot q_iD_i\dot q - \frac12(\dot q^TD_i\dot q)_i$.
fn differenced<D: Dynamics>(sys: &mut MechanismSystem<D>, q: &[f64], v: &[f64]) -> DVector<f64> {
    let n = q.len();
    let qd = DVector::from_column_slice(v);
    let mut h = DVector::zeros(n);
    let mut shifted = q.to_vec();
    for i in 0..n {
        let e = 1e-5 * (1.0 + q[i].abs());
        shifted[i] = q[i] + e;
        let up = sys.mass_matrix(&shifted).unwrap();
        shifted[i] = q[i] - e;
        let down = sys.mass_matrix(&shifted).unwrap();
        shifted[i] = q[i];
        let dv: DVector<f64> = (up - down) / (2.0 * e) * &qd;
        h.axpy(v[i], &dv, 1.0);
        h[i] -= 0.5 * qd.dot(&dv);
    }
    h
}

/// $M(q)$ and $f(q, \dot q)$ of the right-angle cantilever at a bent,
/// twisted and moving state: `spatial_equations_24` as the system
/// evaluates them, `spatial_mass_matrix_24` $M$ alone, and
/// `spatial_equations_24_differences` the former way ($M$, the forces at
/// rest, and $h$ from $2n$ mass matrices).
fn equations(c: &mut Criterion) {
    let m = spatial_from_toml(&cantilever()).unwrap();
    let n = m.dof();
    assert_eq!(n, 24, "two flexures of order 4");
    let q: Vec<f64> = (0..n).map(|i| 0.05 * (i as f64 * 1.3 + 0.2).sin()).collect();
    let v: Vec<f64> = (0..n).map(|i| 0.5 * (1.9 * i as f64 + 0.5).cos()).collect();
    let mut sys = MechanismSystem::<Spatial>::new(&m).unwrap();
    let (mut mass, mut force) = (vec![0.0; n * n], vec![0.0; n]);
    sys.dynamics(&q, &v, 0.0, &mut mass, &mut force).unwrap();
    // The two agree to the differences' truncation.
    let (mut at_rest, mut f0) = (vec![0.0; n * n], vec![0.0; n]);
    sys.dynamics(&q, &vec![0.0; n], 0.0, &mut at_rest, &mut f0).unwrap();
    let h = DVector::from_vec(f0.iter().zip(&force).map(|(a, b)| a - b).collect());
    let former = differenced(&mut sys, &q, &v);
    assert!((&h - &former).amax() < 1e-6 * former.amax(), "h {h} against the differences {former}");
    let mut g = c.benchmark_group("dynamics");
    g.bench_function("spatial_equations_24", |b| {
        b.iter(|| sys.dynamics(black_box(&q), black_box(&v), 0.0, &mut mass, &mut force).unwrap())
    });
    // M alone: the stations' Jacobian-level pass, which h rides along.
    g.bench_function("spatial_mass_matrix_24", |b| b.iter(|| sys.mass_matrix(black_box(&q)).unwrap()));
    g.bench_function("spatial_equations_24_differences", |b| {
        b.iter(|| {
            sys.dynamics(black_box(&q), &vec![0.0; n], 0.0, &mut at_rest, &mut f0).unwrap();
            let h = differenced(&mut sys, black_box(&q), &v);
            (DMatrix::from_column_slice(n, n, &at_rest), h)
        })
    });
    g.finish();
}
