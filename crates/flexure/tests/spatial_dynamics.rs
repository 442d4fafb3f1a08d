//! Spatial mechanisms' dynamics (`dynamics::mechanism` in space): the mass matrix and
//! velocity products against Lagrange's equations by finite differences,
//! modes against closed forms, and motion against a conical pendulum.

use flexure::dynamics::integrate::MotionSettings as Motion;
use flexure::dynamics::mechanism::{MechanismSystem, modes};
use flexure::dynamics::simulation::{SimulationSettings, Start, simulate};
use flexure::mechanism::kinematics::frames;
use flexure::mechanism::spatial::{
    PrismaticUnaligned, RevoluteUnaligned, SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism, Spherical,
};
use flexure::section::SpatialSection;
use flexure::space::Spatial;
use flexure::spatial::SpatialFlexure;
use nalgebra::{DMatrix, DVector, Isometry3, Matrix2, Matrix3, Point3, Translation3, Unit, UnitQuaternion, Vector3};

fn spec(name: &str, kind: SpatialJointKind, parent: usize, child: usize, origin: Isometry3<f64>) -> SpatialJointSpec {
    SpatialJointSpec::new(name, kind, parent, child, origin)
}

fn placed(p: [f64; 3], rpy: [f64; 3]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(p[0], p[1], p[2]),
        UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    )
}

fn body(name: &str, mass: f64, com: [f64; 3], inertia: [f64; 3]) -> SpatialBody {
    SpatialBody {
        name: name.into(),
        mass,
        com: Point3::from(com),
        inertia: Matrix3::from_diagonal(&Vector3::from(inertia)),
    }
}

/// Reference: Lagrange's velocity-product terms $h = \dot M\dot q - \frac12\nabla(\dot q^TM\dot q)$
/// from central differences of the mass matrix (step 1e-6; tolerance 1e-6 of the scale).
#[test]
fn velocity_products_are_lagranges_from_the_mass_matrix() {
    let axis = Unit::new_normalize(Vector3::new(0.2, 1.0, 0.4));
    let flexure = SpatialFlexure::new(0.08, SpatialSection::uniform(0.3, 0.5, 0.4).unwrap(), [2, 2, 2]).unwrap();
    let joints = vec![
        spec("flex", SpatialJointKind::Flexure(Box::new(flexure)), 0, 1, placed([0.0; 3], [0.2, 0.1, 0.0])),
        spec(
            "hinge",
            SpatialJointKind::Revolute(RevoluteUnaligned { axis, stiffness: 1.0, rest: 0.0 }),
            1,
            2,
            placed([0.02, 0.0, 0.0], [0.0, 0.3, 0.1]),
        ),
        spec(
            "ball",
            SpatialJointKind::Spherical(Spherical { stiffness: 1.0, rest: [0.0; 3] }),
            2,
            3,
            placed([0.05, 0.01, 0.0], [0.0; 3]),
        ),
        spec(
            "slide",
            SpatialJointKind::Prismatic(PrismaticUnaligned { axis: Vector3::x_axis(), stiffness: 1.0, rest: 0.0 }),
            3,
            4,
            placed([0.0, 0.02, 0.0], [0.4, 0.0, 0.0]),
        ),
    ];
    let bodies = vec![
        SpatialBody::massless("ground"),
        body("a", 0.1, [0.01, 0.0, 0.0], [1e-4, 2e-4, 3e-4]),
        body("b", 0.2, [0.02, 0.01, -0.01], [2e-4, 1e-4, 1e-4]),
        body("c", 0.3, [0.0, 0.03, 0.01], [3e-4, 2e-4, 4e-4]),
        body("d", 0.1, [0.01, 0.01, 0.01], [1e-4, 1e-4, 2e-4]),
    ];
    let m = SpatialMechanism::new(bodies, joints, vec![], vec![], vec![], Vector3::zeros()).unwrap();
    let n = m.dof();
    let q: Vec<f64> = (0..n).map(|i| 0.3 * (1.3 * i as f64 + 0.2).sin()).collect();
    let v = DVector::from_fn(n, |i, _| (0.7 * i as f64 + 1.0).cos());
    let mut sys = MechanismSystem::<Spatial>::new(&m).unwrap();
    let h = sys.velocity_product(&q, v.as_slice()).unwrap();
    let step = 1e-6;
    let mass_at = |sys: &mut MechanismSystem<Spatial>, i: usize, e: f64| {
        let mut p = q.clone();
        p[i] += e;
        sys.mass_matrix(&p).unwrap()
    };
    let mut expected = DVector::zeros(n);
    for i in 0..n {
        let dm: DMatrix<f64> = (mass_at(&mut sys, i, step) - mass_at(&mut sys, i, -step)) / (2.0 * step);
        // Ṁq̇ = Σ_i ∂_iM q̇_i q̇, and ∂_i(q̇ᵀMq̇)/2.
        expected += &dm * &v * v[i];
        expected[i] -= 0.5 * v.dot(&(&dm * &v));
    }
    let scale = expected.amax();
    assert!((&h - &expected).amax() < 1e-6 * scale, "{h}\nagainst\n{expected}");
}

