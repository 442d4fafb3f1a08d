//! The equations of motion of a mechanism (`flexure::dynamics::mechanism`):
//! M(q) against the kinetic energy integrated independently (section
//! positions by a separate Gauss rule, velocities by finite differences),
//! h against central differences of M, the forces against central
//! differences of the potential, the energy balance d/dt(T + V) = −q̇ᵀDq̇ at
//! random states, the single-flexure mass model, and the file's new keys.

use crate::seeded::Rng;
use flexure::dynamics::System;
use flexure::dynamics::mechanism::MechanismSystem;
use flexure::dynamics::{MassData, MassModel, update_mass};
use flexure::mechanism::file::from_toml;
use flexure::mechanism::kinematics::frames;
use flexure::mechanism::lagrangian::lagrangian;
use flexure::mechanism::{JointKind, Loads, Mechanism};
use nalgebra::{DMatrix, DVector};

/// A tree of every joint kind: a steel-like strip (distributed mass and
/// rotary inertia) from a tilted root, a sprung pin, a tapered flexure with
/// mass per length and rest curvature, a slider; bodies with offset
/// centres of mass and inertia; a tendon, a point load and tilted gravity.
const TREE: &str = r#"
gravity = [0.3, -9.81]

[[joint]]
name = "f1"
kind = "flexure"
parent = "ground"
child = "a"
origin = [0.01, 0.02, 0.3]
length = 0.05
modulus = 2e9
width = 0.01
thickness = 5e-4
density = 1200.0
order = 3
damping = 2e-3

[[body]]
name = "a"
mass = 0.02
inertia = 3e-6
com = [0.01, 0.003]

[[joint]]
name = "r"
kind = "revolute"
parent = "a"
child = "b"
origin = [0.02, 0.0, 0.2]
stiffness = 0.05
rest = 0.1
damping = 1e-4

[[body]]
name = "b"
mass = 0.01
inertia = 1e-6
com = [0.015, -0.002]

[[joint]]
name = "f2"
kind = "flexure"
parent = "b"
child = "c"
origin = [0.03, 0.005, -0.4]
length = 0.04
ei = 1e-3
mass_per_length = [0.01, 0.02]
order = 4
kappa = [0.2, -0.1, 0.05, 0.0]

[[body]]
name = "c"
mass = 0.005
inertia = 5e-7
com = [0.0, 0.004]

[[joint]]
name = "p"
kind = "prismatic"
parent = "c"
child = "d"
origin = [0.0, 0.0, 1.0]
stiffness = 50.0
damping = 0.1

[[body]]
name = "d"
mass = 0.003
com = [0.002, 0.001]

[[tendon]]
name = "t"
tension = 2.0
path = [["ground", 0.0, 0.01], ["a", 0.02, 0.004], ["c", 0.0, 0.003]]

[[force]]
name = "push"
body = "d"
at = [0.01, 0.0]
force = [0.3, -0.2]
moment = 0.01
"#;

/// A random configuration near rest (flexure coefficients up to 0.4, the
/// pin up to 0.5 rad, the slider up to 5 mm) and random rates.
fn state(m: &Mechanism, rng: &mut Rng) -> (Vec<f64>, Vec<f64>) {
    let mut q = m.rest();
    let mut v = vec![0.0; m.dof()];
    for j in &m.joints {
        let (k, scale) = match &j.kind {
            JointKind::Flexure(f) => (f.order(), 0.4),
            JointKind::Revolute(_) => (1, 0.5),
            JointKind::Prismatic(_) => (1, 0.005),
            JointKind::Spherical(none) => match *none {},
            JointKind::Fixed(_) => (0, 0.0),
        };
        for i in 0..k {
            q[j.offset + i] += scale * rng.next() / (i + 1) as f64;
            v[j.offset + i] = 20.0 * scale * rng.next() / (i + 1) as f64;
        }
    }
    (q, v)
}

fn weightless(m: &Mechanism) -> Loads {
    Loads { gravity: nalgebra::Vector2::zeros(), ..m.loads() }
}

/// The potential of the point loads and tendons (constant magnitudes).
fn load_potential(m: &Mechanism, q: &[f64]) -> f64 {
    let l = lagrangian(m, q, &vec![0.0; m.constraints()], &weightless(m)).unwrap();
    l.potential - l.elastic
}

/// T + U + V_loads: conserved by free motion without damping.
fn total_energy(sys: &mut MechanismSystem, q: &[f64], v: &[f64]) -> f64 {
    let m = sys.mechanism().clone();
    sys.energy(q, v, 0.0).unwrap() + load_potential(&m, q)
}

