//! A spatial flexure's own mass (`spatial::mass`, its weight in
//! `mechanism::lagrangian` and its inertia in `dynamics::mechanism`):
//! the stations' Jacobians against central differences, the weight's
//! gradient and Hessian against differences of the potential and gradient,
//! Euler–Bernoulli's bending and the rod's torsion frequencies, the
//! cantilever under its own weight (closed form, and the planar mechanism),
//! energy kept in a free swing, and the file's keys.

use flexure::Level;
use flexure::dynamics::integrate::MotionSettings as Motion;
use flexure::dynamics::mechanism::{MechanismSystem, modes};
use flexure::dynamics::simulation::{SimulationSettings, Start, simulate};
use flexure::mechanism::file::{from_toml, spatial_from_toml};
use flexure::mechanism::kinematics::frames;
use flexure::mechanism::lagrangian::{Assembly, assemble_into};
use flexure::mechanism::spatial::{
    RevoluteUnaligned, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism, Spherical,
};
use flexure::report::placements;
use flexure::section::{Profile, Shear, SpatialSection};
use flexure::space::Spatial;
use flexure::spatial::{MassQuadrature, SpatialFlexure, StationKinematics, stations_update};
use nalgebra::{DMatrix, DVector, Isometry3, Matrix3, Point3, Translation3, UnitQuaternion, Vector3};

fn spec(name: &str, kind: SpatialJointKind, parent: usize, child: usize, origin: Isometry3<f64>) -> SpatialJointSpec {
    SpatialJointSpec::new(name, kind, parent, child, origin)
}

fn placed(p: [f64; 3], rpy: [f64; 3]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(p[0], p[1], p[2]),
        UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    )
}

fn flexure_joint(
    name: &str,
    f: SpatialFlexure,
    parent: usize,
    child: usize,
    origin: Isometry3<f64>,
) -> SpatialJointSpec {
    spec(name, SpatialJointKind::Flexure(Box::new(f)), parent, child, origin)
}

/// A tapered rectangle with a density: mass and rotary inertia varying along it.
fn massive(orders: [usize; 3]) -> SpatialFlexure {
    let section = SpatialSection::rectangle(
        2e9,
        Shear::Poisson(0.3),
        Profile::Linear { root: 0.012, tip: 0.008 },
        Profile::Linear { root: 0.004, tip: 0.003 },
    )
    .unwrap()
    .with_density(1200.0)
    .unwrap();
    SpatialFlexure::new(0.1, section, orders).unwrap()
}

fn kinematics(f: &SpatialFlexure, q: &MassQuadrature, alpha: &[f64], level: Level) -> StationKinematics {
    let mut k = StationKinematics::new(f, q);
    stations_update(f, q, alpha, level, &mut k);
    k
}

/// Reference: central differences (step 1e-6) of the stations' positions
/// and rotations from `stations_update` itself at a bent and twisted shape,
/// and (step 1e-5) of the first moment's Jacobian for its Hessian;
/// tolerance 1e-8 of the scale (the differences' truncation is about 1e-11).
#[test]
fn station_jacobians_are_their_poses_central_differences() {
    let f = massive([2, 3, 3]);
    let q = MassQuadrature::new(&f).unwrap();
    let n = f.coordinates();
    let alpha: Vec<f64> = (0..n).map(|i| 0.6 * (1.3 * i as f64 + 0.5).sin()).collect();
    let k = kinematics(&f, &q, &alpha, Level::Hessian);
    let shifted = |i: usize, e: f64| {
        let mut a = alpha.clone();
        a[i] += e;
        kinematics(&f, &q, &a, Level::Hessian)
    };
    let e = 1e-6;
    let l = f.length();
    // The Jacobian level's root-frame pass and the Hessian level's body-frame one, each against the differences.
    let jacobian_level = kinematics(&f, &q, &alpha, Level::Jacobian);
    for i in 0..n {
        let (up, down) = (shifted(i, e), shifted(i, -e));
        for s in 0..q.stations().len() {
            let dp = (up.position[s] - down.position[s]) / (2.0 * e);
            let u = up.rotation[s] * down.rotation[s].transpose();
            let turn = Vector3::new(u[(2, 1)] - u[(1, 2)], u[(0, 2)] - u[(2, 0)], u[(1, 0)] - u[(0, 1)]) / (4.0 * e);
            for (k, level) in [(&k, "Hessian"), (&jacobian_level, "Jacobian")] {
                assert!((dp - k.velocity[s * n + i]).amax() < 1e-8 * l, "∂p station {s}, coordinate {i} ({level})");
                assert!((turn - k.omega[s * n + i]).amax() < 1e-8, "ω station {s}, coordinate {i} ({level})");
            }
        }
    }
    // The first moment S = Σ m_k p_k, its Jacobian Σ m_k ∂p_k, and its Hessian.
    let jacobian = |k: &StationKinematics, a: usize| -> Vector3<f64> {
        q.stations().iter().enumerate().map(|(s, st)| k.velocity[s * n + a] * st.mass).sum()
    };
    let scale = q.mass() * l;
    let e = 1e-5;
    for b in 0..n {
        let (up, down) = (shifted(b, e), shifted(b, -e));
        for a in 0..n {
            let fd = (jacobian(&up, a) - jacobian(&down, a)) / (2.0 * e);
            assert!((fd - k.moment_hessian[a * n + b]).amax() < 1e-8 * scale, "∂²S ({a}, {b})");
        }
    }
    let moment: Vector3<f64> = q.stations().iter().zip(&k.position).map(|(st, p)| p * st.mass).sum();
    assert!((moment - k.moment).amax() < 1e-15 * scale);
    // The mass is ∫ρA ds (A linear in s times linear: a quadratic, which the rule integrates exactly).
    let exact = 1200.0 * l * (0.012 * 0.004 + (0.012 * 0.003 + 0.008 * 0.004) / 2.0 + 0.008 * 0.003) / 3.0;
    assert!((q.mass() - exact).abs() < 1e-14 * exact, "{} against {exact}", q.mass());
}