/// Reference: a massless rod with a rigid disc at its tip. Torsion:
/// $\omega = \sqrt{GJ/(L I_x)}$. Bending out of the plane, the disc's
/// deflection and slope against the cantilever's tip stiffness
/// $\frac{EI}{L^3}\begin{pmatrix}12 & -6L\cr -6L & 4L^2\end{pmatrix}$ and its mass
/// and inertia: the two roots of $\det(K - \omega^2M) = 0$. The model's
/// compliance is exact for a uniform beam from order 2, so tolerance 1e-8.
#[test]
fn a_rod_with_a_tip_disc_rings_as_its_closed_forms() {
    let (l, gj, ei_y, ei_z) = (0.2, 0.8, 1.5, 2.5);
    let (mass, ix, iy) = (0.3, 2e-4, 1e-4);
    let rod = SpatialFlexure::new(l, SpatialSection::uniform(gj, ei_y, ei_z).unwrap(), [3, 3, 3]).unwrap();
    let joints = vec![spec("rod", SpatialJointKind::Flexure(Box::new(rod)), 0, 1, Isometry3::identity())];
    let disc = body("disc", mass, [0.0; 3], [ix, iy, iy]);
    let m = SpatialMechanism::new(
        vec![SpatialBody::massless("ground"), disc],
        joints,
        vec![],
        vec![],
        vec![],
        Vector3::zeros(),
    )
    .unwrap();
    let found = modes(&m, &Default::default(), 9).unwrap();
    let close = |w: f64| found.omega.iter().map(|o| (o - w).abs() / w).fold(f64::INFINITY, f64::min);
    let torsion = (gj / (l * ix)).sqrt();
    assert!(close(torsion) < 1e-8, "torsion {torsion} not among {:?}", found.omega);
    for (ei, inertia) in [(ei_y, iy), (ei_z, iy)] {
        let k = Matrix2::new(12.0, -6.0 * l, -6.0 * l, 4.0 * l * l) * (ei / l.powi(3));
        // det(K − w M) = 0 for M = diag(m, I): a quadratic in w = ω².
        let (a, b, c) = (mass * inertia, -(k[(0, 0)] * inertia + k[(1, 1)] * mass), k.determinant());
        let disc = (b * b - 4.0 * a * c).sqrt();
        for w2 in [(-b - disc) / (2.0 * a), (-b + disc) / (2.0 * a)] {
            assert!(close(w2.sqrt()) < 1e-8, "bending {} not among {:?}", w2.sqrt(), found.omega);
        }
    }
    // Torsion, two bendings of two modes each; no stretch in the model.
    assert_eq!(found.omega.len(), 5);
}

/// Reference: a conical pendulum, a point mass at $l$ on a ball joint
/// swinging at $\Omega^2 = g/(l\cos\beta)$ about the vertical, keeps its
/// cone (its height $-l\cos\beta$) and its energy (an isotropic bob's spin
/// about the rod does not change the cone: $\omega\times I\omega$ has no part from it); tolerance 1e-6 of $l$ and of the energy
/// for an integrator tolerance of 1e-9 over two turns.
#[test]
fn a_conical_pendulum_keeps_its_cone_and_its_energy() {
    let (l, g, beta): (f64, f64, f64) = (0.5, 9.81, 0.6);
    // A small sphere (isotropic inertia 2/5 m r², which leaves the cone as it is):
    // a point mass would leave the turn about the rod free and massless.
    let i = 0.4 * 0.2 * 0.05f64.powi(2);
    let bob = body("bob", 0.2, [0.0, 0.0, -l], [i; 3]);
    let ball = spec(
        "ball",
        SpatialJointKind::Spherical(Spherical { stiffness: 0.0, rest: [0.0; 3] }),
        0,
        1,
        Isometry3::identity(),
    );
    let mut m = SpatialMechanism::new(
        vec![SpatialBody::massless("ground"), bob],
        vec![ball],
        vec![],
        vec![],
        vec![],
        Vector3::new(0.0, 0.0, -g),
    )
    .unwrap();
    let omega = (g / (l * beta.cos())).sqrt();
    // Tilted by β about x; spinning at Ω about the world's z: θ̇ = J(θ)⁻¹ (0, 0, Ω).
    let theta = [beta, 0.0, 0.0];
    let state = Joint::evaluate(&Spherical { stiffness: 0.0, rest: [0.0; 3] }, &theta);
    let j = Matrix3::from_fn(|r, c| state.jacobian[(r, c)]);
    let rate = j.try_inverse().unwrap() * Vector3::new(0.0, 0.0, omega);
    m.initial = vec![(0, theta.to_vec())];
    m.initial_velocity = vec![(0, rate.as_slice().to_vec())];
    let period = 2.0 * std::f64::consts::PI / omega;
    let motion =
        Motion { duration: 2.0 * period, every: period / 8.0, tolerance: 1e-9, absolute: 1e-9, ..Default::default() };
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none(), "{:?} after {} samples", run.stopped, run.time.len());
    let e0 = run.energy[0];
    for k in 0..run.time.len() {
        let c = frames(&m, run.q(k)).bodies[1] * Point3::new(0.0, 0.0, -l);
        assert!((c.z + l * beta.cos()).abs() < 1e-6 * l, "height {} at t = {}", c.z, run.time[k]);
        assert!((run.energy[k] - e0).abs() < 1e-6 * e0.abs(), "energy {} against {e0}", run.energy[k]);
    }
    // And it went round: from +y (tilted about x), a quarter turn about +z puts it on −x.
    let c = frames(&m, run.q(2)).bodies[1] * Point3::new(0.0, 0.0, -l);
    let r = l * beta.sin();
    assert!((c.x + r).abs() < 1e-5 * l && c.y.abs() < 1e-5 * l, "{c}");
}