fn mass_and_force(sys: &mut MechanismSystem, q: &[f64], v: &[f64]) -> (DMatrix<f64>, DVector<f64>) {
    let n = sys.dim();
    let (mut mass, mut force) = (vec![0.0; n * n], vec![0.0; n]);
    sys.dynamics(q, v, 0.0, &mut mass, &mut force).unwrap();
    (DMatrix::from_column_slice(n, n, &mass), DVector::from_column_slice(&force))
}

/// Richardson-extrapolated central difference of `g` at 0 (error O(ε⁴)).
fn derivative<T>(eps: f64, g: impl Fn(f64) -> T) -> T
where
    T: std::ops::Sub<Output = T> + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T> + Clone,
{
    let d1 = g(eps) - g(-eps);
    let d2 = g(2.0 * eps) - g(-2.0 * eps);
    (d1 * 8.0 - d2) * (1.0 / (12.0 * eps))
}

/// The world positions and angles of every mass element at `q`, with its
/// mass or inertia: bodies at their centres of mass, and each flexure's
/// sections on a composite 24-panel, 8-point Gauss rule, their positions
/// r(s) = ∫(cos φ, sin φ) by a separate 16-point rule on [0, s]: a
/// discretization independent of the library's nested rule.
fn elements(m: &Mechanism, q: &[f64]) -> Vec<(f64, f64, [f64; 2], f64)> {
    let f = frames(m, q);
    let mut out = Vec::new();
    for (b, body) in m.bodies.iter().enumerate() {
        out.push((body.mass, body.inertia, world(&f.bodies[b], body.com), f.bodies[b].phi));
    }
    let rule = |k: usize| {
        let r = gauss_quad::GaussLegendre::new(std::num::NonZeroUsize::new(k).unwrap());
        r.nodes().zip(r.weights()).map(|(x, w)| (*x, *w)).collect::<Vec<(f64, f64)>>()
    };
    let (outer, inner) = (rule(8), rule(16));
    for (ji, j) in m.joints.iter().enumerate() {
        let JointKind::Flexure(flex) = &j.kind else { continue };
        let (n, l) = (flex.order(), flex.length());
        let alpha = &q[j.offset..j.offset + n];
        let mut psi = vec![0.0; n];
        let mut phi = |t: f64| {
            flex.angle_shapes(t, &mut psi);
            psi.iter().zip(alpha).map(|(p, a)| p * a).sum::<f64>()
        };
        let root = f.roots[ji];
        let panels = 24;
        for p in 0..panels {
            let (a, b) = (p as f64 / panels as f64, (p + 1) as f64 / panels as f64);
            for &(x, w) in &outer {
                let t = a + (b - a) * (x + 1.0) / 2.0;
                let ds = l * (b - a) * w / 2.0;
                let mut r = [0.0; 2];
                for &(y, v) in &inner {
                    let tau = t * (y + 1.0) / 2.0;
                    let (s, c) = phi(tau).sin_cos();
                    r[0] += l * t * v / 2.0 * c;
                    r[1] += l * t * v / 2.0 * s;
                }
                let section = flex.section();
                let mu = section.mass_per_length(t, l).unwrap_or(0.0);
                let rho_i = section.rotary_inertia_per_length(t, l).unwrap_or(0.0);
                out.push((mu * ds, rho_i * ds, world(&root, r), root.phi + phi(t)));
            }
        }
    }
    out
}

/// M against T = ½Σ m|ẇ|² + I θ̇², integrated independently, at random
/// states: T's polarization checks every entry of M. Tolerance 1e-9
/// relative: the independent rule is exact to ~1e-13 for these smooth
/// integrands and the Richardson difference (ε = 1e-4) to ~1e-12.
#[test]
fn mass_matrix_is_the_kinetic_energy() {
    let m = from_toml(TREE).unwrap();
    let mut sys = MechanismSystem::new(&m).unwrap();
    let mut rng = Rng(17);
    for _ in 0..4 {
        let (q, _) = state(&m, &mut rng);
        let mass = sys.mass_matrix(&q).unwrap();
        assert!((&mass - mass.transpose()).amax() <= 1e-15 * mass.amax(), "M is not symmetric");
        for _ in 0..3 {
            let (_, v) = state(&m, &mut rng);
            let at = |e: f64| -> Vec<(f64, f64, [f64; 2], f64)> {
                let qe: Vec<f64> = q.iter().zip(&v).map(|(a, b)| a + e * b).collect();
                elements(&m, &qe)
            };
            let eps = 1e-4;
            let (p1, m1, p2, m2) = (at(eps), at(-eps), at(2.0 * eps), at(-2.0 * eps));
            let mut t = 0.0;
            for k in 0..p1.len() {
                let d = |i: usize| {
                    let c = |e: &[(f64, f64, [f64; 2], f64)]| if i < 2 { e[k].2[i] } else { e[k].3 };
                    (8.0 * (c(&p1) - c(&m1)) - (c(&p2) - c(&m2))) / (12.0 * eps)
                };
                t += 0.5 * p1[k].0 * (d(0).powi(2) + d(1).powi(2)) + 0.5 * p1[k].1 * d(2).powi(2);
            }
            let vv = DVector::from_column_slice(&v);
            let model = 0.5 * vv.dot(&(&mass * &vv));
            assert!((model - t).abs() <= 1e-9 * t, "T = {model} from M, {t} integrated independently");
        }
    }
}