/// A tree with massive flexures upstream and downstream of a hinge and a
/// ball, and a body, under gravity out of every plane.
fn tree() -> SpatialMechanism {
    let bodies = vec![
        SpatialBody::massless("ground"),
        SpatialBody::massless("a"),
        SpatialBody {
            name: "b".into(),
            mass: 0.02,
            com: Point3::new(0.01, 0.0, 0.0),
            inertia: Matrix3::identity() * 1e-6,
        },
        SpatialBody::massless("c"),
        SpatialBody::massless("d"),
    ];
    let joints = vec![
        flexure_joint("root", massive([2, 2, 3]), 0, 1, placed([0.0, 0.01, 0.0], [0.1, -0.2, 0.3])),
        spec(
            "hinge",
            SpatialJointKind::Revolute(RevoluteUnaligned { axis: Vector3::y_axis(), stiffness: 0.4, rest: 0.0 }),
            1,
            2,
            placed([0.01, 0.0, 0.0], [0.0, 0.3, 0.0]),
        ),
        spec(
            "ball",
            SpatialJointKind::Spherical(Spherical { stiffness: 0.3, rest: [0.0; 3] }),
            2,
            3,
            placed([0.02, 0.0, 0.0], [0.2, 0.0, -0.1]),
        ),
        flexure_joint(
            "tip",
            SpatialFlexure::new(0.05, SpatialSection::uniform(0.03, 0.05, 0.02).unwrap(), [2, 2, 2])
                .unwrap()
                .with_mass_per_length(Profile::Linear { root: 0.3, tip: 0.1 })
                .unwrap(),
            3,
            4,
            placed([0.0, 0.0, 0.01], [0.0, 0.0, 0.4]),
        ),
    ];
    SpatialMechanism::new(bodies, joints, vec![], vec![], vec![], Vector3::new(0.3, -9.81, 1.5)).unwrap()
}

fn configuration(m: &SpatialMechanism) -> Vec<f64> {
    (0..m.dof()).map(|i| 0.3 * (i as f64 * 1.7 + 0.4).sin()).collect()
}

fn assembled(m: &SpatialMechanism, q: &[f64]) -> Assembly<Spatial> {
    let mut a = Assembly::new(m);
    assemble_into(m, &frames(m, q), &[], &m.loads(), true, &mut a).unwrap();
    a
}

fn step(q: &[f64], i: usize, h: f64) -> Vec<f64> {
    let mut p = q.to_vec();
    p[i] += h;
    p
}

/// Reference: central differences of the potential (step 1e-6) for the
/// gradient and of the gradient (step 1e-5) for the Hessian, as
/// `tests/spatial_mechanism_derivatives.rs`; tolerances 1e-7 and 1e-6 of
/// the scale. The weight alone (gravity minus none) is checked too, so the
/// elastic part cannot hide an error in it.
#[test]
fn the_flexures_weight_has_the_gradient_and_hessian_of_its_potential() {
    let m = tree();
    let q = configuration(&m);
    let a = assembled(&m, &q);
    let mut weightless = m.clone();
    weightless.gravity = Vector3::zeros();
    let b = assembled(&weightless, &q);
    // The bodies' weight, m g·c: what is left beside it is the flexures'.
    let f = frames(&m, &q);
    let body = -(f.bodies[2] * m.bodies[2].com).coords.dot(&m.gravity) * m.bodies[2].mass;
    let flexures = a.potential - b.potential - body;
    let (rho, l) = (1200.0, 0.1);
    let mass = rho * l * (0.012 * 0.004 + (0.012 * 0.003 + 0.008 * 0.004) / 2.0 + 0.008 * 0.003) / 3.0 + 0.05 * 0.2;
    assert!(flexures.abs() > 1e-3 * mass * 9.81 * 0.01, "the flexures weigh: {flexures}");
    let h = 1e-6;
    let scale = (&a.gradient - &b.gradient).amax();
    for i in 0..m.dof() {
        let fd = (assembled(&m, &step(&q, i, h)).potential - assembled(&m, &step(&q, i, -h)).potential) / (2.0 * h);
        assert!((a.gradient[i] - fd).abs() < 1e-7 * a.gradient.amax(), "gradient {i}: {} against {fd}", a.gradient[i]);
    }
    let h = 1e-5;
    let weight = &a.hessian - &b.hessian;
    let hscale = weight.amax();
    for i in 0..m.dof() {
        let fd = (assembled(&m, &step(&q, i, h)).gradient - assembled(&m, &step(&q, i, -h)).gradient) / (2.0 * h);
        let fdw = (assembled(&weightless, &step(&q, i, h)).gradient
            - assembled(&weightless, &step(&q, i, -h)).gradient)
            / (2.0 * h);
        for r in 0..m.dof() {
            assert!((a.hessian[(r, i)] - fd[r]).abs() < 1e-6 * a.hessian.amax(), "Hessian ({r}, {i})");
            let w = fd[r] - fdw[r];
            assert!(
                (weight[(r, i)] - w).abs() < 1e-6 * hscale,
                "weight's Hessian ({r}, {i}): {} against {w}",
                weight[(r, i)]
            );
        }
    }
    assert!(scale > 0.0 && (&weight - weight.transpose()).amax() < 1e-12 * hscale);
}