use flexure::mechanism::Joint;

/// Reference: a free hinge about z carrying a disc of $I_{zz}$ = 2 kg·m²,
/// turned by a scheduled moment $M_z$:
/// - a ramp $M = 4t$ (points (0, 0), (1, 4)) gives $\theta = 4t^3/(6I) = t^3/3$ up to t = 1;
/// - a step of 1 N·m at t = 0.5 (two points at one time), in the same
///   file's `force.kick.mz`, adds $(t - 0.5)^2/(2I)$ after it, which the
///   integrator meets exactly by landing on the step;
///
/// held to 1e-8 rad (integrator tolerance 1e-10). It starts at rest (a free
/// hinge has no equilibrium to start from).
#[test]
fn scheduled_moments_turn_a_free_hinge_as_their_integrals() {
    let text = "dimension = 3\n\
        [[joint]]\nname = \"hinge\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"disc\"\naxis = [0.0, 0.0, 1.0]\n\
        [[body]]\nname = \"disc\"\nmass = 1.0\nizz = 2.0\nixx = 1.0\niyy = 1.0\n\
        [[force]]\nname = \"drive\"\nbody = \"disc\"\nat = [0.0, 0.0, 0.0]\nmoment = [0.0, 0.0, 7.0]\n\
        [[force]]\nname = \"kick\"\nbody = \"disc\"\nat = [0.0, 0.0, 0.0]\n\
        [[schedule]]\nload = \"force.drive.mz\"\npoints = [[0.0, 0.0], [1.0, 4.0]]\n\
        [[schedule]]\nload = \"force.kick.mz\"\npoints = [[0.5, 0.0], [0.5, 1.0]]\n";
    let m = flexure::mechanism::file::spatial_from_toml(text).unwrap();
    assert_eq!(m.schedules.len(), 2);
    let loads = flexure::dynamics::schedule::loads_at(&m, 0.25);
    assert_eq!((loads.force[0][2], loads.force[1][2]), (1.0, 0.0));
    let motion = Motion { duration: 1.0, every: 0.125, tolerance: 1e-10, absolute: 1e-10, ..Default::default() };
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none(), "{:?}", run.stopped);
    assert_eq!(run.time.len(), 9);
    for k in 0..run.time.len() {
        let t = run.time[k];
        let expected = t.powi(3) / 3.0 + if t > 0.5 { (t - 0.5).powi(2) / 4.0 } else { 0.0 };
        assert!((run.q(k)[0] - expected).abs() < 1e-8, "t = {t}: {} against {expected}", run.q(k)[0]);
    }
}