/// h = Ṁq̇ − ½∇(q̇ᵀMq̇) with ∂M/∂q by Richardson central differences
/// (ε = 1e-4): tolerance 1e-8 of |h| + |M||q̇|²/|q| scale, the differences' error.
#[test]
fn velocity_product_is_the_derivative_of_m() {
    let m = from_toml(TREE).unwrap();
    let mut sys = MechanismSystem::new(&m).unwrap();
    let mut rng = Rng(5);
    let n = m.dof();
    for _ in 0..4 {
        let (q, v) = state(&m, &mut rng);
        let h = sys.velocity_product(&q, &v).unwrap();
        let vv = DVector::from_column_slice(&v);
        let mut expected = DVector::zeros(n);
        for c in 0..n {
            let dm = derivative(1e-4, |e| {
                let mut qe = q.clone();
                qe[c] += e;
                sys.clone().mass_matrix(&qe).unwrap()
            });
            // Ṁ q̇ gets v_c ∂_c M q̇; ½∇_c(q̇ᵀMq̇) = ½ q̇ᵀ ∂_c M q̇.
            expected += &dm * &vv * v[c];
            expected[c] -= 0.5 * vv.dot(&(&dm * &vv));
        }
        let scale = expected.amax().max(sys.mass_matrix(&q).unwrap().amax() * vv.amax().powi(2));
        assert!((&h - &expected).amax() <= 1e-8 * scale, "h = {h}, differences give {expected}");
    }
}

/// At rest, f = −∇(U + V_g + V_loads): the elastic, gravity (bodies and
/// flexure sections) and load forces against Richardson central
/// differences of the energy at rest (ε = 1e-5; tolerance 1e-8 of |f|).
#[test]
fn force_at_rest_is_minus_the_potential_gradient() {
    let m = from_toml(TREE).unwrap();
    let mut sys = MechanismSystem::new(&m).unwrap();
    let mut rng = Rng(9);
    let n = m.dof();
    let zero = vec![0.0; n];
    for _ in 0..4 {
        let (q, _) = state(&m, &mut rng);
        let (_, f) = mass_and_force(&mut sys, &q, &zero);
        for c in 0..n {
            let d = derivative(1e-5, |e| {
                let mut qe = q.clone();
                qe[c] += e;
                total_energy(&mut sys.clone(), &qe, &zero)
            });
            assert!((f[c] + d).abs() <= 1e-8 * f.amax(), "f[{c}] = {}, −∂V = {}", f[c], -d);
        }
    }
}

/// The energy balance: along the equations of motion (q̈ = M⁻¹f),
/// d/dt(T + U + V_loads) = −q̇ᵀDq̇, the power of the damping alone, at
/// random states, with the time derivative by Richardson central
/// differences along (q̇, q̈). Tolerance 1e-7 of the power's scale
/// |q̇|·(|f| + |h|): a wrong h, M, gravity or load term breaks it by O(1).
#[test]
fn energy_balance_at_random_states() {
    for damped in [false, true] {
        let text = if damped { TREE.to_string() } else { TREE.replace("damping = ", "# damping = ") };
        let m = from_toml(&text).unwrap();
        let mut sys = MechanismSystem::new(&m).unwrap();
        assert_eq!(sys.damping().amax() > 0.0, damped);
        let mut rng = Rng(23);
        for _ in 0..6 {
            let (q, v) = state(&m, &mut rng);
            let (mass, f) = mass_and_force(&mut sys, &q, &v);
            let a = mass.clone().lu().solve(&f).unwrap();
            let speed = v.iter().fold(0.0_f64, |x, y| x.max(y.abs()));
            let eps = 1e-4 / speed.max(1.0);
            let rate = derivative(eps, |e| {
                let qe: Vec<f64> = q.iter().zip(&v).map(|(x, y)| x + e * y).collect();
                let ve: Vec<f64> = v.iter().zip(a.iter()).map(|(x, y)| x + e * y).collect();
                total_energy(&mut sys.clone(), &qe, &ve)
            });
            let vv = DVector::from_column_slice(&v);
            let power = -vv.dot(&(sys.damping() * &vv));
            let h = sys.velocity_product(&q, &v).unwrap();
            let scale = vv.norm() * (f.norm() + h.norm());
            assert!(
                (rate - power).abs() <= 1e-7 * scale,
                "damped {damped}: dE/dt = {rate}, damping power {power} (scale {scale})"
            );
        }
    }
}