/// Reference: Lagrange's velocity products from central differences of
/// the mass matrix (step 1e-6), as `tests/spatial_dynamics.rs` does for
/// bodies; tolerance 1e-6 of the scale (the system's own are differences
/// of step 1e-5 of the stations' kinetic energy).
#[test]
fn the_stations_velocity_products_are_lagranges_from_their_mass_matrix() {
    let m = tree();
    let q = configuration(&m);
    let v: Vec<f64> = (0..m.dof()).map(|i| 0.7 * (2.1 * i as f64).cos()).collect();
    let mut sys = MechanismSystem::<Spatial>::new(&m).unwrap();
    let mm = sys.mass_matrix(&q).unwrap();
    assert!((&mm - mm.transpose()).amax() < 1e-14 * mm.amax());
    assert!(mm.clone().cholesky().is_some(), "the stations' translation and rotation make M positive definite");
    let h = sys.velocity_product(&q, &v).unwrap();
    let qd = DVector::from_column_slice(&v);
    let e = 1e-6;
    let n = m.dof();
    let mut mdot = DMatrix::zeros(n, n);
    let mut grad = DVector::zeros(n);
    for i in 0..n {
        let (up, down) = (sys.mass_matrix(&step(&q, i, e)).unwrap(), sys.mass_matrix(&step(&q, i, -e)).unwrap());
        mdot += (&up - &down) / (2.0 * e) * v[i];
        grad[i] = qd.dot(&((&up - &down) / (2.0 * e) * &qd));
    }
    let reference = &mdot * &qd - grad * 0.5;
    let scale = reference.amax();
    assert!(scale > 0.0);
    for i in 0..n {
        assert!((h[i] - reference[i]).abs() < 1e-6 * scale, "h[{i}] = {} against {}", h[i], reference[i]);
    }
}

/// Two flexures at a right angle, as Simo and Vu-Quoc's cantilever: the
/// first with a mass per length alone, the second a rectangle with a
/// density (rotary inertia too), an elbow body between them and a tip body.
fn right_angle(orders: [usize; 3]) -> SpatialMechanism {
    let leg = SpatialFlexure::new(1.0, SpatialSection::uniform(2.0, 1.0, 1.5).unwrap(), orders)
        .unwrap()
        .with_mass_per_length(Profile::Constant(1.0))
        .unwrap();
    let section = SpatialSection::rectangle(2e6, Shear::Poisson(0.3), Profile::Constant(0.05), Profile::Constant(0.03))
        .unwrap()
        .with_density(500.0)
        .unwrap();
    let arm = SpatialFlexure::new(0.8, section, orders).unwrap();
    let body = |name: &str, mass: f64, com: [f64; 3], inertia: [f64; 3]| SpatialBody {
        name: name.into(),
        mass,
        com: Point3::from(com),
        inertia: Matrix3::from_diagonal(&Vector3::from(inertia)),
    };
    SpatialMechanism::new(
        vec![
            SpatialBody::massless("ground"),
            body("elbow", 0.1, [0.02, 0.0, 0.01], [1e-3, 2e-3, 1.5e-3]),
            body("tip", 0.3, [0.05, 0.01, 0.0], [1e-3, 2e-3, 3e-3]),
        ],
        vec![
            flexure_joint("leg", leg, 0, 1, placed([0.0; 3], [0.1, 0.2, 0.0])),
            flexure_joint("arm", arm, 1, 2, placed([0.0; 3], [0.0, 0.0, std::f64::consts::FRAC_PI_2])),
        ],
        vec![],
        vec![],
        vec![],
        Vector3::zeros(),
    )
    .unwrap()
}