/// Reference: the file's text: a spatial schedule names a spatial load
/// (`force.NAME.mx|my|mz|fx|fy|fz`, `tendon.NAME.tension`,
/// `gravity.x|y|z`); a planar name, an unknown force, a load scheduled twice
/// and a negative tension are refused at the load's line and column.
#[test]
fn spatial_schedules_refuse_what_they_cannot_set() {
    let base = "dimension = 3\n\
        [[joint]]\nname = \"hinge\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"disc\"\n\
        [[body]]\nname = \"disc\"\nixx = 1.0\niyy = 1.0\nizz = 2.0\n\
        [[force]]\nname = \"drive\"\nbody = \"disc\"\nat = [0.0, 0.0, 0.0]\n\
        [[tendon]]\nname = \"pull\"\ntension = 1.0\npath = [[\"ground\", 0.0, 0.1, 0.0], [\"disc\", 0.1, 0.0, 0.0]]\n";
    let cases = [
        (
            "[[schedule]]\nload = \"force.drive.moment\"\npoints = [[0.0, 1.0]]\n",
            "line 21, column 8",
            "mx, my, mz, fx, fy or fz",
        ),
        ("[[schedule]]\nload = \"force.other.fx\"\npoints = [[0.0, 1.0]]\n", "line 21, column 8", "names no force"),
        (
            "[[schedule]]\nload = \"gravity.z\"\npoints = [[0.0, 1.0]]\n[[schedule]]\nload = \"gravity.z\"\npoints = [[0.0, 2.0]]\n",
            "line 24, column 8",
            "scheduled twice",
        ),
        ("[[schedule]]\nload = \"tendon.pull.tension\"\npoints = [[0.0, -1.0]]\n", "line 22", "negative"),
    ];
    for (schedule, place, why) in cases {
        let text = format!("{base}{schedule}");
        let e = flexure::mechanism::file::spatial_from_toml(&text).unwrap_err().to_string();
        assert!(e.contains(place) && e.contains(why), "{schedule:?}: {e}");
    }
}

/// Reference: the planar mechanism's own dynamics
/// (`dynamics::simulation::simulate`). A sprung four-bar in the plane,
/// written once as a planar file and once with `dimension = 3`: its pin's
/// out-of-plane equations (z, and the axes' tilt) vanish identically, so
/// three of its five are dependent; the spatial system keeps their
/// independent combinations, and both runs, released from the unloaded
/// shape under gravity, swing alike: joint angles to 1e-7 rad over 0.5 s
/// (integrator tolerance 1e-9), closures held to 1e-9.
#[test]
fn a_planar_linkage_in_space_swings_as_in_the_plane() {
    let planar = "gravity = [0.0, -9.81]\n\
        [[joint]]\nname = \"crank\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"a\"\nstiffness = 0.5\n\
        [[joint]]\nname = \"coupler\"\nkind = \"revolute\"\nparent = \"a\"\nchild = \"b\"\norigin = [0.1, 0.0, 0.0]\nstiffness = 0.5\n\
        [[joint]]\nname = \"rocker\"\nkind = \"revolute\"\nparent = \"b\"\nchild = \"c\"\norigin = [0.0, 0.1, 0.0]\nstiffness = 0.5\n\
        [[body]]\nname = \"a\"\nmass = 0.1\ncom = [0.05, 0.0]\ninertia = 1e-4\n\
        [[body]]\nname = \"b\"\nmass = 0.1\ncom = [0.0, 0.05]\ninertia = 1e-4\n\
        [[pin]]\na = \"c\"\na_at = [-0.1, 0.0]\nb = \"ground\"\nb_at = [0.0, 0.1]\n";
    let spatial = "dimension = 3\ngravity = [0.0, -9.81, 0.0]\n\
        [[joint]]\nname = \"crank\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"a\"\nstiffness = 0.5\n\
        [[joint]]\nname = \"coupler\"\nkind = \"revolute\"\nparent = \"a\"\nchild = \"b\"\norigin = [0.1, 0.0, 0.0]\nstiffness = 0.5\n\
        [[joint]]\nname = \"rocker\"\nkind = \"revolute\"\nparent = \"b\"\nchild = \"c\"\norigin = [0.0, 0.1, 0.0]\nstiffness = 0.5\n\
        [[body]]\nname = \"a\"\nmass = 0.1\ncom = [0.05, 0.0, 0.0]\nixx = 1e-5\niyy = 1e-4\nizz = 1e-4\n\
        [[body]]\nname = \"b\"\nmass = 0.1\ncom = [0.0, 0.05, 0.0]\nixx = 1e-4\niyy = 1e-5\nizz = 1e-4\n\
        [[pin]]\na = \"c\"\na_at = [-0.1, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nb = \"ground\"\nb_at = [0.0, 0.1, 0.0]\n";
    let motion = Motion { duration: 0.5, every: 0.05, tolerance: 1e-9, absolute: 1e-9, ..Default::default() };
    let p = flexure::mechanism::file::from_toml(planar).unwrap();
    let s = flexure::mechanism::file::spatial_from_toml(spatial).unwrap();
    let reference = flexure::dynamics::simulation::simulate(
        &p,
        &flexure::dynamics::simulation::SimulationSettings { motion, ..Default::default() },
        flexure::dynamics::simulation::Start::Rest,
    )
    .unwrap();
    let run = simulate(&s, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none() && reference.stopped.is_none(), "{:?} {:?}", run.stopped, reference.stopped);
    assert_eq!(run.time.len(), reference.time.len());
    for k in 0..run.time.len() {
        for (a, b) in run.q(k).iter().zip(reference.q(k)) {
            assert!((a - b).abs() < 1e-7, "t = {}: {:?} against {:?}", run.time[k], run.q(k), reference.q(k));
        }
    }
    assert!(run.violation < 1e-9, "{}", run.violation);
    // And it moved: released unloaded, gravity swings it.
    assert!(run.q(run.time.len() - 1)[0].abs() > 1e-2, "{:?}", run.q(run.time.len() - 1));
}