/// One flexure from the ground with a tip body: M and h equal the
/// single-flexure model's (`flexure::mass`, itself checked against closed
/// forms) to rounding, 1e-12 relative. The mechanism places the body at the
/// tip of the flexure's kinematics (its own Gauss rule, as the statics do),
/// the single-flexure model at the tip of its nested rule; `quadrature = 24`
/// makes the two tips agree to rounding (with the default 7 points they
/// differ by ~4e-9 of M at these deflections).
#[test]
fn one_flexure_matches_the_flexure_mass_model() {
    let text = "[[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.03\n\
                modulus = 2e11\nwidth = [0.01, 0.006]\nthickness = 3e-4\ndensity = 7850.0\norder = 5\nquadrature = 24\n\
                [[body]]\nname = \"tip\"\nmass = 0.004\ninertia = 2e-7\ncom = [0.005, -0.002]\n";
    let m = from_toml(text).unwrap();
    let JointKind::Flexure(f) = &m.joints[0].kind else { unreachable!() };
    let body = flexure::inertia::RigidInertia::new(0.004, 2e-7, [0.005, -0.002]).unwrap();
    let model = MassModel::new(f, Some(&body)).unwrap();
    let mut data = MassData::new(&model);
    let mut sys = MechanismSystem::new(&m).unwrap();
    let mut rng = Rng(31);
    for _ in 0..4 {
        let (q, v) = state(&m, &mut rng);
        update_mass(&model, &q, Some(&v), &mut data);
        let mass = sys.mass_matrix(&q).unwrap();
        let h = sys.velocity_product(&q, &v).unwrap();
        eprintln!(
            "{:e} {:e}",
            (&mass - &data.mass_matrix).amax() / mass.amax(),
            (&h - &data.velocity_product).amax() / h.amax()
        );
        assert!((&mass - &data.mass_matrix).amax() <= 1e-12 * mass.amax());
        assert!((&h - &data.velocity_product).amax() <= 1e-12 * h.amax());
    }
}

/// The file's dynamics keys: values reach the model; bad values are errors
/// naming the key with its line and column; `damping` on a fixed joint is refused.
#[test]
fn file_keys_for_dynamics() {
    let m = from_toml(TREE).unwrap();
    let b = m.body("a").unwrap();
    assert_eq!(
        (m.bodies[b].mass, m.bodies[b].inertia, m.bodies[b].com),
        (0.02, 3e-6, nalgebra::Point2::new(0.01, 0.003))
    );
    let damping: Vec<f64> = m.joints.iter().map(|j| j.damping).collect();
    assert_eq!(damping, [2e-3, 1e-4, 0.0, 0.1]);
    // The damping matrix: β K on a flexure, the viscous coefficient on a pin.
    let sys = MechanismSystem::new(&m).unwrap();
    let JointKind::Flexure(f1) = &m.joints[0].kind else { unreachable!() };
    assert_eq!(sys.damping()[(0, 1)], 2e-3 * f1.stiffness_matrix()[1]);
    assert_eq!(sys.damping()[(3, 3)], 1e-4);
    let cases = [
        ("inertia = 3e-6", "inertia = -3e-6", "line 21, column 11: body \"a\": inertia = -3e-6: must not be negative"),
        (
            "damping = 1e-4",
            "damping = -1e-4",
            "line 32, column 11: joint \"r\": damping = -0.0001: must not be negative",
        ),
        ("damping = 0.1", "damping = nan", "line 65, column 11: joint \"p\": damping = NaN: must be a finite number"),
    ];
    for (from, to, message) in cases {
        let e = from_toml(&TREE.replace(from, to)).unwrap_err().to_string();
        assert!(e.starts_with(message), "{e}");
    }
    let fixed = "[[joint]]\nname = \"w\"\nkind = \"fixed\"\nparent = \"ground\"\nchild = \"b\"\ndamping = 1.0\n";
    let e = from_toml(fixed).unwrap_err().to_string();
    assert!(e.starts_with("line 6, column 11: joint \"w\": `damping` does not apply to a fixed joint"), "{e}");
}