/// $(4D_{e/2} - D_e)/3$ of the central difference $D_e$ of `f` at 0: Richardson's, error $O(e^4)$.
fn richardson(mut f: impl FnMut(f64) -> DVector<f64>, e: f64) -> DVector<f64> {
    let mut central = |e: f64| (f(e) - f(-e)) / (2.0 * e);
    (central(e / 2.0) * 4.0 - central(e)) / 3.0
}

/// Reference, independent of the recursion: Lagrange's equations of
/// $T = \frac12\dot q^TM(q)\dot q$ from the mass matrix alone,
/// $h = \frac{d}{dt}(M\dot q) - \partial T/\partial q$ at $\ddot q = 0$, the first
/// along the path $q + t\dot q$ and the second along each coordinate, by
/// Richardson's extrapolation of central differences (step 1e-3: truncation
/// about 1e-12 and rounding about 1e-13 of the scale); tolerance 1e-9 of
/// the scale. And the former evaluation, central differences of $M$ along
/// each coordinate (step $10^{-5}(1 + \lvert q_i\rvert)$, truncation about
/// 1e-10); tolerance 1e-7. Orders 2 and 4 on two flexures at a right angle
/// with an elbow and a tip body, in a bent and twisted state.
#[test]
fn velocity_products_are_lagranges_along_the_path_and_the_mass_matrix_differences() {
    for orders in [[2, 2, 2], [4, 4, 4]] {
        let m = right_angle(orders);
        let n = m.dof();
        let q: Vec<f64> = (0..n).map(|i| 0.4 * (i as f64 * 1.3 + 0.2).sin()).collect();
        let v: Vec<f64> = (0..n).map(|i| 0.9 * (1.9 * i as f64 + 0.5).cos()).collect();
        let mut sys = MechanismSystem::<Spatial>::new(&m).unwrap();
        let h = sys.velocity_product(&q, &v).unwrap();
        let qd = DVector::from_column_slice(&v);
        let path = |t: f64| -> Vec<f64> { q.iter().zip(&v).map(|(a, b)| a + t * b).collect() };
        let momentum = richardson(|t| sys.clone().mass_matrix(&path(t)).unwrap() * &qd, 1e-3);
        let gradient = DVector::from_fn(n, |i, _| {
            richardson(
                |t| DVector::from_element(1, 0.5 * qd.dot(&(sys.clone().mass_matrix(&step(&q, i, t)).unwrap() * &qd))),
                1e-3,
            )[0]
        });
        let lagrange = momentum - gradient;
        let mut former = DVector::zeros(n);
        for i in 0..n {
            let e = 1e-5 * (1.0 + q[i].abs());
            let d =
                (sys.mass_matrix(&step(&q, i, e)).unwrap() - sys.mass_matrix(&step(&q, i, -e)).unwrap()) / (2.0 * e);
            let dv = &d * &qd;
            former.axpy(v[i], &dv, 1.0);
            former[i] -= 0.5 * qd.dot(&dv);
        }
        let scale = lagrange.amax();
        let (a, b) = ((&h - &lagrange).amax() / scale, (&h - &former).amax() / scale);
        println!(
            "orders {orders:?}: n = {n}, |h| {scale:.3e}, against Lagrange's {a:.1e}, against the differences {b:.1e}"
        );
        assert!(scale > 0.1, "{scale}");
        assert!(a < 1e-9, "orders {orders:?}: h {h} against Lagrange's {lagrange}");
        assert!(b < 1e-7, "orders {orders:?}: h {h} against the differences {former}");
    }
}

/// Reference: conservation, $T + V$ of the undamped right-angle pair
/// (orders 2) released bent and moving, over a quarter of a second (a
/// whole second, about a period of its first mode, took 10 min under load
/// and drifted 2e-11 of 0.318 J); tolerance 1e-7 of the energy at
/// integrator tolerance 1e-10. A velocity product off Lagrange's would
/// pump or drain it.
#[test]
#[ignore = "long: minutes (the leg's mass per length alone leaves its higher twist nearly without inertia, a stiff motion at 1e-10); run by .ci/run (cargo test -- --ignored)"]
fn the_right_angle_pair_swinging_free_keeps_its_energy() {
    let mut m = right_angle([2, 2, 2]);
    let q: Vec<f64> = (0..m.dof()).map(|i| 0.3 * (i as f64 * 1.3 + 0.2).sin()).collect();
    let v: Vec<f64> = (0..m.dof()).map(|i| 0.5 * (1.9 * i as f64 + 0.5).cos()).collect();
    m.initial = vec![(0, q[..6].to_vec()), (1, q[6..].to_vec())];
    m.initial_velocity = vec![(0, v[..6].to_vec()), (1, v[6..].to_vec())];
    let motion = Motion { duration: 0.25, every: 0.05, tolerance: 1e-10, absolute: 1e-10, ..Default::default() };
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none(), "{:?}", run.stopped);
    let e0 = run.energy[0];
    let worst = run.energy.iter().fold(0.0_f64, |a, e| a.max((e - e0).abs()));
    println!("energy {e0:.6e} J, largest change {worst:.3e} J over {} samples", run.time.len());
    assert!(e0 > 0.1 && worst < 1e-7 * e0, "energy {e0} changed by {worst}");
}