/// The example finger with its contact force replaced by `loads` (and
/// `top` before its tables).
fn finger3d_with(top: &str, loads: &str) -> SpatialMechanism {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/finger3d.toml")).unwrap();
    let body = text.split("# A grasp reaction").next().unwrap();
    flexure::mechanism::file::spatial_from_toml(&format!("{top}{body}\n{loads}")).unwrap()
}

/// Massless spatial flexures under motion (issue 39 item 2): the finger of
/// examples/finger3d.toml from its rest shape under its contact force
/// stalled at t = 12 µs ("Newton diverged"), because the error test weighed
/// the velocities of its directions without inertia (the flexures' inner
/// coordinates, quasi-static) as states, while they are index-2 variables;
/// as the deflection grows, these directions take on inertia from zero and
/// their velocities' estimate held the step at rounding's level. Now the
/// run reaches 0.05 s, and, independently of the integrator, keeps the
/// energy balance of an undamped motion under a dead force:
/// $T + V - F\cdot(p(t) - p(0))$ constant, $p$ the contact point, within
/// $10^{-6}$ of the largest elastic-plus-kinetic energy reached.
#[test]
#[ignore = "long: a spatial motion of 0.05 s at about 20 ms a step; run by .ci/run (cargo test -- --ignored)"]
fn a_spatial_finger_with_massless_flexures_moves_from_rest() {
    let force = Vector3::new(0.0, -0.4, 0.1);
    let at = Point3::new(0.0, 0.0, 0.003);
    let m = finger3d_with(
        "",
        &format!(
            "[[force]]\nname = \"contact\"\nbody = \"fingertip\"\nat = [{}, {}, {}]\nforce = [{}, {}, {}]\n",
            at.x, at.y, at.z, force.x, force.y, force.z
        ),
    );
    let motion = Motion { duration: 0.05, every: 0.005, tolerance: 1e-8, absolute: 1e-8, ..Default::default() };
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none(), "{:?}", run.stopped);
    assert_eq!(run.time.last(), Some(&0.05));
    let tip = m.bodies.iter().position(|b| b.name == "fingertip").unwrap();
    let contact = |k: usize| (frames(&m, run.q(k)).bodies[tip] * at).coords;
    let balance: Vec<f64> =
        (0..run.time.len()).map(|k| run.energy[k] - force.dot(&(contact(k) - contact(0)))).collect();
    let scale = run.energy.iter().fold(0.0_f64, |a, e| a.max(e.abs()));
    let drift = balance.iter().map(|b| (b - balance[0]).abs()).fold(0.0, f64::max);
    assert!(scale > 1e-5 && drift <= 1e-6 * scale, "drift {drift:e} of {scale:e}: {balance:?}");
}