/// Bad states are errors, not panics or NaN.
#[test]
fn bad_states_are_errors() {
    let m = from_toml(TREE).unwrap();
    let mut sys = MechanismSystem::new(&m).unwrap();
    let n = m.dof();
    let (mut mass, mut force) = (vec![0.0; n * n], vec![0.0; n]);
    let mut q = m.rest();
    assert!(sys.dynamics(&q[1..], &vec![0.0; n - 1], 0.0, &mut mass[..(n - 1) * (n - 1)], &mut force[1..]).is_err());
    q[0] = f64::NAN;
    let e = sys.dynamics(&q, &vec![0.0; n], 0.0, &mut mass, &mut force).unwrap_err();
    assert!(e.to_string().contains("q"), "{e}");
}

/// The tangents: −∂f/∂q̇ = D + ∂h/∂q̇ against central differences of f in
/// q̇ (f is quadratic in q̇, so they are exact to rounding: 1e-7 of the
/// largest entry); at rest without gravity, −∂f/∂q is the potential's
/// Hessian, against Richardson differences of f (1e-7). The closures of the
/// parallelogram: c = 0 at rest and G is lagrangian's.
#[test]
fn tangents_and_closures() {
    let m = from_toml(&TREE.replace("gravity = [0.3, -9.81]", "")).unwrap();
    let mut sys = MechanismSystem::new(&m).unwrap();
    let n = m.dof();
    let mut rng = Rng(41);
    for _ in 0..3 {
        let (q, v) = state(&m, &mut rng);
        let (mut k, mut d) = (vec![0.0; n * n], vec![0.0; n * n]);
        sys.tangent(&q, &v, 0.0, &mut k, &mut d).unwrap();
        let d = DMatrix::from_column_slice(n, n, &d);
        let zero = vec![0.0; n];
        let mut k_rest = vec![0.0; n * n];
        sys.tangent(&q, &zero, 0.0, &mut k_rest, &mut vec![0.0; n * n]).unwrap();
        let k_rest = DMatrix::from_column_slice(n, n, &k_rest);
        for c in 0..n {
            let dv = derivative(1e-2, |e| {
                let mut ve = v.clone();
                ve[c] += e;
                mass_and_force(&mut sys.clone(), &q, &ve).1
            });
            let dq = derivative(1e-5, |e| {
                let mut qe = q.clone();
                qe[c] += e;
                mass_and_force(&mut sys.clone(), &qe, &zero).1
            });
            assert!((d.column(c) + &dv).amax() <= 1e-7 * d.amax(), "damping column {c}");
            assert!((k_rest.column(c) + &dq).amax() <= 1e-7 * k_rest.amax(), "stiffness column {c}");
        }
    }
    let file =
        std::fs::read_to_string(format!("{}/../../examples/parallelogram.toml", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let p = from_toml(&file).unwrap();
    let mut sys = MechanismSystem::new(&p).unwrap();
    assert_eq!((sys.dim(), sys.closures()), (6, 3));
    let (mut c, mut g) = (vec![1.0; 3], vec![0.0; 18]);
    sys.closure(&p.rest(), &mut c, &mut g).unwrap();
    assert!(c.iter().all(|x| x.abs() < 1e-15), "{c:?}");
    let l = lagrangian(&p, &p.rest(), &[0.0; 3], &p.loads()).unwrap();
    assert_eq!(g, l.closure_jacobian.as_slice());
    // distance: a turn of the pin alone is its angle.
    let m = from_toml(TREE).unwrap();
    let sys = MechanismSystem::new(&m).unwrap();
    let (a, mut b) = (m.rest(), m.rest());
    b[3] += 0.25;
    assert!((sys.distance(&a, &b) - 0.25).abs() < 1e-15 && sys.distance(&a, &a) == 0.0);
}

/// A point given in a frame, in the world, as components.
fn world(frame: &flexure::Pose, r: impl Into<nalgebra::Point2<f64>>) -> [f64; 2] {
    let w = frame.act(&r.into());
    [w.x, w.y]
}