/// A cantilever from the ground along x with a massless tip.
fn cantilever(f: SpatialFlexure, gravity: Vector3<f64>) -> SpatialMechanism {
    SpatialMechanism::new(
        vec![SpatialBody::massless("ground"), SpatialBody::massless("tip")],
        vec![flexure_joint("beam", f, 0, 1, Isometry3::identity())],
        vec![],
        vec![],
        vec![],
        gravity,
    )
    .unwrap()
}

/// Twice the errors measured at orders 2, 3, 4 and 6.
const BENDING_BOUNDS: [f64; 4] = [1e-2, 6e-4, 3.1e-6, 1.9e-10];

/// Euler–Bernoulli's first root of $1 + \cos\lambda\cosh\lambda = 0$.
const LAMBDA_1: f64 = 1.875_104_068_711_961;

/// Reference: Euler–Bernoulli's cantilever, $\omega_1 = \lambda_1^2\sqrt{EI/(\mu L^4)}$,
/// about both axes ($EI_y = 4EI_z$, so $\omega_y = 2\omega_z$), for a mass per
/// length on stiffnesses given directly (no rotary inertia: the
/// Euler–Bernoulli rod exactly). The model is a Ritz approximation, so each
/// frequency is above the rod's and its error falls with the order; the
/// errors measured, both axes alike: 4.8e-3 at orders 2, 3.0e-4 at 3,
/// 1.5e-6 at 4, 9.2e-11 at 6 (each asserted within a factor 2).
#[test]
fn a_cantilevers_first_bending_frequencies_are_euler_bernoullis() {
    let (l, mu, ei_z, ei_y): (f64, f64, f64, f64) = (0.2, 0.05, 0.01, 0.04);
    let exact = |ei: f64| LAMBDA_1 * LAMBDA_1 * (ei / (mu * l.powi(4))).sqrt();
    let mut errors = Vec::new();
    for order in [2, 3, 4, 6] {
        let section = SpatialSection::uniform(0.02, ei_y, ei_z).unwrap();
        let f =
            SpatialFlexure::new(l, section, [order; 3]).unwrap().with_mass_per_length(Profile::Constant(mu)).unwrap();
        let w = modes(&cantilever(f, Vector3::zeros()), &Default::default(), 2).unwrap().omega;
        let (ez, ey) = (w[0] / exact(ei_z) - 1.0, w[1] / exact(ei_y) - 1.0);
        println!("order {order}: about z {ez:.3e}, about y {ey:.3e}");
        errors.push((order, ez, ey));
    }
    let mut last = f64::INFINITY;
    for ((order, ez, ey), bound) in errors.into_iter().zip(BENDING_BOUNDS) {
        for e in [ez, ey] {
            assert!(e > -1e-12 && e < bound, "order {order}: relative error {e:.3e}");
        }
        assert!(ez < last, "the error falls with the order");
        last = ez;
    }
}

/// Reference: the fixed–free rod's first torsion mode, $\omega = \frac{\pi}{2}\sqrt{GJ/(\rho I_pL^2)}$
/// (rotary inertia only), for a circle of density $\rho$: $GJ = G\pi d^4/32$
/// and $\rho I_p = \rho\pi d^4/32$, so $\omega = \frac{\pi}{2L}\sqrt{G/\rho}$. The
/// mode is the one whose shape lies in the twist coordinates. A Ritz
/// approximation again: measured 10.3 % high at twist order 1 (θ linear,
/// $\sqrt3$ for $\pi/2$), 3.8e-3 at 2, 6.8e-5 at 3 and 4.3e-9 at 5, each
/// asserted within a factor 2, falling.
#[test]
fn a_rods_first_torsion_frequency_is_the_closed_forms() {
    let (l, d, e, nu, rho): (f64, f64, f64, f64, f64) = (0.1, 0.004, 2e9, 0.3, 1200.0);
    let g = e / (2.0 * (1.0 + nu));
    let exact = std::f64::consts::FRAC_PI_2 / l * (g / rho).sqrt();
    let mut last = f64::INFINITY;
    for (order, bound) in [(1, 0.11), (2, 8e-3), (3, 1.4e-4), (5, 9e-9)] {
        let section = SpatialSection::circle(e, nu, Profile::Constant(d)).unwrap().with_density(rho).unwrap();
        let f = SpatialFlexure::new(l, section, [order, 3, 3]).unwrap();
        let m = cantilever(f, Vector3::zeros());
        let found = modes(&m, &Default::default(), m.dof()).unwrap();
        // The lowest mode whose shape is mostly in the twist coordinates (0..order).
        let twist = (0..found.omega.len())
            .find(|&k| {
                let s = found.shapes.column(k);
                s.rows(0, order).norm_squared() > 0.5 * s.norm_squared()
            })
            .unwrap();
        let err = found.omega[twist] / exact - 1.0;
        println!("twist order {order}: relative error {err:.3e}");
        assert!(err > -1e-12 && err < bound, "twist order {order}: {err:.3e}");
        assert!(err < last);
        last = err;
    }
}