/// The same finger free of loads, its first flexure set turning about all
/// three axes at once (1 rad/s on the first coefficient of its twist and of
/// both bendings; issue 39: a free spatial finger stalled the same way, here
/// at 11 µs, at tolerances 1e-8, 1e-6 and 1e-4). It runs 0.02 s at each.
/// At 1e-8 it keeps $T + V$ (no damping, no load) within $10^{-4}$ of the
/// largest kinetic energy it has (measured 2.1e-5): the L-stable method
/// damps the unresolved stiff inner modes a little, and wrong equations of
/// motion would be off by their own size. At 1e-6 and 1e-4 its path is
/// the 1e-8 run's to within its tolerance: the fingertip within 10 × the
/// tolerance × the finger's 0.09 m (measured 3.7 and 3.9 × against a run
/// at 1e-10, whose own 1e-8 run is 6.8 × off), its rotation matrix within
/// 30 × the tolerance (measured 17 and 8.9 ×).
#[test]
fn a_free_spatial_finger_keeps_its_energy_at_1e_8_and_that_path_at_1e_6_and_1e_4() {
    let m = finger3d_with("", "[initial_velocity]\nmcp = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0]\n");
    let run_at = |tolerance: f64| {
        let motion = Motion { duration: 0.02, every: 0.002, tolerance, absolute: tolerance, ..Default::default() };
        let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
        assert!(run.stopped.is_none(), "at {tolerance:e}: {:?}", run.stopped);
        assert_eq!(run.time.last(), Some(&0.02), "at {tolerance:e}");
        run
    };
    let reference = run_at(1e-8);
    let mut sys = MechanismSystem::<Spatial>::new(&m).unwrap();
    let kinetic = (0..reference.time.len())
        .map(|k| {
            let v = DVector::from_column_slice(reference.v(k));
            0.5 * v.dot(&(sys.mass_matrix(reference.q(k)).unwrap() * &v))
        })
        .fold(0.0, f64::max);
    let drift = reference.energy.iter().map(|e| (e - reference.energy[0]).abs()).fold(0.0, f64::max);
    assert!(kinetic > 0.0 && drift <= 1e-4 * kinetic, "drift {drift:e} of {kinetic:e}");
    let tip = reference.bodies.iter().position(|b| b.name == "fingertip").unwrap();
    for tolerance in [1e-6, 1e-4] {
        let run = run_at(tolerance);
        let (a, b) = (&run.bodies[tip], &reference.bodies[tip]);
        let (mut position, mut rotation) = (0.0_f64, 0.0_f64);
        for k in 0..run.time.len() {
            for i in 0..3 {
                position = position.max((a.position[k][i] - b.position[k][i]).abs());
                for j in 0..3 {
                    rotation = rotation.max((a.rotation[k][i][j] - b.rotation[k][i][j]).abs());
                }
            }
        }
        assert!(
            position <= 10.0 * tolerance * 0.09 && rotation <= 30.0 * tolerance,
            "at {tolerance:e}: {position:e} m, {rotation:e}"
        );
    }
}

/// examples/continuum_robot.toml with its tendon "up" ramped from 0 to
/// 0.6 N over 10 ms (its tendon "side" holding 0.3 N), from its straight
/// rest shape.
fn ramped_continuum_robot() -> SpatialMechanism {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/continuum_robot.toml")).unwrap();
    let ramp = "\n[[schedule]]\nload = \"tendon.up.tension\"\npoints = [[0.0, 0.0], [0.01, 0.6]]\n";
    flexure::mechanism::file::spatial_from_toml(&format!("{text}{ramp}")).unwrap()
}

/// $\sum_k T_k\ell_k(q)$: the tendons' potential at their file tensions,
/// each length through its via points (the tendons' own definition).
fn tendon_potential(m: &SpatialMechanism, q: &[f64]) -> f64 {
    let f = frames(m, q);
    m.tendons
        .iter()
        .map(|t| {
            let points: Vec<Point3<f64>> = t.path.iter().map(|(b, p)| f.bodies[*b] * p).collect();
            t.tension * points.windows(2).map(|w| (w[1] - w[0]).norm()).sum::<f64>()
        })
        .sum()
}

/// Issue 39 item 2: the ramped continuum robot (massless backbone, five
/// discs) stalled at t = 1.84 ms of 20 ms at the default tolerance 1e-8,
/// "Newton diverged (contraction 250)", the step falling to 1e-17 s. Its
/// flexures' inner directions take on inertia from zero as they deflect,
/// so the mass matrix changes within a step by much of itself there, and
/// the Newton matrix, which took it at the step's start, contracted by
/// only about 0.5 at every step size (measured: the spectral radius of
/// $N^{-1}(J - N)$ was 0.4–0.5 from h = 27 µs down to 7 µs, 0.4 of it
/// from the mass's change): the steps halved until they reached
/// rounding's level. Now, with the stages' own masses in the Newton
/// matrix, it runs the 20 ms; and, independently of the integrator, once
/// the ramp is over (t ≥ 10 ms: the tensions constant, no damping)
/// $T + U + \sum_k T_k\ell_k$ holds within $10^{-7}$ of the largest
/// elastic-plus-kinetic energy reached (measured 1.3e-9). Its error is
/// honest: its discs' positions are within 0.9 × the tolerance × their
/// travel of a run at 1e-10 (0.5 × at 1e-6; measured by the CLI).
#[test]
#[ignore = "long: 20 ms of spatial motion in about 1,000 steps of a 45-coordinate chain; run by .ci/run (cargo test -- --ignored)"]
fn the_ramped_continuum_robot_runs_its_20_ms_at_1e_8_keeping_its_energy_after_the_ramp() {
    let m = ramped_continuum_robot();
    let motion = Motion { duration: 0.02, every: 2e-4, ..Default::default() };
    assert_eq!((motion.tolerance, motion.absolute), (1e-8, 1e-8), "the default tolerances");
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none(), "{:?}", run.stopped);
    assert_eq!(run.time.last(), Some(&0.02));
    let after: Vec<usize> = (0..run.time.len()).filter(|&k| run.time[k] >= 0.01 - 1e-12).collect();
    let balance: Vec<f64> = after.iter().map(|&k| run.energy[k] + tendon_potential(&m, run.q(k))).collect();
    let scale = run.energy.iter().fold(0.0_f64, |a, e| a.max(e.abs()));
    let drift = balance.iter().map(|b| (b - balance[0]).abs()).fold(0.0, f64::max);
    assert!(scale > 1e-5 && drift <= 1e-7 * scale, "drift {drift:e} of {scale:e}: {balance:?}");
}

/// The same robot's first 2.5 ms (past the 1.84 ms where it stalled),
/// sampled as the CLI samples 20 ms: its start is the same run, and it
/// reaches 2.5 ms at the default tolerance.
#[test]
fn the_ramped_continuum_robot_passes_where_it_stalled_at_1e_8() {
    let m = ramped_continuum_robot();
    let motion = Motion { duration: 0.0025, every: 2e-4, ..Default::default() };
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none(), "{:?}", run.stopped);
    assert_eq!(run.time.last(), Some(&0.0025));
}

/// A finger in the plane and its spatial twin: examples/finger3d.toml's
/// three blades (no `poisson`: it sets the plane's plate stiffness but only
/// the shear modulus in space, which moves nothing here), phalanges and
/// joints, written once as a planar file and once with `dimension = 3`,
/// and a fingertip force in the plane, 0.4 N along −y.
fn planar_finger_and_its_spatial_twin() -> (flexure::mechanism::Mechanism, SpatialMechanism) {
    let blade = |name: &str, parent: &str, child: &str| {
        format!(
            "[[joint]]\nname = \"{name}\"\nkind = \"flexure\"\nparent = \"{parent}\"\nchild = \"{child}\"\n\
             length = 0.010\nmodulus = 200e9\nwidth = 0.006\nthickness = 0.0003\n"
        )
    };
    let fixed = |name: &str, parent: &str, child: &str, x: f64| {
        format!(
            "[[joint]]\nname = \"{name}\"\nkind = \"fixed\"\nparent = \"{parent}\"\nchild = \"{child}\"\n\
             origin = [{x}, 0.0, 0.0]\n"
        )
    };
    let joints = [
        blade("mcp", "ground", "proximal_base"),
        fixed("proximal", "proximal_base", "proximal_end", 0.025),
        blade("pip", "proximal_end", "middle_base"),
        fixed("middle", "middle_base", "middle_end", 0.020),
        blade("dip", "middle_end", "distal_base"),
        fixed("distal", "distal_base", "fingertip", 0.015),
    ]
    .concat();
    // (name, mass, com along x, ixx, iyy, izz) of examples/finger3d.toml.
    let bodies = [
        ("proximal_base", 0.0025, 0.0125, 3.4e-8, 1.44e-7, 1.51e-7),
        ("middle_base", 0.002, 0.010, 2.73e-8, 7.73e-8, 8.33e-8),
        ("distal_base", 0.0015, 0.0075, 2.05e-8, 3.61e-8, 4.06e-8),
    ];
    let (mut planar, mut spatial) = (joints.clone(), format!("dimension = 3\n{joints}"));
    for (name, mass, x, ixx, iyy, izz) in bodies {
        planar += &format!("[[body]]\nname = \"{name}\"\nmass = {mass}\ncom = [{x}, 0.0]\ninertia = {izz}\n");
        spatial += &format!(
            "[[body]]\nname = \"{name}\"\nmass = {mass}\ncom = [{x}, 0.0, 0.0]\nixx = {ixx}\niyy = {iyy}\nizz = {izz}\n"
        );
    }
    planar += "[[force]]\nname = \"contact\"\nbody = \"fingertip\"\nat = [0.0, 0.0]\nforce = [0.0, -0.4]\n";
    spatial += "[[force]]\nname = \"contact\"\nbody = \"fingertip\"\nat = [0.0, 0.0, 0.0]\nforce = [0.0, -0.4, 0.0]\n";
    (
        flexure::mechanism::file::from_toml(&planar).unwrap(),
        flexure::mechanism::file::spatial_from_toml(&spatial).unwrap(),
    )
}