/// Reference: a uniform cantilever's tip deflection under its own weight,
/// $w = \mu gL^4/(8EI)$ (linear theory), at $\mu gL^3/EI = 10^{-4}$, where the
/// large-deflection correction is below 1e-8 relative; orders 3 hold the
/// linear answer exactly (the curvature is quadratic in $s$), so the
/// tolerance is 1e-7 relative. Gravity along −z bends about y ($EI_y$).
#[test]
fn a_cantilever_sags_under_its_own_weight_as_the_closed_form() {
    let (l, mu, g): (f64, f64, f64) = (0.3, 0.02, 9.81);
    let ei_y = mu * g * l.powi(3) / 1e-4;
    let section = SpatialSection::uniform(ei_y, ei_y, 3.0 * ei_y).unwrap();
    let f = SpatialFlexure::new(l, section, [3, 3, 3]).unwrap().with_mass_per_length(Profile::Constant(mu)).unwrap();
    let m = cantilever(f, Vector3::new(0.0, 0.0, -g));
    let s = flexure::mechanism::statics::solve(&m, &Default::default()).unwrap();
    let tip = placements(&m, &s.q).into_iter().find(|p| p.name == "tip").unwrap();
    let w = mu * g * l.powi(4) / (8.0 * ei_y);
    assert!((tip.position[2] + w).abs() < 1e-7 * w, "sag {} against {w}", -tip.position[2]);
    assert!(tip.position[1].abs() < 1e-12 * w, "no sideways sag");
}

/// Reference: the planar mechanism (`mechanism::statics::solve`, the
/// planar flexure's distributed weight, `crate::mass::weight`) of the same
/// blade, density and gravity in its plane, at a large sag (μgL³/EI = 2,
/// about 25° at the tip): the same Ritz space (κ_z's coefficients are the
/// planar ones), so only the two quadratures differ; tip within 1e-8 of L
/// and 1e-8 rad.
#[test]
fn a_flexure_in_a_plane_sags_as_the_planar_mechanism_with_the_same_density() {
    let (l, width, thickness, modulus, rho): (f64, f64, f64, f64, f64) = (0.1, 0.01, 2e-4, 2e9, 1200.0);
    let mu = rho * width * thickness;
    let ei = modulus * width * thickness.powi(3) / 12.0;
    let g = 2.0 * ei / (mu * l.powi(3));
    let joint = format!(
        "[[joint]]\nname = \"beam\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = {l:?}\n\
         modulus = {modulus:?}\nwidth = {width:?}\nthickness = {thickness:?}\ndensity = {rho:?}\norder = 8\n"
    );
    let planar =
        from_toml(&format!("gravity = [0.0, {:?}]\n[[body]]\nname = \"tip\"\n{joint}quadrature = 24\n", -g)).unwrap();
    let ps = flexure::mechanism::statics::solve(&planar, &Default::default()).unwrap();
    let frame = flexure::mechanism::statics::body_frames(&planar, &ps).bodies[1];
    let spatial = spatial_from_toml(&format!(
        "dimension = 3\ngravity = [0.0, {:?}, 0.0]\n[[body]]\nname = \"tip\"\n{joint}subintervals = 32\n",
        -g
    ))
    .unwrap();
    let s = flexure::mechanism::statics::solve(&spatial, &Default::default()).unwrap();
    let tip = placements(&spatial, &s.q).into_iter().find(|p| p.name == "tip").unwrap();
    let angle = tip.rotation[1][0].atan2(tip.rotation[0][0]);
    println!(
        "planar ({}, {}, {}), spatial ({}, {}, {angle})",
        frame.x, frame.y, frame.phi, tip.position[0], tip.position[1]
    );
    assert!(frame.phi < -0.25, "a large sag: {}", frame.phi);
    assert!((tip.position[0] - frame.x).abs() < 1e-8 * l && (tip.position[1] - frame.y).abs() < 1e-8 * l);
    assert!((angle - frame.phi).abs() < 1e-8 && tip.position[2].abs() < 1e-14);
}