/// Issue 39 item 2: "the planar twin of the same finger runs" — and the
/// spatial one now moves as it does. Reference: the planar finger's own
/// motion (`simulate` in the plane). Both start from their rest shape
/// (massless blades, so each first goes onto their quasi-static
/// equilibrium) under the same in-plane force and run 5 ms at the default
/// tolerance 1e-8: the fingertip's x and y agree within 1e-9 m (measured
/// 7e-12 m, over a travel of 3.2 mm), its angle within 3e-8 rad (measured
/// 1.3e-9 rad, over 0.07 rad turned), and the spatial finger leaves the
/// plane by less than 1e-8 (m, and rotation-matrix entries; measured 2e-11).
#[test]
fn a_planar_finger_in_space_moves_as_in_the_plane_at_1e_8() {
    let (planar, spatial) = planar_finger_and_its_spatial_twin();
    let motion = Motion { duration: 0.005, every: 0.0005, ..Default::default() };
    let settings = SimulationSettings { motion, ..Default::default() };
    let reference = flexure::dynamics::simulation::simulate(&planar, &settings, Start::Rest).unwrap();
    let run = simulate(&spatial, &settings, Start::Rest).unwrap();
    assert!(run.stopped.is_none() && reference.stopped.is_none(), "{:?} {:?}", run.stopped, reference.stopped);
    assert_eq!(run.time, reference.time);
    let tip = |names: Vec<&String>| names.iter().position(|n| n.as_str() == "fingertip").unwrap();
    let p = &reference.bodies[tip(reference.bodies.iter().map(|b| &b.name).collect())];
    let s = &run.bodies[tip(run.bodies.iter().map(|b| &b.name).collect())];
    let (mut position, mut angle, mut out_of_plane) = (0.0_f64, 0.0_f64, 0.0_f64);
    for k in 0..run.time.len() {
        let (x, r) = (s.position[k], s.rotation[k]);
        position = position.max((x[0] - p.x[k]).abs()).max((x[1] - p.y[k]).abs());
        angle = angle.max((r[1][0].atan2(r[0][0]) - p.phi[k]).abs());
        out_of_plane = out_of_plane.max(x[2].abs()).max(r[2][0].abs()).max(r[2][1].abs()).max(r[0][2].abs());
    }
    assert!(
        position <= 1e-9 && angle <= 3e-8 && out_of_plane <= 1e-8,
        "{position:e} m, {angle:e} rad, {out_of_plane:e}"
    );
    // And it moved: the force turns the fingertip by more than 0.05 rad.
    assert!(p.phi.last().unwrap().abs() > 0.05, "{:?}", p.phi);
}

/// The ramped continuum robot with material damping on its backbone
/// (β = 0.023 s on each segment: its two lowest modes, 61 rad/s, damped
/// near critically, the others overdamped, decaying at about 1/β) settles,
/// 0.4 s after the ramp began, where the statics put it under the final
/// tensions (0.6 N and 0.3 N). Reference: `statics::solve_between` from
/// the unloaded shape (what `flexure solve` answers). Every disc within
/// 2e-9 m of it (measured 3.7e-10 m against a deflection of 13 mm; the
/// last 40 ms still moved it 7.7e-10 m), at the default tolerance 1e-8.
#[test]
fn the_damped_ramped_continuum_robot_settles_at_its_static_equilibrium_at_1e_8() {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/continuum_robot.toml")).unwrap();
    let ramp = "\n[[schedule]]\nload = \"tendon.up.tension\"\npoints = [[0.0, 0.0], [0.01, 0.6]]\n";
    let damped = text.replace("poisson = 0.33\n", "poisson = 0.33\ndamping = 0.023\n");
    assert_eq!(damped.matches("damping").count(), 5);
    let m = flexure::mechanism::file::spatial_from_toml(&format!("{damped}{ramp}")).unwrap();
    let motion = Motion { duration: 0.4, every: 0.04, ..Default::default() };
    let run = simulate(&m, &SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    assert!(run.stopped.is_none(), "{:?}", run.stopped);
    let settings = flexure::mechanism::statics::Settings::default();
    let unloaded = flexure::mechanism::statics::assemble_unloaded(&m, &settings).unwrap();
    let loads = flexure::dynamics::schedule::loads_at(&m, 0.4);
    assert_eq!(loads.tension, [0.6, 0.3]);
    let statics = flexure::mechanism::statics::solve_between(&m, &unloaded, &loads, &settings).unwrap();
    let f = frames(&m, &statics.q);
    let last = run.time.len() - 1;
    for (b, body) in run.bodies.iter().enumerate() {
        let expected = f.bodies[b + 1].translation.vector;
        let off = (Vector3::from(body.position[last]) - expected).norm();
        assert!(off <= 2e-9, "{}: {:?} against {expected:?}, {off:e} m", body.name, body.position[last]);
    }
    // And it bent: the last disc 13 mm off the axis.
    assert!(f.bodies[5].translation.vector.y > 0.01, "{:?}", f.bodies[5].translation.vector);
}