/// Reference: a conservative system keeps $T + V$; the integrator holds
/// each step's error to its tolerance (1e-9 relative, 1e-12 absolute), so
/// over a free swing of a massive flexible rod on a hinge (released
/// horizontal, no damping; the rod's weight and inertia upstream through
/// the hinge) the energy stays within 1e-6 of the swing's energy scale.
#[test]
#[ignore = "long: soak, a flexible rod's swing at tolerance 1e-9; run by .ci/run (cargo test -- --ignored)"]
fn a_massive_rod_swinging_free_keeps_its_energy() {
    let section = SpatialSection::circle(2e7, 0.3, Profile::Constant(0.004)).unwrap().with_density(1200.0).unwrap();
    let rod = SpatialFlexure::new(0.1, section, [1, 2, 1]).unwrap();
    let weight = 1200.0 * std::f64::consts::PI * 4e-6 * 0.1 * 9.81;
    let mut m = SpatialMechanism::new(
        vec![SpatialBody::massless("ground"), SpatialBody::massless("link"), SpatialBody::massless("tip")],
        vec![
            spec(
                "hinge",
                SpatialJointKind::Revolute(RevoluteUnaligned { axis: Vector3::y_axis(), stiffness: 0.0, rest: 0.0 }),
                0,
                1,
                Isometry3::identity(),
            ),
            flexure_joint("rod", rod, 1, 2, Isometry3::identity()),
        ],
        vec![],
        vec![],
        vec![],
        Vector3::new(0.0, 0.0, -9.81),
    )
    .unwrap();
    m.initial = vec![(0, vec![0.0]), (1, vec![0.0; 4])];
    m.initial_velocity = vec![(0, vec![0.5])];
    let motion = Motion { duration: 0.1, every: 0.01, tolerance: 1e-9, absolute: 1e-12, ..Default::default() };
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none(), "{:?}", run.stopped);
    let scale = weight * 0.05;
    let e0 = run.energy[0];
    let worst = run.energy.iter().fold(0.0_f64, |a, e| a.max((e - e0).abs()));
    println!("energy {e0:.6e} J, largest change {worst:.3e} J over {} samples", run.time.len());
    for k in 0..run.time.len() {
        assert!(
            (run.energy[k] - e0).abs() < 1e-6 * scale,
            "energy {} against {e0} at t = {}",
            run.energy[k],
            run.time[k]
        );
    }
    // It swung: the hinge turned down (about y, positive turns x towards −z).
    let last = run.q(run.time.len() - 1)[0];
    assert!(last > 0.3, "the hinge turned {last} rad");
}

fn error(text: &str) -> String {
    spatial_from_toml(text).unwrap_err().to_string()
}

/// Reference: the file's own text, each error at the key it names; the
/// keys build the flexure `with_density` or `with_mass_per_length` would.
#[test]
fn the_file_takes_density_and_mass_per_length_on_a_spatial_flexure() {
    let head = "dimension = 3\n[[body]]\nname = \"tip\"\n[[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.1\n";
    let circle = "modulus = 2e9\ndiameter = 0.004\n";
    let m = spatial_from_toml(&format!("{head}{circle}density = 1200.0\n")).unwrap();
    let f = m.joints[0].kind.flexure().unwrap();
    let area = std::f64::consts::PI * 4e-6;
    assert!((f.section().mass_per_length(0.5).unwrap() - 1200.0 * area).abs() < 1e-15);
    let m = spatial_from_toml(&format!("{head}ei = 1.0\nmass_per_length = [0.2, 0.1]\n")).unwrap();
    let f = m.joints[0].kind.flexure().unwrap();
    assert!((f.section().mass_per_length(0.5).unwrap() - 0.15).abs() < 1e-16);
    assert_eq!(f.section().rotary_inertia_per_length(0.5), Some([0.0; 3]));
    let cases = [
        (format!("{head}{circle}density = -1.0\n"), "line 12, column 11", "density"),
        (format!("{head}ei = 1.0\ndensity = 1200.0\n"), "line 11, column 11", "density"),
        (format!("{head}ei = 1.0\nmass_per_length = [0.2, -0.1]\n"), "line 11, column 19", "mass_per_length"),
        (format!("{head}{circle}density = 1200.0\nmass_per_length = 0.1\n"), "line 13, column 19", "not both"),
        (
            "dimension = 3\n[[body]]\nname = \"a\"\n[[joint]]\nname = \"h\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"a\"\ndensity = 1.0\n".into(),
            "line 9, column 11",
            "`density` does not apply to a revolute joint",
        ),
    ];
    for (text, place, what) in cases {
        let e = error(&text);
        assert!(e.contains(place) && e.contains(what), "{e}\n(expected {place}, {what})");
    }
}

/// Reference: the mode solver's own error, which now counts a flexure's mass.
#[test]
fn a_massless_spatial_mechanism_has_no_modes_and_a_massive_flexure_has_some() {
    let f = SpatialFlexure::new(0.1, SpatialSection::uniform(0.01, 0.01, 0.01).unwrap(), [2, 2, 2]).unwrap();
    let e = modes(&cantilever(f.clone(), Vector3::zeros()), &Default::default(), 1).unwrap_err().to_string();
    assert!(e.contains("no flexure has a density or mass per length"), "{e}");
    let massive = f.with_mass_per_length(Profile::Constant(0.1)).unwrap();
    assert!(modes(&cantilever(massive, Vector3::zeros()), &Default::default(), 1).is_ok());
}

/// Reference: the closed form of a straight flexure of orders [1, 1, 1]
/// (each component's turn linear along it, $\theta(s) = \alpha s/L$, the
/// centreline's offset $\alpha s^2/2L$ to first order), with a mass per
/// length $\mu$ and a rotary inertia per length $(\rho J_x, \rho J_y, \rho J_z)$
/// given directly: at rest
/// $M = \mathrm{diag}\big(\rho J_xL/3,\ \mu L^3/20 + \rho J_yL/3,\ \mu L^3/20 + \rho J_zL/3\big)$
/// (twist moves no mass off the axis; at the straight shape the three are
/// uncoupled). Tolerance 1e-12 of the largest entry (the stations' Gauss
/// rule integrates these polynomials exactly). Simo and Vu-Quoc's section,
/// $\mu = 1$ and $(20, 10, 10)$, on a leg of 10: the rotary inertia is most
/// of the twist's and a sixth of the bendings'.
#[test]
fn a_given_rotary_inertia_enters_the_mass_matrix_as_the_closed_form() {
    let (l, mu, rotary) = (10.0, 1.0, [20.0, 10.0, 10.0]);
    let f = SpatialFlexure::new(l, SpatialSection::uniform(1e3, 1e3, 1e3).unwrap(), [1, 1, 1])
        .unwrap()
        .with_mass_per_length(Profile::Constant(mu))
        .unwrap()
        .with_rotary_inertia_per_length(rotary)
        .unwrap();
    let m = cantilever(f, Vector3::zeros());
    let mut sys = MechanismSystem::<Spatial>::new(&m).unwrap();
    let mm = sys.mass_matrix(&[0.0; 3]).unwrap();
    let exact =
        [rotary[0] * l / 3.0, mu * l.powi(3) / 20.0 + rotary[1] * l / 3.0, mu * l.powi(3) / 20.0 + rotary[2] * l / 3.0];
    println!("M = {mm}, closed form diag {exact:?}");
    for i in 0..3 {
        for j in 0..3 {
            let want = if i == j { exact[i] } else { 0.0 };
            assert!((mm[(i, j)] - want).abs() < 1e-12 * exact[1], "M[{i}, {j}] = {} against {want}", mm[(i, j)]);
        }
    }
    // Without it, the same flexure (no geometry) has no rotary inertia: the twist has no mass.
    let bare = SpatialFlexure::new(l, SpatialSection::uniform(1e3, 1e3, 1e3).unwrap(), [1, 1, 1])
        .unwrap()
        .with_mass_per_length(Profile::Constant(mu))
        .unwrap();
    let mm =
        MechanismSystem::<Spatial>::new(&cantilever(bare, Vector3::zeros())).unwrap().mass_matrix(&[0.0; 3]).unwrap();
    assert!(mm[(0, 0)].abs() < 1e-12 * exact[1] && (mm[(2, 2)] - mu * l.powi(3) / 20.0).abs() < 1e-12 * exact[1]);
}

/// Reference: the file's own text, each error at the key it names; the key
/// builds the flexure `with_rotary_inertia_per_length` would, and a planar
/// file refuses it.
#[test]
fn the_file_takes_a_rotary_inertia_per_length_with_a_mass_per_length() {
    let head = "dimension = 3\n[[body]]\nname = \"tip\"\n[[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 10.0\nei = 1e3\n";
    let m =
        spatial_from_toml(&format!("{head}mass_per_length = 1.0\nrotary_inertia_per_length = [20.0, 10.0, 10.0]\n"))
            .unwrap();
    let f = m.joints[0].kind.flexure().unwrap();
    assert_eq!(f.section().rotary_inertia_per_length(0.7), Some([20.0, 10.0, 10.0]));
    let circle = "modulus = 2e9\ndiameter = 0.004\n";
    let head_circle = head.replace("ei = 1e3\n", circle);
    let cases = [
        (format!("{head}rotary_inertia_per_length = [2.0, 1.0, 1.0]\n"), "line 11, column 29", "needs mass_per_length"),
        (
            format!("{head_circle}density = 1.0\nrotary_inertia_per_length = [2.0, 1.0, 1.0]\n"),
            "line 13, column 29",
            "needs mass_per_length",
        ),
        (
            format!("{head}mass_per_length = 1.0\nrotary_inertia_per_length = [2.0, -1.0, 1.0]\n"),
            "line 12, column 29",
            "not negative",
        ),
        (
            format!("{head}mass_per_length = 1.0\nrotary_inertia_per_length = [30.0, 10.0, 10.0]\n"),
            "line 12, column 29",
            "triangle inequality",
        ),
    ];
    for (text, place, what) in cases {
        let e = error(&text);
        assert!(e.contains(place) && e.contains(what), "{e}\n(expected {place}, {what})");
    }
    let planar = "[[body]]\nname = \"tip\"\n[[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.1\nei = 1.0\nmass_per_length = 1.0\nrotary_inertia_per_length = [2.0, 1.0, 1.0]\n";
    let e = from_toml(planar).unwrap_err().to_string();
    assert!(e.contains("line 11") && e.contains("rotary_inertia_per_length") && e.contains("planar"), "{e}");
}
